"""pair_victims.py (features of pairs of nets, a victim classifier), order_ceiling.py's stubborn-marker
row and victims_order.py (a learned order of the victims search's victims), on drawn grids and the
generated imitation sample (experiments/conftest.py). Experiment tests: ``-m experiment`` runs them."""

from __future__ import annotations

import numpy as np
import pytest

torch = pytest.importorskip("torch")

pytestmark = pytest.mark.experiment

SIZE = 2  # regions of the imitation_sample fixture: 64 of 2x2 GCells
HOLD_OUT = 3


def test_pair_features_on_a_drawn_grid() -> None:
    """Five candidates and one other net on a 2-layer 5x6 grid; every column worked out by hand."""
    from experiments.net_order import pair_victims as pv

    access = np.full((2, 5, 6), -1, np.int32)
    access[0, 0, 0] = access[0, 0, 1] = 10
    access[0, 0, 2] = 20  # 1 step from 10
    access[0, 3, 3] = 30
    access[1, 3, 3] = 40  # straight above 30
    access[0, 2, 0] = 50  # 2 steps from 10 and from 20
    access[0, 1, 3] = 99  # not a candidate: 1 step from 20, 2 from 30
    ids = np.array([10, 20, 30, 40, 50])
    heuristic = np.array([1, 0, 4, 2, 3])  # ranks: 10 -> 1, 20 -> 0, 30 -> 3, 40 -> 4, 50 -> 2
    f = pv.pair_features(access, ids, heuristic)
    one, two = 1 / 3, np.log2(3) / 3
    col = {n: i for i, n in enumerate(pv.PAIR_FEATURES)}
    expect = {
        "near1_before": [one, 0, 0, one, 0],
        "near1_after": [0, one, one, 0, 0],
        "near2_before": [one, 0, 0, one, two],
        "near2_after": [one, two, one, 0, 0],
        "near1_fixed": [0, one, 0, 0, 0],
        "touch1_share": [0.5, 1, 1, 1, 0],
        "touch2_share": [1, 1, 1, 1, 1],
        "rank": [0.25, 0, 0.75, 1, 0.5],
    }
    assert set(expect) == set(pv.PAIR_FEATURES)
    for name, values in expect.items():
        np.testing.assert_allclose(f[:, col[name]], values, atol=1e-6, err_msg=name)
    assert pv.pair_features(access, ids[:0], heuristic[:0]).shape == (0, len(pv.PAIR_FEATURES))


def test_auc_matches_counting_pairs() -> None:
    from experiments.net_order import pair_victims as pv

    rng = np.random.default_rng(3)
    score = rng.integers(0, 6, 80).astype(float)  # many ties
    label = rng.random(80) < 0.3
    pos, neg = score[label], score[~label]
    brute = ((pos[:, None] > neg[None, :]).sum() + 0.5 * (pos[:, None] == neg[None, :]).sum()) / (len(pos) * len(neg))
    assert pv.auc(score, label) == pytest.approx(brute)
    assert np.isnan(pv.auc(score, np.zeros(80, bool)))


