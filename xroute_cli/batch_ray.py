"""The Ray backend of ``xroute batch`` (optional extra ``ray``: ``pip install 'xroute[ray]'``).

Each job runs as a Ray task (one CPU each) with :func:`xroute.cli.batch.run_job`; the workers
must see the same testcases and output folder (a shared file system on a cluster). Connects
to ``address`` (``ray://host:10001`` or ``host:6379``) or, with None, starts a local Ray instance
for the run and shuts it down afterwards.
"""

from __future__ import annotations

import pickle
from pathlib import Path
from typing import Any, Callable

import xroute.cli
from xroute.cli.batch import BatchProgress, Job
from xroute.errors import XrouteError


def _job_runner(package_root: str | None) -> Callable[[bytes, str], dict[str, Any]]:
    """The Ray task body. A nested function, so Ray ships it by value: the worker imports nothing of
    xroute before it runs. With ``package_root`` (a local instance) the worker first puts the folder
    this driver imported xroute from at the front of ``sys.path``: local workers start in the
    driver's working directory, which may be a source checkout whose package has no compiled
    engine. The job travels pickled for the same reason (unpickling imports its classes)."""

    def run(job_bytes: bytes, out_root: str) -> dict[str, Any]:
        import pickle as _pickle
        import sys

        if package_root is not None and (not sys.path or sys.path[0] != package_root):
            sys.path.insert(0, package_root)
        from xroute.cli.batch import run_job

        return run_job(_pickle.loads(job_bytes), out_root)

    return run


def run_ray(jobs: list[Job], out_root: Path, workers: int, progress: BatchProgress,
            address: str | None) -> dict[str, dict[str, Any]]:
    try:
        import ray
    except ImportError as exc:
        raise XrouteError("the ray backend needs Ray: pip install 'xroute[ray]'") from exc
    records: dict[str, dict[str, Any]] = {}
    if not jobs:
        return records
    started_here = not ray.is_initialized()
    if started_here:
        try:
            if address:
                ray.init(address=address, log_to_driver=False)
            else:
                ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False)
        except Exception as exc:  # noqa: BLE001 - connection problems are user errors
            raise XrouteError(f"cannot start or reach Ray{' at ' + address if address else ''}: {exc}") from exc
    try:
        # On a cluster the workers use their own installed xroute; locally, the driver's.
        package_root = None if address else str(Path(xroute.cli.__file__).resolve().parent.parent)
        task = ray.remote(num_cpus=1)(_job_runner(package_root))
        refs = {task.remote(pickle.dumps(job), str(out_root.resolve())): job for job in jobs}
        for job in jobs:
            progress.on_start(job)
        while refs:
            done, _ = ray.wait(list(refs), num_returns=1)
            for ref in done:
                job = refs.pop(ref)
                records[job.id] = ray.get(ref)
                progress.on_done(job, records[job.id])
    finally:
        if started_here:
            ray.shutdown()
    return records
