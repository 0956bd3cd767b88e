"""Training a schedule model (xroute.policies.schedule_train) on generated designs and using it on another.

The designs come from our own generator (800 cells, seeds 1 and 2 to train, seed 4 held out) and
are routed with an iteration limit of 3 at region size 1, where the rule's flow still leaves
violations (at the default size 10 these designs route clean in their first pass: nothing to learn):
the model trained in well under a minute (four candidates, two designs) on two of them must end the
held-out design at a lower cost (the paper's: 0.5 per um + 4 per via + 500 per violation) than the
rule's flow.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from xroute.errors import XrouteError
from xroute.schedule_model import SwitchSchedule, load_schedule_model
from xroute.policies.schedule_train import RunFigures, TrainCase, default_grid, feasible, score, train

# Slow set: trains schedule models (many routes per test).
pytestmark = pytest.mark.slow

ITERATIONS = 3
REGION_SIZE = 1  # GCells: the base every run shares (the rule's flow, and the models until they switch)
CELLS = 800


def case(tmp: Path, seed: int) -> TrainCase:
    from xroute.testcases.generator import make_testcase

    folder = make_testcase(CELLS, seed, tmp / f"gen{seed}")
    name = folder.name
    return TrainCase(name, (str(folder / f"{name}.lef"),), str(folder / f"{name}.def"), str(folder / f"{name}.guide"))


def cost(result: Any) -> float:
    last = result.iterations[-1]
    return 0.5 * last.wirelength_um + 4 * last.vias + 500 * last.violations


def test_the_grid_has_no_candidate_twice_and_keeps_the_rules_size() -> None:
    grid = default_grid()
    assert len({tuple(sorted(c.parameters().items())) for c in grid}) == len(grid) == 20
    assert {c.late_size for c in grid} == {5, 10} and {c.late_budget for c in grid} == {0, 4}


def test_a_run_that_ends_like_the_default_scores_zero_whatever_its_time() -> None:
    ref = RunFigures(violations=9, opens=0, wirelength_um=100.0, vias=1000, cpu_s=10.0, iterations=10)
    assert score(RunFigures(9, 0, 100.0, 1000, 7.0, 10), ref, 1.0) == 0.0  # same routing: the time is noise
    assert score(RunFigures(9, 0, 100.0, 1000, 7.0, 8), ref, 1.0) < 0  # a stop: two iterations fewer


def test_score_and_band() -> None:
    ref = RunFigures(violations=9, opens=0, wirelength_um=100.0, vias=1000, cpu_s=10.0, iterations=10)
    better = RunFigures(violations=4, opens=0, wirelength_um=100.4, vias=1004, cpu_s=10.0, iterations=10)
    assert score(better, ref, 1.0) == pytest.approx(-0.6931, abs=1e-4)  # log(5/10)
    assert score(RunFigures(9, 0, 100.0, 1000, 5.0, 9), ref, 1.0) == pytest.approx(-0.6931, abs=1e-4)
    assert feasible(better, ref, 0.005)
    assert not feasible(RunFigures(4, 0, 100.6, 1000, 10.0, 10), ref, 0.005)  # wire +0.6%
    assert not feasible(RunFigures(4, 1, 100.0, 1000, 10.0, 10), ref, 0.005)  # an open net


def test_a_model_trained_on_two_designs_beats_the_default_on_a_third(tmp_path: Path) -> None:
    from xroute.design import load_design
    from xroute.router import route_design

    grid = [SwitchSchedule(5, 1.0), SwitchSchedule(10, 0.3, patience=3), SwitchSchedule(10, 1.0, late_budget=4),
            SwitchSchedule(5, 0.3, late_budget=4)]
    # The cost this test judges by does not count time: trained with time_weight 0 to match it.
    doc = train([case(tmp_path, 1), case(tmp_path, 2)], tmp_path / "train", grid=grid, jobs=2, time_weight=0.0,
                route_args=["--iterations", str(ITERATIONS), "--region-size", str(REGION_SIZE)])
    assert doc["parameters"] is not None, json.dumps(doc["candidates"])[:2000]
    assert len(doc["candidates"]) == len(grid) and doc["chosen_score"] < -0.05
    model_file = tmp_path / "schedule.json"
    model_file.write_text(json.dumps(doc))
    model = load_schedule_model(model_file)
    assert isinstance(model, SwitchSchedule)

    held_out = case(tmp_path, 4)
    plain = load_design(lef=list(held_out.lef), def_=held_out.def_file, guide=held_out.guide)
    default = route_design(plain, iterations=ITERATIONS, region_size=REGION_SIZE)
    learned_design = load_design(lef=list(held_out.lef), def_=held_out.def_file, guide=held_out.guide)
    learned = route_design(learned_design, iterations=ITERATIONS, region_size=REGION_SIZE, schedule_policy=model)
    assert default.iterations[-1].violations > 0, "the held-out design must leave violations to the default"
    assert cost(learned) < cost(default), (model.parameters(), cost(learned), cost(default))


def test_a_failing_training_run_is_one_error_naming_the_design(tmp_path: Path) -> None:
    bad = TrainCase("broken", (str(tmp_path / "missing.lef"),), str(tmp_path / "missing.def"), None)
    with pytest.raises(XrouteError, match="training run on broken failed: .*missing"):
        train([bad], tmp_path / "train", grid=[SwitchSchedule(5, 1.0)], jobs=1)
