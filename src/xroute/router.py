"""Route a loaded design: ``route_design(design, region_size=10, iterations=10, threads=1, policy=...)``.

The engine routes every net of the design in place (any routing the DEF had is replaced):
iteration 0 routes all nets region by region (regions of ``region_size`` x ``region_size``
GCells, non-touching regions in parallel on ``threads`` threads); each later iteration rips up
and reroutes the nets in design-rule markers, and the flow stops early when an iteration ends
with no marker. The result is the same for any thread count, and for a given policy and seed.

The run's settings are the engine's own struct, :class:`RouterSettings` (with its
:class:`MazeCosts`), bound from C++ and re-exported here: route_design's setting keywords fill one
through :func:`router_settings`, which checks each value against the engine's limits
(:mod:`xroute.defaults`) where it enters; the policy, its seed and its time limit are
route_design's own arguments.

The library never prints; ``progress`` receives a :class:`RouteProgress` after each batch of
regions and at the end of each iteration.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING, Any, Callable, Sequence

import numpy as np

from xroute.net_order import (
    NetOrderPolicy,
    SequentialPolicy,
    builtin_policy,
    check_order,
)
from xroute import defaults
from xroute._engine import MazeCosts, RouterSettings
from xroute.errors import PolicyError, RouteArgumentError
from xroute.schedule import IterationReport, SchedulePolicy, engine_planner, is_default

if TYPE_CHECKING:
    from xroute.design import Design

__all__ = ["MazeCosts", "RouteProgress", "RouteResult", "RouterSettings", "route_design", "router_settings"]


# From the engine's RouterSettings and limits (xroute.defaults): GCells per region side (0: auto,
# region_size_for), iteration limit, the largest region side and thread count a
# run may ask for.
DEFAULT_REGION_SIZE = defaults.REGION_SIZE
DEFAULT_ITERATIONS = defaults.ITERATIONS
MAX_ITERATIONS = defaults.MAX_ITERATIONS
MAX_REGION_SIZE = defaults.MAX_REGION_SIZE
MAX_THREADS = defaults.MAX_THREADS

VIOLATION_TYPES: tuple[str, ...] = (
    "Short",
    "MetalSpacing",
    "EndOfLine",
    "CutShort",
    "CutSpacing",
    "AdjacentCuts",
    "MinArea",
    "CornerSpacing",
)
"""Design-rule marker types, in the engine's order."""


