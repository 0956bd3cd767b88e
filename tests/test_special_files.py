"""Special files as inputs and outputs, and file names that are not UTF-8.

A FIFO, device or folder where a regular file is read is one error line (never a run blocked on
the FIFO); one where a file would be written is refused and left as it was; a name holding bytes
that are not UTF-8 is one error line, not a TypeError from the engine.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest
from typer.testing import CliRunner

from xroute.cli.app import app
from xroute.errors import InputError
from xroute.regular_files import check_input, check_output, read_regular_bytes
from conftest import one_error

DEMO = Path(__file__).resolve().parents[1] / "testcases" / "data" / "demo"
NOT_UTF8 = os.fsdecode(b"out\xff")  # what the shell passes for a name with a stray byte


@pytest.fixture
def fifo(tmp_path: Path) -> Path:
    p = tmp_path / "pipe"
    os.mkfifo(p)
    return p


def still_fifo(p: Path) -> bool:
    return stat.S_ISFIFO(os.lstat(p).st_mode)


def demo_routed(runner: CliRunner, out: Path) -> Path:
    result = runner.invoke(app, ["route", "--quiet", "--out", str(out)])
    assert result.exit_code == 0, result.output
    return out


# ----------------------------------------------------------------------------- the helpers
def test_helpers_refuse_special_files(tmp_path: Path, fifo: Path) -> None:
    with pytest.raises(InputError, match="is a FIFO, not a regular file"):
        check_input(fifo)
    with pytest.raises(InputError, match="is a FIFO, not a regular file"):
        read_regular_bytes(fifo)  # returns at once: opened without blocking
    with pytest.raises(InputError, match="is a folder"):
        check_input(tmp_path)
    with pytest.raises(InputError, match="exists and is a FIFO: refusing to replace it"):
        check_output(fifo)
    with pytest.raises(InputError, match="is a character device"):
        check_output("/dev/null")
    with pytest.raises(InputError, match="is a folder"):
        check_output(tmp_path)
    (tmp_path / "f").write_text("x")
    os.symlink(tmp_path / "f", tmp_path / "link")
    assert check_output(tmp_path / "link") == tmp_path / "link"  # a link is replaced, not its target
    assert read_regular_bytes(tmp_path / "link") == b"x"


# ----------------------------------------------------------------------------- inputs
@pytest.mark.parametrize("args", [
    ["route", "--config", "{fifo}"],
    ["route", "--policy", "{fifo}.py"],
    ["route", "--schedule-policy", "{fifo}.py"],
    ["info", "--lef", "{fifo}", "--def", str(DEMO / "demo.def")],
    ["info", "--lef", str(DEMO / "demo.lef"), "--def", "{fifo}"],
    ["info", "--lef", str(DEMO / "demo.lef"), "--def", str(DEMO / "demo.def"), "--guide", "{fifo}"],
])
def test_a_fifo_as_an_input_is_one_line(runner: CliRunner, tmp_path: Path, fifo: Path, args: list[str]) -> None:
    os.mkfifo(f"{fifo}.py")
    argv = [a.format(fifo=fifo) for a in args] + (["--out", str(tmp_path / "o")] if args[0] == "route" else [])
    line = one_error(runner.invoke(app, argv), "FIFO")
    assert str(fifo) in line
    assert not (tmp_path / "o").exists()


def test_a_fifo_as_a_batch_baseline_is_one_line(runner: CliRunner, tmp_path: Path, fifo: Path) -> None:
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [demo]\npolicies: [heuristic]\ngates:\n  baseline: {fifo}\n")
    one_error(runner.invoke(app, ["batch", str(batch), "--out", str(tmp_path / "o")]), "b.yaml:4", "not a regular file")


# ----------------------------------------------------------------------------- outputs
def test_report_never_replaces_a_fifo_or_a_device(runner: CliRunner, tmp_path: Path, fifo: Path) -> None:
    runs = demo_routed(runner, tmp_path / "run")
    one_error(runner.invoke(app, ["report", str(runs), "--out", str(fifo)]), str(fifo), "FIFO")
    assert still_fifo(fifo)
    one_error(runner.invoke(app, ["report", str(runs), "--out", "/dev/null"]), "/dev/null", "character device")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    one_error(runner.invoke(app, ["report", str(runs), "--out", str(tmp_path)]), "is a folder")


def test_global_route_never_replaces_a_fifo(runner: CliRunner, fifo: Path) -> None:
    one_error(runner.invoke(app, ["global-route", "demo", "--out", str(fifo)]), str(fifo), "FIFO")
    assert still_fifo(fifo)


def test_batch_write_baseline_never_replaces_a_fifo(runner: CliRunner, tmp_path: Path, fifo: Path) -> None:
    batch = tmp_path / "b.yaml"
    batch.write_text("testcases: [demo]\npolicies: [heuristic]\n")
    one_error(runner.invoke(app, ["batch", str(batch), "--out", str(tmp_path / "o"), "--write-baseline", str(fifo)]),
              str(fifo), "FIFO")
    assert still_fifo(fifo) and not (tmp_path / "o").exists()  # refused before any job ran


def test_route_never_replaces_a_fifo_among_its_outputs(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "o"
    out.mkdir()
    os.mkfifo(out / "demo.metrics.json")
    one_error(runner.invoke(app, ["route", "--out", str(out)]), "demo.metrics.json", "FIFO")
    assert still_fifo(out / "demo.metrics.json")
    assert sorted(p.name for p in out.iterdir()) == ["demo.metrics.json"]  # nothing else written
    one_error(runner.invoke(app, ["route", "--out", str(out / "demo.metrics.json")]), "not a folder")


# ----------------------------------------------------------------------------- names that are not UTF-8
@pytest.mark.parametrize("args", [
    ["route", "--out", "{bad}"],
    ["route", "--config", "{bad}.yaml"],
    ["info", "--lef", "{bad}.lef", "--def", str(DEMO / "demo.def")],
    ["report", str(DEMO), "--out", "{bad}.html"],
    ["global-route", "demo", "--out", "{bad}.guide"],
])
def test_a_name_that_is_not_utf8_is_one_line(runner: CliRunner, tmp_path: Path, args: list[str]) -> None:
    bad = os.path.join(str(tmp_path), NOT_UTF8)
    result = runner.invoke(app, [a.format(bad=bad) for a in args])
    line = one_error(result)
    assert "\\xff" in line or "not found" in line or "no *.metrics.json" in line
    assert os.listdir(tmp_path) == []


def test_an_ascii_terminal_never_crashes_the_command(tmp_path: Path) -> None:
    import subprocess
    import sys

    env = {**os.environ, "PYTHONIOENCODING": "ascii"}
    proc = subprocess.run([sys.executable, "-m", "xroute", "info", "demo"], capture_output=True, text=True,
                          env=env, timeout=300)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    assert "\\xb5m" in proc.stdout  # the micro sign, escaped
