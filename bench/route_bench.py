"""Route a testcase end to end and print per-iteration figures, wall time and peak memory.

    python bench/route_bench.py [TESTCASE] [--region-size C] [--iterations N] [--threads T]
                                [--policy heuristic|random|FILE.py] [--seed S] [--repeat R]

Each repetition runs in a fresh Python process (load, route, write the DEF, re-read and check
it). Printed per iteration: wirelength (um), vias, violations (total and by type) and the
iteration's wall time; per run: the routing time, the child's whole wall time (Python start,
imports, load, route, outputs) and its peak RSS as the kernel reports it (wait4), and the
opens and violations found on the written DEF. Routing is deterministic, so the iteration
figures are printed once; the times of every run are listed, then min and median.

Default: ispd18_test1 with the router's region size (0: 10 GCells there), up to 10 iterations, 1 thread.
The reference route on the 2-core development machine: TritonRoute 25 s wall with 2 threads, 600 MB, 86,456 um,
35,443 vias, 0 violations. `--policy examples/python_heuristic_policy.py` routes with the built-in
heuristic written in Python (same order, one Python call per region): the cost of the seam.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent

CHILD = r"""
import json, sys, time
t0 = time.perf_counter()
from xroute import prepare_design
from xroute.outputs import write_route_outputs
from xroute.policies import get_policy
from xroute.router import route_design
a = json.loads(sys.argv[1])
t1 = time.perf_counter()
d = prepare_design(a["testcase"])
t2 = time.perf_counter()
r = route_design(d, region_size=a["region_size"], iterations=a["iterations"], threads=a["threads"],
                 policy=get_policy(a["policy"], a["seed"]), seed=a["seed"])
t3 = time.perf_counter()
o = write_route_outputs(d, r, a["out"], started=t1)
t4 = time.perf_counter()
print(json.dumps({"import_s": t1 - t0, "load_s": t2 - t1, "route_s": r.seconds, "outputs_s": t4 - t3,
                  "policy": r.policy, "iterations": [it.to_dict() for it in r.iterations], "final": o.final}))
"""


def run_once(args: argparse.Namespace) -> dict:
    from xroute.route_process import run_process

    with tempfile.TemporaryDirectory(prefix="route_bench_") as out:
        payload = json.dumps({"testcase": args.testcase, "region_size": args.region_size,
                              "iterations": args.iterations, "threads": args.threads, "policy": args.policy,
                              "seed": args.seed, "out": out})
        run = run_process([sys.executable, "-c", CHILD, payload])
    if run.returncode != 0:
        sys.exit(f"route_bench: the child failed with status {run.returncode}: {run.last_line}")
    result = json.loads(run.stdout)
    result["wall_s"] = run.wall_s
    result["peak_rss_mb"] = run.peak_rss_mb
    return result


def print_iterations(run: dict) -> None:
    types = [t for t in run["iterations"][0]["violations_by_type"]]
    shown = [t for t in types if any(it["violations_by_type"][t] for it in run["iterations"])]
    head = f"{'iter':>4} {'WL (um)':>12} {'vias':>8} {'violations':>10}" + "".join(f" {t:>12}" for t in shown)
    print(head + f" {'seconds':>8}")
    for it in run["iterations"]:
        row = f"{it['iteration']:>4} {it['wirelength_um']:>12,.1f} {it['vias']:>8,} {it['violations']:>10}"
        row += "".join(f" {it['violations_by_type'][t]:>12}" for t in shown)
        print(row + f" {it['seconds']:>8.2f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("testcase", nargs="?", default="ispd18_test1")
    ap.add_argument("--region-size", type=int, default=0, help="GCells (0: the router's for the design)")
    ap.add_argument("--iterations", type=int, default=10)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--policy", default="heuristic", help="heuristic, random or a .py policy file")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    if args.policy.endswith(".py"):
        args.policy = str(Path(args.policy).resolve())

    print(f"{args.testcase}: region size {args.region_size or 'auto'}, up to {args.iterations} iterations, "
          f"{args.threads} thread(s), policy {args.policy}, seed {args.seed}, {args.repeat} run(s), "
          f"{os.cpu_count()} CPUs")
    runs = []
    for i in range(max(1, args.repeat)):
        run = run_once(args)
        runs.append(run)
        if i == 0:
            print_iterations(run)
        f = run["final"]
        by_type = ", ".join(f"{k} {v}" for k, v in f["violations_by_type"].items() if v) or "none"
        print(f"run {i + 1}: route {run['route_s']:.2f} s, child wall {run['wall_s']:.2f} s "
              f"(imports {run['import_s']:.2f}, load {run['load_s']:.2f}, outputs + checks {run['outputs_s']:.2f}), "
              f"peak RSS {run['peak_rss_mb']:.0f} MB; written DEF: WL {f['wirelength_um']:,.1f} um, "
              f"{f['vias']:,} vias, {f['open_nets']} opens, {f['violations']} violations ({by_type})")
    if len(runs) > 1:
        route = [r["route_s"] for r in runs]
        wall = [r["wall_s"] for r in runs]
        print(f"route s: min {min(route):.2f} median {statistics.median(route):.2f}; "
              f"child wall s: min {min(wall):.2f} median {statistics.median(wall):.2f}; "
              f"peak RSS max {max(r['peak_rss_mb'] for r in runs):.0f} MB")


if __name__ == "__main__":
    main()
