"""What a policy does to the process around it (xroute.policy_process), seen from outside: each test
runs ``python -m xroute route`` as its own process on the demo, as a user or a CI job would.

A policy that calls ``os._exit`` ends the run with one error line naming its file and line and
status 2, never 0; one that closes stdout and stderr inside a call closes them for that call only;
its prints (C-level writes to file descriptor 1 included) go to stderr, so ``--json`` is JSON; a
child it forks from an engine worker thread does not come back into the run ("Fatal Python error"
spam).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ORDER = "import os, sys, threading\ndef order(region, features):\n    {body}\n    return list(range(len(features)))\n"


def route(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "CI": "true"}
    return subprocess.run([sys.executable, "-m", "xroute", "route", "--out", str(tmp_path / "o"), *args],
                          capture_output=True, text=True, timeout=300, env=env, cwd=tmp_path)


def policy(tmp_path: Path, text: str, name: str = "pol.py") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def only_error(proc: subprocess.CompletedProcess) -> str:
    """The one stderr line of a run that failed with status 2 and wrote no routed DEF."""
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    return lines[0]


@pytest.mark.parametrize("where, method", [("order", "order"), ("plan", "plan")])
def test_os_exit_inside_a_policy_is_an_error_naming_the_line(tmp_path: Path, where: str, method: str) -> None:
    if where == "order":
        pol = policy(tmp_path, ORDER.format(body="os._exit(0)"))
        proc = route(tmp_path, "--policy", str(pol), "--quiet", "--iterations", "1")
    else:
        pol = policy(tmp_path, "import os\ndef plan(history, rule):\n    os._exit(0)\n")
        proc = route(tmp_path, "--schedule-policy", str(pol), "--quiet", "--iterations", "1")
    assert only_error(proc) == (f"error: {pol}:3: policy 'pol' called os._exit(0) inside {method}(): a policy cannot "
                                "end the run")
    assert not (tmp_path / "o" / "demo.routed.def").exists()


def test_os_exit_from_a_policys_thread_is_an_error_not_a_success(tmp_path: Path) -> None:
    body = "threading.Thread(target=os._exit, args=(0,)).start(); threading.Event().wait(30)"
    pol = policy(tmp_path, ORDER.format(body=body))
    line = only_error(route(tmp_path, "--policy", str(pol), "--quiet", "--iterations", "1"))
    assert line.startswith(f"error: {pol}: os._exit(0) called before xroute finished") and "did not finish" in line


def test_a_policy_that_closes_stdout_and_stderr_closes_them_for_its_call_only(tmp_path: Path) -> None:
    pol = policy(tmp_path, ORDER.format(body="os.close(1); os.close(2); sys.stdout.close()"))
    proc = route(tmp_path, "--policy", str(pol), "--quiet", "--iterations", "1")
    assert proc.returncode == 0 and proc.stderr == "", proc.stderr
    assert proc.stdout.startswith("demo: routed: 317 nets") and (tmp_path / "o" / "demo.routed.def").is_file()


def test_streams_closed_by_a_policys_thread_give_a_message_and_status_2(tmp_path: Path) -> None:
    text = ("import os, threading, time\nthreading.Timer(0.01, lambda: (os.close(1), os.close(2))).start()\n"
            "def order(region, features):\n    time.sleep(0.05)\n    return list(range(len(features)))\n")
    line = only_error(route(tmp_path, "--policy", str(policy(tmp_path, text)), "--quiet", "--iterations", "1"))
    assert "closed during the run (by a policy?)" in line


def test_json_stays_json_whatever_the_policy_prints(tmp_path: Path) -> None:
    """Prints at import and in order(), a C-level write, libc's buffered puts, and a thread that
    goes on writing to descriptor 1 after the run."""
    text = ("import ctypes, os, threading, time\nprint('loaded')\n"
            "def chatter():\n    for _ in range(400):\n        os.write(1, b'{\\n'); time.sleep(0.005)\n"
            "threading.Thread(target=chatter, daemon=True).start()\n"
            "def order(region, features):\n    print('hello'); os.write(1, b'raw bytes\\n')\n"
            "    ctypes.CDLL(None).puts(b'from libc')\n"
            "    return list(range(len(features)))\n")
    proc = route(tmp_path, "--policy", str(policy(tmp_path, text)), "--json", "--iterations", "1")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["design"] == "demo"
    lines = proc.stderr.splitlines()
    # Each text is on stderr, though not always on a line of its own: print() writes "hello" and its
    # newline apart, and another call's flush or the chattering thread can come between them.
    assert lines[0] == "loaded" and all(text in proc.stderr for text in ("hello", "raw bytes", "from libc"))


def test_a_child_forked_in_a_worker_thread_does_not_run_on(tmp_path: Path) -> None:
    """Two threads and regions of 2 GCells: order() runs on the engine's worker threads; each call
    forks a child that returns from order() as its parent does."""
    pol = policy(tmp_path, ORDER.format(body="os.fork()"))
    proc = route(tmp_path, "--policy", str(pol), "--quiet", "--iterations", "2", "--threads", "2",
                 "--region-size", "2")
    assert proc.returncode == 0, proc.stderr
    assert "Fatal Python error" not in proc.stderr and proc.stderr == ""
    assert proc.stdout.count("demo: routed:") == 1  # the parent's line only
