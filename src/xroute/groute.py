"""The built-in global router: ``global_route(design, out=...)`` gives a design route guides.

The engine routes every net on the GCell grid (DEF GCELLGRID, else a regular grid of 15 track
pitches), with pattern routing, then rip-up and maze rerouting under negotiated congestion,
then layer assignment (see ``engine_cpp/groute/README.md``). The guides replace any the design
had, in memory, so that :func:`xroute.router.route_design` can run on them without a file;
``out`` also writes them in the ISPD guide format (atomically). Deterministic.
"""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING, Any

from xroute import defaults
from xroute.errors import GlobalRouteArgumentError

if TYPE_CHECKING:
    from xroute.design import Design

# From the engine's GlobalRouteSettings (xroute.defaults); the measurements behind them are in
# engine_cpp/groute/README.md.
DEFAULT_ITERATIONS = defaults.GROUTE_ITERATIONS  # rip-up-and-reroute rounds at most (stops at zero overflow)
DEFAULT_CAPACITY_PERCENT = defaults.GROUTE_CAPACITY_PERCENT  # share of each GCell edge's free tracks
DEFAULT_CONGESTION_COST = defaults.GROUTE_CONGESTION_COST  # layer assignment: cost of an edge at full use


@dataclass(frozen=True)
class GlobalRouteStats:
    """What the global router did. Overflow in tracks; wirelength in GCell edges."""

    gcells: tuple[int, int]  # GCells along x and y
    layers: int  # routing layers
    nets: int  # nets with two or more pin GCells
    initial_overflow: int  # 2D overflow after pattern routing
    overflow: int  # 2D overflow at the end
    overflow_edges: int  # 2D GCell edges over capacity at the end
    overflow_3d: int  # per-layer overflow after layer assignment
    wirelength_gcells: int
    vias: int  # via-stack heights the guides imply
    guides: int  # guide rectangles
    iterations: int  # rip-up rounds run
    reroutes: int  # nets maze-routed over all rounds
    seconds: float

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["gcells"] = list(self.gcells)
        return d


def global_route(
    design: Design,
    out: str | os.PathLike[str] | None = None,
    *,
    iterations: int = DEFAULT_ITERATIONS,
    capacity_percent: int = DEFAULT_CAPACITY_PERCENT,
    min_layer: int = defaults.GROUTE_MIN_LAYER,
    slack: int = defaults.GROUTE_SLACK,
    congestion_cost: float = DEFAULT_CONGESTION_COST,
) -> GlobalRouteStats:
    """Global-routes ``design``, installs the guides in it and, with ``out``, writes them there."""
    for name, value, lo, hi in (
        ("iterations", iterations, 0, 1000),
        ("capacity_percent", capacity_percent, 1, 100),
        ("min_layer", min_layer, 0, 64),
        ("slack", slack, 0, 100),
    ):
        if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
            raise GlobalRouteArgumentError(f"{name} must be an integer in {lo}..{hi}, got {value!r}")
    if isinstance(congestion_cost, bool) or not isinstance(congestion_cost, (int, float)) or not congestion_cost >= 0:
        raise GlobalRouteArgumentError(f"congestion_cost must be a number >= 0, got {congestion_cost!r}")
    if out is not None:
        from xroute.regular_files import check_output

        out = check_output(out, "guide file")  # never replace a folder, FIFO or device
    raw = _engine().global_route(
        design.engine,
        out=os.fspath(out) if out is not None else "",
        iterations=iterations,
        capacity_percent=capacity_percent,
        min_layer=min_layer,
        slack=slack,
        congestion_cost=float(congestion_cost),
    )
    stats = GlobalRouteStats(**{**raw, "gcells": tuple(raw["gcells"])})
    design.global_route_stats = stats
    return stats


def _engine() -> Any:
    from xroute import _engine as engine  # compiled module; imported on first use

    return engine
