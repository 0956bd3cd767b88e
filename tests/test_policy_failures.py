"""Hostile policies: whatever a user's policy file does, the run ends with one line or its outputs.

Any ``BaseException`` that is not ``KeyboardInterrupt`` (``GeneratorExit``, a user's subclass,
``SystemExit``), raised when the file is loaded or inside ``order()`` / ``plan()``, is one line
naming the file and line; so is an exception whose ``__str__`` fails. A policy that calls
``os.chdir`` does not move where the outputs go, and one that leaves a thread running does not
keep the process alive after the outputs are written, nor a ``batch`` worker at the pool's shutdown.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from xroute.cli.app import app
from conftest import one_error

BAD_STR = "class Bad({base}):\n    def __str__(self):\n        raise RuntimeError('no text')\n"
ORDER = "def order(region, features):\n    {body}\n    return list(range(len(features)))\n"
PLAN = "def plan(history, rule):\n    {body}\n"
RAISES = {  # what the file's function raises -> the text the error line holds
    "raise GeneratorExit('bye')": "raised GeneratorExit: bye",
    "raise Boom('custom')": "raised Boom: custom",
    "raise Bad()": "raised Bad: <Bad: unprintable>",
    "raise BadBase()": "raised BadBase: <BadBase: unprintable>",
    "raise SystemExit(0)": "called sys.exit(0)",
}
PRELUDE = ("class Boom(BaseException):\n    pass\n" + BAD_STR.format(base="Exception")
           + BAD_STR.format(base="BaseException").replace("class Bad(", "class BadBase("))


def policy_file(tmp_path: Path, text: str, name: str = "pol.py") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


@pytest.mark.parametrize("raise_line", list(RAISES))
def test_order_raising_anything_is_one_line(runner: CliRunner, tmp_path: Path, raise_line: str) -> None:
    pol = policy_file(tmp_path, PRELUDE + ORDER.format(body=raise_line))
    line = one_error(runner.invoke(app, ["route", "--policy", str(pol), "--out", str(tmp_path / "o")]),
                     str(pol), RAISES[raise_line])
    assert f"{pol}:{PRELUDE.count(chr(10)) + 2}:" in line  # the line of the raise
    assert not any((tmp_path / "o").glob("*.def"))


@pytest.mark.parametrize("raise_line", list(RAISES))
def test_plan_raising_anything_is_one_line(runner: CliRunner, tmp_path: Path, raise_line: str) -> None:
    pol = policy_file(tmp_path, PRELUDE + PLAN.format(body=raise_line))
    one_error(runner.invoke(app, ["route", "--schedule-policy", str(pol), "--out", str(tmp_path / "o")]),
              str(pol), RAISES[raise_line].replace("called sys.exit(0)", "sys.exit(0)"))


@pytest.mark.parametrize("raise_line", list(RAISES))
def test_loading_a_file_that_raises_anything_is_one_line(runner: CliRunner, tmp_path: Path, raise_line: str) -> None:
    pol = policy_file(tmp_path, PRELUDE + raise_line + "\n")
    expected = RAISES[raise_line].replace("raised ", "").replace("called sys.exit(0)", "SystemExit")
    one_error(runner.invoke(app, ["route", "--policy", str(pol), "--out", str(tmp_path / "o")]),
              f"{pol}:{PRELUDE.count(chr(10)) + 1}: policy file", "failed to load", expected)


@pytest.mark.parametrize("where", ["order", "import"])
def test_a_policy_that_changes_folder_does_not_move_the_outputs(runner: CliRunner, tmp_path: Path,
                                                                monkeypatch: pytest.MonkeyPatch, where: str) -> None:
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    chdir = f"import os\nos.chdir({str(elsewhere)!r})"
    text = (ORDER.format(body=chdir.replace("\n", "\n    ")) if where == "order"
            else chdir + "\n" + ORDER.format(body="pass"))
    pol = policy_file(tmp_path, text)
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    result = runner.invoke(app, ["route", "--policy", str(pol), "--out", "rel", "--quiet"])
    assert result.exit_code == 0, result.output
    assert result.output.strip().endswith("-> rel")
    assert sorted(p.name for p in (work / "rel").iterdir()) == ["demo.drc.rpt", "demo.metrics.json", "demo.routed.def"]
    assert list(elsewhere.iterdir()) == [] and Path.cwd() == work


@pytest.mark.parametrize("where", ["import", "order"])
def test_a_thread_left_running_does_not_keep_the_process_alive(tmp_path: Path, where: str) -> None:
    start = "import threading, time\nthreading.Thread(target=time.sleep, args=(3600,), daemon=False).start()"
    text = (start + "\n" + ORDER.format(body="pass") if where == "import"
            else ORDER.format(body=start.replace("\n", "\n    ")))
    pol = policy_file(tmp_path, text)
    env = {**os.environ, "PYTHONIOENCODING": "ascii"}  # the terminal's encoding never crashes either
    proc = subprocess.run([sys.executable, "-m", "xroute", "route", "--policy", str(pol), "--out",
                           str(tmp_path / "o")], capture_output=True, text=True, timeout=300, env=env)
    assert proc.returncode == 0, proc.stderr
    assert "-> " in proc.stdout and "Traceback" not in proc.stderr
    assert (tmp_path / "o" / "demo.routed.def").is_file()


@pytest.mark.parametrize("where", ["import", "order"])
def test_a_thread_left_running_does_not_hang_a_batch(tmp_path: Path, where: str) -> None:
    """In a batch the policy runs in pool workers too: a thread it leaves running must not keep a
    worker (so the pool's shutdown, so the batch) alive. A hang is the subprocess timeout."""
    start = "import threading, time\nthreading.Thread(target=time.sleep, args=(3600,), daemon=False).start()"
    text = (start + "\n" + ORDER.format(body="pass") if where == "import"
            else ORDER.format(body=start.replace("\n", "\n    ")))
    pol = policy_file(tmp_path, text)
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [demo]\npolicies: [{pol}, heuristic]\n"
                     "settings:\n  - {name: one, iteration_count: 1}\n")
    out = tmp_path / "o"
    proc = subprocess.run([sys.executable, "-m", "xroute", "batch", str(batch), "--out", str(out), "--jobs", "2",
                           "--quiet"], capture_output=True, text=True, timeout=240)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    doc = json.loads((out / "summary.json").read_text())
    assert doc["counts"] == {"jobs": 2, "failed": 0, "errors": 0, "resumed": 0}
    assert [r["status"] for r in doc["jobs"]] == ["done", "done"]
    assert (out / "jobs" / "demo__pol__one" / "demo.routed.def").is_file()


