"""How routing cost grows with design size: a real testcase tiled 1x1, 2x2, 4x4, each routed in a fresh process.

    python bench/scale_bench.py [TESTCASE] [--by 1x1,2x2,4x4] [--threads 2] [--iterations 16]
                                [--region-size 0] [--keep DIR] [--json FILE]

The tiled testcases (``xroute.testcases.tiling``: R x C renamed copies of TESTCASE, default
ispd18_test1) are written into a temporary folder (or --keep DIR) and routed with the
heuristic policy, one fresh Python process each (the child of ``route_bench.py``: load,
route, write the DEF, re-read and check it). Printed per size: nets, routing time, the
child's whole wall time, its peak RSS (wait4), wirelength, vias, violations and opens of the
written DEF, and a line per size with each iteration's seconds and the violations it left
(`late` gives, for the iterations after the first that start from under 1% of the first one's
count, the largest share of the first iteration's time one of them took); then the growth
exponents b of time ~ nets^b and peak RSS ~ nets^b (least-squares fit of the logarithms over all
sizes). 1x1 routes the original testcase itself. The region size and iterations default to
the router's own (0: its automatic region size; 16).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import route_bench  # noqa: E402  (bench/route_bench.py: the child process and its measurement)

from xroute.testcases import ENV_VAR  # noqa: E402
from xroute.testcases.tiling import parse_by, tile_testcase  # noqa: E402


def slope(xs: list[float], ys: list[float]) -> float:
    """Least-squares slope of log(ys) against log(xs) (nan with fewer than two sizes)."""
    if len(xs) < 2:
        return math.nan
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    var = sum((x - mx) ** 2 for x in lx)
    return sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / var if var else math.nan


def iteration_rows(iterations: list[dict]) -> list[dict]:
    """Per iteration: seconds, the check's seconds, the shapes it looked at, the violations it left."""
    return [{"iteration": it["iteration"], "seconds": it["seconds"], "check_s": it["stage_seconds"].get("check", 0.0),
             "checked_shapes": it.get("checked_shapes", 0), "violations": it["violations"]} for it in iterations]


def late_share(rows: list[dict]) -> float | None:
    """The largest seconds / first iteration's seconds among the later iterations that start from under
    1% of the first iteration's violations (None when there is no such iteration)."""
    if len(rows) < 2 or rows[0]["seconds"] <= 0:
        return None
    first = rows[0]
    shares = [rows[k]["seconds"] / first["seconds"] for k in range(1, len(rows))
              if rows[k - 1]["violations"] < 0.01 * first["violations"]]
    return max(shares) if shares else None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("testcase", nargs="?", default="ispd18_test1")
    ap.add_argument("--by", default="1x1,2x2,4x4", help="comma-separated ROWSxCOLS tilings")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--iterations", type=int, default=16)
    ap.add_argument("--region-size", type=int, default=0, help="GCells per region side (0: the router's choice)")
    ap.add_argument("--keep", type=Path, help="write the tiled testcases here (kept) instead of a temporary folder")
    ap.add_argument("--json", type=Path, help="also write the figures to this JSON file")
    args = ap.parse_args()
    tilings = [parse_by(b) for b in args.by.split(",")]

    with tempfile.TemporaryDirectory(prefix="scale_bench_") as tmp:
        root = args.keep or Path(tmp)
        os.environ[ENV_VAR] = os.pathsep.join(p for p in (str(root), os.environ.get(ENV_VAR, "")) if p)
        print(f"{args.testcase}: tilings {args.by}, {args.threads} thread(s), up to {args.iterations} iterations, "
              f"region size {args.region_size or 'auto'}, heuristic policy, {os.cpu_count()} CPUs", flush=True)
        print(f"{'copies':>6} {'nets':>7} {'route s':>8} {'wall s':>8} {'RSS MB':>7} {'WL (um)':>12} "
              f"{'vias':>9} {'viol':>6} {'opens':>5}", flush=True)
        rows = []
        for r, c in tilings:
            name = args.testcase if (r, c) == (1, 1) else tile_testcase(args.testcase, r, c, root / f"{args.testcase}_{r}x{c}").name
            run_args = argparse.Namespace(testcase=name, region_size=args.region_size, iterations=args.iterations,
                                          threads=args.threads, policy="heuristic", seed=1)
            run = route_bench.run_once(run_args)
            f = run["final"]
            row = {"testcase": name, "copies": r * c, "nets": f["nets"], "route_s": run["route_s"],
                   "wall_s": run["wall_s"], "peak_rss_mb": run["peak_rss_mb"], "wirelength_um": f["wirelength_um"],
                   "vias": f["vias"], "violations": f["violations"], "violations_by_type": f["violations_by_type"],
                   "open_nets": f["open_nets"], "iterations": iteration_rows(run["iterations"])}
            row["late_share"] = late_share(row["iterations"])
            rows.append(row)
            print(f"{r * c:>6} {f['nets']:>7,} {run['route_s']:>8.1f} {run['wall_s']:>8.1f} {run['peak_rss_mb']:>7.0f} "
                  f"{f['wirelength_um']:>12,.1f} {f['vias']:>9,} {f['violations']:>6,} {f['open_nets']:>5}", flush=True)
            late = "-" if row["late_share"] is None else f"{100 * row['late_share']:.1f}% of the first"
            print("       iterations (s / violations left): "
                  + ", ".join(f"{it['seconds']:.1f}/{it['violations']}" for it in row["iterations"]) + f"; late {late}",
                  flush=True)
    nets = [float(r["nets"]) for r in rows]
    exp_time = slope(nets, [r["route_s"] for r in rows])
    exp_wall = slope(nets, [r["wall_s"] for r in rows])
    exp_rss = slope(nets, [r["peak_rss_mb"] for r in rows])
    print(f"growth exponent (log-log fit vs nets): route time {exp_time:.2f}, child wall {exp_wall:.2f}, "
          f"peak RSS {exp_rss:.2f}")
    if args.json:
        args.json.write_text(json.dumps({"rows": rows, "exponent_route_s": exp_time, "exponent_wall_s": exp_wall,
                                         "exponent_peak_rss": exp_rss}, indent=2))


if __name__ == "__main__":
    main()
