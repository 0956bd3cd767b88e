"""``xroute check`` on a routed DEF holding copies of one wire, each shifted by 1 DBU (a hostile-input case).

    python bench/check_copies_bench.py [--copies 50000] [--repeat 1]

The demo is routed once; then, for its shortest and its longest wire, the copies are added to the
wire's net, shifted across the wire (they overlap into a band as wide as the count) or along it,
and ``xroute check`` runs on each DEF in a fresh process. Prints the wall time (best of --repeat),
the markers and the opens of each. The DRC's per-layer index, edge sweep and collinear joins keep
these near linear (engine_cpp/drc/README.md).
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

WIRE = re.compile(r"(?:ROUTED|NEW) (Metal\d+) \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)")


def xroute(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "xroute", *args], capture_output=True, text=True)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--copies", type=int, default=50000)
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="xroute-copies-") as tmp:
        root = Path(tmp)
        assert xroute("route", "--out", str(root / "demo"), "--quiet").returncode == 0
        lines = (root / "demo" / "demo.routed.def").read_text().split("\n")
        wires = sorted((abs(int(m[4]) - int(m[2])) + abs(int(m[5]) - int(m[3])), i, m)
                       for i, line in enumerate(lines) if (m := WIRE.search(line)))
        print(f"{'wire':28s} {'copies':>7s} {'shift':6s} {'seconds':>8s} {'markers':>8s} {'opens':>6s}")
        for length, at, m in (wires[0], wires[-1]):
            layer, x1, y1, x2, y2 = m[1], *map(int, m.groups()[1:])
            for shift in ("across", "along"):
                dx, dy = (0, 1) if (y1 == y2) == (shift == "across") else (1, 0)
                extra = [f"    NEW {layer} ( {x1 + i * dx} {y1 + i * dy} ) ( {x2 + i * dx} {y2 + i * dy} )"
                         for i in range(args.copies)]
                path = root / f"{length}-{shift}.def"
                path.write_text("\n".join(lines[: at + 1] + extra + lines[at + 1:]))
                best = float("inf")
                for _ in range(args.repeat):
                    started = time.perf_counter()
                    proc = xroute("check", "demo", "--def", str(path), "--out", str(root / "c"), "--json")
                    best = min(best, time.perf_counter() - started)
                doc = json.loads(proc.stdout)
                print(f"{layer} {length:>6,} DBU line {at + 1:<8d} {args.copies:>7,} {shift:6s} {best:8.1f} "
                      f"{doc['violations']:>8,} {doc['opens']:>6,}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