def test_pair_victims_bench_labels_the_heuristic_routing_and_scores_out_of_sample(imitation_sample: str) -> None:
    """Each region's label is the victims of its heuristic routing, its rule cost a fresh routing of
    the true victims first; the cross-validation scores every region once, and its orders are the
    heuristic's with the predicted victims moved to the front."""
    from experiments.net_order import pair_victims as pv
    from experiments.net_order.holdout import marker_roles
    from xroute.policies.rl.teacher import load_first_pass, route_order
    from xroute.net_order import heuristic_order

    torch.set_num_threads(1)
    regions = pv.collect([imitation_sample], 1, region_size=SIZE, hold_out_every=HOLD_OUT, max_regions=24)
    assert len(regions) >= 10
    fp, dbu = load_first_pass(imitation_sample, SIZE)
    for r in regions:
        region = fp.open_region(r.index)
        heuristic = np.asarray(heuristic_order(np.asarray(region.candidates)))
        assert (r.heuristic == heuristic).all()
        for k in heuristic:
            region.route_net(int(k))
        victims = set(marker_roles(region)[0])
        assert [int(n) in victims for n in np.asarray(region.candidates)[:, 0]] == r.victim.tolist()
        first = r.victim[heuristic]
        assert r.costs[1] == pytest.approx(route_order(fp, r.index, np.concatenate([heuristic[first], heuristic[~first]]), dbu))
    assert any(r.victim.any() for r in regions)
    r = next(r for r in regions if len(r.victim) >= 3)
    prob = np.linspace(0.9, 0.1, len(r.victim))
    orders = pv.predicted_orders(r, prob)
    for order in orders.values():
        assert sorted(order) == list(range(len(r.victim)))
    top = int(round(prob.sum()))
    assert set(orders["top sum(p) first"][:top]) == set(range(top))
    rows = pv.evaluate(regions, steps=20, region_size=SIZE)[imitation_sample]
    assert rows["regions"] == len(regions)
    assert rows["nets"] == sum(len(x.victim) for x in regions)
    assert rows["heuristic"] == pytest.approx(sum(x.costs[0] for x in regions))
    assert rows["victims"] == sum(int(x.victim.sum()) for x in regions)
    assert 0 < rows["victims"] < rows["nets"]  # both classes, so every AUC is defined
    for w in pv.INPUTS:
        # Out of sample, a classifier that learned nothing scores every net alike: exactly 0.5.
        assert 0.0 < rows[f"AUC {w}"] < 1.0 and rows[f"AUC {w}"] != 0.5, w


def test_order_ceiling_counts_stubborn_markers(imitation_sample: str) -> None:
    """The best-of-K rows are the minimum of holdout.best_of_random's orders; the heuristic's markers
    are its violations; a stubborn marker is in every routing, so no region has more of them than
    its random order with the fewest violations; and each marker some routing avoids takes 500 off
    the optimistic row."""
    import argparse

    from experiments.net_order import order_ceiling as oc
    from xroute import load_design
    from experiments.net_order.holdout import best_of_random, held_out_regions, route_in_context
    from xroute.session import first_pass, open_session

    a = argparse.Namespace(region_size=SIZE, hold_out_every=HOLD_OUT, min_candidates=2, best_of=[1, 3], threads=1)
    res = oc.bench_testcase(imitation_sample, a)
    design = load_design(imitation_sample)
    dbu = design.dbu_per_micron
    fp = first_pass(open_session(design), SIZE)
    regions = list(held_out_regions(fp, HOLD_OUT, SIZE, 2))
    assert res["regions"] == len(regions) > 0
    samples = [best_of_random(fp, reg, 3, dbu) for reg in regions]
    assert res["totals"]["best-of-3"] == pytest.approx(sum(min(s.cost for s in x) for x in samples))
    assert res["totals"]["best-of-1"] == pytest.approx(sum(x[0].cost for x in samples))
    heuristic = [route_in_context(fp, reg, "heuristic", 1, dbu) for reg in regions]
    assert res["markers"] == sum(s.drvs for s in heuristic) > 0
    assert res["stubborn"] <= sum(min(s.drvs for s in x) for x in samples)
    removed = res["totals"]["heuristic"] - res["totals"]["avoidable removed"]
    assert removed == pytest.approx(500.0 * (res["markers"] - res["stubborn"]))


def test_victims_order_positions_on_a_drawn_order() -> None:
    from experiments.net_order import victims_order as vo

    t = vo.SearchTrials("x", 0, False, np.zeros((10, 1), np.float32), np.arange(10, dtype=np.int32),
                        np.array([5, 2, 9], np.int32), np.zeros(1), np.zeros((0, 3), np.int32), np.zeros(0))
    np.testing.assert_allclose(vo.positions(t, np.array([9, 5, 2])), [0.5, 1.0, 0.0])  # victims 5, 2, 9
    assert (vo.with_victims_first(np.array([3, 9, 1, 5, 2]), np.array([5, 9])) == [5, 9, 3, 1, 2]).all()


