"""``xroute batch`` without the terminal: plan the jobs of a matrix, run them, resume.

Layout of the output folder ``OUT``::

    OUT/jobs/<job id>/            one folder per finished job: <design>.routed.def, .metrics.json,
                                  .drc.rpt and job.json (the job's record)
    OUT/jobs/.<job id>.tmp-<pid>  a job being run (renamed into place when complete)
    OUT/summary.{json,csv,md}, OUT/junit.xml   one set, summary.json its manifest
                                  (see :mod:`xroute.cli.batch_summary`)

A job writes everything into its temporary folder (locked while the job runs) and renames it to
``jobs/<job id>`` as its last step, so an interrupted batch leaves no partial job folder; the
next run removes the temporary folders whose lock is free, whatever the process id in their name
(:func:`xroute.atomic_files.owner_gone`). On Linux the worker processes end with the batch
process, even when it is killed, so none of them goes on writing into a folder a rerun cleans. A job whose folder holds a ``job.json`` with status ``done`` and the
same fingerprint (testcase, settings, policy file content) is skipped. The summary files are
published as one set (:mod:`xroute.output_set`): a batch killed between their renames leaves a
staging folder that the next batch finishes or undoes first, so the folder holds the old set or
the new one.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import signal
import sys
import time
from collections import Counter
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from xroute.cli.batch_config import BatchConfig
from xroute.config import CostSection, RunSettings, run_settings
from xroute.cli.runs import policy_label

JOB_RECORD = "job.json"
JOB_FORMAT = 1


@dataclass(frozen=True)
class Job:
    """One cell of the matrix."""

    id: str  # testcase__policy__settings (names folders)
    testcase: str
    policy_label: str  # the policy's short name in ids and tables
    settings_name: str
    run: RunSettings
    cost: CostSection

    def fingerprint(self) -> str:
        """What decides the job's result: testcase, settings, and the policy file's content."""
        h = hashlib.sha1(json.dumps([self.testcase, self.run.to_dict()], sort_keys=True).encode())
        p = Path(self.run.policy)
        if p.is_file():
            h.update(p.read_bytes())
        return h.hexdigest()[:16]


def plan_jobs(cfg: BatchConfig) -> list[Job]:
    """The jobs of the matrix, testcase-major, in the file's order."""
    b = cfg.batch
    entries = b.settings or ()
    jobs: list[Job] = []
    for testcase in b.testcases:
        for policy in b.policies:
            label = policy_label(policy)
            for entry in entries or (None,):
                steps = entry.iteration_schedule if entry else None  # None: the base config's; []: none
                base = run_settings(
                    cfg.base,
                    region_size=entry.region_size if entry else None,
                    iterations=entry.iteration_count if entry else None,
                    threads=entry.thread_count if entry else None,
                    policy=policy,
                    seed=entry.seed if entry else None,
                    schedule=None if steps is None else tuple((e.region_size, e.offset) for e in steps),
                )
                name = entry.name if entry else "default"
                jobs.append(Job(f"{testcase}__{label}__{name}", testcase, label, name, base, cfg.base.cost))
    ids = [j.id for j in jobs]
    dupes = sorted(i for i, n in Counter(ids).items() if n > 1)  # linear: a 300 x 300 matrix is instant
    if dupes:
        from xroute.config_schema import ConfigError

        raise ConfigError(f"two jobs would share the id {dupes[0]} (policies with the same file name?)", cfg.path, 0)
    return jobs



def job_dir(out_root: Path, job: Job) -> Path:
    return out_root / "jobs" / job.id


def completed_record(out_root: Path, job: Job) -> dict[str, Any] | None:
    """The record of a finished job with the same fingerprint, or None."""
    from xroute.json_files import read_json

    path = job_dir(out_root, job) / JOB_RECORD
    if not path.exists():
        return None
    try:
        record = read_json(path, "job record")
    except ValueError:  # InputError: unreadable, not JSON, nested too deep: the job runs again
        return None
    if not isinstance(record, dict):
        return None
    if record.get("status") == "done" and record.get("fingerprint") == job.fingerprint():
        return record
    return None


def clean_stale_job_folders(out_root: Path) -> list[Path]:
    """Removes temporary job folders whose job has ended (an interrupted batch): their lock is free."""
    from xroute.atomic_files import owner_gone

    removed = []
    jobs = out_root / "jobs"
    if not jobs.is_dir():
        return removed
    for p in jobs.iterdir():
        pid_text = p.name.rpartition(".tmp-")[2]
        if p.name.startswith(".") and ".tmp-" in p.name and p.is_dir() and not p.is_symlink():
            if owner_gone(p, int(pid_text) if pid_text.isdigit() else None):
                shutil.rmtree(p, ignore_errors=True)
                removed.append(p)
    return removed


