"""Do features of pairs of nets tell which nets the heuristic order leaves in violation?

    python -m experiments.net_order.pair_victims [--testcase ispd18_test1 --testcase ispd19_test1] [--workers 2]
                                 [--steps 600] [--json out.json]

Earlier benches (``victims_learning.py``, ``net_effects.py``) found that a net's 19 set features do
not say whether routing it early helps, while the heuristic routing's markers do: its *victims*
(``holdout.marker_roles``) moved first is the victims search's second trial. This asks whether
features of *pairs* of nets predict those victims before anything is routed. A victim is the later
of two nets that meet, so the features count, per net, the other nets whose terminal nodes lie
within 1 or 2 grid steps of its own (same layer, or straight above / below), split by whether
the heuristic routes them before or after it (:data:`PAIR_FEATURES`).

The regions are the set scorer's teacher regions (first-pass training regions with >= 2
candidates, opened in context). Per region: route the heuristic order (its victims are the label)
and the rule's order (the true victims first). Then 5-fold cross-validation (fold = region index
% 5) of a victim classifier (a small MLP, binary cross-entropy) on three inputs: the set
features, the pair features, both. Out of sample it reports the ROC AUC per testcase and routes
two orders in context: the nets with predicted probability > 0.5 first, and the top
round(sum of probabilities) first, both parts in heuristic order.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from .net_effects import print_against_heuristic, run_shards, training_regions_parser
from xroute.defaults import REGION_SIZE

PAIR_FEATURES: tuple[str, ...] = (
    "near1_before",  # other candidates with a terminal node within 1 step, routed earlier by the heuristic (log2(1+n)/3)
    "near1_after",  # the same, routed later
    "near2_before",  # within 2 steps, earlier
    "near2_after",  # within 2 steps, later
    "near1_fixed",  # non-candidate nets with a terminal node within 1 step
    "touch1_share",  # share of the net's terminal nodes with another net's terminal node within 1 step
    "touch2_share",  # within 2 steps
    "rank",  # heuristic rank / (N - 1)
)


def _shifts(d: int) -> list[tuple[int, int, int]]:
    out = [(0, dy, dx) for dy in range(-d, d + 1) for dx in range(-d, d + 1) if (dy, dx) != (0, 0)]
    return out + [(-1, 0, 0), (1, 0, 0)]


def _shifted(a: np.ndarray, s: tuple[int, int, int]) -> tuple[tuple[slice, ...], tuple[slice, ...]]:
    """Slices (src, dst) so that a[dst] is the neighbour at offset ``s`` of a[src]."""
    src, dst = [], []
    for off, n in zip(s, a.shape):
        src.append(slice(max(0, -off), n - max(0, off)))
        dst.append(slice(max(0, off), n - max(0, -off)))
    return tuple(src), tuple(dst)


def pair_features(access: np.ndarray, net_ids: np.ndarray, heuristic: np.ndarray) -> np.ndarray:
    """float32[N, len(PAIR_FEATURES)] from a region grid's ``access_net`` (nz, ny, nx; -1 = none), the
    candidates' net ids and the heuristic order (row indices)."""
    access = np.asarray(access)
    ids = np.asarray(net_ids, np.int64)
    n = len(ids)
    out = np.zeros((n, len(PAIR_FEATURES)), np.float32)
    if n == 0:
        return out
    rank = np.empty(n, np.int64)
    rank[np.asarray(heuristic, np.int64)] = np.arange(n)
    row = {int(v): k for k, v in enumerate(ids)}
    own = access >= 0
    terminals = np.zeros(n, np.int64)
    owners, counts = np.unique(access[own], return_counts=True)
    for o, c in zip(owners, counts):
        if int(o) in row:
            terminals[row[int(o)]] = c
    for d, (before_col, after_col, share_col) in ((1, (0, 1, 5)), (2, (2, 3, 6))):
        touched = np.zeros(access.shape, bool)
        pairs = set()
        for s in _shifts(d):
            src, dst = _shifted(access, s)
            a, b = access[src], access[dst]
            meet = (a >= 0) & (b >= 0) & (a != b)
            if not meet.any():
                continue
            touched[src] |= meet
            pairs.update(zip(a[meet].tolist(), b[meet].tolist()))
        near_before = np.zeros(n)
        near_after = np.zeros(n)
        near_fixed = np.zeros(n)
        for a, b in pairs:
            ka = row.get(a)
            if ka is None:
                continue
            kb = row.get(b)
            if kb is None:
                near_fixed[ka] += 1
            elif rank[kb] < rank[ka]:
                near_before[ka] += 1
            else:
                near_after[ka] += 1
        out[:, before_col] = np.log2(1 + near_before) / 3
        out[:, after_col] = np.log2(1 + near_after) / 3
        if d == 1:
            out[:, 4] = np.log2(1 + near_fixed) / 3
        hit = np.zeros(n)
        for o, c in zip(*np.unique(access[touched], return_counts=True)):
            if int(o) in row:
                hit[row[int(o)]] = c
        out[:, share_col] = hit / np.maximum(1, terminals)
    out[:, 7] = rank / max(1, n - 1)
    return out


