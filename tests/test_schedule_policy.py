"""The iteration seam (xroute.schedule): a schedule policy chooses each iteration's plan.

Routed on ispd19_sample4 (or its generated stand-in) at region size 1, where the flow runs several
iterations with markers left, so that a plan that changes anything changes the routing.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from conftest import pick, require_testcase
from xroute.errors import PolicyError
from xroute.policies import get_schedule_policy
from xroute.router import route_design
from xroute.schedule import CallableSchedule, IterationPlan, IterationReport, RuleSchedule

SAMPLE4 = pick("ispd19_sample4")
# A generated design where the victims search changes the routing at region size 2 (on
# ispd18_sample at region size 1 it stopped doing so once fixed pins' open line ends across the
# tracks were in the footprint, as on ispd19_sample4 before).
SEARCHED = "standin_marked"
SIZE = 1  # GCells: several iterations with markers on the sample


def routed(size: int = SIZE, name: str = SAMPLE4, **kw: Any) -> tuple[str, Any]:
    """(DEF text, RouteResult) of the sample ``name`` routed at region size ``size`` with ``kw``."""
    require_testcase(name)
    from xroute.design import load_design

    design = load_design(name)
    result = route_design(design, region_size=size, **kw)
    return design.def_text(), result


def figures(reports: Any) -> list[dict[str, Any]]:
    """The reports without their wall times (which differ from run to run)."""
    return [{k: v for k, v in r.to_dict().items() if k not in ("seconds", "stage_seconds")} for r in reports]


@pytest.fixture(scope="module")
def default() -> tuple[str, Any]:
    text, result = routed()
    assert len(result.iterations) >= 3, "the test needs a routing of three iterations or more"
    return text, result


@pytest.mark.slow
def test_the_rule_and_a_policy_that_keeps_it_route_as_without_one(default: tuple[str, Any]) -> None:
    """RuleSchedule is not even called (the engine runs its rule); a Python policy returning the rule,
    or None, is called before every iteration and routes the same DEF byte for byte."""
    seen: list[tuple[int, IterationPlan]] = []

    def keep(history: list[IterationReport], rule: IterationPlan) -> None:
        seen.append((len(history), rule))

    assert routed(schedule_policy=RuleSchedule())[0] == default[0]
    text, result = routed(schedule_policy=CallableSchedule(keep, name="keep"))
    assert text == default[0]
    assert [n for n, _ in seen] == list(range(len(default[1].iterations)))
    assert result.schedule_policy == "keep"


def test_the_policy_sees_the_reports_so_far_and_the_rules_plan(default: tuple[str, Any]) -> None:
    """history: the reports of the iterations done, as the result reports them; rule: the region
    size, the offset shifted by a third of a region, and the other-net weight growing by its step."""
    calls: list[tuple[list[IterationReport], IterationPlan]] = []
    routed(schedule_policy=CallableSchedule(lambda h, r: calls.append((list(h), r)), name="spy"))
    reports = default[1].iterations
    for i, (history, rule) in enumerate(calls):
        assert figures(history) == figures(reports[:i])
        assert (rule.region_size, rule.offset, rule.stop) == (SIZE, 0, False)
        assert rule.use_penalty == calls[0][1].use_penalty + i * (calls[1][1].use_penalty - calls[0][1].use_penalty)
    assert calls[1][1].use_penalty > calls[0][1].use_penalty


def test_a_plan_of_region_sizes_routes_as_the_same_static_schedule() -> None:
    """A policy that asks for size 3 after the first iteration routes exactly as --schedule with the
    same steps: the plan's partition reaches the engine."""
    steps = [(SIZE, 0), (3, 1), (3, 2), (3, 0), (3, 1), (3, 2), (3, 0), (3, 1), (3, 2), (3, 0)]
    text, result = routed(schedule_policy=CallableSchedule(
        lambda h, r: {"region_size": steps[len(h)][0], "offset": steps[len(h)][1]}, name="steps"))
    static, _ = routed(schedule=steps)
    assert text == static
    assert [(it.region_size, it.offset) for it in result.iterations] == steps[: len(result.iterations)]


