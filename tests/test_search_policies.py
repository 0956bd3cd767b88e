"""Search as a net-order policy (rollout, victims, best-of-K), the sequential seam (next_net after every
routed net) and the features that came with it (crossings, guide span, routed_nearby).

The design is a generated one (testcases.generator, 1,200 cells), large enough for regions whose
heuristic order leaves design-rule markers that another order avoids. No shuffled victims order wins
a region of it (nor of any generated design tried, 800 and 1,200 cells, regions of 2 to 4 GCells,
since fixed pins' open line ends are in the footprint), so the tests of the shuffles open regions of
ispd19_test1 (skipped without the contest data)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

from conftest import require_testcase

from xroute.config_schema import ConfigError
from xroute.errors import PolicyError, RouteArgumentError
from xroute.net_order import FEATURE_COLUMNS, BestOfPolicy, RolloutPolicy, VictimsPolicy, builtin_policy, heuristic_order
from xroute.router import route_design

COL = {name: i for i, name in enumerate(FEATURE_COLUMNS)}
WEIGHTS = (0.5, 4.0, 500.0)  # the paper's cost: per um of wire, per via, per marker


@pytest.fixture(scope="module")
def generated(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from xroute.testcases.generator import make_testcase

    return make_testcase(1200, 1, tmp_path_factory.mktemp("search"))


def contest_design() -> Any:
    """ispd19_test1 (its regions of 3 GCells have markers that shuffled victims orders avoid), or a skip."""
    from xroute import load_design

    require_testcase("ispd19_test1")
    return load_design("ispd19_test1")


def contest_boxes(session: Any) -> list[tuple[int, int, int, int]]:
    """Twelve boxes of 3 x 3 GCells in the middle of the design."""
    found = boxes(session)
    return found[len(found) // 2:len(found) // 2 + 12]


def load(folder: Path) -> Any:
    from xroute import load_design

    stem = folder / folder.name  # the generator names the files after their folder
    return load_design(lef=f"{stem}.lef", def_=f"{stem}.def", guide=f"{stem}.guide")


def region_cost(region: Any, dbu: int) -> float:
    m = region.metrics()
    return WEIGHTS[0] * m["wirelength_dbu"] / dbu + WEIGHTS[1] * m["vias"] + WEIGHTS[2] * m["violations"]


def boxes(session: Any, size: int = 3) -> list[tuple[int, int, int, int]]:
    xs, ys = (np.asarray(a) for a in session.gcell_lines)
    out = []
    for gx in range(0, len(xs) - 1, size):
        for gy in range(0, len(ys) - 1, size):
            out.append((int(xs[gx]), int(ys[gy]), int(xs[min(gx + size, len(xs) - 1)]),
                        int(ys[min(gy + size, len(ys) - 1)])))
    return out


@pytest.mark.slow
def test_search_is_never_costlier_than_the_heuristic_and_better_somewhere(generated: Path) -> None:
    from xroute.session import open_session

    design = load(generated)
    session = open_session(design)
    dbu = design.dbu_per_micron
    totals = {"heuristic": 0.0, "rollout": 0.0, "victims": 0.0, "best-of-4": 0.0}
    for box in boxes(session):
        costs = {}
        for name in totals:
            region = session.open_region(box)
            region.route_rest(name, 1, search_budget=8)
            costs[name] = region_cost(region, dbu)
            totals[name] += costs[name]
        # All keep the heuristic's order among their trials and keep the cheapest.
        for name in ("rollout", "victims", "best-of-4"):
            assert costs[name] <= costs["heuristic"] + 1e-9, (box, name, costs)
    # ... and on this design some regions have markers that another order avoids. (Each search saved
    # at least 5% in total while reserved landings cost other nets; at the engine's costs of
    # 2026-11-27 rollout and victims save 3.7%, best-of-4 9.5%.)
    for name in ("rollout", "victims", "best-of-4"):
        assert totals[name] < totals["heuristic"], totals


def victims_of(region: Any) -> set[int]:
    """The nets a routed region's markers leave in violation: of two nets the one routed later
    (a net the region did not route counts as earliest), a one-net marker's own net."""
    nets = np.asarray(region.candidates)[:, COL["net"]]
    position: dict[int, int] = {}
    for p, k in enumerate(region.route_order):
        position.setdefault(int(nets[k]), p)
    out: set[int] = set()
    for m in region.markers():
        a, b = (int(n) for n in m["nets"])
        if a >= 0 and b >= 0 and a != b:
            out.add(a if position.get(a, -1) > position.get(b, -1) else b)
        else:
            out.update(n for n in (a, b) if n >= 0)
    return out


