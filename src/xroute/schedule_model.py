"""A learned schedule policy that is a small data file: smaller regions once the run converges, a stop
when it stalls.

The policy family (:class:`SwitchSchedule`) has five parameters. Until the violations fall to
``switch_ratio`` times the first iteration's, every iteration runs the rule's plan; from then on the
regions are ``late_size`` GCells a side (offset shifted by a third of a region each iteration, as the
rule shifts its own), with ``late_repair`` repair rounds and, when ``late_budget`` > 0, each region's
nets ordered by the victims search with that many trial routings (where few regions are left to
mend, the search is cheap). With ``patience`` > 0 the run stops once
that many iterations in a row found no new lowest violation count. :mod:`xroute.policies.schedule_train`
chooses the parameters on training designs; the result is a JSON file (``--schedule-policy
FILE.json``)::

    {"format": "xroute-schedule-switch", "version": 1,
     "parameters": {"late_size": 5, "switch_ratio": 0.2, "patience": 2, "late_repair": 0, "late_budget": 4},
     ...what it was trained on and the figures it was chosen by...}

A file whose ``parameters`` is null keeps the rule (training found nothing better than the default).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Sequence

from xroute.net_order import PolicyError
from xroute.schedule import IterationReport

if TYPE_CHECKING:
    from xroute.schedule import IterationPlan

FORMAT = "xroute-schedule-switch"
VERSION = 1
MAX_LATE_SIZE = 30  # GCells: far above any useful region side; the engine's own limit is checked too
MAX_LATE_BUDGET = 64  # trial routings per region: far above any budget worth its time


@dataclass(frozen=True)
class SwitchSchedule:
    """The rule's plans until the run converges, then ``late_size`` regions; a stop on a stall."""

    late_size: int  # region side once switched, GCells
    switch_ratio: float  # switch once violations <= switch_ratio * the first iteration's (1.0: at once)
    patience: int = 0  # stop after this many iterations without a new lowest count (0: never)
    late_repair: int = 0  # repair rounds once switched
    late_budget: int = 0  # once switched: the victims search with this many trial routings per region (0: none)
    name: str = "switch"
    source: str = field(default="", compare=False)  # the model file it was read from (named in errors)

    def __post_init__(self) -> None:
        checks = (
            (isinstance(self.late_size, int) and not isinstance(self.late_size, bool)
             and 1 <= self.late_size <= MAX_LATE_SIZE, f"late_size must be an integer in 1..{MAX_LATE_SIZE}"),
            (isinstance(self.switch_ratio, (int, float)) and not isinstance(self.switch_ratio, bool)
             and math.isfinite(self.switch_ratio) and 0.0 <= self.switch_ratio <= 1.0,
             "switch_ratio must be a number in 0..1"),
            (isinstance(self.patience, int) and not isinstance(self.patience, bool) and 0 <= self.patience <= 100,
             "patience must be an integer in 0..100"),
            (isinstance(self.late_repair, int) and not isinstance(self.late_repair, bool)
             and 0 <= self.late_repair <= 100, "late_repair must be an integer in 0..100"),
            (isinstance(self.late_budget, int) and not isinstance(self.late_budget, bool)
             and 0 <= self.late_budget <= MAX_LATE_BUDGET, f"late_budget must be an integer in 0..{MAX_LATE_BUDGET}"),
        )
        for ok, message in checks:
            if not ok:
                raise ValueError(message)

    def parameters(self) -> dict[str, Any]:
        d = asdict(self)
        d.pop("name")
        d.pop("source")
        return d

    def switched(self, history: Sequence[IterationReport]) -> bool:
        first = history[0].violations
        return min(r.violations for r in history) <= self.switch_ratio * first

    def stalled(self, history: Sequence[IterationReport]) -> bool:
        p = self.patience
        if p == 0 or len(history) <= p:
            return False
        best_before = min(r.violations for r in history[:-p])
        return min(r.violations for r in history[-p:]) >= best_before

    def plan(self, history: Sequence[IterationReport], rule: IterationPlan) -> IterationPlan:
        if not history:
            return rule  # the first iteration routes every net with the rule's plan
        if self.stalled(history):
            return rule.replace(stop=True)
        if not self.switched(history):
            return rule
        i, size = len(history), self.late_size
        return rule.replace(region_size=size, offset=(i % 3) * size // 3, repair_rounds=self.late_repair,
                            search_budget=self.late_budget)


class RuleKept:
    """What a model file with null parameters runs: the rule's plan (named after the file)."""

    def __init__(self, name: str, source: str = "") -> None:
        self.name = name
        self.source = source  # the model file (named in errors)

    def plan(self, history: Sequence[IterationReport], rule: IterationPlan) -> IterationPlan:
        return rule


def model_document(schedule: SwitchSchedule | None, **about: Any) -> dict[str, Any]:
    """The JSON document of a model file: its parameters (None: keep the rule) and ``about``."""
    return {"format": FORMAT, "version": VERSION,
            "parameters": schedule.parameters() if schedule is not None else None, **about}


def schedule_from_document(doc: Any, source: str) -> SwitchSchedule | RuleKept:
    """The policy a model document describes; PolicyError naming ``source`` when it is not one."""
    if not isinstance(doc, Mapping) or doc.get("format") != FORMAT:
        raise PolicyError(f"{source}: not a schedule model (expected \"format\": \"{FORMAT}\")")
    if doc.get("version") != VERSION:
        raise PolicyError(f"{source}: schedule model version {doc.get('version')!r} is not supported "
                          f"(this xroute reads version {VERSION})")
    params = doc.get("parameters")
    name = Path(source).stem
    if params is None:
        return RuleKept(name, source)
    if not isinstance(params, Mapping):
        raise PolicyError(f"{source}: \"parameters\" must be an object or null")
    known = {"late_size", "switch_ratio", "patience", "late_repair", "late_budget"}
    unknown = sorted(set(map(str, params)) - known)
    if unknown:
        raise PolicyError(f"{source}: unknown parameter(s) {', '.join(unknown)} (known: {', '.join(sorted(known))})")
    missing = sorted({"late_size", "switch_ratio"} - set(params))
    if missing:
        raise PolicyError(f"{source}: missing parameter(s) {', '.join(missing)}")
    try:
        return SwitchSchedule(**{str(k): v for k, v in params.items()}, name=name, source=source)
    except ValueError as exc:
        raise PolicyError(f"{source}: {exc}") from None


def load_schedule_model(path: str | Path) -> SwitchSchedule | RuleKept:
    """The schedule policy of a model file (PolicyError, one line naming the file, when it is not one)."""
    from xroute.errors import InputError
    from xroute.json_files import read_json

    p = Path(path)
    if not p.exists():
        raise PolicyError(f"schedule model not found: {p}")
    try:
        doc = read_json(p, what="schedule model")
    except InputError as exc:
        raise PolicyError(str(exc)) from None
    return schedule_from_document(doc, str(p))
