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
  (a dict changes the fields it names; None keeps the rule), e.g. from a policy file's ``plan``
  (:func:`xroute.policies.get_schedule_policy`).

:class:`IterationPlan` is the engine's struct (``xroute._engine.IterationPlan``, loop/router.hpp),
bound field by field and re-exported here (loaded on first use: importing this module loads no
engine); ``rule.replace(region_size=5)`` is a changed copy, ``plan.to_dict()`` its fields.

Every iteration's report carries the plan it ran (``IterationReport.plan``), so a run's metrics JSON
is a logged run: :func:`logged_transitions` turns it into (history, plan, report) transitions for
offline learning.

Whatever a schedule policy answers - None, a plan or a dict of the fields to change - becomes the
iteration's plan in one place, :func:`plan_from`, which checks it against the engine's limits: a
value out of range or of the wrong type, a field the plan does not have or an answer of another type
is a :class:`~xroute.net_order.PolicyError` naming the policy (never clamped); an exception raised
inside ``plan`` propagates, tagged with the policy's file and line (the command line prints it as one
line).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Mapping, Protocol, Sequence, runtime_checkable

from xroute.net_order import PolicyError
from xroute.policy_guard import policy_code, policy_where, user_failure

if TYPE_CHECKING:
    from xroute._engine import IterationPlan

MAX_PENALTY = 10**12  # cost units: far above any weight that steers the maze (its defaults are 1,000-8,000)


def _plan_type() -> type:
    from xroute._engine import IterationPlan

    return IterationPlan


def __getattr__(name: str) -> Any:
    if name == "IterationPlan":  # the engine's, loaded on first use (see the module doc)
        return _plan_type()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def plan_problem(values: Mapping[str, Any]) -> str | None:
    """What is wrong with a plan's field values (IterationPlan.to_dict() keys), against the engine's
    limits; None when nothing is."""
    from xroute import defaults  # the engine's limits (loads the engine: not on import)

    size = values["region_size"] if isinstance(values["region_size"], int) else 1
    limits = {"region_size": (1, defaults.MAX_REGION_SIZE), "offset": (0, size - 1),
              "repair_rounds": (0, defaults.MAX_REPAIR_ROUNDS), "marker_penalty": (0, MAX_PENALTY),
              "history_penalty": (0, MAX_PENALTY), "use_penalty": (0, MAX_PENALTY),
              "search_budget": (0, defaults.MAX_SEARCH_BUDGET)}
    for name, (lo, hi) in limits.items():
        value = values[name]
        if not isinstance(value, int) or isinstance(value, bool):
            return f"{name} must be an integer, got {value!r}"
        if not lo <= value <= hi:
            return f"{name} must be in {lo}..{hi}, got {value}"
    if not isinstance(values["stop"], bool):
        return f"stop must be true or false, got {values['stop']!r}"
    return None


def named(policy: Any) -> str:
    """``<file>:<line>: schedule policy '<name>'`` (the file alone for a model, no file for the rule)."""
    where = policy_where(policy)
    return (f"{where}: " if where else "") + f"schedule policy '{getattr(policy, 'name', 'schedule')}'"


def plan_from(answer: Any, rule: IterationPlan, policy: Any, iteration: int) -> IterationPlan:
    """The plan of iteration ``iteration`` from what schedule policy ``policy`` answered: None (the rule's
    plan), an IterationPlan, or a dict of the fields to change in ``rule``; checked (:func:`plan_problem`,
    and no stop in the first iteration). The one place an answer becomes a plan: PolicyError naming the
    policy (its file and line, :func:`named`) when it cannot."""
    where = named(policy)
    fields = rule.to_dict()
    if answer is None:
        answer = rule
    if isinstance(answer, type(rule)):
        changes: dict[str, Any] = {}
        values = answer.to_dict()
    elif isinstance(answer, Mapping):
        changes = {str(k): v for k, v in answer.items()}
        unknown = sorted(set(changes) - set(fields))
        if unknown:
            raise PolicyError(f"{where}: plan() returned unknown key(s) {', '.join(unknown)} "
                              f"(known: {', '.join(fields)})")
        values = {**fields, **changes}
    else:
        raise PolicyError(f"{where}: plan() must return an IterationPlan, a dict or None, got {type(answer).__name__}")
    problem = plan_problem(values)
    if problem is not None:
        raise PolicyError(f"{where}, iteration {iteration}: {problem}")
    if values["stop"] and iteration == 0:
        raise PolicyError(f"{where}: the first iteration cannot stop the run (it routes every net)")
    return rule.replace(**changes) if isinstance(answer, Mapping) else answer


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
    # wall seconds by stage (setup, route, commit, index, trim, check; about `seconds` in all)
    stage_seconds: dict[str, float] = field(default_factory=dict)
    checked_shapes: int = 0  # shapes the check after it looked at (all of them when the check was whole)
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
            stage_seconds={str(k): float(v) for k, v in d.get("stage_seconds", {}).items()},
            checked_shapes=int(d.get("checked_shapes", 0)),
            plan=_plan_type()(**d["plan"]) if d.get("plan") else None,
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
            "stage_seconds": dict(self.stage_seconds),
            "checked_shapes": self.checked_shapes,
            "plan": self.plan.to_dict() if self.plan is not None else None,
        }


@runtime_checkable
class SchedulePolicy(Protocol):
    """Chooses each iteration's plan: ``plan(history, rule) -> IterationPlan`` (or a dict of the fields to
    change, or None: :func:`plan_from`)."""

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
        return plan_from(self.fn(history, rule), rule, self, len(history))


def engine_planner(policy: SchedulePolicy) -> Callable[[list[Any], IterationPlan], IterationPlan]:
    """The engine's ``planner(history, rule) -> plan`` callback around ``policy``: its answers made plans
    by :func:`plan_from`, failures named (PolicyError) or tagged with the policy's file and line."""

    def planner(history: list[Any], rule: IterationPlan) -> IterationPlan:
        reports = [IterationReport.from_engine(d) for d in history]
        try:
            with policy_code(policy, "plan"):
                answer = policy.plan(reports, rule)
        except BaseException as exc:  # noqa: BLE001 - the user's code: named (policy_guard.user_failure)
            failure = user_failure(exc, policy, "plan")
            if failure is exc:
                raise
            raise failure from None
        return plan_from(answer, rule, policy, len(reports))

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