@pytest.mark.slow
def test_victims_routes_the_heuristic_routings_victims_first(generated: Path) -> None:
    """With a budget of 2 the victims search tries two orders: the heuristic's, then the nets its
    markers leave in violation first (both parts in heuristic order), and keeps the cheaper."""
    from xroute.session import open_session

    design = load(generated)
    session = open_session(design)
    dbu = design.dbu_per_micron
    moved = 0
    for box in boxes(session):
        first = session.open_region(box)
        rows = np.asarray(first.candidates)
        if len(rows) < 2:
            continue
        heuristic = [int(k) for k in heuristic_order(rows)]
        for k in heuristic:
            first.route_net(k)
        victims = victims_of(first)
        nets = rows[:, COL["net"]]
        again = [k for k in heuristic if nets[k] in victims] + [k for k in heuristic if nets[k] not in victims]
        second = session.open_region(box)
        for k in again:
            second.route_net(k)
        searched = session.open_region(box)
        searched.route_rest("victims", 1, search_budget=2)
        want = min(region_cost(first, dbu), region_cost(second, dbu))
        assert region_cost(searched, dbu) == pytest.approx(want, abs=1e-9), box
        if region_cost(second, dbu) < region_cost(first, dbu) - 1e-9:
            assert list(searched.route_order) == again, box
            moved += 1
        else:
            assert list(searched.route_order) == heuristic, box
    assert moved > 0  # some region is cheaper with its victims first


@pytest.mark.slow
def test_a_larger_victims_budget_adds_shuffled_trials_and_is_never_costlier() -> None:
    """The victims search's trials for a budget are the first trials for any larger budget (the
    shuffles are seeded by the trial, not the budget), so a larger budget never ends costlier; once
    no new victim appears, the rest of the budget routes the victims first in shuffled orders, so
    some region adopts an order whose victims are not in heuristic rank."""
    from xroute.session import open_session

    design = contest_design()
    session = open_session(design)
    dbu = design.dbu_per_micron
    totals = dict.fromkeys((2, 4, 16), 0.0)
    shuffled = 0
    for box in contest_boxes(session):
        costs = {}
        for budget in totals:
            region = session.open_region(box)
            region.route_rest("victims", 1, search_budget=budget)
            costs[budget] = region_cost(region, dbu)
            totals[budget] += costs[budget]
        assert costs[16] <= costs[4] + 1e-9 and costs[4] <= costs[2] + 1e-9, (box, costs)
        rows = np.asarray(region.candidates)
        if len(rows) < 2:
            continue
        rank = {int(k): p for p, k in enumerate(heuristic_order(rows))}
        order = [int(k) for k in region.route_order]
        # The adopted order is some set first, then the rest, each part in heuristic rank, unless shuffled.
        breaks = sum(rank[a] > rank[b] for a, b in zip(order, order[1:]))
        shuffled += breaks > 1
    assert shuffled > 0
    assert totals[16] < totals[4], totals


def test_a_search_routes_the_order_it_returns(generated: Path) -> None:
    """The region adopts the cheapest trial's routing: replaying its order net by net gives the same cost."""
    from xroute.session import open_session

    design = load(generated)
    session = open_session(design)
    dbu = design.dbu_per_micron
    checked = 0
    for box in boxes(session)[:6]:
        region = session.open_region(box)
        region.route_rest("best-of-4", 3)
        searched = region_cost(region, dbu)
        order = list(region.route_order)
        again = session.open_region(box)
        for i in order:
            again.route_net(int(i))
        assert region_cost(again, dbu) == pytest.approx(searched, abs=1e-9)
        checked += 1
    assert checked == 6


@pytest.mark.parametrize("policy", [RolloutPolicy(4), VictimsPolicy(4), BestOfPolicy(3, seed=2)],
                         ids=["rollout", "victims", "best-of-3"])
@pytest.mark.slow
def test_search_policies_route_the_same_def_for_any_thread_count(generated: Path, policy: Any) -> None:
    defs = []
    for threads in (1, 2):
        design = load(generated)
        result = route_design(design, policy=policy, threads=threads, iterations=2, region_size=3)
        assert result.policy == policy.name
        defs.append(design.def_text())
    assert defs[0] == defs[1]
    heuristic = load(generated)
    route_design(heuristic, iterations=2, region_size=3)
    assert heuristic.def_text() != defs[0]  # the search changed some region's routing


