"""Can a learned order of the victims replace the victims search's random shuffles?

    python -m experiments.net_order.victims_order [--testcase ispd18_test1 --testcase ispd19_test1] [--shuffles 12]
                                  [--workers 2] [--json out.json]

The victims search (``--policy victims``) routes the heuristic order, then the victims of every
trial so far first, until no trial names a new victim (the *rule* trials); the rest of its budget
routes the victims first in random orders (the *shuffles*), the other nets after them in
heuristic rank. This replays that search in Python on the training regions (as
``experiments/net_order/victims_learning.py`` opens them) and on the held-out regions of ``experiments/net_order/rl_holdout.py``,
and asks whether a learned score can order the victims better than a shuffle does.

The model is linear in each victim's 19 set features (as the region opens) plus three outcome
columns of the rule trials (trials naming it a victim, an aggressor, alone; ``holdout.marker_roles``)
and a constant. A victim's score says how much a region's cost grows as that victim moves later
among the victims: cost(order) - mean cost = sum over victims of score * (position - mean
position), positions in [0, 1]. It is fitted by ridge regression on each region's shuffles,
costs divided by the region's heuristic cost so that every region weighs alike. The learned
order routes the victims by score, highest first, the rest in heuristic rank.

Rows, summed per testcase against the heuristic: the rule trials' best, the mean shuffle, the
learned order (out of sample: 5-fold by region index on the training regions; fitted on all the
training regions for the held-out ones), and the search at budgets 4 and 8 with its first shuffle
replaced by the learned order ("learned in search") or not ("search").

A replay, not the engine's search: its victims are those of the rule trials (the engine also adds
those its shuffles name) and its shuffles are numpy's, so its search rows differ a little from
``rl_holdout.py --policy victims``. Regions whose rule names fewer than 2 victims are left out.
The figures of a run are in experiments/net_order/LOG.md.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from .net_effects import print_against_heuristic, run_shards, training_regions_parser

OUTCOME = ("victim", "aggressor", "alone")
RULE_TRIALS = 4  # the rule stops earlier when a trial names no new victim
RIDGE = 1e-3


@dataclass
class SearchTrials:
    testcase: str
    index: int
    held_out: bool
    inputs: np.ndarray  # float32[N, 23]: set features, outcome columns, 1
    heuristic: np.ndarray  # int32[N]
    victims: np.ndarray  # int32[V]: candidate rows of the victims of the rule trials, heuristic rank
    rule_costs: np.ndarray  # float64[R]: the rule trials (the heuristic's first)
    shuffles: np.ndarray  # int32[S, V]: the victims' order of each shuffle
    shuffle_costs: np.ndarray  # float64[S]


def trial(fp: Any, index: int, order: np.ndarray, dbu: int) -> tuple[float, Any]:
    """(cost, holdout.marker_roles) of region ``index`` opened in context and routed in ``order``."""
    from .holdout import marker_roles, region_score

    r = fp.open_region(index)
    for k in order:
        r.route_net(int(k))
    return region_score(r, dbu).cost, marker_roles(r)


def with_victims_first(heuristic: np.ndarray, victims_order: np.ndarray) -> np.ndarray:
    """int32[N]: ``victims_order`` (candidate rows) first, the other rows after them in heuristic rank."""
    rest = heuristic[~np.isin(heuristic, victims_order)]
    return np.concatenate([victims_order, rest]).astype(np.int32)


def search_trials(fp: Any, index: int, dbu: int, features: np.ndarray, shuffles: int, held_out: bool,
                  testcase: str) -> SearchTrials | None:
    """The rule trials of region ``index`` and ``shuffles`` seeded shuffles of their victims (None when
    the rule names fewer than 2 victims)."""
    from .holdout import moved_first
    from xroute.policies.rl.teacher import route_order
    from xroute.net_order import heuristic_order

    region = fp.open_region(index)
    rows = np.asarray(region.candidates)
    nets = rows[:, 0].astype(np.int64)
    heuristic = np.asarray(heuristic_order(rows), np.int32)
    outcome = np.zeros((len(nets), len(OUTCOME)), np.float32)
    victims: set[int] = set()
    costs, order = [], heuristic
    while True:
        cost, (v, g, a) = trial(fp, index, order, dbu)
        costs.append(cost)
        for col, roles in enumerate((v, g, a)):
            outcome[:, col] += np.isin(nets, list(roles))
        new = set(v) - victims
        victims |= set(v)
        if not new or len(costs) == RULE_TRIALS:
            break
        order = moved_first(heuristic, np.isin(nets, list(victims)))
    vic = heuristic[np.isin(nets[heuristic], list(victims))].astype(np.int32)
    if len(vic) < 2:
        return None
    rng = np.random.default_rng([11, index])
    drawn = np.stack([rng.permutation(vic) for _ in range(shuffles)]).astype(np.int32)
    shuffle_costs = np.array([route_order(fp, index, with_victims_first(heuristic, o), dbu) for o in drawn])
    inputs = np.concatenate([features, outcome, np.ones((len(nets), 1), np.float32)], 1)
    return SearchTrials(testcase, index, held_out, inputs, heuristic, vic, np.asarray(costs), drawn, shuffle_costs)


def collect_shard(job: tuple) -> list[SearchTrials]:
    """The search trials of shard ``shard`` of ``shards`` of ``testcase``'s training regions (the first
    ``max_regions``, 0: all) and of its held-out regions (as many at most)."""
    testcase, shard, shards, region_size, hold_out_every, shuffles, max_regions = job
    from .holdout import held_out_regions
    from xroute.policies.rl.set_features import region_set_features
    from xroute.policies.rl.teacher import load_first_pass, training_regions

    fp, dbu = load_first_pass(testcase, region_size)
    out = []
    for index, region in training_regions(fp, region_size, hold_out_every, 2, shard=shard, shards=shards,
                                          max_regions=max_regions):
        t = search_trials(fp, index, dbu, region_set_features(region), shuffles, False, testcase)
        if t is not None:
            out.append(t)
    for k, h in enumerate(held_out_regions(fp, hold_out_every, region_size, 2)):
        if max_regions and k >= max_regions:
            break
        if k % shards == shard:
            t = search_trials(fp, h.index, dbu, region_set_features(fp.open_region(h.index)), shuffles, True,
                              testcase)
            if t is not None:
                out.append(t)
    return out


def positions(t: SearchTrials, order: np.ndarray) -> np.ndarray:
    """float64[V]: each victim's (t.victims') position in ``order`` (a victims' order), in [0, 1]."""
    where = np.argsort(order)
    return where[np.searchsorted(order[where], t.victims)] / (len(order) - 1)


def design(t: SearchTrials) -> tuple[np.ndarray, np.ndarray]:
    """(X float64[S, F], y float64[S]): per shuffle, sum over victims of inputs * centred position, and
    its centred cost over the heuristic's."""
    p = np.stack([positions(t, o) for o in t.shuffles])
    p -= p.mean(0)
    x = p @ t.inputs[t.victims].astype(np.float64)
    y = (t.shuffle_costs - t.shuffle_costs.mean()) / t.rule_costs[0]
    return x, y


def fit(regions: list[SearchTrials]) -> np.ndarray:
    """float64[F]: the ridge fit of every region's shuffles (:func:`design`); columns that do not vary
    between a region's victims (the constant, the region's candidate count) get weight 0."""
    parts = [design(t) for t in regions]
    x = np.concatenate([p[0] for p in parts])
    y = np.concatenate([p[1] for p in parts])
    scale = x.std(0)
    live = scale > 1e-9 * max(1.0, float(scale.max()))  # a column constant within every region sums to 0
    xs = x[:, live] / scale[live]
    w = np.zeros(x.shape[1])
    w[live] = np.linalg.solve(xs.T @ xs + RIDGE * len(y) * np.eye(xs.shape[1]), xs.T @ y) / scale[live]
    return w


def learned(t: SearchTrials, w: np.ndarray) -> np.ndarray:
    """int32[V]: the victims by score under weights ``w``, highest first (ties in heuristic rank)."""
    s = t.inputs[t.victims].astype(np.float64) @ w
    return t.victims[np.argsort(-s, kind="stable")]


def rows_for(regions: list[SearchTrials], models: dict[int, np.ndarray], fps: dict[str, Any]) -> dict[str, dict]:
    """Per "testcase held-out" / "testcase training (5-fold)": the regions, and the summed cost of the
    heuristic and of each row of the module docstring. ``models``: weights by fold (region index % 5)
    for training regions, -1 for the held-out ones; ``fps``: (first pass, DBU) by testcase."""
    from xroute.policies.rl.teacher import route_order

    names = ("rule", "shuffle (mean)", "learned", "search b4", "learned in search b4", "search b8",
             "learned in search b8")
    rows: dict[str, dict] = {}
    for t in regions:
        key = f"{t.testcase} {'held-out' if t.held_out else 'training (5-fold)'}"
        row = rows.setdefault(key, dict.fromkeys(("regions", "heuristic") + names, 0.0))
        w = models[-1 if t.held_out else t.index % 5]
        fp, dbu = fps[t.testcase]
        cost = route_order(fp, t.index, with_victims_first(t.heuristic, learned(t, w)), dbu)
        row["regions"] += 1
        row["heuristic"] += t.rule_costs[0]
        row["rule"] += t.rule_costs.min()
        row["shuffle (mean)"] += t.shuffle_costs.mean()
        row["learned"] += cost
        for b in (4, 8):
            left = max(0, b - len(t.rule_costs))
            base = t.rule_costs[:b].min()
            row[f"search b{b}"] += min([base, *t.shuffle_costs[:left]])
            row[f"learned in search b{b}"] += min([base, *([cost] if left else []), *t.shuffle_costs[:max(0, left - 1)]])
    return rows


def main() -> None:
    ap = training_regions_parser(__doc__)
    ap.add_argument("--shuffles", type=int, default=12, help="random victims' orders routed per region")
    a = ap.parse_args()
    from xroute.policies.rl.teacher import load_first_pass

    t0 = time.perf_counter()
    testcases = a.testcase or ["ispd18_test1", "ispd19_test1"]
    jobs = [(t, s, a.workers, a.region_size, a.hold_out_every, a.shuffles, 0) for t in testcases for s in range(a.workers)]
    regions = run_shards(collect_shard, jobs, a.workers)
    collected = time.perf_counter() - t0
    train = [t for t in regions if not t.held_out]
    models = {f: fit([t for t in train if t.index % 5 != f]) for f in range(5)}
    models[-1] = fit(train)
    fps = {t: load_first_pass(t, a.region_size) for t in testcases}
    rows = rows_for(regions, models, fps)
    for key, row in sorted(rows.items()):
        print(f"{key}: {int(row['regions'])} regions, heuristic {row['heuristic']:,.1f}")
        print_against_heuristic(row, [n for n in row if n not in ("regions", "heuristic")], 26)
    print(f"collection {collected:.0f} s, all {time.perf_counter() - t0:.0f} s")
    if a.json:
        a.json.write_text(json.dumps({"rows": rows, "weights": models[-1].tolist(),
                                      "seconds": time.perf_counter() - t0}, indent=1))


if __name__ == "__main__":
    main()
