"""Can a score per net tell which net to route first? Single-net moves on the training regions, in context.

    python -m experiments.net_order.net_effects [--testcase ispd18_test1 --testcase ispd19_test1] [--per-region 12]
                                [--workers 2] [--steps 800] [--loss mse|listwise] [--json out.json]

The regions are the set scorer's teacher regions (``policies/rl/teacher.py``: the first pass's
regions that the hold-out rule keeps for training, with >= 2 candidates, opened in context). Per
region it routes the heuristic order, then for up to ``--per-region`` nets (drawn per region from
a seeded generator) the heuristic order with that one net moved to the front. A net's *effect* is
the cost change of that move: exact, since routing is deterministic. Cost: the region's
first-pass cost 0.5 WL(um) + 4 vias + 500 violations.

Rows, each summed over the regions and given against the heuristic:

* ``oracle``: per region the best tried move, or none; what knowing the effects gains.
* ``random``: a tried net moved first at random (the mean effect).
* ``learned``: 5-fold cross-validation (fold = region index % 5). On four folds the set scorer
  (``policies/rl/set_scorer.py``, no heuristic prior) learns to score the tried nets by their
  effect, from the set features, with the loss ``--loss``. On the fifth, the net it scores
  highest among the tried ones is moved first.
  ``corr``: the mean correlation within a region between its scores and the gains (minus the
  effects), on the folds it trained on and on the held-out fold.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from xroute.defaults import REGION_SIZE


@dataclass
class RegionEffects:
    testcase: str
    index: int
    features: np.ndarray  # float32[N, F]: set features as the region opens
    heuristic: float  # cost of the heuristic order
    effects: np.ndarray  # float64[N]: cost change of moving that net first; NaN where not tried


def collect_shard(testcase: str, shard: int, shards: int, region_size: int, hold_out_every: int,
                  per_region: int, max_regions: int = 0) -> list[RegionEffects]:
    """The single-net moves of shard ``shard`` of ``shards`` of the testcase's training regions."""
    from xroute.policies.rl.set_features import region_set_features
    from xroute.policies.rl.teacher import load_first_pass, route_order, training_regions
    from xroute.net_order import heuristic_order

    fp, dbu = load_first_pass(testcase, region_size)
    out = []
    for index, region in training_regions(fp, region_size, hold_out_every, 2, shard=shard, shards=shards,
                                          max_regions=max_regions):
        rows = np.asarray(region.candidates)
        n = len(rows)
        features = region_set_features(region)
        order = np.asarray(heuristic_order(rows), dtype=np.int32)
        base = route_order(fp, index, order, dbu)
        effects = np.full(n, np.nan)
        for i in np.sort(np.random.default_rng([7, index]).choice(n, min(n, per_region), replace=False)):
            moved = np.concatenate([[i], order[order != i]]).astype(np.int32)
            effects[i] = route_order(fp, index, moved, dbu) - base
        out.append(RegionEffects(testcase, index, features, base, effects))
    return out


def _shard(job: tuple) -> list[RegionEffects]:
    return collect_shard(*job)


def run_shards(fn: Any, jobs: list[tuple], workers: int) -> list[Any]:
    """``fn(job)`` (a list per job) for every job, in ``workers`` processes (spawned; 1: here), the
    results put together and sorted by (testcase, index)."""
    if workers <= 1:
        parts = [fn(j) for j in jobs]
    else:
        with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
            parts = list(pool.map(fn, jobs))
    return sorted((r for p in parts for r in p), key=lambda r: (r.testcase, r.index))


def collect(testcases: list[str], workers: int, **kwargs: Any) -> list[RegionEffects]:
    """Every testcase's regions, ``workers`` shards each in as many processes; sorted by (testcase, index)."""
    jobs = [(t, s, workers, kwargs["region_size"], kwargs["hold_out_every"], kwargs["per_region"],
             kwargs.get("max_regions", 0)) for t in testcases for s in range(workers)]
    return run_shards(_shard, jobs, workers)


def fit(regions: list[RegionEffects], steps: int, loss_kind: str, seed: int = 1) -> Any:
    """A set scorer (no heuristic prior) trained to score each region's tried nets by gain (-effect / 500)."""
    import torch

    from xroute.policies.rl.imitation import mirrored
    from xroute.policies.rl.set_features import SET_FEATURES
    from xroute.policies.rl.set_scorer import SetScorer

    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    model = SetScorer(len(SET_FEATURES), prior=0.0)
    model.prior.requires_grad_(False)
    opt = torch.optim.AdamW([p for p in model.parameters() if p.requires_grad], lr=1e-3, weight_decay=1e-4)
    data = [r for r in regions if np.nanstd(r.effects) > 0]
    for _ in range(steps):
        pick = rng.choice(len(data), size=min(16, len(data)), replace=False)
        n = max(len(data[i].features) for i in pick)
        feats = np.zeros((len(pick), n, len(SET_FEATURES)), np.float32)
        real = np.zeros((len(pick), n), bool)
        tried = np.zeros((len(pick), n), bool)
        gain = np.zeros((len(pick), n), np.float32)
        for j, i in enumerate(pick):
            r, m = data[i], len(data[i].features)
            feats[j, :m] = mirrored(r.features, bool(rng.integers(2)), bool(rng.integers(2)))
            real[j, :m] = True
            tried[j, :m] = ~np.isnan(r.effects)
            gain[j, :m] = np.nan_to_num(-r.effects / 500.0)
        s = model(torch.from_numpy(feats), torch.from_numpy(real))
        t, g = torch.from_numpy(tried), torch.from_numpy(gain)
        if loss_kind == "mse":
            loss = (((s - g) ** 2) * t).sum() / t.sum()
        else:  # listwise: the region's softmax of scores against the softmax of the gains
            target = torch.softmax(torch.where(t, g, torch.full_like(g, -1e4)), -1)
            loss = -(target * torch.log_softmax(torch.where(t, s, torch.full_like(s, -1e4)), -1)).sum(-1).mean()
        opt.zero_grad()
        loss.backward()
        torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
        opt.step()
    return model.eval()


