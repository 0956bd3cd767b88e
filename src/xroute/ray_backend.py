"""Running xroute's work on Ray (the optional ``ray`` extra: ``pip install 'xroute[ray]'``).

One place for what every Ray user here needs: :func:`start` connects to a cluster (``address``:
``ray://host:10001`` or ``host:6379``) or starts a local instance, and turns failures into one-line
:class:`~xroute.errors.XrouteError`; :func:`call_by_name` is the body of a task (or an actor's
method) that imports a module on the worker and calls one of its functions. Arguments travel
pickled and the body is shipped by value, so a worker imports nothing of xroute before it runs;
with :func:`package_root` (a local instance) it first puts the folder the driver imported xroute
from at the front of ``sys.path``: local workers start in the driver's working directory, which
may be a source checkout without the compiled engine. On a cluster the workers use their own
installed xroute. Users: ``xroute batch --backend ray`` (:mod:`xroute.cli.batch_ray`) and the set
scorer's teacher and fine-tuning (:mod:`xroute.policies.rl.ray_pool`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable

from xroute.errors import XrouteError


def start(workers: int, address: str | None) -> bool:
    """Connects to ``address``, or starts a local instance of ``workers`` CPUs, unless Ray is up already;
    True if this call started or joined it (the caller then shuts it down)."""
    try:
        import ray
    except ImportError as exc:
        raise XrouteError("running on Ray needs Ray: pip install 'xroute[ray]'") from exc
    if ray.is_initialized():
        return False
    if address:
        check_address(address)
    try:
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False)
    except Exception as exc:  # noqa: BLE001 - connection problems are user errors
        raise XrouteError(f"cannot start or reach Ray{' at ' + address if address else ''}: {exc}") from exc
    return True


def check_address(address: str, timeout: float = 10.0) -> None:
    """A one-line error at once when nothing listens at ``host:port`` (``ray.init`` retries for minutes)."""
    import socket

    host, sep, port = address.removeprefix("ray://").rpartition(":")
    if not sep or not port.isdigit() or not host:
        return  # "auto", a bare host: left to Ray
    try:
        with socket.create_connection((host.strip("[]"), int(port)), timeout=timeout):
            pass
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise XrouteError(f"cannot start or reach Ray at {address}: nothing answers there ({reason.lower()})") from exc


def package_root(address: str | None) -> str | None:
    """The folder holding the driver's ``xroute`` package for a local instance; None on a cluster."""
    import xroute

    return None if address else str(Path(xroute.__file__).resolve().parent.parent)


def call_by_name(root: str | None) -> Callable[[str, str, bytes], Any]:
    """``run(module, name, payload)``: ``module.name(*pickle.loads(payload))`` on the worker, ``root`` first
    on its ``sys.path`` (see the module docstring). A nested function, so Ray ships it by value."""

    def run(module: str, name: str, payload: bytes) -> Any:
        import importlib
        import pickle
        import sys

        if root is not None and (not sys.path or sys.path[0] != root):
            sys.path.insert(0, root)
        return getattr(importlib.import_module(module), name)(*pickle.loads(payload))

    return run
