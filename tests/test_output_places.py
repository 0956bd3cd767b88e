"""Where outputs go: ``~`` in a config's output folder is the home folder (as the shell makes it
on the command line)."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import make_runner
from xroute.cli.app import app

BATCH = "testcases: [demo]\nout_dir: ~/runs/b\nsettings:\n  - {name: one, iteration_count: 1}\n"


@pytest.fixture
def home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A fresh home folder, and a fresh current folder beside it."""
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    (tmp_path / "cwd").mkdir()
    monkeypatch.chdir(tmp_path / "cwd")
    return home


def test_a_route_config_out_dir_under_home(home: Path, tmp_path: Path) -> None:
    from xroute.config import load_config

    config = tmp_path / "c.yaml"
    config.write_text("output:\n  out_dir: ~/runs/r\nrouter:\n  iteration_count: 1\n")
    assert load_config(config).output.out_dir == str(home / "runs" / "r")
    result = make_runner().invoke(app, ["route", "--config", str(config), "--quiet"])
    assert result.exit_code == 0, result.output
    assert (home / "runs" / "r" / "demo.routed.def").is_file()
    assert list(Path.cwd().iterdir()) == []  # no folder named '~'


def test_a_batch_out_dir_under_home(home: Path, tmp_path: Path) -> None:
    batch = tmp_path / "b.yaml"
    batch.write_text(BATCH)
    result = make_runner().invoke(app, ["batch", str(batch), "--quiet"], env={"CI": "true"})
    assert result.exit_code == 0, result.output
    assert (home / "runs" / "b" / "summary.json").is_file()
    assert list(Path.cwd().iterdir()) == []