def mean_corr(model: Any, regions: list[RegionEffects]) -> float:
    """Mean over regions of the correlation between the scores and the gains of the tried nets."""
    from xroute.policies.rl.imitation import model_scores

    got = []
    for r in regions:
        t = ~np.isnan(r.effects)
        s, e = model_scores(model, r.features)[t], r.effects[t]
        if e.std() > 0 and s.std() > 0:
            got.append(float(np.corrcoef(s, -e)[0, 1]))
    return float(np.mean(got)) if got else 0.0


def evaluate(regions: list[RegionEffects], steps: int, loss_kind: str) -> dict[str, Any]:
    """Per testcase: heuristic cost and the oracle, random and learned rows' cost changes; the correlations."""
    from xroute.policies.rl.imitation import model_scores

    cases = sorted({r.testcase for r in regions})
    rows = {c: {"regions": 0, "heuristic": 0.0, "oracle": 0.0, "random": 0.0, "learned": 0.0} for c in cases}
    corr_train, corr_test = [], []
    for fold in range(5):
        train = [r for r in regions if r.index % 5 != fold]
        test = [r for r in regions if r.index % 5 == fold]
        if not train or not test:
            continue
        model = fit(train, steps, loss_kind)
        corr_train.append(mean_corr(model, train))
        corr_test.append(mean_corr(model, test))
        for r in test:
            t = np.flatnonzero(~np.isnan(r.effects))
            row = rows[r.testcase]
            row["regions"] += 1
            row["heuristic"] += r.heuristic
            row["oracle"] += min(0.0, float(r.effects[t].min()))
            row["random"] += float(r.effects[t].mean())
            row["learned"] += float(r.effects[t[int(np.argmax(model_scores(model, r.features)[t]))]])
    return {"testcases": rows, "corr_train": float(np.mean(corr_train)), "corr_test": float(np.mean(corr_test))}


def print_against_heuristic(row: dict[str, Any], names: list[str], width: int) -> None:
    """One line per name of ``row``: its summed cost and its change against ``row["heuristic"]``."""
    base = row["heuristic"]
    for name in names:
        cost = row[name]
        print(f"  {name:<{width}}{cost:>12,.1f}{100.0 * (cost - base) / base if base else 0.0:>+8.2f}%")


def training_regions_parser(doc: str) -> argparse.ArgumentParser:
    """The options of a bench over the training regions: --testcase (repeatable), --region-size,
    --hold-out-every, --workers, --steps (of the scorer's training) and --json."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--testcase", action="append")
    ap.add_argument("--region-size", type=int, default=REGION_SIZE)
    ap.add_argument("--hold-out-every", type=int, default=3)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--steps", type=int, default=800)
    ap.add_argument("--json", type=Path)
    return ap


def main() -> None:
    import torch

    ap = training_regions_parser(__doc__)
    ap.add_argument("--per-region", type=int, default=12, help="nets tried per region (drawn, seeded)")
    ap.add_argument("--loss", choices=("mse", "listwise"), default="mse")
    a = ap.parse_args()
    torch.set_num_threads(1)
    t0 = time.perf_counter()
    regions = collect(a.testcase or ["ispd18_test1", "ispd19_test1"], a.workers, region_size=a.region_size,
                      hold_out_every=a.hold_out_every, per_region=a.per_region)
    tried = np.concatenate([r.effects[~np.isnan(r.effects)] for r in regions])
    print(f"{len(regions)} regions, {len(tried)} single-net moves routed, {time.perf_counter() - t0:.1f} s; "
          f"moves that lower / raise / keep the cost: {np.mean(tried < 0):.1%} / {np.mean(tried > 0):.1%} / "
          f"{np.mean(tried == 0):.1%}")
    res = evaluate(regions, a.steps, a.loss)
    for name, row in res["testcases"].items():
        h = row["heuristic"]
        parts = "  ".join(f"{k} {100 * row[k] / h:+.2f}%" for k in ("oracle", "random", "learned"))
        print(f"  {name}: {row['regions']} regions, heuristic {h:,.1f}; {parts}")
    print(f"  learned ({a.loss}, {a.steps} steps): correlation of scores and gains within a region "
          f"{res['corr_train']:+.3f} on its training folds, {res['corr_test']:+.3f} on the held-out fold")
    if a.json:
        a.json.write_text(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
