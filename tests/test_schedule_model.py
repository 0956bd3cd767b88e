"""Schedule models (xroute.schedule_model): the switch rule's plans, its file format and its errors.

The plans are checked on drawn histories (no routing); one route on a generated design checks that
a model file reaches the engine from the command line and is recorded in the metrics.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from xroute.errors import PolicyError
from xroute.policies import get_schedule_policy
from xroute.schedule import IterationPlan, IterationReport
from xroute.schedule_model import RuleKept, SwitchSchedule, load_schedule_model, model_document

RULE = IterationPlan(region_size=10, offset=0, repair_rounds=0, marker_penalty=4000, history_penalty=1000,
                     use_penalty=2000)


def history(*violations: int) -> list[IterationReport]:
    return [IterationReport(iteration=i, region_size=10, offset=0, regions=4, net_routes=10, unreached=0,
                            wirelength_dbu=1000, wirelength_um=1.0, vias=10, violations=v)
            for i, v in enumerate(violations)]


def test_the_rule_runs_until_the_violations_fall_to_the_switch_ratio() -> None:
    s = SwitchSchedule(late_size=5, switch_ratio=0.1)
    assert s.plan([], RULE) == RULE  # the first iteration
    assert s.plan(history(1000), RULE) == RULE
    assert s.plan(history(1000, 101), RULE) == RULE
    switched = s.plan(history(1000, 101, 100), RULE)
    assert (switched.region_size, switched.repair_rounds, switched.stop) == (5, 0, False)
    assert switched.marker_penalty == RULE.marker_penalty  # the weights stay the rule's
    # Once switched it stays switched, even when the count rises again.
    assert s.plan(history(1000, 100, 150), RULE).region_size == 5


def test_switched_offsets_shift_by_a_third_of_a_region_like_the_rule() -> None:
    s = SwitchSchedule(late_size=6, switch_ratio=1.0)
    offsets = [s.plan(history(*([9] * n)), RULE).offset for n in range(1, 7)]
    assert offsets == [2, 4, 0, 2, 4, 0]  # iteration n: (n % 3) * 6 // 3


def test_late_repair_rounds_apply_once_switched() -> None:
    s = SwitchSchedule(late_size=7, switch_ratio=0.5, late_repair=2)
    assert s.plan(history(100, 80), RULE).repair_rounds == 0
    assert s.plan(history(100, 40), RULE).repair_rounds == 2


def test_a_late_budget_asks_for_the_victims_search_once_switched() -> None:
    s = SwitchSchedule(late_size=10, switch_ratio=0.5, late_budget=4)
    assert s.plan(history(100, 80), RULE).search_budget == 0
    late = s.plan(history(100, 40), RULE)
    assert (late.search_budget, late.region_size) == (4, 10)


def test_patience_stops_a_run_without_a_new_lowest_count() -> None:
    s = SwitchSchedule(late_size=5, switch_ratio=0.0, patience=2)
    assert not s.plan(history(100, 50), RULE).stop
    assert not s.plan(history(100, 50, 50), RULE).stop  # one iteration without progress
    assert s.plan(history(100, 50, 50, 51), RULE).stop  # two
    assert not s.plan(history(100, 50, 50, 49), RULE).stop  # a new lowest count
    assert not SwitchSchedule(5, 0.0, patience=0).plan(history(9, 9, 9, 9, 9), RULE).stop  # 0: never


def test_a_zero_ratio_never_switches_before_zero_violations() -> None:
    s = SwitchSchedule(late_size=5, switch_ratio=0.0)
    assert s.plan(history(100, 1), RULE) == RULE
    assert s.plan(history(100, 0), RULE).region_size == 5


@pytest.mark.parametrize("params,message", [
    ({"late_size": 0, "switch_ratio": 0.5}, "late_size must be an integer in 1..30"),
    ({"late_size": 5.0, "switch_ratio": 0.5}, "late_size must be an integer"),
    ({"late_size": 5, "switch_ratio": float("nan")}, "switch_ratio must be a number in 0..1"),
    ({"late_size": 5, "switch_ratio": 1.5}, "switch_ratio must be a number in 0..1"),
    ({"late_size": 5, "switch_ratio": True}, "switch_ratio must be a number in 0..1"),
    ({"late_size": 5, "switch_ratio": 0.5, "patience": -1}, "patience must be an integer in 0..100"),
    ({"late_size": 5, "switch_ratio": 0.5, "late_budget": 65}, "late_budget must be an integer in 0..64"),
    ({"late_size": 5, "switch_ratio": 0.5, "size": 3}, "unknown parameter(s) size"),
    ({"late_size": 5}, "missing parameter(s) switch_ratio"),
])
def test_bad_parameters_are_one_error_naming_the_file(tmp_path: Path, params: dict, message: str) -> None:
    f = tmp_path / "m.json"
    f.write_text(json.dumps({"format": "xroute-schedule-switch", "version": 1, "parameters": params}))
    with pytest.raises(PolicyError) as err:
        load_schedule_model(f)
    assert str(f) in str(err.value) and message in str(err.value)


@pytest.mark.parametrize("text,message", [
    ("{", ":1: schedule model is not valid JSON"),
    ("[1, 2]", "not a schedule model"),
    ('{"format": "xroute-schedule-switch", "version": 7, "parameters": null}', "version 7 is not supported"),
    ('{"format": "xroute-schedule-switch", "version": 1, "parameters": [5]}', "must be an object or null"),
    ("[" * 100000 + "]" * 100000, "nested too deeply"),
])
def test_files_that_are_not_models_are_refused(tmp_path: Path, text: str, message: str) -> None:
    f = tmp_path / "m.json"
    f.write_text(text)
    with pytest.raises(PolicyError, match="m.json") as err:
        load_schedule_model(f)
    assert message in str(err.value)


def test_a_model_file_round_trips_and_null_parameters_keep_the_rule(tmp_path: Path) -> None:
    s = SwitchSchedule(late_size=5, switch_ratio=0.3, patience=3)
    f = tmp_path / "learned.json"
    f.write_text(json.dumps(model_document(s, trained_on=["x"])))
    loaded = get_schedule_policy(str(f))
    assert isinstance(loaded, SwitchSchedule) and loaded.parameters() == s.parameters()
    assert loaded.name == "learned"
    f.write_text(json.dumps(model_document(None)))
    kept = get_schedule_policy(str(f))
    assert isinstance(kept, RuleKept) and kept.plan(history(5, 4), RULE) == RULE
    with pytest.raises(PolicyError, match="schedule model not found"):
        get_schedule_policy(str(tmp_path / "missing.json"))


def test_cli_routes_with_a_model_file_and_records_it(runner: Any, tmp_path: Path) -> None:
    """On a generated design: the model's plans are the ones the metrics log (switched to size 3 once
    the violations halved), and its name is the run's schedule policy."""
    from xroute.cli.app import app
    from xroute.testcases.generator import make_testcase

    folder = make_testcase(400, 3, tmp_path / "gen")  # at region size 2: 7 violations, then 1, then 0
    model = tmp_path / "half.json"
    model.write_text(json.dumps(model_document(SwitchSchedule(late_size=3, switch_ratio=0.5))))
    out = tmp_path / "out"
    args = ["route", "--lef", str(folder / "gen.lef"), "--def", str(folder / "gen.def"), "--guide",
            str(folder / "gen.guide"), "--quiet", "--region-size", "2", "--out", str(out),
            "--schedule-policy", str(model)]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    metrics = json.loads((out / "gen.metrics.json").read_text())
    assert metrics["settings"]["schedule_policy"] == "half"
    its = metrics["iterations"]
    assert len(its) >= 3, "the test needs three iterations or more"
    first = its[0]["violations"]
    for i, it in enumerate(its[1:], start=1):
        switched = min(x["violations"] for x in its[:i]) <= 0.5 * first
        assert it["region_size"] == (3 if switched else 2), (i, it["region_size"])
    assert any(it["region_size"] == 3 for it in its)