@pytest.mark.slow
def test_the_victims_search_shuffles_from_its_seed() -> None:
    """The seed reaches the victims search's shuffled trials: with a budget large enough to shuffle,
    two seeds adopt different orders in some region, and one seed the same orders twice (the route's
    seed reaches the engine's policy as the random policy's does: test_route)."""
    from xroute.session import open_session

    design = contest_design()
    adopted: dict[int, list[list[int]]] = {}
    for seed in (1, 2, 1):
        session = open_session(design)  # a new session: its regions get the same ids, which seed the shuffles too
        orders = []
        for box in contest_boxes(session):
            region = session.open_region(box)
            region.route_rest("victims", seed, search_budget=16)
            orders.append(list(region.route_order))
        adopted.setdefault(seed, []).append(orders)
    assert adopted[1][0] == adopted[1][1]
    assert adopted[1][0] != adopted[2][0]


def test_search_policy_names_and_bad_budgets() -> None:
    assert builtin_policy("best-of-8").name == "best-of-8" and builtin_policy("best-of-8").k == 8
    assert builtin_policy("bestof", search_budget=5).k == 5
    assert builtin_policy("rollout", search_budget=6).budget == 6
    assert builtin_policy("victims", search_budget=3).budget == 3 and builtin_policy("victims").name == "victims"
    for bad in (0, -3, 2.5, True):
        with pytest.raises(PolicyError, match=r"must be an integer >= 1"):
            RolloutPolicy(bad)
        with pytest.raises(PolicyError, match=r"victims search budget .* must be an integer >= 1"):
            VictimsPolicy(bad)
    with pytest.raises(PolicyError, match=r"best-of-K: K .* must be an integer >= 1, got 0"):
        builtin_policy("best-of-0")
    with pytest.raises(PolicyError, match="unknown policy 'best-of-x'"):
        builtin_policy("best-of-x")


def test_a_budget_above_the_engine_limit_is_one_line_error(generated: Path) -> None:
    from xroute.defaults import MAX_SEARCH_BUDGET

    with pytest.raises(RouteArgumentError, match=rf"rollout search budget must be an integer in 1..{MAX_SEARCH_BUDGET}"):
        route_design(load(generated), policy=RolloutPolicy(MAX_SEARCH_BUDGET + 1), iterations=1)
    with pytest.raises(RouteArgumentError, match=rf"victims search budget must be an integer in 1..{MAX_SEARCH_BUDGET}"):
        route_design(load(generated), policy=VictimsPolicy(MAX_SEARCH_BUDGET + 1), iterations=1)
    from xroute import _engine

    for name in ("rollout", "victims"):
        with pytest.raises(ValueError, match=r"search budget must be in 1\.\.\d+, got 0"):
            _engine.route(load(generated).engine, policy=name, search_budget=0,
                          settings=_engine.RouterSettings(iterations=1))


def test_cli_and_config_reject_bad_budgets(generated: Path, tmp_path: Path) -> None:
    from xroute.cli.app import app
    from xroute.config import load_config

    runner = CliRunner()
    stem = generated / generated.name
    args = ["route", "--lef", f"{stem}.lef", "--def", f"{stem}.def", "--guide", f"{stem}.guide", "--out", str(tmp_path)]
    result = runner.invoke(app, [*args, "--policy", "rollout", "--search-budget", "0"])
    assert result.exit_code == 2 and "--search-budget" in result.output + result.stderr
    result = runner.invoke(app, [*args, "--policy", "best-of-0"])
    assert result.exit_code == 2
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and "best-of-K: K" in lines[0], lines
    cfg = tmp_path / "c.yaml"
    cfg.write_text("policy:\n  policy: rollout\n  search_budget: 0\n")
    with pytest.raises(ConfigError, match=r"c\.yaml:3: .*search_budget"):
        load_config(cfg)
    cfg.write_text("policy:\n  policy: best-of-99999\n")
    with pytest.raises(ConfigError, match=r"c\.yaml:2: .*K must be in 1\.\."):
        load_config(cfg)
    cfg.write_text("policy:\n  policy: best-of-6\n  search_budget: 9\n")
    assert load_config(cfg).policy.policy == "best-of-6" and load_config(cfg).policy.search_budget == 9


def test_cli_routes_with_the_victims_search(generated: Path, tmp_path: Path) -> None:
    import json

    from xroute.cli.app import app
    from xroute.config import load_config

    stem = generated / generated.name
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["route", "--lef", f"{stem}.lef", "--def", f"{stem}.def", "--guide", f"{stem}.guide",
                                      "--out", str(out), "--policy", "victims", "--search-budget", "3",
                                      "--iterations", "1", "--quiet"])
    assert result.exit_code == 0, result.output
    metrics = json.loads(next(out.glob("*.metrics.json")).read_text())
    assert metrics["policy"] == "victims" and metrics["final"]["open_nets"] == 0
    cfg = tmp_path / "c.yaml"
    cfg.write_text("policy:\n  policy: victims\n  search_budget: 2\n")
    assert load_config(cfg).policy.policy == "victims"


