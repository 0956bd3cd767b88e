"""The engine's structure as Python sees it: the marker types follow the C++ enum (one count,
held by a static_assert) and match the library's list and the reports' keys; the router's
settings are bound struct fields with the engine's defaults, not string keys."""

from __future__ import annotations

import pytest

from xroute import _engine
from xroute.design import load_design
from xroute.router import VIOLATION_TYPES
from xroute.testcases import DEMO


def test_marker_types_are_the_enum_in_order() -> None:
    types = _engine.MARKER_TYPES
    assert len(types) == len(set(types)) == 8
    assert types == VIOLATION_TYPES


def test_reports_count_every_marker_type() -> None:
    out = _engine.route(load_design(DEMO).engine, settings=_engine.RouterSettings(iterations=1))
    assert tuple(out["iterations"][0]["violations_by_type"]) == _engine.MARKER_TYPES


def test_router_settings_defaults_are_the_engines() -> None:
    s = _engine.RouterSettings()
    d = _engine.DEFAULTS
    assert (s.region_size, s.iterations, s.threads) == (d["region_size"], d["iterations"], d["threads"])
    assert (s.repair_rounds, s.marker_penalty, s.history_penalty) == (
        d["repair_rounds"], d["marker_penalty"], d["history_penalty"])
    assert isinstance(s.costs, _engine.MazeCosts)
    assert _engine.RouterSettings(repair_rounds=2, costs=_engine.MazeCosts(via_cost=7)).costs.via_cost == 7


def test_router_settings_reject_unknown_fields() -> None:
    with pytest.raises(TypeError):
        _engine.RouterSettings(no_such_setting=1)  # type: ignore[call-arg]


def test_settings_structs_are_bound_field_by_field() -> None:
    """MazeCosts, RouterSettings and IterationPlan: keyword-only constructors over the bound fields,
    changed copies, their fields as a dict, equality by value, copies and pickling."""
    import copy
    import pickle

    plan = _engine.IterationPlan(region_size=4, use_penalty=9)
    assert plan.to_dict() == {"region_size": 4, "offset": 0, "repair_rounds": 0,
                              "marker_penalty": _engine.DEFAULTS["marker_penalty"],
                              "history_penalty": _engine.DEFAULTS["history_penalty"], "use_penalty": 9,
                              "stop": False, "search_budget": 0}
    changed = plan.replace(stop=True)
    assert changed.stop and not plan.stop and changed != plan and changed.replace(stop=False) == plan
    s = _engine.RouterSettings(threads=3, costs=_engine.MazeCosts(via_cost=7))
    for twin in (pickle.loads(pickle.dumps(s)), copy.deepcopy(s)):
        assert twin == s and twin is not s
    twin.costs.via_cost = 8
    assert s.costs.via_cost == 7 and twin != s
    with pytest.raises(TypeError, match="IterationPlan has no field 'colour'"):
        plan.replace(colour=1)
    with pytest.raises(TypeError):
        _engine.MazeCosts(1200)  # keywords only


def test_a_plan_out_of_the_engines_limits_is_refused_not_clamped() -> None:
    """The engine's own check of a planner's plan (the library names the schedule policy before it)."""
    db = load_design(DEMO).engine
    with pytest.raises(ValueError, match=r"plan: offset must be in 0\.\.1, got 5"):
        _engine.route(db, planner=lambda history, rule: rule.replace(region_size=2, offset=5))


def test_route_checks_the_settings_fields() -> None:
    db = load_design(DEMO).engine
    with pytest.raises(ValueError, match=r"region_size must be in 0\.\.1000 \(0: auto\)"):
        _engine.route(db, settings=_engine.RouterSettings(region_size=-1))
    with pytest.raises(ValueError, match="iterations must be in 1"):
        _engine.route(db, settings=_engine.RouterSettings(iterations=0))


# A generated design that, at region size 2, ends its first two iterations with markers (15, 21); the
# demo routes clean in its first pass.
MARKED = "standin_marked"


def _search_budgets(**settings: int) -> list[tuple[int, int]]:
    """(violations, the plan's search budget) per iteration of MARKED routed at region size 2 with these settings."""
    s = _engine.RouterSettings(region_size=2, threads=2)
    for key, value in settings.items():
        setattr(s, key, value)
    out = _engine.route(load_design(MARKED).engine, settings=s)
    return [(r["violations"], r["plan"]["search_budget"]) for r in out["iterations"]]


def test_the_late_search_starts_once_a_check_leaves_few_markers(testcase) -> None:
    testcase(MARKED)
    late = _search_budgets(late_search_markers=50, late_search_budget=3)
    assert len(late) >= 3
    assert late[0][1] == 0  # iteration 0 routes every net with the run's policy
    for (before, _), (_, budget) in zip(late, late[1:]):
        assert budget == (3 if 0 < before <= 50 else 0)
    assert any(budget == 3 for _, budget in late)  # the design gets there: the rule is exercised
    assert all(budget == 0 for _, budget in _search_budgets(late_search_budget=0))


def test_the_late_search_leaves_a_python_policy_alone(testcase) -> None:
    testcase(MARKED)
    s = _engine.RouterSettings(iterations=4, region_size=2)
    s.late_search_markers = 10**6
    out = _engine.route(load_design(MARKED).engine, settings=s, policy_fn=lambda region, features: list(
        range(len(features))))
    assert len(out["iterations"]) > 1  # markers were left: the rule would have searched
    assert [r["plan"]["search_budget"] for r in out["iterations"]] == [0] * len(out["iterations"])
