"""Can learning add to the victims search? A set scorer that sees the heuristic routing's outcome.

    python -m experiments.net_order.victims_learning [--testcase ispd18_test1 --testcase ispd19_test1] [--variants 8]
                                     [--workers 2] [--steps 800] [--json out.json]

The victims search (``--policy victims``) routes a region's heuristic order, reads its markers and
routes again with the victims first. This asks whether a learned second order does better than
that rule. The regions are the set scorer's teacher regions (``policies/rl/teacher.py``: the
first pass's training regions with >= 2 candidates, opened in context). Per region:

* route the heuristic order; its markers give four *outcome* columns per net (victim, aggressor,
  log(1 + markers naming the net), named by a one-net marker: ``holdout.marker_roles``);
* route the *rule*'s order (victims first, both parts in heuristic order) and ``--variants`` orders
  drawn around it (seeded per region): each victim moved to the front with probability 0.7, each
  aggressor 0.2, any other net 0.05; the moved nets in heuristic order or, half the time, shuffled.

Then 5-fold cross-validation (fold = region index % 5): on four folds the set scorer
(``policies/rl/set_scorer.py``) sees the 19 set features plus the outcome columns and imitates
the second orders weighted by cost (Plackett-Luce, temperature 200, as ``xroute train imitate``);
on the fifth its order is routed. Two scorers: ``learned`` (no prior) and ``learned from the
rule`` (a heuristic-rank prior and a learnable victim prior, so that it starts as the rule's
order and learns what to change). Rows, summed per testcase against the heuristic: the rule, the
learned orders, each kept only where cheaper than the heuristic (what a search with that second
trial gives), the mean of the variants and the best of all orders tried.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from .net_effects import print_against_heuristic, run_shards, training_regions_parser
from xroute.defaults import REGION_SIZE

OUTCOME = ("victim", "aggressor", "markers", "alone")
TEMPERATURE = 200.0


@dataclass
class RegionTrials:
    testcase: str
    index: int
    features: np.ndarray  # float32[N, 19]: set features as the region opens
    outcome: np.ndarray  # float32[N, 4]: OUTCOME columns of the heuristic routing
    orders: np.ndarray  # int32[2 + variants, N]: heuristic, rule, variants
    costs: np.ndarray  # float64[2 + variants]


def outcome_columns(region: Any) -> np.ndarray:
    """float32[N, 4]: the OUTCOME columns of a routed region's candidates."""
    from .holdout import marker_roles

    victims, aggressors, alone = marker_roles(region)
    nets = np.asarray(region.candidates)[:, 0]
    out = np.zeros((len(nets), len(OUTCOME)), np.float32)
    for k, n in enumerate(int(x) for x in nets):
        out[k] = (n in victims, n in aggressors, np.log1p(victims.get(n, 0) + aggressors.get(n, 0)), n in alone)
    return out


def variant_orders(rng: np.random.Generator, heuristic: np.ndarray, outcome: np.ndarray, count: int) -> list[np.ndarray]:
    p = np.where(outcome[:, 0] > 0, 0.7, np.where(outcome[:, 1] > 0, 0.2, 0.05))
    out = []
    for _ in range(count):
        moved = rng.random(len(heuristic)) < p
        first = heuristic[moved[heuristic]]
        if rng.random() < 0.5:
            first = rng.permutation(first)
        out.append(np.concatenate([first, heuristic[~moved[heuristic]]]).astype(np.int32))
    return out


def collect_shard(job: tuple) -> list[RegionTrials]:
    testcase, shard, shards, region_size, hold_out_every, variants, max_regions = job
    from .holdout import moved_first, region_score
    from xroute.policies.rl.set_features import region_set_features
    from xroute.policies.rl.teacher import load_first_pass, route_order, training_regions
    from xroute.net_order import heuristic_order

    fp, dbu = load_first_pass(testcase, region_size)
    out = []
    for index, region in training_regions(fp, region_size, hold_out_every, 2, shard=shard, shards=shards,
                                          max_regions=max_regions):
        features = region_set_features(region)
        heuristic = np.asarray(heuristic_order(np.asarray(region.candidates)), np.int32)
        for k in heuristic:
            region.route_net(int(k))
        base = region_score(region, dbu).cost
        outcome = outcome_columns(region)
        tried = [moved_first(heuristic, outcome[:, 0] > 0)]  # the victims search's second trial
        tried += variant_orders(np.random.default_rng([7, index]), heuristic, outcome, variants)
        costs = [base] + [route_order(fp, index, o, dbu) for o in tried]
        out.append(RegionTrials(testcase, index, features, outcome, np.stack([heuristic] + tried),
                                np.asarray(costs, np.float64)))
    return out


def collect(testcases: list[str], workers: int, region_size: int = REGION_SIZE, hold_out_every: int = 3,
            variants: int = 8, max_regions: int = 0) -> list[RegionTrials]:
    shards = max(1, workers)
    jobs = [(t, s, shards, region_size, hold_out_every, variants, max_regions) for t in testcases for s in range(shards)]
    return run_shards(collect_shard, jobs, workers)


