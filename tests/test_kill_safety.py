"""Kill safety: ``route``, ``check`` and ``batch`` (its jobs and its summary) killed (SIGKILL) just
before each rename that publishes their outputs leave, after the next run's clean-up, a
consistent set (its files' SHA-256 agree with its manifest) or the previous one; ``report`` warns about a mixed set meanwhile; the
next run removes every leftover, whatever the process id in its name.

The kill comes from the test hook ``XROUTE_TEST_KILL_AT=N`` (the process kills itself just before
its N-th rename, :mod:`xroute.atomic_files`): the same moments on every run, no timing.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

from xroute.atomic_files import KILL_AT_VARIABLE
from xroute.cli.app import app
from xroute.output_set import NOTE, STAGE_PREFIX, file_sha256
from xroute.outputs import clean_stale_temporaries

# Slow set: kills routes and batches at each rename (many child processes).
pytestmark = pytest.mark.slow

ROUTE_RENAMES = 5  # staged metrics JSON, the publishing note, then DEF, DRC report, metrics JSON into place
CHECK_RENAMES = 6  # staged marker database and check JSON, the note, then DRC report, lyrdb, check JSON
BATCH_RENAMES = 8  # in the worker: the route's 5, the job's metrics JSON and job.json, the job folder
SUMMARY_RENAMES = 9  # in the batch process: 4 staged summary files, the note, then the 4 into place
SUMMARY_FILES = ("summary.csv", "summary.md", "junit.xml", "summary.json")  # publishing order


def xroute(args: list[str], kill_at: int | None = None, cwd: Path | None = None) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != KILL_AT_VARIABLE}
    if kill_at is not None:
        env[KILL_AT_VARIABLE] = str(kill_at)
    return subprocess.run([sys.executable, "-m", "xroute", *args], capture_output=True, text=True, env=env,
                          cwd=cwd, timeout=300)


def leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def route_set_state(out: Path) -> str:
    """"consistent" when the metrics JSON's hashes match the DEF and DRC report, else "mixed"."""
    run = json.loads((out / "demo.metrics.json").read_text())["run"]
    same = (run["sha256"]["def"] == file_sha256(out / "demo.routed.def")
            and run["sha256"]["drc_report"] == file_sha256(out / "demo.drc.rpt"))
    return "consistent" if same else "mixed"


@pytest.mark.parametrize("at", range(1, ROUTE_RENAMES + 2))
def test_route_killed_at_each_rename(runner: CliRunner, tmp_path: Path, at: int) -> None:
    out = tmp_path / "out"
    assert runner.invoke(app, ["route", "--out", str(out), "--quiet"]).exit_code == 0  # the previous set
    before = file_sha256(out / "demo.metrics.json")
    # One iteration at region size 1 leaves markers: its DRC report differs from the clean previous
    # set's (an identical file would already count as placed, and the cleaner would finish the set).
    proc = xroute(["route", "--out", str(out), "--quiet", "--policy", "random", "--iterations", "1",
                   "--region-size", "1"], kill_at=at)
    if at > ROUTE_RENAMES:  # the count above is every rename of the run
        assert proc.returncode in (0, 1), proc.stderr
        assert leftovers(out) == [] and route_set_state(out) == "consistent"
        return
    assert proc.returncode == -signal.SIGKILL, proc.stderr
    state = route_set_state(out)
    report = runner.invoke(app, ["report", str(out), "--out", str(tmp_path / "r.html")])
    assert report.exit_code == 0, report.output
    warnings = report.stderr.strip().splitlines()
    if state == "mixed":  # killed between the DEF and the metrics: said in one line
        assert len(warnings) == 1 and warnings[0].startswith(f"warning: {out / 'demo.metrics.json'}: "), warnings
    else:
        assert warnings == []
    assert leftovers(out)  # the killed run's staging folder (its process id is gone now)
    clean_stale_temporaries(out)  # what the next run does first: finishes or undoes the publish
    assert leftovers(out) == [] and route_set_state(out) == "consistent"
    assert sorted(p.name for p in out.iterdir()) == ["demo.drc.rpt", "demo.metrics.json", "demo.routed.def"]
    if at <= 3:  # killed before the first file moved: the previous set, untouched
        assert file_sha256(out / "demo.metrics.json") == before
    assert runner.invoke(app, ["route", "--out", str(out), "--quiet"]).exit_code == 0
    assert leftovers(out) == [] and route_set_state(out) == "consistent"


