"""The Ray backend of ``xroute batch`` (optional extra ``ray``: ``pip install 'xroute[ray]'``).

Each job runs as a Ray task (one CPU each) with :func:`xroute.cli.batch.run_job`
(:mod:`xroute.ray_backend` starts Ray and ships the call); the workers must see the same
testcases and output folder (a shared file system on a cluster). Connects to ``address``
(``ray://host:10001`` or ``host:6379``) or, with None, starts a local Ray instance for the run and
shuts it down afterwards.
"""

from __future__ import annotations

import pickle
from pathlib import Path
from typing import Any

from xroute.cli.batch import BatchProgress, Job
from xroute.ray_backend import call_by_name, package_root, start


def run_ray(jobs: list[Job], out_root: Path, workers: int, progress: BatchProgress,
            address: str | None) -> dict[str, dict[str, Any]]:
    records: dict[str, dict[str, Any]] = {}
    if not jobs:
        return records
    started_here = start(workers, address)
    import ray

    try:
        task = ray.remote(num_cpus=1)(call_by_name(package_root(address)))
        out = str(out_root.resolve())
        refs = {task.remote("xroute.cli.batch", "run_job", pickle.dumps((job, out))): job for job in jobs}
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