def test_weights_and_repair_rounds_reach_the_engine() -> None:
    """Each of the plan's weights changes the routing when it changes, at region size 2: the marker and
    history weights from the second iteration on, the other-net weight and two repair rounds in
    every iteration (at size 1 the sample's later regions have no other-net conflict or region
    marker for them to act on, and since a rip-up no longer joins again what its kept routing
    joins, the markers left there do not move for these weights either)."""
    at_two = routed(size=2)[0]
    for change in ({"marker_penalty": 0}, {"history_penalty": 10**7}):
        policy = CallableSchedule(lambda h, r, change=change: change if h else None, name="weights")
        assert routed(size=2, schedule_policy=policy)[0] != at_two, change
    no_use = CallableSchedule(lambda h, r: {"use_penalty": 0}, name="no-use")
    repair = CallableSchedule(lambda h, r: {"repair_rounds": 2}, name="repair")
    assert routed(size=2, schedule_policy=no_use)[0] != at_two
    assert routed(size=2, schedule_policy=repair)[0] != at_two


@pytest.mark.slow
def test_a_search_budget_in_every_plan_routes_as_the_victims_policy() -> None:
    """search_budget B in every iteration's plan orders each region's nets by the victims search with
    budget B: the same DEF byte for byte as --policy victims --search-budget B (on SEARCHED at region
    size 2, where that search changes the routing); asked from the second iteration on, the first
    iteration is the heuristic's."""
    from xroute.net_order import VictimsPolicy

    heuristic, plain = routed(size=2, name=SEARCHED)
    victims, _ = routed(size=2, name=SEARCHED, policy=VictimsPolicy(3))
    assert victims != heuristic
    search = CallableSchedule(lambda h, r: {"search_budget": 3}, name="search")
    text, result = routed(size=2, name=SEARCHED, schedule_policy=search)
    assert text == victims
    assert all(it.plan.search_budget == 3 for it in result.iterations)
    late = CallableSchedule(lambda h, r: {"search_budget": 3} if h else None, name="late")
    _, late_result = routed(size=2, name=SEARCHED, schedule_policy=late)
    assert figures(late_result.iterations[:1]) == figures(plain.iterations[:1])
    assert [it.plan.search_budget for it in late_result.iterations][:2] == [0, 3]


def test_stop_ends_the_run_before_the_iteration(default: tuple[str, Any]) -> None:
    text, result = routed(schedule_policy=CallableSchedule(lambda h, r: {"stop": len(h) == 2}, name="two"))
    assert len(result.iterations) == 2
    assert figures(result.iterations) == figures(default[1].iterations[:2])


@pytest.mark.parametrize("answer, message", [
    ({"region_size": 0}, "region_size must be in 1.."),
    ({"offset": 5}, "offset must be in 0..0"),
    ({"repair_rounds": -1}, "repair_rounds must be in 0.."),
    ({"use_penalty": 2.5}, "use_penalty must be an integer"),
    ({"search_budget": -1}, "search_budget must be in 0..1024"),
    ({"colour": 1}, "unknown key(s) colour"),
    ([1, 2], "must return an IterationPlan, a dict or None, got list"),
    ({"stop": True}, "the first iteration cannot stop the run"),
])
def test_bad_plans_are_one_error_naming_the_policy(answer: Any, message: str) -> None:
    with pytest.raises(PolicyError, match="schedule policy 'bad'") as info:
        routed(schedule_policy=CallableSchedule(lambda h, r: answer, name="bad"))
    assert message in str(info.value)


def test_get_schedule_policy_loads_a_file_and_refuses_others(tmp_path: Path) -> None:
    assert isinstance(get_schedule_policy(None), RuleSchedule) and isinstance(get_schedule_policy("rule"), RuleSchedule)
    good = tmp_path / "coarse_fine.py"
    good.write_text("NAME = 'coarse-fine'\n\ndef plan(history, rule):\n    return {'region_size': 3} if history else None\n")
    policy = get_schedule_policy(str(good))
    assert policy.name == "coarse-fine"
    with pytest.raises(PolicyError, match="unknown schedule policy 'fast'"):
        get_schedule_policy("fast")
    empty = tmp_path / "empty.py"
    empty.write_text("X = 1\n")
    with pytest.raises(PolicyError, match="defines no function plan"):
        get_schedule_policy(str(empty))


