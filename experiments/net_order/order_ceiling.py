"""How much can one net order per region gain? Oracle orders on the held-out in-context regions.

    python -m experiments.net_order.order_ceiling [--testcase ispd18_test1 --testcase ispd19_test1] [--region-size 10]
                                  [--hold-out-every 3] [--best-of 20 --best-of 100] [--json out.json]

The regions are those of ``experiments/net_order/rl_holdout.py`` (same rule, same state: opened in context, every
order routed from the same start). A net-order policy chooses one order per region without
routing it. The rows here are orders that a policy cannot produce, because each one knows how
routings of the region came out. They bound what a learned order could reach:

* ``victims-first``: route the heuristic order and read the region's markers
  (``Region.markers()``). The *victims* are the nets the markers leave in violation: of a
  marker's two nets the one routed later; a marker naming one net (minimum area, an
  obstruction) names its victim. Then route again with the victims first (heuristic order among
  them, then the rest in heuristic order).
* ``victims-first-2``: the victims of both routings above first.
* ``best-of-K``: per region the cheapest of K random orders (the engine's, seeds 1..K: the orders
  of ``rl_holdout.py``'s random-best-of-K row).
* ``avoidable removed``: the heuristic's cost less 500 for each of its markers that at least one
  of the other routings above does not have (a marker is its type, layer, box and nets). No
  single order need avoid them all at once, so this figure is optimistic, not one any order is
  known to reach. The markers every routing has are printed as ``stubborn``.

Cost: the region's first-pass cost 0.5 WL(um) + 4 vias + 500 violations, summed over the regions.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

import numpy as np

from xroute import load_design
from xroute.config import CostSection
from xroute.defaults import REGION_SIZE
from xroute.net_order import heuristic_order
from .holdout import held_out_regions, marker_roles, moved_first, region_score
from xroute.session import first_pass, open_session


MARKER_COST = CostSection().drv_weight  # what one marker adds to a region's cost


def marker_keys(region: Any) -> set[tuple]:
    """The markers of a routed engine Region, each as (type, layer, box, nets)."""
    return {(m["type"], m["layer"], tuple(m["box"]), tuple(sorted(m["nets"]))) for m in region.markers()}


def route_victims(fp: Any, index: int, order: Any, dbu: int) -> tuple[float, set[int], set[tuple]]:
    """Cost of region ``index`` routed in ``order``, the nets its markers leave in violation, its markers."""
    r = fp.open_region(index)
    for k in order:
        r.route_net(int(k))
    return region_score(r, dbu).cost, set(marker_roles(r)[0]), marker_keys(r)


def route_random(fp: Any, index: int, seed: int, dbu: int) -> tuple[float, set[tuple]]:
    """Cost and markers of region ``index`` in the engine's random order ``seed`` (as ``holdout.best_of_random``)."""
    r = fp.open_region(index)
    r.route_rest("random", seed)
    return region_score(r, dbu).cost, marker_keys(r)


def bench_testcase(name: str, a: argparse.Namespace) -> dict[str, Any]:
    t0 = time.perf_counter()
    design = load_design(name)
    dbu = design.dbu_per_micron
    fp = first_pass(open_session(design), a.region_size, threads=a.threads)
    names = ["heuristic", "victims-first", "victims-first-2"] + [f"best-of-{k}" for k in a.best_of]
    names.append("avoidable removed")
    totals = dict.fromkeys(names, 0.0)
    better = dict.fromkeys(names, 0)
    regions = markers = stubborn = 0
    for reg in held_out_regions(fp, a.hold_out_every, a.region_size, a.min_candidates):
        rows = np.asarray(fp.open_region(reg.index).candidates)
        nets = rows[:, 0]
        order = [int(k) for k in heuristic_order(rows)]
        c0, v0, m0 = route_victims(fp, reg.index, order, dbu)
        c1, v1, m1 = route_victims(fp, reg.index, moved_first(order, np.isin(nets, list(v0))), dbu)
        c2, _, m2 = route_victims(fp, reg.index, moved_first(order, np.isin(nets, list(v0 | v1))), dbu)
        costs = {"heuristic": c0, "victims-first": c1, "victims-first-2": c2}
        samples = [route_random(fp, reg.index, s, dbu) for s in range(1, max(a.best_of) + 1)]
        for k in a.best_of:
            costs[f"best-of-{k}"] = min(c for c, _ in samples[:k])
        kept = m0 & m1 & m2
        for _, m in samples:
            kept &= m
        costs["avoidable removed"] = c0 - MARKER_COST * (len(m0) - len(kept))
        markers += len(m0)
        stubborn += len(kept)
        for n, c in costs.items():
            totals[n] += c
            better[n] += c < c0 - 1e-9
        regions += 1
    return {"testcase": name, "region_size": a.region_size, "regions": regions, "totals": totals, "better": better,
            "markers": markers, "stubborn": stubborn, "seconds": round(time.perf_counter() - t0, 1)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--testcase", action="append")
    ap.add_argument("--region-size", type=int, default=REGION_SIZE)
    ap.add_argument("--hold-out-every", type=int, default=3)
    ap.add_argument("--min-candidates", type=int, default=2)
    ap.add_argument("--best-of", type=int, action="append", help="K of a best-of-K row (repeatable; default 20 and 100)")
    ap.add_argument("--threads", type=int, default=1, help="threads of the first pass")
    ap.add_argument("--json", type=Path)
    a = ap.parse_args()
    a.best_of = sorted(set(a.best_of or [20, 100]))
    if min(a.best_of) < 1:
        ap.error("--best-of must be >= 1")
    out = []
    for name in a.testcase or ["ispd18_test1"]:
        res = bench_testcase(name, a)
        base = res["totals"]["heuristic"]
        print(f"{name}: {res['regions']} held-out in-context {a.region_size}x{a.region_size} regions "
              f"(hold-out-every {a.hold_out_every}), {res['seconds']} s")
        for n, c in res["totals"].items():
            rel = 100.0 * (c - base) / base if base else 0.0
            print(f"  {n:<18}{c:>12,.1f}{rel:>+8.1f}%   better than the heuristic in {res['better'][n]} regions")
        print(f"  the heuristic's markers: {res['markers']}, of which every routing above has {res['stubborn']} (stubborn)")
        out.append(res)
    if a.json:
        a.json.write_text(json.dumps({"results": out}, indent=1))


if __name__ == "__main__":
    main()
