"""Where outputs go and what a failed write says: ``~`` in a config's output folder is the home
folder (as the shell makes it on the command line), and a full disk names the file it could not
write while the folder keeps its previous set whole.

The full disk is simulated here: ``fsync`` (where a full disk also shows on some file systems)
fails with ENOSPC for the one file named; ``fuzz/hostile_cli.py`` fills a real tmpfs.
"""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest

from conftest import make_runner, one_error
from xroute.cli.app import app
from xroute.output_set import file_sha256

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


@pytest.fixture
def routed_once(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    """An output folder holding one routed set of the demo, and the SHA-256 of its files."""
    out = tmp_path / "o"
    assert make_runner().invoke(app, ["route", "--out", str(out), "--quiet", "--iterations", "1"]).exit_code == 0
    return out, {p.name: file_sha256(p) for p in out.iterdir()}


@pytest.mark.parametrize("nth, named", [(1, "demo.metrics.json"), (2, "")])
def test_a_full_disk_names_the_file_and_keeps_the_old_set(routed_once: tuple[Path, dict[str, str]],
                                                         monkeypatch: pytest.MonkeyPatch, nth: int, named: str) -> None:
    """The n-th flush of the run fails as on a full disk: the metrics JSON (1st), the note that
    publishes the set (2nd, named by the output folder)."""
    import xroute.atomic_files as atomic_files

    out, before = routed_once
    real_fsync, calls = os.fsync, []

    def fsync(fd: int) -> None:
        calls.append(fd)
        if len(calls) == nth:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        real_fsync(fd)

    monkeypatch.setattr(atomic_files.os, "fsync", fsync)
    result = make_runner().invoke(app, ["route", "--out", str(out), "--quiet", "--iterations", "2"])
    one_error(result, f"{out / named if named else out}: No space left on device")
    assert {p.name: file_sha256(p) for p in out.iterdir()} == before  # the old set, whole, nothing else


def test_an_engine_write_error_names_the_final_file(routed_once: tuple[Path, dict[str, str]],
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """The routed DEF (written by the engine into the staging folder) cannot be written: the error
    names the file it would have become, not the staging folder that is gone."""
    import xroute.output_set as output_set

    out, before = routed_once
    make_stage = output_set.make_stage

    def blocked_stage(out_dir: Path) -> Path:
        stage = make_stage(out_dir)
        (stage / "demo.routed.def").mkdir()  # what the DEF would replace: the engine refuses a folder
        return stage

    monkeypatch.setattr(output_set, "make_stage", blocked_stage)
    result = make_runner().invoke(app, ["route", "--out", str(out), "--quiet", "--iterations", "2"])
    one_error(result, f"{out / 'demo.routed.def'}: ")
    assert {p.name: file_sha256(p) for p in out.iterdir()} == before


def test_a_batch_job_that_cannot_write_names_its_final_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A job routes into a temporary folder beside its final one: its error names the final one."""
    import xroute.output_set as output_set
    from xroute.cli.batch import plan_jobs, run_job
    from xroute.cli.batch_config import load_batch_config

    batch = tmp_path / "b.yaml"
    batch.write_text(BATCH.replace("out_dir: ~/runs/b\n", ""))
    (job,) = plan_jobs(load_batch_config(batch))
    make_stage = output_set.make_stage

    def blocked_stage(out_dir: Path) -> Path:
        stage = make_stage(out_dir)
        (stage / "demo.routed.def").mkdir()
        return stage

    monkeypatch.setattr(output_set, "make_stage", blocked_stage)
    record = run_job(job, str(tmp_path / "out"))
    assert record["status"] == "error"
    assert record["message"] == f"{tmp_path / 'out' / 'jobs' / job.id / 'demo.routed.def'}: cannot write DEF: Is a directory"