def _integer(name: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise RouteArgumentError(f"{name} must be an integer, got {value!r}")
    return value


# RouterSettings field -> (lowest, highest: the engine's limits; the error below, the error above).
_RANGES: dict[str, tuple[int, int, str, str]] = {
    "region_size": (0, MAX_REGION_SIZE, "region size must be at least 1 GCell (0: auto)",
                    "region size must be at most {hi} GCells"),
    "iterations": (1, MAX_ITERATIONS, "iterations must be between 1 and {hi}", "iterations must be between 1 and {hi}"),
    "threads": (1, MAX_THREADS, "threads must be at least 1", "threads must be at most {hi}"),
    "repair_rounds": (0, defaults.MAX_REPAIR_ROUNDS, "repair_rounds must be an integer in 0..{hi}",
                      "repair_rounds must be an integer in 0..{hi}"),
}


def _in_range(name: str, value: Any) -> int:
    lo, hi, below, above = _RANGES[name]
    n = _integer(name, value)
    if not lo <= n <= hi:
        raise RouteArgumentError(f"{(below if n < lo else above).format(hi=hi)}, got {n}")
    return n


def _schedule(value: Any) -> list[tuple[int, int]]:
    steps = [tuple(step) for step in value]
    if not steps:
        raise RouteArgumentError("schedule must have at least one (region_size, offset) step")
    for i, step in enumerate(steps):
        if len(step) != 2 or any(isinstance(v, bool) or not isinstance(v, int) for v in step):
            raise RouteArgumentError(f"schedule step {i} must be two integers (region_size, offset), got {step!r}")
        size, offset = step
        if size < 1:
            raise RouteArgumentError(f"schedule step {i}: region size must be at least 1 GCell, got {size}")
        if size > MAX_REGION_SIZE:
            raise RouteArgumentError(f"schedule step {i}: region size must be at most {MAX_REGION_SIZE} GCells, "
                                     f"got {size}")
        if not 0 <= offset < size:
            raise RouteArgumentError(f"schedule step {i}: offset must be in 0..{size - 1} GCells, got {offset}")
    return steps  # type: ignore[return-value]


# The settings route_design and the commands take by name, each with its check (the engine's limits).
_CHECKS: dict[str, Callable[[Any], Any]] = {**{name: partial(_in_range, name) for name in _RANGES},
                                             "schedule": _schedule}


def router_settings(base: RouterSettings | None = None, **fields: Any) -> RouterSettings:
    """A copy of ``base`` (None: the engine's defaults) with the ``fields`` that are not None (RouterSettings
    field names). ``region_size``, ``iterations``, ``threads``, ``schedule`` (per-iteration ``(region_size,
    offset)`` pairs, GCells, cycled) and ``repair_rounds`` are checked here against the engine's limits:
    :class:`RouteArgumentError` naming the setting. Every route_design keyword and every command's flag or
    config value enters the engine's settings through here; the engine's own check then only refuses
    values set directly on a RouterSettings."""
    changes = {name: _CHECKS[name](value) if name in _CHECKS else value
               for name, value in fields.items() if value is not None}
    try:
        return (RouterSettings() if base is None else base).replace(**changes)
    except TypeError as exc:  # a field RouterSettings does not have, or a value of the wrong type
        raise RouteArgumentError(str(exc)) from None


def check_seed(seed: Any) -> int:
    """``seed`` if it is an integer in 0..2^64 - 1 (the engine's seeds are unsigned 64-bit), else RouteArgumentError."""
    seed = _integer("seed", seed)
    if not 0 <= seed < 2**64:
        raise RouteArgumentError(f"seed must be between 0 and 2^64 - 1, got {seed}")
    return seed


def check_policy_timeout(t: Any) -> float | None:
    """``t`` if it is None or a finite number of seconds >= 0 (0: no limit), else RouteArgumentError."""
    if t is not None and (isinstance(t, bool) or not isinstance(t, (int, float)) or not 0 <= t < math.inf):
        # NaN would switch the watchdog off silently (every comparison with it is false)
        raise RouteArgumentError(f"policy_timeout must be a finite number of seconds >= 0 (0: no limit), got {t!r}")
    return t


@dataclass(frozen=True)
class RouteProgress:
    """One progress event: ``report`` is the iteration so far (its wirelength, vias and violations
    are final only when ``iteration_done``)."""

    report: IterationReport
    regions_done: int  # regions routed so far in this iteration
    regions_total: int  # regions of the iteration with work (known before the first is routed)
    iteration_done: bool  # the iteration's design-rule check is done and its figures are final
    iterations: int  # the iteration limit of the run


@dataclass(frozen=True)
class RouteResult:
    """The outcome of :func:`route_design` (the design itself now holds the routing)."""

    iterations: tuple[IterationReport, ...]  # one per iteration run (the flow may stop early)
    policy: str  # the policy's name
    settings: RouterSettings  # as the run was asked (region_size 0: auto)
    seconds: float  # wall time of the whole run
    violations_by_type: dict[str, int]  # after the last iteration
    policy_seconds: float | None = None  # wall time inside a Python policy's order(); None for built-ins (C++)
    policy_calls: int = 0  # calls of a Python policy's order() (one per region with candidates)
    schedule_policy: str = "rule"  # the schedule policy's name (xroute.schedule)
    seed: int = 1  # route_design's seed
    # The maze's sole-landing penalty the run used (settings' -1, automatic, resolved for the design).
    sole_landing_penalty: int | None = None

    @property
    def final(self) -> IterationReport:
        return self.iterations[-1]

    @property
    def region_size(self) -> int:
        """GCells per region side the run used (settings.region_size 0 resolved; a schedule's sizes are per
        iteration)."""
        return self.settings.region_size or (self.iterations[0].region_size if self.iterations else 0)

    @property
    def violations(self) -> int:
        return sum(self.violations_by_type.values())

    @property
    def wirelength_um(self) -> float:
        return self.final.wirelength_um

    @property
    def vias(self) -> int:
        return self.final.vias


def region_size_for(design: Design, region_size: int = 0) -> int:
    """GCells per region side of a run with ``region_size`` on ``design``: itself, or for 0 the engine's
    choice: ``defaults.REGION_GCELLS`` GCells, or more while three in four regions' grids stay within
    ``defaults.REGION_GRID_NODES`` nodes a layer and a region does not cover the die (15 GCells on
    ispd18_test1, 16 on ispd19_test1, 10 on ispd19_test3); or fewer, down to
    ``defaults.LEAST_REGION_GCELLS``, while they are over it at 10 (fine tracks over large GCells:
    6 on OpenROAD's gcd on asap7 and on sky130hs)."""
    return int(region_size) if region_size else int(_engine().auto_region_size(design.engine))


def _engine() -> Any:
    from xroute import _engine as engine  # compiled module; imported on first use

    return engine


def resolve_policy(policy: str | NetOrderPolicy, seed: int) -> NetOrderPolicy:
    """A policy object from a built-in's name or a policy object (policy files and ONNX models:
    :func:`xroute.policies.get_policy`)."""
    if isinstance(policy, str):
        return builtin_policy(policy, seed)
    if not isinstance(policy, (NetOrderPolicy, SequentialPolicy)):
        raise PolicyError(f"not a net-order policy (needs name and order(region, features) or "
                          f"next_net(region, features)): {policy!r}")
    return policy


def _builtin(policy: NetOrderPolicy) -> str | None:
    """The engine's name for a built-in policy; None for one that must be called from Python
    (including a subclass of a built-in that overrides ``order``)."""
    if isinstance(policy, SequentialPolicy):
        return None
    # The nearest class of xroute.net_order that names a built-in (its `builtin` attribute), so a new
    # built-in needs no list here.
    for cls in type(policy).__mro__:
        if cls.__module__ == "xroute.net_order" and cls.__dict__.get("builtin"):
            return cls.builtin if type(policy).order is cls.order else None
    return None


class _PolicyCallback:
    """The engine's policy_fn for a Python policy: calls ``policy.order``, checks its result and
    adds up the time spent in it (the check included)."""

    def __init__(self, policy: NetOrderPolicy, timeout: float | None = None) -> None:
        from xroute.policy_guard import DEFAULT_CALL_TIMEOUT, Watchdog, policy_where

        self.policy = policy
        self.name = policy.name  # the engine names the policy by it in its errors
        self.where = policy_where(policy)  # its file (and line): named in errors about what it returned
        self.seconds = 0.0  # wall time in order() and the check
        self.calls = 0
        limit = DEFAULT_CALL_TIMEOUT if timeout is None else timeout
        self.watchdog = Watchdog(limit, policy) if limit > 0 else None  # per-call time limit

    def __call__(self, region: dict[str, Any], features: Any) -> list[int]:
        from xroute.policy_guard import call_policy

        start = time.perf_counter()
        try:
            order = call_policy(self.policy, region, features, self.watchdog)  # SystemExit -> PolicyError
            return check_order(order, len(features), self.policy.name, self.where)
        finally:
            self.seconds += time.perf_counter() - start
            self.calls += 1

    def next_net(self, region: dict[str, Any], features: Any) -> int:
        """A sequential policy's ``next_net``, checked: a row index of ``features``."""
        from xroute.policy_guard import call_policy

        start = time.perf_counter()
        try:
            index = call_policy(self.policy, region, features, self.watchdog, method="next_net")
            return check_next(index, len(features), self.policy.name, self.where)
        finally:
            self.seconds += time.perf_counter() - start
            self.calls += 1


def check_next(index: Any, n: int, policy_name: str, source: str = "") -> int:
    """``index`` as an int if it is a row of ``n`` unrouted candidates; otherwise a :class:`PolicyError`."""
    where = (f"{source}: " if source else "") + f"net-order policy '{policy_name}'"
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)):
        raise PolicyError(f"{where}: next_net returned {type(index).__name__}, not the int index of a candidate row")
    if not 0 <= int(index) < n:
        raise PolicyError(f"{where}: next_net returned {int(index)}, outside range({n}) (the unrouted candidates)")
    return int(index)


