"""An interrupted ``xroute route`` (SIGKILL or Ctrl-C while it writes its outputs) leaves no half-written
DEF, JSON or report under the final names, and the next run cleans up and completes. The signal comes at
known points of the output writing (no timing: the child signals itself), so every run tests the same
moments."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import pick

# Slow set: kills and reruns routes in child processes.
pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parent.parent
DESIGN = pick("ispd19_sample4")  # or its generated stand-in without the contest data


# The child routes through this wrapper, which sends itself the signal just before the N-th
# os.replace of the run (N = 0: never); for Ctrl-C it raises the KeyboardInterrupt that Python makes
# of SIGINT right there (a self-sent SIGINT reaches Python asynchronously: in one run of .ci/run
# the route then ended with status 0). A route's output writing calls os.replace five times, in this
# order: the staged metrics JSON, the publishing note, then the DEF, the DRC report and the metrics
# JSON moved to their final names (xroute.output_set.publish). Stopping before each of them covers
# every stage: files staged, the note written, none / one / two of the three files published.
CHILD = """
import os, signal, sys
sig, at = int(sys.argv[1]), int(sys.argv[2])
real_replace, calls = os.replace, 0

def replace(src, dst, **kwargs):
    global calls
    calls += 1
    if calls == at:
        if sig == signal.SIGINT:
            raise KeyboardInterrupt  # what Python makes of Ctrl-C, raised here and not at a later bytecode
        os.kill(os.getpid(), sig)
    return real_replace(src, dst, **kwargs)

os.replace = replace
sys.argv = ["xroute", *sys.argv[3:]]
from xroute.cli.app import main
main()
"""
REPLACES = 5  # os.replace calls of one route's outputs


def start_route(out: Path, testcases_root: Path, sig: int = 0, at: int = 0) -> subprocess.Popen:
    # The child runs in a temporary folder: name the testcases' root (an installed package has no
    # checkout beside which to look for ../shared/testcases).
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p), "CI": "true",
           "XROUTE_TESTCASES": str(testcases_root)}
    return subprocess.Popen([sys.executable, "-c", CHILD, str(int(sig)), str(at), "route", DESIGN, "--iterations", "1",
                             "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, cwd=out.parent)


def assert_complete_or_absent(out: Path) -> None:
    """Every file under a final name is whole."""
    def_path, metrics, drc = (out / f"{DESIGN}{s}" for s in (".routed.def", ".metrics.json", ".drc.rpt"))
    if def_path.exists():
        assert def_path.read_text().rstrip().endswith("END DESIGN")
    if metrics.exists():
        assert json.loads(metrics.read_text())["final"]["open_nets"] == 0
    if drc.exists():
        lines = drc.read_text().splitlines()
        assert lines[0].startswith("# markers") and len(lines) == 1 + int(lines[0].split()[2])


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGINT])
def test_killed_route_leaves_whole_files_and_rerun_completes(testcase, tmp_path: Path, sig: int) -> None:
    root = testcase(DESIGN).folder.parent
    out = tmp_path / "out"
    # Stop the run before each os.replace of its output writing, one run after another in the same folder.
    for at in range(1, REPLACES + 1):
        proc = start_route(out, root, sig, at)
        _, stderr = proc.communicate(timeout=120)
        # Killed, or ended by KeyboardInterrupt (Typer exits 130): never a run that went on to the end.
        assert proc.returncode == (-signal.SIGKILL if sig == signal.SIGKILL else 130), (at, stderr)
        assert_complete_or_absent(out)
        if sig == signal.SIGINT:  # Ctrl-C: the atomic writers and the staging folder clean up themselves
            assert [p.name for p in out.iterdir() if ".tmp" in p.name or p.name.startswith(".xroute-stage.")] == []
    proc = start_route(out, root)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 0, stderr
    assert sorted(p.name for p in out.iterdir()) == sorted(f"{DESIGN}{s}" for s in (".drc.rpt", ".metrics.json", ".routed.def"))
    assert_complete_or_absent(out)
