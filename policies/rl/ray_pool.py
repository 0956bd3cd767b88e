"""Routing orders on a Ray cluster (or a local Ray instance): the teacher's shards and fine-tuning's routings.

:func:`ray_map` runs the teacher's shards (:func:`xroute.policies.rl.teacher.collect` with
``backend="ray"``) as Ray tasks: each loads its design and routes its own first pass.

:class:`RayPool` is an :class:`concurrent.futures.Executor` whose ``map`` runs module-level job
functions of :mod:`~xroute.policies.rl.finetune` (``_regions_job``, ``_route_job``) on ``workers``
Ray actors. Each actor routes the first pass of every testcase once when it starts, as a worker
process of the local pool does, and keeps it; jobs go to the actors in turn and the results come
back in the jobs' order, so a run gives the same numbers on Ray as in local processes. The actors
must see the same testcases (a shared file system, or the ``XROUTE_TESTCASES`` folder on each node).

``address`` None starts a local Ray instance for the pool and stops it at ``shutdown``; otherwise
the pool connects to it (``ray://host:10001`` or ``host:6379``) and leaves the cluster running.
Needs the ``ray`` extra (``pip install 'xroute[ray]'``).
"""

from __future__ import annotations

from concurrent.futures import Executor
from pathlib import Path
from typing import Any, Callable, Iterable

from xroute.errors import XrouteError


def _start(workers: int, address: str | None) -> bool:
    """Connects to ``address`` or starts a local instance of ``workers`` CPUs (unless Ray is up already);
    True if this call started it."""
    try:
        import ray
    except ImportError as exc:
        raise XrouteError("routing on Ray needs Ray: pip install 'xroute[ray]'") from exc
    if ray.is_initialized():
        return False
    try:
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False)
    except Exception as exc:  # noqa: BLE001 - connection problems are user errors
        raise XrouteError(f"cannot start or reach Ray{' at ' + address if address else ''}: {exc}") from exc
    return True


def _package_root(address: str | None) -> str | None:
    """On a cluster the workers use their own installed xroute; locally, the driver's."""
    import xroute

    return None if address else str(Path(xroute.__file__).resolve().parent.parent)


def _task(package_root: str | None) -> Callable[[str, str, Any], Any]:
    """The body of a Ray task running ``module.name(job)`` (shipped by value, see :func:`_actor_class`)."""

    def run(module: str, name: str, job: Any) -> Any:
        import importlib
        import sys

        if package_root is not None and (not sys.path or sys.path[0] != package_root):
            sys.path.insert(0, package_root)
        return getattr(importlib.import_module(module), name)(job)

    return run


def ray_map(fn: Callable[[Any], Any], jobs: list[Any], workers: int, address: str | None = None) -> list[Any]:
    """``[fn(job) for job in jobs]`` as Ray tasks of one CPU each (``fn`` a module-level function), in the
    jobs' order; a local instance of ``workers`` CPUs when ``address`` is None (stopped afterwards)."""
    import ray

    started = _start(workers, address)
    try:
        task = ray.remote(num_cpus=1)(_task(_package_root(address)))
        return ray.get([task.remote(fn.__module__, fn.__name__, job) for job in jobs])
    finally:
        if started:
            ray.shutdown()


def _actor_class(package_root: str | None) -> type:
    """The actor, defined in a function so that Ray ships it by value. With ``package_root`` (a local
    instance) the actor first puts the folder the driver imported xroute from at the front of
    ``sys.path``: local workers start in the driver's working directory, which may be a source
    checkout without the compiled engine."""

    class RouteActor:
        def __init__(self, testcases: list[str], region_size: int) -> None:
            import sys

            if package_root is not None and (not sys.path or sys.path[0] != package_root):
                sys.path.insert(0, package_root)
            from xroute.policies.rl import finetune

            finetune._init_worker(testcases, region_size)
            self._module = finetune

        def run(self, name: str, job: Any) -> Any:
            return getattr(self._module, name)(job)

    return RouteActor


class RayPool(Executor):
    """``workers`` Ray actors that each hold the first passes of ``testcases`` (see the module docstring)."""

    def __init__(self, testcases: list[str], region_size: int, workers: int, address: str | None = None) -> None:
        self._started_here = _start(workers, address)
        import ray

        self._ray = ray
        actor = ray.remote(num_cpus=1)(_actor_class(_package_root(address)))
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