class Stepper:
    """A sequential policy: records each call and picks the heuristic's first unrouted net."""

    name = "stepper"

    def __init__(self) -> None:
        self.calls: list[tuple[int, int, np.ndarray]] = []

    def next_net(self, region: dict[str, Any], features: np.ndarray) -> int:
        self.calls.append((int(region["iteration"]), int(region["region"]), features.copy()))
        return int(heuristic_order(features)[0])


def test_the_sequential_seam_is_asked_once_per_net_with_shrinking_candidates(generated: Path) -> None:
    stepper = Stepper()
    design = load(generated)
    result = route_design(design, policy=stepper, iterations=1, region_size=3, threads=2)
    assert result.policy_calls == len(stepper.calls) == result.iterations[0].net_routes
    by_region: dict[tuple[int, int], list[np.ndarray]] = {}
    for it, reg, rows in stepper.calls:
        by_region.setdefault((it, reg), []).append(rows)
    nearby_grew = False
    for calls in by_region.values():
        n = len(calls[0])
        assert [len(rows) for rows in calls] == list(range(n, 0, -1))
        assert calls[0][:, COL["routed_nearby"]].sum() == 0  # nothing routed yet
        for before, after in zip(calls, calls[1:]):
            routed = set(before[:, COL["net"]]) - set(after[:, COL["net"]])
            assert len(routed) == 1  # exactly the net it chose is gone
            common = np.isin(after[:, COL["net"]], before[:, COL["net"]])
            prev = {int(r[COL["net"]]): int(r[COL["routed_nearby"]]) for r in before}
            now = after[common]
            assert all(int(r[COL["routed_nearby"]]) >= prev[int(r[COL["net"]])] for r in now)
            nearby_grew |= any(int(r[COL["routed_nearby"]]) > prev[int(r[COL["net"]])] for r in now)
    assert nearby_grew  # the features are updated as nets are routed
    # Choosing the heuristic's first net each time is the heuristic order: the same routing.
    heuristic = load(generated)
    route_design(heuristic, iterations=1, region_size=3)
    assert heuristic.def_text() == design.def_text()


def test_a_sequential_policy_index_out_of_range_is_a_policy_error(generated: Path) -> None:
    class Bad:
        name = "bad"

        def next_net(self, region: dict[str, Any], features: np.ndarray) -> int:
            return len(features)

    with pytest.raises(PolicyError, match=r"net-order policy 'bad': next_net returned \d+, outside range\(\d+\)"):
        route_design(load(generated), policy=Bad(), iterations=1)


def test_crossings_and_guide_span_in_the_features(generated: Path) -> None:
    from xroute.session import open_session

    design = load(generated)
    session = open_session(design)
    saw_crossing_only = False
    for box in boxes(session, size=1)[:40]:
        region = session.open_region(box)
        rows = region.candidates
        if not len(rows):
            continue
        c = {name: rows[:, i] for name, i in COL.items()}
        assert (c["crossings"] == c["terminals"] - c["pins"]).all()
        assert ((c["guide_xlo"] >= box[0]) & (c["guide_ylo"] >= box[1]) & (c["guide_xhi"] <= box[2])
                & (c["guide_yhi"] <= box[3])).all()
        assert ((c["guide_xlo"] <= c["guide_xhi"]) & (c["guide_ylo"] <= c["guide_yhi"])).all()
        saw_crossing_only |= bool(((c["pins"] == 0) & (c["crossings"] >= 2)).any())
    assert saw_crossing_only  # nets that only cross a region now show how


def test_a_budget_of_one_is_the_heuristic(generated: Path) -> None:
    """One trial routing per region is the heuristic's order alone: the same DEF."""
    heuristic = load(generated)
    route_design(heuristic, iterations=1, region_size=3)
    for policy in (RolloutPolicy(1), VictimsPolicy(1), BestOfPolicy(1)):
        design = load(generated)
        route_design(design, policy=policy, iterations=1, region_size=3)
        assert design.def_text() == heuristic.def_text(), policy


def test_a_policy_file_with_next_net_is_sequential(generated: Path, tmp_path: Path) -> None:
    from xroute.policies.registry import get_policy
    from xroute.net_order import CallableSequentialPolicy

    path = tmp_path / "last_first.py"
    path.write_text(
        "NAME = 'last-first'\n"
        "CALLS = []\n"
        "def next_net(region, features):\n"
        "    CALLS.append(len(features))\n"
        "    return len(features) - 1\n"
    )
    pol = get_policy(str(path))
    assert isinstance(pol, CallableSequentialPolicy) and pol.name == "last-first"
    design = load(generated)
    result = route_design(design, policy=pol, iterations=1, region_size=3)
    assert result.policy == "last-first"
    assert result.policy_calls == result.iterations[0].net_routes > 0
