"""Region-by-region routing for the learning side: a routing session over a loaded design.

The environments, static regions and benchmarks open regions of a design one at a time, route
their nets in an order they choose and read the grid, candidates and metrics back. The session
and its regions are the compiled engine's objects (typed in ``_engine.pyi``); this module is
where the layers above the library get them, so none of them imports the private engine.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from xroute import _engine

if TYPE_CHECKING:
    from xroute.design import Design

RoutingSession = _engine.RoutingSession
"""A design's shared routing state (tracks, pin access, fixed shapes): ``open_region(box, iteration)``,
``gcell_lines``; see ``engine_cpp/loop/README.md``."""

Region = _engine.Region
"""One region being routed: ``candidates``, ``grid()``, ``route_net(i)``, ``unrouted()``, ``metrics()``, ``commit()``."""


FirstPass = _engine.FirstPass
"""The flow's first pass of a session's design, kept for replay: ``regions``, ``open_region(i)`` (region i in
context: the colours routed before it committed), ``restore(colour)``, ``report``; see ``engine_cpp/loop/README.md``."""


def open_session(design: Design, threads: int = 1) -> RoutingSession:
    """A routing session over ``design`` (which must outlive it)."""
    return _engine.RoutingSession(design.engine, threads=threads)


def first_pass(session: RoutingSession, region_size: int | None = None, *, policy: str = "heuristic", seed: int = 1,
               threads: int = 1) -> FirstPass:
    """Routes the first pass (iteration 0) of ``session``'s design as ``xroute route`` does, regions of
    ``region_size`` GCells (default: the router's), ``policy`` ``heuristic`` or ``random``, and keeps it so that
    each region can be opened again in context (:attr:`FirstPass.regions`, :meth:`FirstPass.open_region`)."""
    from xroute.defaults import REGION_SIZE

    size = REGION_SIZE if region_size is None else int(region_size)
    return _engine.FirstPass(session, region_size=size, policy=policy, seed=seed, threads=threads)