def run_job(job: Job, out_root: str, events: Any = None) -> dict[str, Any]:
    """Runs one job in this process and returns its record (status done, or error with the message).

    ``events``: a queue receiving progress tuples ``(job id, iteration, regions done, regions total,
    violations or None, iteration done, line)``; None for no progress.
    """
    from xroute.cli.console import error_line
    from xroute.errors import XrouteError
    from xroute.atomic_files import atomic_write_text, open_locked_folder, replace
    from xroute.cli.progress import iteration_line
    from xroute.cli.runs import route_testcase, run_summary

    root = Path(out_root)
    final = job_dir(root, job)
    tmp = root / "jobs" / f".{job.id}.tmp-{os.getpid()}"
    shutil.rmtree(tmp, ignore_errors=True)
    tmp.mkdir(parents=True)
    lock = open_locked_folder(tmp)  # in use until this job ends (clean_stale_job_folders)
    record: dict[str, Any] = {
        "format": JOB_FORMAT,
        "id": job.id,
        "testcase": job.testcase,
        "policy": job.policy_label,
        "policy_spec": job.run.policy,
        "settings_name": job.settings_name,
        "settings": job.run.to_dict(),
        "fingerprint": job.fingerprint(),
        "run_dir": str(final),
    }

    def progress(ev: Any) -> None:
        if events is not None:
            r = ev.report
            events.put((job.id, r.iteration, ev.regions_done, ev.regions_total,
                        r.violations if ev.iteration_done else None, ev.iteration_done,
                        iteration_line(ev) if ev.iteration_done else ""))

    started = time.perf_counter()
    try:
        outputs = route_testcase(job.testcase, job.run, tmp, progress=progress)
        metrics = dict(outputs.metrics)  # name the final folder, not the temporary one
        metrics["outputs"] = {k: str(final / Path(v).name) for k, v in metrics["outputs"].items()}
        atomic_write_text(outputs.metrics_path, json.dumps(metrics, indent=2) + "\n")
        record.update(status="done", seconds=time.perf_counter() - started, summary=run_summary(outputs, job.cost))
        record["summary"]["out_dir"] = str(final)
        record["summary"]["metrics"] = str(final / outputs.metrics_path.name)
        atomic_write_text(tmp / JOB_RECORD, json.dumps(record, indent=2) + "\n")
        if final.exists():
            shutil.rmtree(final)  # an outdated result (other fingerprint)
        replace(tmp, final)
    except (XrouteError, OSError) as exc:
        shutil.rmtree(tmp, ignore_errors=True)
        message = error_line(exc)[len("error: "):].replace(str(tmp), str(final))  # the folder the user will look in
        record.update(status="error", seconds=time.perf_counter() - started, message=message)
    except Exception as exc:
        from xroute.policy_guard import policy_failure_line

        shutil.rmtree(tmp, ignore_errors=True)
        if (line := policy_failure_line(exc)) is None:
            raise
        record.update(status="error", seconds=time.perf_counter() - started, message=line)  # the user's policy raised
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    finally:
        os.close(lock)
    return record


def end_with_parent(parent: int) -> None:
    """Pool worker initializer: on Linux the kernel kills the worker when the batch process ends,
    however it ends (``PR_SET_PDEATHSIG``), so a killed batch leaves no worker behind; and a
    thread a user's policy left running does not keep the worker alive at the pool's shutdown
    (:func:`end_despite_threads`)."""
    import multiprocessing.util

    from xroute.policy_process import install_exit_guard, real_exit

    install_exit_guard()  # os._exit in a policy's order(): the job's error, not a silent end
    # Run when the worker's loop has returned (every result sent), before the process waits for its
    # threads; the lowest priority, so after the other exit finalizers.
    multiprocessing.util.Finalize(None, end_despite_threads, exitpriority=-100)
    if sys.platform.startswith("linux"):
        import ctypes

        try:
            ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGKILL))  # 1: PR_SET_PDEATHSIG
        except (OSError, AttributeError):
            return
    if os.getppid() != parent:  # the batch ended before the signal was set up
        real_exit(1)


def end_despite_threads() -> None:
    """Ends a pool worker at once (``os._exit(0)``, streams flushed) when a thread that is neither
    a daemon nor the main thread is still running: a process waits for such threads before it
    exits, and the pool's shutdown waits for the process, so a policy's endless thread would hang
    the batch. The worker's results were all sent before this runs (as ``xroute route`` does,
    :func:`xroute.cli.app.finish`)."""
    from xroute.policy_guard import stray_threads
    from xroute.policy_process import real_exit

    if not stray_threads():
        return
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (ValueError, OSError):
            pass
    real_exit(0)


@dataclass
class BatchProgress:
    """Callbacks of :func:`run_local` (the command layer shows them)."""

    on_start: Callable[[Job], None] = lambda job: None
    on_event: Callable[[tuple], None] = lambda ev: None
    on_done: Callable[[Job, dict[str, Any]], None] = lambda job, rec: None


def run_local(jobs: list[Job], out_root: Path, workers: int, progress: BatchProgress) -> dict[str, dict[str, Any]]:
    """Runs ``jobs`` in ``workers`` processes; returns their records by job id.

    Progress events come back through a manager queue, drained here while waiting.
    """
    import multiprocessing as mp
    import queue as queue_mod

    records: dict[str, dict[str, Any]] = {}
    if not jobs:
        return records
    ctx = mp.get_context("spawn")  # no fork of a process that may hold threads
    with ctx.Manager() as manager, ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=end_with_parent,
                                                       initargs=(os.getpid(),)) as pool:
        events = manager.Queue()
        pending = {}
        for job in jobs:
            pending[pool.submit(run_job, job, str(out_root), events)] = job
        started: set[str] = set()
        while pending:
            done, _ = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
            while True:
                try:
                    ev = events.get_nowait()
                except queue_mod.Empty:
                    break
                if ev[0] not in started:
                    started.add(ev[0])
                    progress.on_start(next(j for j in jobs if j.id == ev[0]))
                progress.on_event(ev)
            for fut in done:
                job = pending.pop(fut)
                try:
                    records[job.id] = fut.result()
                except BrokenProcessPool:
                    from xroute.errors import XrouteError

                    raise XrouteError(f"a worker process ended abruptly (killed, or out of memory) during job {job.id}; "
                                      "the finished jobs are kept: run the batch again to resume") from None
                progress.on_done(job, records[job.id])
    return records
