"""The iteration seam: what each iteration of the flow runs with, chosen before it starts.

Before every iteration the router asks a schedule policy for the iteration's
:class:`IterationPlan` - the region size and offset, the repair rounds inside each region, and the
maze's weights for markers of the last iteration, for the history of earlier markers and for
other nets' shapes, and the search that orders each region's nets (the run's net-order policy, or
the victims search at a budget of the plan's) - showing it the :class:`IterationReport` of every iteration done so far
(violations by type, wirelength, vias, seconds) and the plan the router's own rule would run. A
plan may also stop the run (from the second iteration on: the first routes every net).

* :class:`RuleSchedule` (``"rule"``, the default) runs the rule's plan: the routing is the one the
  router makes without a schedule policy, byte for byte.
* :class:`CallableSchedule` wraps a function ``plan(history, rule) -> IterationPlan | dict | None``
  (a dict changes the keys it names; None keeps the rule), e.g. from a policy file's ``plan``
  (:func:`xroute.policies.get_schedule_policy`).

Every iteration's report carries the plan it ran (``IterationReport.plan``), so a run's metrics JSON
is a logged run: :func:`logged_transitions` turns it into (history, plan, report) transitions for
offline learning.

Plans are checked here (:meth:`IterationPlan.checked`): a value out of range, a key the plan does
not have or a return of another type is a :class:`~xroute.net_order.PolicyError` naming the
policy; an exception raised inside ``plan`` propagates, tagged with the policy's file and line
(the command line prints it as one line).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any, Callable, Mapping, Protocol, Sequence, runtime_checkable

from xroute.net_order import PolicyError
from xroute.policy_guard import policy_code, policy_where, user_failure

MAX_PENALTY = 10**12  # cost units: far above any weight that steers the maze (its defaults are 1,000-8,000)


@dataclass(frozen=True)
class IterationPlan:
    """What one iteration runs with (the engine's IterationPlan, flow/router.hpp)."""

    region_size: int  # GCells per region side, 1..MAX_REGION_SIZE
    offset: int  # GCells, 0 <= offset < region_size
    repair_rounds: int  # check-and-reroute rounds inside each region, 0..MAX_REPAIR_ROUNDS
    marker_penalty: int  # cost units per node near a marker of the last iteration
    history_penalty: int  # what each marker this iteration leaves adds near it from then on
    use_penalty: int  # cost units per shape of another net that a step would violate
    stop: bool = False  # end the run instead of running this iteration (not the first)
    search_budget: int = 0  # 0: the run's net-order policy; B >= 1: the victims search, B trial routings per region

    @classmethod
    def from_engine(cls, d: Mapping[str, Any]) -> IterationPlan:
        return cls(**{f.name: d[f.name] for f in fields(cls)})

    def to_engine(self) -> dict[str, Any]:
        return asdict(self)

    def checked(self) -> IterationPlan:
        """This plan; ValueError naming the first field out of range."""
        from xroute import defaults  # the engine's limits (loads the engine: not on import)

        size = self.region_size if isinstance(self.region_size, int) else 1
        limits = {"region_size": (1, defaults.MAX_REGION_SIZE), "offset": (0, size - 1),
                  "repair_rounds": (0, defaults.MAX_REPAIR_ROUNDS), "marker_penalty": (0, MAX_PENALTY),
                  "history_penalty": (0, MAX_PENALTY), "use_penalty": (0, MAX_PENALTY),
                  "search_budget": (0, defaults.MAX_SEARCH_BUDGET)}
        for name, (lo, hi) in limits.items():
            value = getattr(self, name)
            if not isinstance(value, int) or isinstance(value, bool):
                raise ValueError(f"{name} must be an integer, got {value!r}")
            if not lo <= value <= hi:
                raise ValueError(f"{name} must be in {lo}..{hi}, got {value}")
        if not isinstance(self.stop, bool):
            raise ValueError(f"stop must be true or false, got {self.stop!r}")
        return self


@dataclass(frozen=True)
class IterationReport:
    """What one iteration did and the state after it (lengths in DBU unless named _um)."""

    iteration: int
    region_size: int  # region side of this iteration, GCells
    offset: int  # region offset of this iteration, GCells
    regions: int  # regions with work
    net_routes: int  # (net, region) pairs routed
    unreached: int  # terminals the maze could not reach
    wirelength_dbu: int  # all wires after the iteration
    wirelength_um: float
    vias: int
    violations_by_type: dict[str, int] = field(default_factory=dict)  # marker type -> count
    violations: int = 0  # all markers after the iteration
    seconds: float = 0.0  # wall time of the iteration (routing + check)
    plan: IterationPlan | None = None  # what the iteration ran with (None while it runs)

    @classmethod
    def from_engine(cls, d: Mapping[str, Any]) -> IterationReport:
        return cls(
            iteration=int(d["iteration"]),
            region_size=int(d["region_size"]),
            offset=int(d["offset"]),
            regions=int(d["regions"]),
            net_routes=int(d["net_routes"]),
            unreached=int(d["unreached"]),
            wirelength_dbu=int(d["wirelength_dbu"]),
            wirelength_um=float(d["wirelength_um"]),
            vias=int(d["vias"]),
            violations_by_type={str(k): int(v) for k, v in d["violations_by_type"].items()},
            violations=int(d["violations"]),
            seconds=float(d["seconds"]),
            plan=IterationPlan.from_engine(d["plan"]) if d.get("plan") else None,
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "iteration": self.iteration,
            "region_size": self.region_size,
            "offset": self.offset,
            "regions": self.regions,
            "net_routes": self.net_routes,
            "unreached": self.unreached,
            "wirelength_dbu": self.wirelength_dbu,
            "wirelength_um": self.wirelength_um,
            "vias": self.vias,
            "violations": self.violations,
            "violations_by_type": dict(self.violations_by_type),
            "seconds": self.seconds,
            "plan": self.plan.to_engine() if self.plan is not None else None,
        }


@runtime_checkable
class SchedulePolicy(Protocol):
    """Chooses each iteration's plan: ``plan(history, rule) -> IterationPlan``."""

    name: str

    def plan(self, history: Sequence[IterationReport], rule: IterationPlan) -> IterationPlan: ...


class RuleSchedule:
    """The router's own rule (the default): every iteration runs the rule's plan."""

    name = "rule"
    builtin = True

    def plan(self, history: Sequence[IterationReport], rule: IterationPlan) -> IterationPlan:
        return rule


class CallableSchedule:
    """A schedule policy from a function ``fn(history, rule)`` returning an IterationPlan, a dict of
    the fields to change, or None (the rule's plan)."""

    def __init__(self, fn: Callable[..., Any], name: str = "python") -> None:
        self.fn = fn
        self.name = name

    def plan(self, history: Sequence[IterationReport], rule: IterationPlan) -> IterationPlan:
        got = self.fn(history, rule)
        if got is None:
            return rule
        if isinstance(got, IterationPlan):
            return got
        where = _named(self)
        if isinstance(got, Mapping):
            unknown = sorted(set(map(str, got)) - {f.name for f in fields(IterationPlan)})
            if unknown:
                raise PolicyError(f"{where}: plan() returned unknown key(s) "
                                  f"{', '.join(unknown)} (known: {', '.join(f.name for f in fields(IterationPlan))})")
            try:
                return replace(rule, **{str(k): v for k, v in got.items()})
            except TypeError as exc:  # e.g. a key that is not a string
                raise PolicyError(f"{where}: plan() returned a dict that is not a plan: {exc}") from None
        raise PolicyError(f"{where}: plan() must return an IterationPlan, a dict or None, "
                          f"got {type(got).__name__}")


def _named(policy: Any) -> str:
    """``<file>:<line>: schedule policy '<name>'`` (the file alone for a model, nothing for the rule)."""
    where = policy_where(policy)
    return (f"{where}: " if where else "") + f"schedule policy '{getattr(policy, 'name', 'schedule')}'"


def engine_planner(policy: SchedulePolicy) -> Callable[[list[Any], dict[str, Any]], dict[str, Any]]:
    """The engine's ``planner(history, rule) -> plan`` callback around ``policy``: plans checked,
    failures named (PolicyError) or tagged with the policy's file and line."""

    def planner(history: list[Any], rule: dict[str, Any]) -> dict[str, Any]:
        reports = [IterationReport.from_engine(d) for d in history]
        base = IterationPlan.from_engine(rule)
        try:
            with policy_code(policy, "plan"):
                plan = policy.plan(reports, base)
        except BaseException as exc:  # noqa: BLE001 - the user's code: named (policy_guard.user_failure)
            failure = user_failure(exc, policy, "plan")
            if failure is exc:
                raise
            raise failure from None
        if not isinstance(plan, IterationPlan):
            raise PolicyError(f"{_named(policy)}: plan() must return an IterationPlan, "
                              f"got {type(plan).__name__}")
        try:
            plan.checked()
        except ValueError as exc:
            raise PolicyError(f"{_named(policy)}, iteration {len(reports)}: {exc}") from None
        if plan.stop and not reports:
            raise PolicyError(f"{_named(policy)}: the first iteration cannot stop the run "
                              "(it routes every net)")
        return plan.to_engine()

    return planner


def is_default(policy: SchedulePolicy | None) -> bool:
    """Whether routing with ``policy`` is routing without one (the rule, run in C++)."""
    return policy is None or isinstance(policy, RuleSchedule)


@dataclass(frozen=True)
class Transition:
    """One iteration of a logged run, as offline learning reads it: what the policy saw, what ran, what came of it."""

    design: str
    history: tuple[IterationReport, ...]  # the reports of the iterations before (the policy's view)
    plan: IterationPlan  # what the iteration ran with
    report: IterationReport  # the iteration's outcome


def logged_transitions(metrics: Mapping[str, Any]) -> list[Transition]:
    """The transitions of a routed run from its metrics JSON (``xroute route``'s ``<design>.metrics.json``,
    read with ``json.load``): the logged-runs format is a folder of such files, one per run, whatever
    schedule policy made them. ValueError for a file whose iterations do not record their plans."""
    reports = [IterationReport.from_engine(it) for it in metrics["iterations"]]
    if any(r.plan is None for r in reports):
        raise ValueError("the run's iterations do not record their plans (routed before xroute logged them)")
    design = str(metrics.get("design", ""))
    return [Transition(design, tuple(reports[:i]), r.plan, r) for i, r in enumerate(reports)]  # type: ignore[arg-type]
