"""Routing orders on a Ray cluster (or a local Ray instance): the teacher's shards and fine-tuning's routings.

:func:`ray_map` runs the teacher's shards (:func:`xroute.policies.rl.teacher.collect` with
``backend="ray"``) as Ray tasks: each loads its design and routes its own first pass.

:class:`RayPool` is an :class:`concurrent.futures.Executor` whose ``map`` runs module-level job
functions of :mod:`~xroute.policies.rl.finetune` (``_regions_job``, ``_route_job``) on ``workers``
Ray actors. Each actor routes the first pass of every testcase once when it starts, as a worker
process of the local pool does, and keeps it; jobs go to the actors in turn and the results come
back in the jobs' order, so a run gives the same numbers on Ray as in local processes. The actors
must see the same testcases (a shared file system, or the ``XROUTE_TESTCASES`` folder on each node).

Starting Ray and shipping the calls: :mod:`xroute.ray_backend`. ``address`` None starts a local
instance for the run and stops it afterwards; otherwise the run joins that cluster and leaves it
running. Needs the ``ray`` extra (``pip install 'xroute[ray]'``).
"""

from __future__ import annotations

import pickle
from collections.abc import Callable, Iterable
from concurrent.futures import Executor
from typing import Any

from xroute.ray_backend import call_by_name, package_root, start

_FINETUNE = "xroute.policies.rl.finetune"


def ray_map(fn: Callable[[Any], Any], jobs: list[Any], workers: int, address: str | None = None) -> list[Any]:
    """``[fn(job) for job in jobs]`` as Ray tasks of one CPU each (``fn`` a module-level function), in the
    jobs' order."""
    import ray

    started = start(workers, address)
    try:
        task = ray.remote(num_cpus=1)(call_by_name(package_root(address)))
        return ray.get([task.remote(fn.__module__, fn.__name__, pickle.dumps((job,))) for job in jobs])
    finally:
        if started:
            ray.shutdown()


def _actor_class(call: Callable[[str, str, bytes], Any]) -> type:
    """The actor (defined in a function so that Ray ships it, and ``call``, by value)."""

    class RouteActor:
        def __init__(self, testcases: list[str], region_size: int) -> None:
            call(_FINETUNE, "_init_worker", pickle.dumps((testcases, region_size)))

        def run(self, name: str, job: Any) -> Any:
            return call(_FINETUNE, name, pickle.dumps((job,)))

    return RouteActor


class RayPool(Executor):
    """``workers`` Ray actors that each hold the first passes of ``testcases`` (see the module docstring)."""

    def __init__(self, testcases: list[str], region_size: int, workers: int, address: str | None = None) -> None:
        self._started_here = start(workers, address)
        import ray

        self._ray = ray
        actor = ray.remote(num_cpus=1)(_actor_class(call_by_name(package_root(address))))
        self._actors = [actor.remote(list(testcases), int(region_size)) for _ in range(max(1, workers))]

    def map(self, fn: Callable, *iterables: Iterable, timeout: Any = None, chunksize: int = 1) -> list:  # noqa: ARG002
        jobs = list(zip(*iterables))
        if any(len(args) != 1 for args in jobs):
            raise TypeError("RayPool.map takes one iterable of jobs")
        refs = [self._actors[i % len(self._actors)].run.remote(fn.__name__, args[0]) for i, args in enumerate(jobs)]
        return self._ray.get(refs)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:  # noqa: ARG002
        for a in self._actors:
            self._ray.kill(a)
        self._actors = []
        if self._started_here and self._ray.is_initialized():
            self._ray.shutdown()
