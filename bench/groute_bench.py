"""The built-in global router: guide quality measured by detailed routing, and ispd19_test3 end to end.

    python bench/groute_bench.py [--compare TESTCASE] [--route TESTCASE] [--capacity P] [--slack S]

--compare (default ispd18_test1): the testcase detailed-routed twice, once with its contest guides
and once with guides from the built-in global router (contest guide ignored); printed for each:
wirelength (um), vias, violations by type, opens, routing and whole wall time, peak RSS.
--route (default ispd19_test3, which has no contest guide): routed end to end with built-in guides,
the same figures plus the global router's own (overflow, GCell wirelength, time).
Each run is a fresh Python process (load, [global route,] route, write the DEF, re-read and check
it); peak RSS is the child's own (getrusage). Pass --compare '' or --route '' to skip one.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO_ROOT / "bench"))
from route_bench import _child_env  # noqa: E402

CHILD = r"""
import json, sys, time
t0 = time.perf_counter()
from xroute import load_design
from xroute.groute import global_route
from xroute.outputs import write_route_outputs
from xroute.router import route_design
a = json.loads(sys.argv[1])
d = load_design(a["testcase"], use_guide=a["use_guide"])
gr = None
if not d.has_guides:
    gr = global_route(d, capacity_percent=a["capacity"], slack=a["slack"]).to_dict()
r = route_design(d)
o = write_route_outputs(d, r, a["out"], started=t0)
print(json.dumps({"route_s": r.seconds, "global_route": gr, "final": o.final}))
"""


def run(testcase: str, use_guide: bool, capacity: int, slack: int) -> dict:
    with tempfile.TemporaryDirectory() as out:
        args = json.dumps({"testcase": testcase, "use_guide": use_guide, "out": out, "capacity": capacity,
                           "slack": slack})
        start = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-c", CHILD, args], stdout=subprocess.PIPE, env=_child_env(),
                                cwd=REPO_ROOT)
        stdout, _ = proc.communicate()
        wall = time.perf_counter() - start
        if proc.returncode != 0:
            raise SystemExit(f"child failed on {testcase} (status {proc.returncode})")
        data = json.loads(stdout.decode().strip().splitlines()[-1])
        data["wall_s"] = wall
        data["peak_rss_mb"] = data["final"]["peak_rss_mb"]  # the child's own ru_maxrss
        return data


def show(label: str, d: dict) -> None:
    f = d["final"]
    kinds = ", ".join(f"{k} {v}" for k, v in f["violations_by_type"].items() if v) or "none"
    print(f"{label}: WL {f['wirelength_um']:,.1f} um, {f['vias']:,} vias, {f['violations']} violations ({kinds}), "
          f"{f['open_nets']} open nets, route {d['route_s']:.1f} s, wall {d['wall_s']:.1f} s, "
          f"peak {d['peak_rss_mb']:.0f} MB")
    gr = d.get("global_route")
    if gr:
        print(f"  global route: {gr['gcells'][0]} x {gr['gcells'][1]} GCells, {gr['nets']} nets, overflow "
              f"{gr['overflow']} (pattern {gr['initial_overflow']}, 3D {gr['overflow_3d']}), "
              f"{gr['wirelength_gcells']:,} GCells, {gr['vias']:,} vias, {gr['guides']:,} guides, "
              f"{gr['iterations']} rounds, {gr['seconds']:.2f} s")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--compare", default="ispd18_test1")
    p.add_argument("--route", default="ispd19_test3")
    p.add_argument("--capacity", type=int, default=70)
    p.add_argument("--slack", type=int, default=0)
    a = p.parse_args()
    if a.compare:
        show(f"{a.compare} contest guides ", run(a.compare, True, a.capacity, a.slack))
        show(f"{a.compare} built-in guides", run(a.compare, False, a.capacity, a.slack))
    if a.route:
        show(f"{a.route} built-in guides", run(a.route, False, a.capacity, a.slack))


if __name__ == "__main__":
    main()
