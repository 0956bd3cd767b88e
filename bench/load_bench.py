"""Time and peak memory to load a testcase (LEF + DEF + guide).

    python bench/load_bench.py [TESTCASE ...] [--repeat N]

Each repetition runs in a fresh Python process, so the peak resident set size
is the load's own: the figure printed is the peak RSS of the process after the
load minus its peak RSS after importing the engine (and the whole-process peak
beside it). Times are wall clock of the load call alone. For comparison each
child also times reading the same files raw from the page cache (best of 3)
and the load again, warm, in stages (LEF alone, LEF + DEF, all; best of 3). The floors set
for ispd18_test1: under 1 s and 150 MB.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys

CHILD = r"""
import json, os, resource, sys, time
from xroute import _engine, load_design
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
d = load_design(sys.argv[1])
t1 = time.perf_counter()
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
files = d.lef_paths + [d.def_path] + ([d.guide_path] if d.guide_path else [])

def best(fn, n=3):
    times = []
    for _ in range(n):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)

def read_all():
    for f in files:
        with open(f, "rb") as fh:
            fh.read()

# The same files read raw (from the page cache, as the load just read them),
# and the load in stages: LEF alone, LEF + DEF (the full load is the above).
read_s = best(read_all)
lef_s = best(lambda: _engine.load_lef(d.lef_paths))
def_s = best(lambda: _engine.load(d.lef_paths, d.def_path))
full_s = best(lambda: _engine.load(d.lef_paths, d.def_path, d.guide_path or None))
print(json.dumps({"seconds": t1 - t0, "peak_kb": peak, "base_kb": base,
                  "bytes": sum(os.path.getsize(f) for f in files),
                  "read_seconds": read_s, "lef_seconds": lef_s, "lef_def_seconds": def_s, "warm_seconds": full_s,
                  "counts": d.counts()}))
"""


def run_once(testcase: str) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, testcase], check=True, capture_output=True, text=True, env=os.environ.copy()
    )
    return json.loads(out.stdout)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("testcases", nargs="*", default=["ispd18_test1"])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    print(f"{'testcase':<16} {'MB read':>8} {'median s':>9} {'min s':>7} {'MB/s':>7} {'peak RSS MB':>12} {'load MB':>8}")
    for name in args.testcases:
        runs = [run_once(name) for _ in range(args.repeat)]
        secs = [r["seconds"] for r in runs]
        med = statistics.median(secs)
        mb = runs[0]["bytes"] / 1e6
        peak = max(r["peak_kb"] for r in runs) / 1024
        delta = max(r["peak_kb"] - r["base_kb"] for r in runs) / 1024
        print(f"{name:<16} {mb:>8.2f} {med:>9.3f} {min(secs):>7.3f} {mb / med:>7.1f} {peak:>12.1f} {delta:>8.1f}")
        read = min(r["read_seconds"] for r in runs)
        lef = statistics.median(r["lef_seconds"] for r in runs)
        lef_def = statistics.median(r["lef_def_seconds"] for r in runs)
        warm = statistics.median(r["warm_seconds"] for r in runs)
        print(
            f"{'':<16} raw read {read * 1e3:.2f} ms ({mb / read:.0f} MB/s, page cache); warm load {warm * 1e3:.1f} ms "
            f"({mb / warm:.0f} MB/s, {warm / read:.0f}x the raw read): LEF {lef * 1e3:.1f} ms, "
            f"+DEF {(lef_def - lef) * 1e3:.1f} ms, +guide {(warm - lef_def) * 1e3:.1f} ms"
        )
        c = runs[0]["counts"]
        print(f"{'':<16} components={c['components']} nets={c['nets']} pins={c['net_pins']} guides={c['guides']}")


if __name__ == "__main__":
    main()