def check_set_state(out: Path) -> str:
    run = json.loads((out / "demo.check.json").read_text())["run"]
    same = (run["sha256"]["drc_report"] == file_sha256(out / "demo.drc.rpt")
            and run["sha256"]["lyrdb"] == file_sha256(out / "demo.lyrdb"))
    return "consistent" if same else "mixed"


@pytest.fixture(scope="module")
def two_routings(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """Two different routed DEFs of the demo, both named demo.routed.def."""
    from conftest import make_runner

    root = tmp_path_factory.mktemp("routed")
    for name, policy in (("a", "heuristic"), ("b", "random")):
        result = make_runner().invoke(app, ["route", "--out", str(root / name), "--quiet", "--policy", policy,
                                            "--iterations", "1"])
        assert result.exit_code in (0, 1), result.output
    return root / "a" / "demo.routed.def", root / "b" / "demo.routed.def"


@pytest.mark.parametrize("at", range(1, CHECK_RENAMES + 2))
def test_check_killed_at_each_rename(runner: CliRunner, tmp_path: Path, two_routings: tuple[Path, Path],
                                     at: int) -> None:
    first, second = two_routings
    out = tmp_path / "check"
    assert runner.invoke(app, ["check", "demo", "--def", str(first), "--out", str(out), "--quiet"]).exit_code in (0, 1)
    assert check_set_state(out) == "consistent"
    proc = xroute(["check", "demo", "--def", str(second), "--out", str(out), "--quiet"], kill_at=at)
    if at > CHECK_RENAMES:
        assert proc.returncode in (0, 1), proc.stderr
        assert leftovers(out) == [] and check_set_state(out) == "consistent"
        return
    assert proc.returncode == -signal.SIGKILL, proc.stderr
    assert leftovers(out)
    result = runner.invoke(app, ["check", "demo", "--def", str(first), "--out", str(out), "--quiet"])  # cleans first
    assert result.exit_code in (0, 1), result.output
    assert leftovers(out) == [] and check_set_state(out) == "consistent"
    assert sorted(p.name for p in out.iterdir()) == ["demo.check.json", "demo.drc.rpt", "demo.lyrdb"]


def test_batch_killed_at_each_rename_of_its_job(tmp_path: Path) -> None:
    batch = tmp_path / "b.yaml"
    batch.write_text("testcases: [demo]\nsettings:\n  - {name: one, iteration_count: 1}\n")
    out = tmp_path / "out"
    job = out / "jobs" / "demo__heuristic__one"
    for at in range(1, BATCH_RENAMES + 1):  # one killed run after another in the same folder
        proc = xroute(["batch", str(batch), "--out", str(out), "--quiet", "--jobs", "1", "--force"], kill_at=at)
        lines = proc.stderr.strip().splitlines()
        assert proc.returncode == 2 and len(lines) == 1 and "worker process ended abruptly" in lines[0], proc.stderr
        assert "Traceback" not in proc.stderr
        if job.exists():  # a job folder is only ever whole
            assert json.loads((job / "job.json").read_text())["status"] == "done"
            assert route_set_state(job) == "consistent"
    assert leftovers(out / "jobs")  # the killed job's temporary folder
    proc = xroute(["batch", str(batch), "--out", str(out), "--quiet", "--jobs", "1", "--force"])
    assert proc.returncode == 0, proc.stderr
    assert leftovers(out / "jobs") == [] and leftovers(job) == []
    assert route_set_state(job) == "consistent"


def summary_state(out: Path) -> str:
    """"consistent" when summary.json's hashes match the other three summary files, else "mixed"."""
    run = json.loads((out / "summary.json").read_text())["run"]
    same = all(run["sha256"][role] == file_sha256(out / name)
               for role, name in (("csv", "summary.csv"), ("md", "summary.md"), ("junit", "junit.xml")))
    return "consistent" if same else "mixed"


def test_batch_killed_at_each_rename_of_its_summary(tmp_path: Path) -> None:
    """The batch process itself killed before each rename of its summary: the job is resumed
    (no worker runs), so the process's renames are the summary's alone."""
    batch = tmp_path / "b.yaml"
    batch.write_text("testcases: [demo]\nsettings:\n  - {name: one, iteration_count: 1}\n")
    out = tmp_path / "out"
    args = ["batch", str(batch), "--out", str(out), "--quiet", "--jobs", "1"]
    assert xroute(args).returncode == 0
    for at in range(1, SUMMARY_RENAMES + 2):  # one killed run after another in the same folder
        before = {name: file_sha256(out / name) for name in SUMMARY_FILES}
        proc = xroute(args, kill_at=at)
        if at > SUMMARY_RENAMES:  # the count above is every rename of the run
            assert proc.returncode == 0, proc.stderr
            assert leftovers(out) == [] and summary_state(out) == "consistent"
            break
        assert proc.returncode == -signal.SIGKILL, proc.stderr
        stages = [p for p in out.iterdir() if p.name.startswith(STAGE_PREFIX)]
        assert leftovers(out) == [stages[0].name]  # the killed run's staging folder, nothing else
        moved = max(0, at - (SUMMARY_RENAMES - len(SUMMARY_FILES)) - 1)  # files renamed into place before the kill
        if at > SUMMARY_RENAMES - len(SUMMARY_FILES):  # the note is written: each file is the old one or the new
            note = json.loads((stages[0] / NOTE).read_text())
            assert sorted(p.name for p in stages[0].iterdir()) == sorted([NOTE, *SUMMARY_FILES[moved:]])
            now = {name: file_sha256(out / name) for name in SUMMARY_FILES}
            assert all(now[name] == note["sha256"][name] for name in SUMMARY_FILES[:moved])  # the new ones
            assert all(now[name] == before[name] for name in SUMMARY_FILES[moved:])  # the old ones
        clean_stale_temporaries(out)  # what the next batch does first: finishes or undoes the publish
        assert leftovers(out) == [] and summary_state(out) == "consistent"
        assert sorted(p.name for p in out.iterdir()) == ["jobs", "junit.xml", "summary.csv", "summary.json",
                                                        "summary.md"]
        if not moved:  # killed before the first file moved: the previous set, untouched
            assert {name: file_sha256(out / name) for name in SUMMARY_FILES} == before
    proc = xroute(args)
    assert proc.returncode == 0, proc.stderr
    assert leftovers(out) == [] and summary_state(out) == "consistent"


def test_leftovers_go_whatever_their_process_id(tmp_path: Path) -> None:
    """A temporary whose lock is free is removed even when the id in its name is alive (pid 1: ids
    are reused), once it is older than an instant; one whose lock is held stays."""
    from xroute.atomic_files import LOCK_GRACE_SECONDS, open_locked_folder
    from xroute.cli.batch import clean_stale_job_folders

    out = tmp_path / "out"
    (out / "jobs").mkdir(parents=True)
    old = [out / ".xroute-stage.1.0000abcd", out / ".demo.metrics.json.1.0000abcd.tmp",
           out / "jobs" / ".demo__heuristic__one.tmp-1"]
    for p in old:
        p.mkdir() if not p.name.endswith(".tmp") else p.write_text("{")
    held = out / ".xroute-stage.1.0000beef"
    held.mkdir()
    fresh = out / ".xroute-stage.1.0000cafe"  # just made by a live process, not locked yet
    fresh.mkdir()
    stamp = os.stat(out).st_mtime - 10 * LOCK_GRACE_SECONDS
    for p in (*old, held):
        os.utime(p, (stamp, stamp))
    fd = open_locked_folder(held)
    try:
        removed = set(clean_stale_temporaries(out)) | set(clean_stale_job_folders(out))
    finally:
        os.close(fd)
    assert removed == set(old)
    assert held.exists() and fresh.exists()