@dataclass
class RegionVictims:
    testcase: str
    index: int
    features: np.ndarray  # float32[N, 19]: set features as the region opens
    pairs: np.ndarray  # float32[N, len(PAIR_FEATURES)]
    victim: np.ndarray  # bool[N]: a victim of the heuristic routing
    heuristic: np.ndarray  # int32[N]: the heuristic order
    costs: np.ndarray  # float64[2]: heuristic, rule (victims first)


def region_inputs(region: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(set features, pair features, heuristic order) of an engine Region as it opens."""
    from xroute.policies.rl.set_features import region_set_features
    from xroute.net_order import heuristic_order

    cand = np.asarray(region.candidates)
    heuristic = np.asarray(heuristic_order(cand), np.int32)
    return region_set_features(region), pair_features(region.grid()["access_net"], cand[:, 0], heuristic), heuristic


def collect_shard(job: tuple) -> list[RegionVictims]:
    testcase, shard, shards, region_size, hold_out_every, max_regions = job
    from .holdout import marker_roles, moved_first, region_score
    from xroute.policies.rl.teacher import load_first_pass, route_order, training_regions

    fp, dbu = load_first_pass(testcase, region_size)
    out = []
    for index, region in training_regions(fp, region_size, hold_out_every, 2, shard=shard, shards=shards,
                                          max_regions=max_regions):
        features, pairs, heuristic = region_inputs(region)
        for k in heuristic:
            region.route_net(int(k))
        base = region_score(region, dbu).cost
        victims = marker_roles(region)[0]
        victim = np.isin(np.asarray(region.candidates)[:, 0], list(victims))
        rule = route_order(fp, index, moved_first(heuristic, victim), dbu) if victim.any() else base
        out.append(RegionVictims(testcase, index, features, pairs, victim, heuristic, np.array([base, rule])))
    return out


def collect(testcases: list[str], workers: int, region_size: int = REGION_SIZE, hold_out_every: int = 3,
            max_regions: int = 0) -> list[RegionVictims]:
    jobs = [(t, s, max(1, workers), region_size, hold_out_every, max_regions) for t in testcases
            for s in range(max(1, workers))]
    return run_shards(collect_shard, jobs, workers)


INPUTS = ("set features", "pair features", "both")


def inputs(r: RegionVictims, which: str) -> np.ndarray:
    if which == "set features":
        return r.features
    if which == "pair features":
        return r.pairs
    return np.concatenate([r.features, r.pairs], 1)


def fit(x: np.ndarray, y: np.ndarray, steps: int, seed: int = 1) -> Any:
    """A victim classifier: standardised inputs, an MLP (F -> 32 -> 32 -> 1), full-batch Adam on
    class-balanced binary cross-entropy. Returns a function from float32[N, F] to probabilities."""
    import torch

    torch.manual_seed(seed)
    mean, std = x.mean(0), x.std(0) + 1e-6
    xt = torch.as_tensor((x - mean) / std, dtype=torch.float32)
    yt = torch.as_tensor(y, dtype=torch.float32)
    net = torch.nn.Sequential(torch.nn.Linear(x.shape[1], 32), torch.nn.ReLU(), torch.nn.Linear(32, 32),
                              torch.nn.ReLU(), torch.nn.Linear(32, 1))
    opt = torch.optim.Adam(net.parameters(), lr=3e-3, weight_decay=1e-4)
    pos = float(yt.mean().clamp(1e-3, 1 - 1e-3))
    loss_fn = torch.nn.BCEWithLogitsLoss(pos_weight=torch.tensor((1 - pos) / pos))
    for _ in range(steps):
        opt.zero_grad()
        loss = loss_fn(net(xt).squeeze(-1), yt)
        loss.backward()
        opt.step()
    net.eval()

    def predict(z: np.ndarray) -> np.ndarray:
        with torch.no_grad():
            return torch.sigmoid(net(torch.as_tensor((z - mean) / std, dtype=torch.float32))).squeeze(-1).numpy()

    return predict


def auc(score: np.ndarray, label: np.ndarray) -> float:
    """ROC AUC (ties count half)."""
    label = np.asarray(label, bool)
    p, q = int(label.sum()), int((~label).sum())
    if not p or not q:
        return float("nan")
    order = np.argsort(score, kind="stable")
    s = np.asarray(score)[order]
    ranks = np.empty(len(s))
    i = 0
    while i < len(s):  # average ranks over ties
        j = i
        while j + 1 < len(s) and s[j + 1] == s[i]:
            j += 1
        ranks[order[i:j + 1]] = (i + j) / 2 + 1
        i = j + 1
    return float((ranks[label].sum() - p * (p + 1) / 2) / (p * q))


def predicted_orders(r: RegionVictims, prob: np.ndarray) -> dict[str, np.ndarray]:
    from .holdout import moved_first

    top = int(round(float(prob.sum())))
    chosen = np.zeros(len(prob), bool)
    chosen[np.argsort(-prob, kind="stable")[:top]] = True
    return {"p > 0.5 first": moved_first(r.heuristic, prob > 0.5), "top sum(p) first": moved_first(r.heuristic, chosen)}


def evaluate(regions: list[RegionVictims], steps: int, region_size: int = REGION_SIZE) -> dict[str, Any]:
    """Per testcase: AUC per input and the summed costs of each order, every learned figure out of sample."""
    from xroute.policies.rl.teacher import load_first_pass, route_order

    tests = sorted({r.testcase for r in regions})
    passes = {t: load_first_pass(t, region_size) for t in tests}
    rows = {t: {"regions": 0, "heuristic": 0.0, "rule (true victims first)": 0.0} for t in tests}
    scores = {t: {w: [] for w in INPUTS} for t in tests}
    labels = {t: [] for t in tests}
    for fold in range(5):
        train = [r for r in regions if r.index % 5 != fold]
        test = [r for r in regions if r.index % 5 == fold]
        if not train or not test:
            continue
        y = np.concatenate([r.victim for r in train]).astype(np.float32)
        models = {w: fit(np.concatenate([inputs(r, w) for r in train]), y, steps) for w in INPUTS}
        for r in test:
            fp, dbu = passes[r.testcase]
            row = rows[r.testcase]
            row["regions"] += 1
            row["heuristic"] += float(r.costs[0])
            row["rule (true victims first)"] += float(r.costs[1])
            labels[r.testcase].append(r.victim)
            for w, model in models.items():
                prob = model(inputs(r, w))
                scores[r.testcase][w].append(prob)
                for name, order in predicted_orders(r, prob).items():
                    key = f"{w}: {name}"
                    row[key] = row.get(key, 0.0) + route_order(fp, r.index, order, dbu)
    for t in tests:
        y = np.concatenate(labels[t])
        rows[t]["nets"] = int(len(y))
        rows[t]["victims"] = int(y.sum())
        for w in INPUTS:
            rows[t][f"AUC {w}"] = auc(np.concatenate(scores[t][w]), y)
    return rows


def main() -> None:
    import torch

    ap = training_regions_parser(__doc__)
    ap.set_defaults(steps=600)
    a = ap.parse_args()
    torch.set_num_threads(1)
    t0 = time.perf_counter()
    regions = collect(a.testcase or ["ispd18_test1", "ispd19_test1"], a.workers, a.region_size, a.hold_out_every)
    collected = time.perf_counter() - t0
    rows = evaluate(regions, a.steps, a.region_size)
    for t, row in rows.items():
        base = row["heuristic"]
        print(f"{t}: {row['regions']} training regions, {row['nets']} nets, {row['victims']} victims, "
              f"heuristic {base:,.1f}")
        for w in INPUTS:
            print(f"  AUC, {w:<30}{row[f'AUC {w}']:>8.3f}")
        print_against_heuristic(row, [n for n, c in row.items() if isinstance(c, float) and n != "heuristic"
                                      and not n.startswith("AUC")], 50)
    print(f"collection {collected:.0f} s, all {time.perf_counter() - t0:.0f} s")
    if a.json:
        a.json.write_text(json.dumps({"rows": rows, "seconds": time.perf_counter() - t0}, indent=1))


if __name__ == "__main__":
    main()