@pytest.mark.slow
def test_cli_routes_with_a_policy_file_and_records_it(runner, tmp_path: Path) -> None:
    """`xroute route --schedule-policy FILE` (and the config's router.schedule_policy, relative to the
    config file): the metrics name the policy and its plans; a policy that raises is one error line
    with its file and line, exit 2, and no outputs."""
    from xroute.cli.app import app

    require_testcase(SAMPLE4)
    policy = tmp_path / "fine.py"
    policy.write_text("NAME = 'fine'\n\ndef plan(history, rule):\n    return {'region_size': 2} if history else None\n")
    out = tmp_path / "run"
    res = runner.invoke(app, ["route", SAMPLE4, "--region-size", "1", "--schedule-policy", str(policy),
                              "--out", str(out), "--quiet"])
    assert res.exit_code == 0, res.output
    metrics = json.loads(next(out.glob("*.metrics.json")).read_text())
    assert metrics["settings"]["schedule_policy"] == "fine"
    assert [it["region_size"] for it in metrics["iterations"]][:2] == [1, 2]

    cfg = tmp_path / "cfg.yaml"
    cfg.write_text("router:\n  schedule_policy: fine.py\n")
    out2 = tmp_path / "run2"
    res = runner.invoke(app, ["route", SAMPLE4, "--region-size", "1", "--config", str(cfg), "--out", str(out2),
                              "--quiet"])
    assert res.exit_code == 0, res.output
    assert json.loads(next(out2.glob("*.metrics.json")).read_text())["settings"]["schedule_policy"] == "fine"

    broken = tmp_path / "broken.py"
    broken.write_text("def plan(history, rule):\n    if history:\n        raise RuntimeError('no plan')\n")
    out3 = tmp_path / "run3"
    res = runner.invoke(app, ["route", SAMPLE4, "--region-size", "1", "--schedule-policy", str(broken),
                              "--out", str(out3), "--quiet"])
    assert res.exit_code == 2
    lines = [line for line in res.output.splitlines() if line.strip()]
    assert len(lines) == 1 and f"{broken}:3" in lines[0] and "RuntimeError: no plan" in lines[0], res.output
    assert not list(out3.glob("*.routed.def"))


def test_config_refuses_a_missing_schedule_policy_file(tmp_path: Path) -> None:
    from xroute.config import ConfigError, load_config

    cfg = tmp_path / "cfg.yaml"
    cfg.write_text("router:\n  schedule_policy: nowhere.py\n")
    with pytest.raises(ConfigError, match=r"cfg.yaml:2: .*schedule_policy: schedule policy file not found"):
        load_config(cfg)


def test_the_metrics_log_every_iterations_plan_as_transitions(tmp_path: Path) -> None:
    """A run's metrics JSON records each iteration's plan; logged_transitions gives, per iteration,
    the reports before it, the plan it ran (the policy's, here size 2 after the first) and its report."""
    from xroute.design import load_design
    from xroute.outputs import write_route_outputs
    from xroute.schedule import logged_transitions

    require_testcase(SAMPLE4)
    design = load_design(SAMPLE4)
    policy = CallableSchedule(lambda h, r: {"region_size": 2, "offset": 0} if h else None, name="two")
    result = route_design(design, region_size=SIZE, schedule_policy=policy)
    outputs = write_route_outputs(design, result, tmp_path)
    metrics = json.loads(outputs.metrics_path.read_text())
    steps = logged_transitions(metrics)
    assert len(steps) == len(result.iterations) >= 2
    assert [(t.plan.region_size, t.plan.offset) for t in steps] == [(SIZE, 0)] + [(2, 0)] * (len(steps) - 1)
    for i, t in enumerate(steps):
        assert figures(t.history) == figures(result.iterations[:i])
        assert t.report.violations == result.iterations[i].violations and t.design == design.name
    old = dict(metrics, iterations=[{k: v for k, v in it.items() if k != "plan"} for it in metrics["iterations"]])
    with pytest.raises(ValueError, match="do not record their plans"):
        logged_transitions(old)


@pytest.mark.slow
def test_a_policy_file_may_decide_the_search_region_by_region(tmp_path: Path) -> None:
    """NEEDS_REGION = True lends each region to a policy file's order(): one that runs the victims
    search in every region routes as --policy victims (on SEARCHED at region size 2, where that
    search changes the routing); the example that searches only regions with three nets or more
    from the second iteration on routes without opens."""
    from xroute.net_order import VictimsPolicy
    from xroute.policies import load_policy_file

    always = tmp_path / "always.py"
    always.write_text("from xroute.net_order import heuristic_order\nNEEDS_REGION = True\n\n"
                      "def order(region, features):\n"
                      "    region['engine_region'].route_rest('victims', search_budget=4)\n"
                      "    return heuristic_order(features)\n")
    policy = load_policy_file(always)
    assert policy.needs_region
    text, _ = routed(size=2, name=SEARCHED, policy=policy)
    assert text == routed(size=2, name=SEARCHED, policy=VictimsPolicy(4))[0] != routed(size=2, name=SEARCHED)[0]
    example = load_policy_file(Path(__file__).resolve().parent.parent / "examples" / "region_search.py")
    assert example.needs_region and example.name == "region-search"
    from xroute.design import load_design

    design = load_design(SAMPLE4)
    route_design(design, region_size=2, policy=example)
    assert design.engine.check_connectivity()["open_nets"] == 0