def test_a_thread_that_fails_is_one_warning_line(tmp_path: Path) -> None:
    text = ("import threading\ndef boom():\n    raise ValueError('in a thread')\n"
            "threading.Thread(target=boom).start()\n" + ORDER.format(body="pass"))
    pol = policy_file(tmp_path, text)
    proc = subprocess.run([sys.executable, "-m", "xroute", "route", "--policy", str(pol), "--out", str(tmp_path / "o"),
                           "--quiet"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("warning: thread ") and "ValueError: in a thread" in lines[0]


@pytest.mark.parametrize("returned, message", [
    ("42", "plan() must return an IterationPlan, a dict or None, got int"),
    ("{'bogus': 1}", "plan() returned unknown key(s) bogus"),
    ("{'region_size': 10**9}", "iteration 0: region_size must be in 1.."),
])
def test_a_plan_that_is_no_plan_names_the_file_and_line(runner: CliRunner, tmp_path: Path, returned: str,
                                                         message: str) -> None:
    pol = policy_file(tmp_path, "import os\n" + PLAN.format(body=f"return {returned}"))
    one_error(runner.invoke(app, ["route", "--schedule-policy", str(pol), "--out", str(tmp_path / "o")]),
              f"{pol}:2: schedule policy 'pol'", message)


def test_an_order_that_is_no_permutation_names_the_file_and_line(runner: CliRunner, tmp_path: Path) -> None:
    pol = policy_file(tmp_path, "\n" + ORDER.format(body="return [0] * len(features)"))
    one_error(runner.invoke(app, ["route", "--policy", str(pol), "--out", str(tmp_path / "o")]),
              f"{pol}:2: net-order policy 'pol' returned index 0 twice")


@pytest.mark.slow
def test_a_policy_thread_that_keeps_changing_folder_does_not_move_a_batch(tmp_path: Path) -> None:
    """The thread starts when the batch loads the policy (before it routes) and calls os.chdir for
    as long as the process lives: the relative --out is the folder the batch was started in."""
    work, elsewhere = tmp_path / "work", tmp_path / "elsewhere"
    work.mkdir()
    elsewhere.mkdir()
    text = (f"import os, threading\nthreading.Thread(target=lambda: [os.chdir({str(elsewhere)!r}) for _ in iter(int, 1)],"
            " daemon=True).start()\n" + ORDER.format(body="pass"))
    pol = policy_file(tmp_path, text)
    (tmp_path / "b.yaml").write_text(f"testcases: [demo]\npolicies: [{pol}]\nsettings:\n  - {{name: one, iteration_count: 1}}\n")
    proc = subprocess.run([sys.executable, "-m", "xroute", "batch", str(tmp_path / "b.yaml"), "--out", "out", "--quiet"],
                          capture_output=True, text=True, timeout=240, cwd=work)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert (work / "out" / "summary.json").is_file() and (work / "out" / "jobs" / "demo__pol__one").is_dir()
    assert list(elsewhere.iterdir()) == []
