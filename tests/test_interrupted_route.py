"""An interrupted ``xroute route`` (SIGKILL or Ctrl-C at any moment) leaves no half-written DEF, JSON or
report under the final names, and the next run cleans up and completes."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import pick

REPO = Path(__file__).resolve().parent.parent
DESIGN = pick("ispd19_sample4")  # or its generated stand-in without the contest data


def start_route(out: Path, testcases_root: Path) -> subprocess.Popen:
    # The child runs in a temporary folder: name the testcases' root (an installed package has no
    # checkout beside which to look for ../shared/testcases).
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p), "CI": "true",
           "XROUTE_TESTCASES": str(testcases_root)}
    return subprocess.Popen([sys.executable, "-m", "xroute", "route", DESIGN, "--iterations", "1", "--out", str(out)],
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
    # Kill at several moments after the only iteration ends: while the outputs are written and checked.
    for delay in (0.0, 0.05, 0.1, 0.15):
        proc = start_route(out, root)
        assert proc.stdout is not None
        for line in proc.stdout:
            if line.startswith("iteration 0:"):
                break
        time.sleep(delay)
        proc.send_signal(sig)
        proc.communicate(timeout=60)
        assert_complete_or_absent(out)
        if sig == signal.SIGINT:  # Ctrl-C: the atomic writers remove their temporary files themselves
            assert not [p.name for p in out.iterdir() if ".tmp" in p.name]
    proc = start_route(out, root)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 0, stderr
    assert sorted(p.name for p in out.iterdir()) == sorted(f"{DESIGN}{s}" for s in (".drc.rpt", ".metrics.json", ".routed.def"))
    assert_complete_or_absent(out)