def _policy_kwargs(pol: NetOrderPolicy, seed: int, timeout: float | None) -> tuple[dict[str, Any], _PolicyCallback | None]:
    """The engine's policy arguments: a built-in's name (run in C++), or a checked, timed callback."""
    if _builtin(pol) is not None:
        return pol.engine_arguments(seed), None  # a class of xroute.net_order.BUILTINS
    callback = _PolicyCallback(pol, timeout)  # seconds per call (None: default, 0: none)
    # A policy that declares needs_region = True finds the region being routed (an _engine.Region
    # lent for the call: grid views, candidates, route_net) in region["engine_region"].
    kwargs: dict[str, Any] = {"policy_needs_region": bool(getattr(pol, "needs_region", False))}
    if isinstance(pol, SequentialPolicy):
        kwargs["policy_next"] = callback.next_net  # asked after every routed net
    else:
        kwargs["policy_fn"] = callback
    return kwargs, callback


def route_design(
    design: Design,
    *,
    settings: RouterSettings | None = None,
    region_size: int | None = None,
    iterations: int | None = None,
    threads: int | None = None,
    schedule: Sequence[tuple[int, int]] | None = None,
    repair_rounds: int | None = None,
    policy: str | NetOrderPolicy = "heuristic",
    seed: int = 1,
    progress: Callable[[RouteProgress], None] | None = None,
    policy_timeout: float | None = None,
    schedule_policy: SchedulePolicy | None = None,
) -> RouteResult:
    """Routes every net of ``design`` in place and returns the per-iteration reports.

    ``settings``: a :class:`RouterSettings` (None: the engine's defaults); ``region_size``, ``iterations``,
    ``threads``, ``schedule`` and ``repair_rounds``, when given, replace its fields (:func:`router_settings`
    checks them: :class:`RouteArgumentError`).

    ``policy``: ``"heuristic"``, ``"random"`` (seeded with ``seed``), ``"rollout"``, ``"victims"``, ``"bestof"``,
    ``"best-of-K"`` (the engine's search policies with their default budget), or a policy object
    (:class:`~xroute.net_order.HeuristicPolicy`, ``RandomPolicy(seed)`` - whose own seed is used -,
    ``RolloutPolicy(budget)``, ``VictimsPolicy(budget)``, ``BestOfPolicy(k, seed)``, ``CallablePolicy(fn)``, anything with
    ``name`` and ``order``, or with ``name`` and ``next_net`` (asked after every routed net);
    policy files and ONNX models through :func:`xroute.policies.get_policy`).
    Built-in policies run in C++; any other is called once per region (a sequential one once per net), at most
    ``policy_timeout`` seconds a call (None: :mod:`xroute.policy_guard`'s default, 0: no limit). Raises
    :class:`RouteArgumentError` for invalid settings and :class:`~xroute.net_order.PolicyError`
    when the policy cannot be loaded or returns something other than a permutation; an exception
    raised inside a policy's ``order`` (or ``progress``) propagates unchanged. When routing
    raises, the design holds a partial routing.

    ``region_size``: GCells per region side; 0 (the default): :func:`region_size_for` the design.

    ``schedule``: per-iteration ``(region_size, offset)`` pairs in GCells, cycled over the
    iterations (iteration ``i`` uses step ``i % len(schedule)``); it overrides ``region_size``.
    Default: ``region_size`` in every iteration, the offset shifted by a third of a region.

    ``schedule_policy``: asked before each iteration for its plan (:mod:`xroute.schedule`: region
    size and offset, repair rounds, marker / history / other-net weights, or stop), seeing the
    reports so far and the plan the settings above give; None or the rule: those plans.
    """
    settings = router_settings(settings, region_size=region_size, iterations=iterations, threads=threads,
                               schedule=schedule, repair_rounds=repair_rounds)
    seed = check_seed(seed)
    policy_timeout = check_policy_timeout(policy_timeout)
    pol = resolve_policy(policy, seed)
    kwargs, callback = _policy_kwargs(pol, seed, policy_timeout)
    if progress is not None:

        def on_progress(report: dict[str, Any], done: int, total: int) -> None:
            rep = IterationReport.from_engine(report)
            progress(RouteProgress(rep, int(done), int(total), bool(report["done"]), settings.iterations))

        kwargs["progress"] = on_progress
    if not is_default(schedule_policy):
        kwargs["planner"] = engine_planner(schedule_policy)

    start = time.perf_counter()
    # The engine raises PolicyError (not a permutation: the Python wrapper checks first) and
    # RouteArgumentError (a region too large for this design) itself.
    try:
        out = _engine().route(design.engine, settings=settings, **kwargs)
    finally:
        if callback is not None and callback.watchdog is not None:
            callback.watchdog.close()
    seconds = time.perf_counter() - start
    reports = tuple(IterationReport.from_engine(d) for d in out["iterations"])
    return RouteResult(
        iterations=reports,
        policy=pol.name,
        settings=settings,
        seconds=seconds,
        violations_by_type=dict(reports[-1].violations_by_type) if reports else {},
        policy_seconds=callback.seconds if callback is not None else None,
        policy_calls=callback.calls if callback is not None else 0,
        schedule_policy=schedule_policy.name if schedule_policy is not None else "rule",
        seed=seed,
        sole_landing_penalty=int(out["sole_landing_penalty"]),
    )
