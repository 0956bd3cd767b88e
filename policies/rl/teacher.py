"""Teacher data for the set scorer: several net orders routed per training region of the first pass.

For every region of the router's first pass that the hold-out rule keeps for training
(:func:`~xroute.policies.rl.region_filter.held_out` false) with at least ``min_candidates`` nets,
opened in context (:meth:`FirstPass.open_region`): the candidates' :func:`set_features` as the
region opens (what the policy sees), then the heuristic order and ``orders`` seeded random
orders, each routed from that same state (the region reopened each time) and scored with the
region's first-pass cost (:meth:`xroute.config.CostSection.region_cost`).

Work is split into shards (region index % shards); :func:`collect_shard` is a plain function of
its arguments (it loads the design and routes its own first pass), so a process pool runs it
here (:func:`collect`, ``workers`` processes) and Ray tasks on a cluster run the same shards
(``backend="ray"``). Numpy and the engine only (no torch).
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator

import numpy as np

from xroute.atomic_files import atomic_write_from
from xroute.config import CostSection
from xroute.net_order import heuristic_order
from xroute.policies.rl.region_filter import held_out
from xroute.policies.rl.set_features import SET_FEATURES, region_set_features


@dataclass
class TeacherRegion:
    """One training region: features as it opens, the orders tried and their costs (row 0: heuristic)."""

    testcase: str
    index: int
    features: np.ndarray  # float32[N, len(SET_FEATURES)]
    orders: np.ndarray  # int32[K + 1, N]
    costs: np.ndarray  # float64[K + 1]


def route_order(first_pass: Any, index: int, order: np.ndarray, dbu_per_micron: int,
                weights: CostSection = CostSection()) -> float:
    """Opens region ``index`` in context, routes its candidates in ``order``, returns its cost."""
    region = first_pass.open_region(index)
    for i in order:
        region.route_net(int(i))
    region.route_rest("heuristic", 1)
    return float(weights.region_cost(region.metrics(), dbu_per_micron))


def training_indices(first_pass: Any, region_size: int, hold_out_every: int) -> list[int]:
    """Indices of the first pass's regions that are not held out (region_size 0: the pass's own)."""
    size = region_size or int(first_pass.report["region_size"])
    return [i for i, (loc, _box, _colour, _nets) in enumerate(first_pass.regions)
            if not held_out(tuple(loc), hold_out_every, size)]


def load_first_pass(testcase: str, region_size: int) -> tuple[Any, int]:
    """The router's first pass of ``testcase`` at ``region_size`` (the state regions open in) and its DBU per micron."""
    from xroute import load_design
    from xroute.session import first_pass, open_session

    design = load_design(testcase)
    return first_pass(open_session(design), region_size), design.dbu_per_micron


def training_regions(first_pass: Any, region_size: int, hold_out_every: int, min_candidates: int = 2, *,
                     shard: int = 0, shards: int = 1, max_regions: int = 0) -> Iterator[tuple[int, Any]]:
    """(index, region opened in context) of the training regions (:func:`training_indices`; the first
    ``max_regions`` of them, 0: all) of shard ``shard`` of ``shards`` with >= ``min_candidates`` nets."""
    indices = training_indices(first_pass, region_size, hold_out_every)
    if max_regions:
        indices = indices[:max_regions]
    for index in indices[shard::shards]:
        region = first_pass.open_region(index)
        if len(region.candidates) >= min_candidates:
            yield index, region


def collect_shard(testcase: str, shard: int, shards: int, *, region_size: int | None = None,
                  hold_out_every: int = 3, orders: int = 8, min_candidates: int = 2, seed: int = 1,
                  max_regions: int = 0, jitter: float = 0.0, promote: float = 0.0) -> list[TeacherRegion]:
    """The teacher regions of shard ``shard`` of ``shards`` (see the module docstring). ``jitter`` > 0: the
    random orders are the heuristic's perturbed (sorted by heuristic position / N + normal noise of that
    deviation) instead of uniform permutations. ``promote`` > 0: each order is the heuristic's with a random
    subset of the nets (each with that probability: :func:`promoted`) moved to the front, both parts in
    heuristic order; a randomised experiment per net on what routing it early does."""
    from xroute.defaults import REGION_SIZE

    size = REGION_SIZE if region_size is None else int(region_size)
    fp, dbu = load_first_pass(testcase, size)
    out = []
    for index, region in training_regions(fp, size, hold_out_every, min_candidates, shard=shard, shards=shards,
                                          max_regions=max_regions):
        rows = np.asarray(region.candidates)
        n = len(rows)
        features = region_set_features(region)
        rng = np.random.default_rng([seed, index])
        tried = [np.asarray(heuristic_order(rows), dtype=np.int32)]
        if promote > 0:
            tried += [promoted_order(tried[0], mask) for mask in promoted(rng, n, orders, promote)]
        elif jitter > 0:
            position = np.empty(n)
            position[tried[0]] = np.arange(n) / n
            tried += [np.argsort(position + rng.normal(0, jitter, n), kind="stable").astype(np.int32)
                      for _ in range(orders)]
        else:
            tried += [rng.permutation(n).astype(np.int32) for _ in range(orders)]
        costs = np.array([route_order(fp, index, o, dbu) for o in tried], dtype=np.float64)
        out.append(TeacherRegion(testcase, index, features, np.stack(tried), costs))
    return out