def make_scorer(from_rule: bool) -> Any:
    """A set scorer over the set features and the outcome columns; ``from_rule``: starts as the rule's order."""
    import torch

    from xroute.policies.rl.set_features import SET_FEATURES
    from xroute.policies.rl.set_scorer import SetScorer

    width = len(SET_FEATURES) + len(OUTCOME)
    if not from_rule:
        return SetScorer(width, 64, 4, 2, 0.0)

    class FromRule(SetScorer):
        def __init__(self) -> None:
            super().__init__(width, 64, 4, 2, 4.0)
            self.victim_prior = torch.nn.Parameter(torch.tensor(10.0))

        def forward(self, features: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
            s = super().forward(features, mask)
            return torch.where(mask, s + self.victim_prior * features[..., len(SET_FEATURES)], s)

    return FromRule()


def inputs(r: RegionTrials) -> np.ndarray:
    """float32[N, 23]: the set features and the outcome columns."""
    return np.concatenate([r.features, r.outcome], 1).astype(np.float32)


def fit(regions: list[RegionTrials], steps: int, from_rule: bool, seed: int = 1) -> Any:
    """The scorer trained by ``xroute train imitate``'s loop (:func:`~xroute.policies.rl.imitation.train`)
    to imitate each region's second orders (all but the heuristic's), weighted by cost."""
    import torch

    from xroute.policies.rl.imitation import ImitationConfig, train
    from xroute.policies.rl.teacher import TeacherRegion

    torch.manual_seed(seed)
    model = make_scorer(from_rule)
    second = [TeacherRegion(r.testcase, r.index, inputs(r), r.orders[1:], r.costs[1:]) for r in regions]
    cfg = ImitationConfig(steps=steps, temperature=TEMPERATURE, seed=seed, device="cpu")
    return train(second, cfg, model=model)[0]


def learned_order(model: Any, r: RegionTrials) -> np.ndarray:
    from xroute.policies.rl.imitation import model_scores, scores_order

    return scores_order(r.features, model_scores(model, inputs(r))).astype(np.int32)


def evaluate(regions: list[RegionTrials], steps: int, region_size: int = REGION_SIZE) -> dict[str, Any]:
    """Per testcase: the heuristic's cost and each row's cost, summed over the regions (learned rows out of sample)."""
    from xroute.policies.rl.teacher import load_first_pass, route_order

    names = ("rule", "learned", "learned from the rule", "rule kept if cheaper", "learned kept if cheaper",
             "learned from the rule kept if cheaper", "variants (mean)", "best tried")
    rows = {t: dict.fromkeys(("regions", "heuristic") + names, 0.0) for t in sorted({r.testcase for r in regions})}
    passes = {t: load_first_pass(t, region_size) for t in rows}
    for fold in range(5):
        train = [r for r in regions if r.index % 5 != fold]
        test = [r for r in regions if r.index % 5 == fold]
        if not train or not test or not any(np.ptp(r.costs[1:]) > 1e-6 for r in train):
            continue
        models = {"learned": fit(train, steps, False), "learned from the rule": fit(train, steps, True)}
        for r in test:
            fp, dbu = passes[r.testcase]
            row, base = rows[r.testcase], float(r.costs[0])
            row["regions"] += 1
            row["heuristic"] += base
            row["rule"] += r.costs[1]
            row["rule kept if cheaper"] += min(base, r.costs[1])
            for name, model in models.items():
                cost = route_order(fp, r.index, learned_order(model, r), dbu)
                row[name] += cost
                row[f"{name} kept if cheaper"] += min(base, cost)
            row["variants (mean)"] += float(np.mean(r.costs[2:])) if len(r.costs) > 2 else float(r.costs[1])
            row["best tried"] += float(r.costs.min())
    return rows


def main() -> None:
    ap = training_regions_parser(__doc__)
    ap.add_argument("--variants", type=int, default=8, help="orders drawn around the rule's per region")
    a = ap.parse_args()
    import torch

    torch.set_num_threads(1)
    t0 = time.perf_counter()
    regions = collect(a.testcase or ["ispd18_test1", "ispd19_test1"], a.workers, a.region_size, a.hold_out_every,
                      a.variants)
    collected = time.perf_counter() - t0
    rows = evaluate(regions, a.steps, a.region_size)
    for t, row in rows.items():
        base = row["heuristic"]
        print(f"{t}: {int(row['regions'])} training regions, heuristic {base:,.1f}")
        print_against_heuristic(row, [n for n in row if n not in ("regions", "heuristic")], 40)
    print(f"collection {collected:.0f} s, all {time.perf_counter() - t0:.0f} s")
    if a.json:
        a.json.write_text(json.dumps({"rows": rows, "seconds": time.perf_counter() - t0}, indent=1))


if __name__ == "__main__":
    main()
