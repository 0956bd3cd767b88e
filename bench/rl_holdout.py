"""Net-order policies compared on held-out regions of a testcase (prints a table, writes JSON).

    python bench/rl_holdout.py [--testcase ispd18_test1] [--hold-out-every 8] [--min-candidates 2]
                               [--random-seeds 5] [--json out.json] MODEL.onnx ...

The held-out regions are the 1x1-GCell regions ``xroute train --hold-out-every K`` never trains
on (lower-left GCell x % K == K // 2 and y % K == K // 2) with at least ``--min-candidates``
candidate nets. Each region is opened on the freshly loaded design (no neighbour routed) once per
policy, routed completely in that policy's order and dropped (never committed), so every policy
starts from the same state. Per policy: the paper's cost (0.5 WL(um) + 4 vias + 500 DRVs), WL,
vias and DRVs (the design-rule markers inside the region box after routing), summed over the
regions; random = the mean over ``--random-seeds`` seeds; for ONNX models also the milliseconds
of one order() call (observation + model).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np


from xroute.policies.onnx_policy import OnnxPolicy  # noqa: E402
from xroute.policies.rl.region_filter import held_out  # noqa: E402
from xroute import load_design  # noqa: E402
from xroute.session import open_session  # noqa: E402

WEIGHTS = (0.5, 4.0, 500.0)  # per um of wire, per via, per DRV


def region_figures(region, dbu: int) -> dict[str, float]:
    m = region.metrics()
    wl_um = m["wirelength_dbu"] / dbu
    cost = WEIGHTS[0] * wl_um + WEIGHTS[1] * m["vias"] + WEIGHTS[2] * m["violations"]
    return {"cost": cost, "wl_um": wl_um, "vias": m["vias"], "drvs": m["violations"], "unreached": m["unreached"]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("models", nargs="*", type=Path)
    ap.add_argument("--testcase", default="ispd18_test1")
    ap.add_argument("--hold-out-every", type=int, default=8)
    ap.add_argument("--min-candidates", type=int, default=2)
    ap.add_argument("--random-seeds", type=int, default=5)
    ap.add_argument("--json", type=Path)
    args = ap.parse_args()

    design = load_design(args.testcase)
    dbu = design.dbu_per_micron
    session = open_session(design)
    xs, ys = (np.asarray(a) for a in session.gcell_lines)
    policies = {p.stem: OnnxPolicy(p) for p in args.models}
    rows = []
    ms: dict[str, list[float]] = {name: [] for name in policies}
    for gy in range(len(ys) - 1):
        for gx in range(len(xs) - 1):
            if not held_out((gx, gy), args.hold_out_every):
                continue
            box = (int(xs[gx]), int(ys[gy]), int(xs[gx + 1]), int(ys[gy + 1]))
            probe = session.open_region(box)
            n = len(probe.candidates)
            del probe
            if n < args.min_candidates:
                continue
            row = {"location": [gx, gy], "candidates": n}
            r = session.open_region(box)
            r.route_rest("heuristic", 1)
            row["heuristic"] = region_figures(r, dbu)
            samples = []
            for seed in range(1, args.random_seeds + 1):
                r = session.open_region(box)
                r.route_rest("random", seed)
                samples.append(region_figures(r, dbu))
            row["random"] = {k: float(np.mean([s[k] for s in samples])) for k in samples[0]}
            for name, policy in policies.items():
                r = session.open_region(box)
                t0 = time.perf_counter()
                order = policy.order({"iteration": 0, "region": 0, "box": box, "engine_region": r}, r.candidates)
                ms[name].append(1000 * (time.perf_counter() - t0))
                for i in order:
                    r.route_net(int(i))
                row[name] = region_figures(r, dbu)
            rows.append(row)
    names = ["heuristic", "random", *policies]
    totals = {name: {k: float(sum(row[name][k] for row in rows)) for k in ("cost", "wl_um", "vias", "drvs")}
              for name in names}
    for name in policies:
        c = np.array([row[name]["cost"] - row["heuristic"]["cost"] for row in rows])
        totals[name].update(better=int((c < -1e-9).sum()), same=int((np.abs(c) <= 1e-9).sum()), worse=int((c > 1e-9).sum()),
                            ms_per_region=float(np.mean(ms[name])) if ms[name] else 0.0)
    print(f"{args.testcase}: {len(rows)} held-out 1x1 regions (hold-out-every {args.hold_out_every}, >= "
          f"{args.min_candidates} nets; {sum(r['candidates'] for r in rows)} nets)")
    print(f"{'policy':<12}{'cost':>12}{'WL um':>12}{'vias':>8}{'DRVs':>6}   vs heuristic (better/same/worse), ms/region")
    for name in names:
        t = totals[name]
        extra = f"   {t['better']}/{t['same']}/{t['worse']}, {t['ms_per_region']:.1f} ms" if name in policies else ""
        print(f"{name:<12}{t['cost']:>12,.1f}{t['wl_um']:>12,.1f}{t['vias']:>8,.0f}{t['drvs']:>6,.1f}{extra}")
    if args.json:
        args.json.write_text(json.dumps({"testcase": args.testcase, "regions": rows, "totals": totals}, indent=1))


if __name__ == "__main__":
    main()