def test_victims_order_fit_recovers_a_cost_linear_in_positions() -> None:
    """Shuffle costs drawn from a known per-victim score (cost grows by score x position) are fitted back
    to that score; a column that is constant within each region gets weight 0; and the learned order
    (highest score first) is the cheapest of every order of the victims under that cost."""
    import itertools

    from experiments.net_order import victims_order as vo

    rng = np.random.default_rng(5)
    true = np.array([3.0, -2.0, 0.5, 0.0])  # three features and a constant column
    regions = []
    for index in range(30):
        n = int(rng.integers(5, 9))
        inputs = np.concatenate([rng.normal(size=(n, 3)), np.ones((n, 1))], 1).astype(np.float32)
        victims = np.sort(rng.choice(n, int(rng.integers(2, n)), replace=False)).astype(np.int32)
        shuffles = np.stack([rng.permutation(victims) for _ in range(12)]).astype(np.int32)
        heuristic_cost = float(rng.uniform(1e3, 1e4))
        t = vo.SearchTrials("x", index, False, inputs, np.arange(n, dtype=np.int32), victims,
                            np.array([heuristic_cost]), shuffles, np.zeros(12))
        score = inputs[victims].astype(np.float64) @ true
        t.shuffle_costs = heuristic_cost * (1.0 + np.array([score @ vo.positions(t, o) for o in shuffles]))
        regions.append(t)
    w = vo.fit(regions)
    np.testing.assert_allclose(w[:3], true[:3], rtol=1e-2, atol=1e-2)
    assert w[3] == 0.0
    t = next(r for r in regions if 3 <= len(r.victims) <= 6)
    cost = {o: float(t.inputs[t.victims].astype(np.float64) @ true @ vo.positions(t, np.array(o)))
            for o in itertools.permutations(t.victims.tolist())}
    assert cost[tuple(vo.learned(t, true).tolist())] == pytest.approx(min(cost.values()))


def test_victims_order_bench_replays_the_search(imitation_sample: str) -> None:
    """Each region's rule trials start with the heuristic's routing and its victims include that
    routing's victims; every shuffle routes the victims first in a new order and its cost is that
    routing's; the budget rows never exceed the heuristic and a larger budget never costs more."""
    from experiments.net_order import victims_order as vo
    from experiments.net_order.holdout import marker_roles
    from xroute.policies.rl.teacher import load_first_pass
    from xroute.net_order import heuristic_order

    regions = vo.collect_shard((imitation_sample, 0, 1, SIZE, HOLD_OUT, 3, 24))
    assert any(not t.held_out for t in regions) and any(t.held_out for t in regions)
    fp, dbu = load_first_pass(imitation_sample, SIZE)
    for t in regions:
        region = fp.open_region(t.index)
        nets = np.asarray(region.candidates)[:, 0]
        assert (t.heuristic == np.asarray(heuristic_order(np.asarray(region.candidates)))).all()
        cost, (victims, _, _) = vo.trial(fp, t.index, t.heuristic, dbu)
        assert t.rule_costs[0] == pytest.approx(cost)
        assert set(victims) <= set(nets[t.victims].tolist())
        assert 1 <= len(t.rule_costs) <= vo.RULE_TRIALS and len(t.victims) >= 2
        for o, c in zip(t.shuffles, t.shuffle_costs):
            assert sorted(o) == sorted(t.victims)
            order = vo.with_victims_first(t.heuristic, o)
            assert sorted(order) == list(range(len(nets)))
            assert c == pytest.approx(vo.trial(fp, t.index, order, dbu)[0])
    train = [t for t in regions if not t.held_out]
    models = {k: vo.fit(train) for k in (-1, 0, 1, 2, 3, 4)}
    rows = vo.rows_for(regions, models, {imitation_sample: (fp, dbu)})
    assert sum(int(r["regions"]) for r in rows.values()) == len(regions)
    for r in rows.values():
        assert r["search b8"] <= r["search b4"] <= r["rule"] <= r["heuristic"]
        assert r["learned in search b8"] <= r["rule"]
