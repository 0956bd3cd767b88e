"""Net-order policies compared on held-out in-context regions of the first pass (prints a table, writes JSON).

    python -m experiments.net_order.rl_holdout [--testcase ispd18_test1 --testcase ispd19_test1] [--region-size 5]
                               [--hold-out-every 3] [--min-candidates 2] [--random-seeds 5]
                               [--best-of 20] [--search-budget 4] [--limit N] [--json out.json]
                               [POLICY ...]

Per testcase: the router's first pass (iteration 0, heuristic, regions of ``--region-size`` GCells,
default the router's) is routed once and kept (:func:`xroute.session.first_pass`); the held-out
regions are those ``xroute train --hold-out-every K`` never draws (region column x and row y with
x % K == K // 2 and y % K == K // 2; K odd mixes the four colours) with at least
``--min-candidates`` nets. Each is opened in context (the regions of earlier colours routed as the
first pass routed them, the rest unrouted), once per policy and seed, routed completely and
dropped, so every policy starts from the same state. Score: the region's first-pass cost
0.5 WL(um) + 4 vias + 500 DRVs (DRVs: the markers inside the box after routing), summed over the
regions (:mod:`experiments.net_order.holdout`).

Rows: heuristic (the router's order, so exactly what the first pass routed there); random (mean
over ``--random-seeds`` seeds); random-best-of-K (per region the cheapest of K random orders, seeds
1..K, its time the K routings); then each POLICY: a built-in name (``heuristic``, ``random``,
the engine's searches ``rollout`` / ``victims`` / ``bestof`` / ``best-of-K`` with ``--search-budget``, routed
by the engine via ``Region.route_rest``), a ``.py`` policy file or an ``.onnx`` model.
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict
from pathlib import Path
from typing import Any

from xroute import load_design
from xroute.defaults import REGION_SIZE, SEARCH_BUDGET
from xroute.net_order import is_builtin_name
from xroute.policies.registry import get_policy
from .holdout import (
    FIGURES,
    PolicyScore,
    best_of_random,
    best_score,
    held_out_regions,
    mean_score,
    route_in_context,
)
from xroute.session import first_pass, open_session


def bench_testcase(name: str, args: argparse.Namespace, policies: dict[str, Any]) -> dict[str, Any]:
    t0 = time.perf_counter()
    design = load_design(name)
    dbu = design.dbu_per_micron
    session = open_session(design)
    fp = first_pass(session, args.region_size, threads=args.threads)
    pass_seconds = time.perf_counter() - t0
    regions = list(held_out_regions(fp, args.hold_out_every, args.region_size, args.min_candidates))
    if args.limit:
        regions = regions[: args.limit]
    best_name = f"random-best-of-{args.best_of}"
    names = ["heuristic", "random", best_name, *policies]
    rows = []
    for reg in regions:
        row: dict[str, Any] = {"index": reg.index, "location": list(reg.location), "colour": reg.colour,
                               "candidates": reg.candidates}
        scores: dict[str, PolicyScore] = {"heuristic": route_in_context(fp, reg, "heuristic", 1, dbu)}
        samples = best_of_random(fp, reg, max(args.random_seeds, args.best_of), dbu)
        scores["random"] = mean_score(samples[: args.random_seeds])
        scores[best_name] = best_score(samples[: args.best_of])
        for pname, spec in policies.items():
            scores[pname] = route_in_context(fp, reg, spec, args.seed, dbu, search_budget=args.search_budget)
        row.update({k: asdict(v) for k, v in scores.items()})
        rows.append(row)
    totals: dict[str, dict[str, float]] = {}
    base = [row["heuristic"]["cost"] for row in rows]
    for n in names:
        t = {k: float(sum(row[n][k] for row in rows)) for k in FIGURES}
        diffs = [row[n]["cost"] - b for row, b in zip(rows, base)]
        t.update(better=sum(d < -1e-9 for d in diffs), same=sum(abs(d) <= 1e-9 for d in diffs),
                 worse=sum(d > 1e-9 for d in diffs),
                 seconds_per_region=float(sum(row[n]["seconds"] for row in rows)) / max(1, len(rows)))
        totals[n] = t
    return {"testcase": name, "region_size": args.region_size, "hold_out_every": args.hold_out_every,
            "min_candidates": args.min_candidates, "first_pass_regions": len(fp.regions),
            "first_pass": {k: fp.report[k] for k in ("wirelength_um", "vias", "violations")},
            "first_pass_seconds": round(pass_seconds, 2), "seconds": round(time.perf_counter() - t0, 2),
            "regions": rows, "totals": totals, "policies": names}


def print_table(res: dict[str, Any]) -> None:
    rows, totals = res["regions"], res["totals"]
    print(f"{res['testcase']}: {len(rows)} held-out in-context {res['region_size']}x{res['region_size']} regions "
          f"of {res['first_pass_regions']} (hold-out-every {res['hold_out_every']}, >= {res['min_candidates']} nets; "
          f"{sum(r['candidates'] for r in rows)} nets); first pass {res['first_pass_seconds']:.1f} s, "
          f"all {res['seconds']:.1f} s")
    w = max(14, *(len(n) + 2 for n in res["policies"]))
    print(f"{'policy':<{w}}{'cost':>12}{'vs heur.':>9}{'WL um':>11}{'vias':>8}{'DRVs':>7}"
          f"{'better/same/worse':>19}{'s/region':>10}")
    base = totals["heuristic"]["cost"]
    for n in res["policies"]:
        t = totals[n]
        rel = 100.0 * (t["cost"] - base) / base if base else 0.0
        bsw = f"{t['better']}/{t['same']}/{t['worse']}"
        print(f"{n:<{w}}{t['cost']:>12,.1f}{rel:>+8.1f}%{t['wl_um']:>11,.1f}{t['vias']:>8,.0f}{t['drvs']:>7,.1f}"
              f"{bsw:>19}{t['seconds_per_region']:>10.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("policies", nargs="*", help="built-in policy names, .py policy files or .onnx models")
    ap.add_argument("--testcase", action="append", help="testcase (repeatable; default ispd18_test1)")
    ap.add_argument("--region-size", type=int, default=REGION_SIZE, help="GCells per region side (router's default)")
    ap.add_argument("--hold-out-every", type=int, default=3)
    ap.add_argument("--min-candidates", type=int, default=2)
    ap.add_argument("--random-seeds", type=int, default=5)
    ap.add_argument("--best-of", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1, help="seed passed to the named policies")
    ap.add_argument("--search-budget", type=int, default=SEARCH_BUDGET,
                    help="trial routings per region of rollout and victims (bestof's K)")
    ap.add_argument("--threads", type=int, default=1, help="threads of the first pass")
    ap.add_argument("--limit", type=int, default=0, help="score only the first N held-out regions (0: all)")
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()
    policies: dict[str, Any] = {}
    for spec in args.policies:
        policies[Path(spec).stem] = spec if is_builtin_name(spec) else get_policy(spec, args.seed)
    results = []
    for name in args.testcase or ["ispd18_test1"]:
        res = bench_testcase(name, args, policies)
        print_table(res)
        results.append(res)
    if args.json:
        args.json.write_text(json.dumps({"results": results}, indent=1))


if __name__ == "__main__":
    main()
