"""The one child-process runner (xroute.route_process): exit status, both streams, the kernel's
resource figures, the time limit and the route's metrics JSON."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from xroute.errors import InputError
from xroute.route_process import run_process, xroute_command


def python(code: str) -> list[str]:
    return [sys.executable, "-c", code]


def test_status_and_both_streams_come_back_whole() -> None:
    # More than a pipe holds on each stream: a runner reading one pipe after the other would wait forever.
    run = run_process(python("import sys; sys.stdout.write('o' * 200_000); sys.stderr.write('e' * 200_000 + "
                             "'\\nlast words\\n'); sys.exit(3)"))
    assert run.returncode == 3 and not run.stopped
    assert run.stdout == "o" * 200_000 and run.stderr.startswith("e" * 200_000)
    assert run.last_line == "last words"
    assert run.metrics is None


def test_the_kernel_figures_are_the_childs() -> None:
    run = run_process(python("b = bytearray(200 * 2**20); sum(range(3_000_000))"))
    assert run.returncode == 0
    assert run.peak_rss_mb >= 200  # the child's 200 MB, not this process's
    assert run.cpu_s > 0 and run.wall_s > 0


def test_a_child_past_its_time_limit_is_killed() -> None:
    run = run_process(python("import time; time.sleep(60)"), timeout=0.5)
    assert run.stopped and run.returncode == -9 and run.last_line == "stopped at its time limit"
    busy = run_process(python("while True: pass"), cpu_limit=0.5)  # CPU seconds, not wall
    assert busy.stopped and busy.returncode == -9 and busy.cpu_s >= 0.5
    assert not run_process(python("pass"), cpu_limit=60).stopped


def test_the_environment_is_added_to(tmp_path: Path) -> None:
    run = run_process(python("import os; print(os.environ['XROUTE_PROBE'], 'PATH' in os.environ)"),
                      env={"XROUTE_PROBE": "seen"})
    assert run.stdout.split() == ["seen", "True"]


def test_the_metrics_json_of_the_folder_is_read(tmp_path: Path) -> None:
    (tmp_path / "d.metrics.json").write_text(json.dumps({"final": {"violations": 0}}))
    assert run_process(python("pass"), metrics_dir=tmp_path).metrics == {"final": {"violations": 0}}
    assert run_process(python("pass"), metrics_dir=tmp_path / "missing").metrics is None
    (tmp_path / "d.metrics.json").write_text("{")
    with pytest.raises(InputError, match="d.metrics.json"):
        run_process(python("pass"), metrics_dir=tmp_path)


def test_a_route_in_a_child(tmp_path: Path) -> None:
    run = run_process(xroute_command("route", "--quiet", "--iterations", "1", "--out", str(tmp_path)),
                      env={"CI": "true"}, metrics_dir=tmp_path)
    assert run.returncode == 0, run.last_line
    assert run.metrics["design"] == "demo" and run.metrics["settings"]["iterations"] == 1