def promoted(rng: np.random.Generator, n: int, orders: int, share: float) -> np.ndarray:
    """bool[orders, n]: which nets each promoted order moves to the front (drawn from ``rng``)."""
    return rng.random((orders, n)) < share


def promoted_order(heuristic: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """The heuristic order with the nets of ``mask`` first, both parts keeping their heuristic order."""
    first = mask[heuristic]
    return np.concatenate([heuristic[first], heuristic[~first]]).astype(np.int32)


def score_orders(first_pass: Any, indices: list[int], order_fns: dict[str, Any], dbu_per_micron: int,
                 ) -> dict[str, list[float]]:
    """Per named order function (set features float32[N, F] -> order): the cost of each region of ``indices``
    routed in context in that function's order."""
    out: dict[str, list[float]] = {name: [] for name in order_fns}
    for index in indices:
        features = region_set_features(first_pass.open_region(index))
        for name, fn in order_fns.items():
            out[name].append(route_order(first_pass, index, np.asarray(fn(features)), dbu_per_micron))
    return out


def _run_shard(args: tuple[str, int, int, dict[str, Any]]) -> list[TeacherRegion]:
    testcase, shard, shards, kwargs = args
    return collect_shard(testcase, shard, shards, **kwargs)


def collect(testcases: list[str], *, workers: int = 2, backend: str = "local", ray_address: str | None = None,
            **kwargs: Any) -> list[TeacherRegion]:
    """Teacher regions of every testcase, ``workers`` shards per testcase in as many processes (1: in this
    process), or as Ray tasks with ``backend="ray"`` (:func:`xroute.policies.rl.ray_pool.ray_map`; ``ray_address``
    None: a local instance). The regions do not depend on the worker count or the backend."""
    jobs = [(t, s, workers, kwargs) for t in testcases for s in range(workers)]
    if backend == "ray":
        from xroute.policies.rl.ray_pool import ray_map

        parts = ray_map(_run_shard, jobs, workers, ray_address)
    elif backend != "local":
        raise ValueError(f"unknown backend {backend!r}: use local or ray")
    elif workers <= 1:
        parts = [_run_shard(j) for j in jobs]
    else:
        import multiprocessing

        with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
            parts = list(pool.map(_run_shard, jobs))
    regions = [r for part in parts for r in part]
    regions.sort(key=lambda r: (r.testcase, r.index))
    return regions


def save(regions: list[TeacherRegion], path: str | Path) -> None:
    """Writes the regions to one .npz (features and orders concatenated, offsets kept), atomically."""
    sizes = np.array([len(r.features) for r in regions], dtype=np.int64)
    ptr = np.concatenate([[0], np.cumsum(sizes)])
    atomic_write_from(path, lambda f: np.savez_compressed(
        f,
        features=np.concatenate([r.features for r in regions]) if regions else np.zeros((0, len(SET_FEATURES))),
        orders=np.concatenate([r.orders.reshape(-1) for r in regions]) if regions else np.zeros(0, np.int32),
        costs=np.stack([r.costs for r in regions]) if regions else np.zeros((0, 1)),
        ptr=ptr, testcases=np.array([r.testcase for r in regions]), indices=np.array([r.index for r in regions]),
        feature_names=np.array(SET_FEATURES)))


def load(path: str | Path) -> list[TeacherRegion]:
    """The regions :func:`save` wrote."""
    z = np.load(path)
    if tuple(z["feature_names"]) != SET_FEATURES:
        raise ValueError(f"{path}: teacher data of other features ({', '.join(z['feature_names'])})")
    ptr, costs = z["ptr"], z["costs"]
    k1 = costs.shape[1]
    out, o = [], 0
    for j in range(len(costs)):
        n = int(ptr[j + 1] - ptr[j])
        out.append(TeacherRegion(str(z["testcases"][j]), int(z["indices"][j]), z["features"][ptr[j]:ptr[j + 1]],
                                 z["orders"][o:o + k1 * n].reshape(k1, n), costs[j]))
        o += k1 * n
    return out
