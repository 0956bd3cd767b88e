"""Generate and route one design per real technology: the floors on every LEF we have.

    python bench/techs_bench.py [NAME ...] [--cells 5000] [--threads 2] [--seed 1] [--utilization U]
                                [--techs DIR] [--testcases DIR] [--timeout S] [--keep DIR]

The technologies: every ``*.lef`` in ``--techs`` (default ``../shared/techs`` beside the repository
root: ISPD-2018 test2-test10, ISPD-2019 test4-test5) and the LEF of every contest testcase folder in
``--testcases`` (default ``../shared/testcases``: ``<name>/<name>.input.lef``); NAMEs keep only those
whose name contains one of them. Per technology, two child processes: ``xroute make-testcase --lef L
--cells N --seed S`` (its wall time is the generation time: LEF read, placement, netlist, DEF, the
built-in global router and the reload check), then ``xroute route --lef L --def D --guide G --threads
T --quiet --out O``, whose peak RSS comes from wait4 (ru_maxrss) and whose figures come from its
metrics JSON and DRC report (nets with violations: the distinct regular nets its markers name).

Printed per technology: cells, nets, violations by type, violations, nets with violations, opens,
wirelength (um), vias, the router's own route time, the child's wall and CPU time, peak RSS,
generation time, and whether the floors hold (0 opens, violations on at most 0.5 % of the
nets, route time under 120 s). The machine's load average is printed before and after: on a shared
machine the wall times grow with it, the CPU times less so.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
import time
from pathlib import Path

from xroute.route_process import run_process, xroute_command

REPO_ROOT = Path(__file__).resolve().parent.parent
SHARED = REPO_ROOT.parent / "shared"
FLOOR_NETS_SHARE = 0.005  # violations on at most this share of the nets
FLOOR_ROUTE_S = 120.0  # route time under this
SHORT = {"Short": "Sh", "MetalSpacing": "Sp", "EndOfLine": "EOL", "CutShort": "CSh", "CutSpacing": "CSp",
         "AdjacentCuts": "Adj", "MinArea": "MA", "CornerSpacing": "Cor"}
NET_NAME = re.compile(r"n\d+")  # the generator's net names (special nets and '-' are not counted)


def _natural(name: str) -> list:
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", name)]


def technologies(techs: Path, testcases: Path, names: list[str]) -> list[tuple[str, Path]]:
    found = [(p.name.split(".")[0], p) for p in techs.glob("*.lef")] if techs.is_dir() else []
    if testcases.is_dir():
        found += [(d.name, d / f"{d.name}.input.lef") for d in testcases.iterdir()
                  if (d / f"{d.name}.input.lef").is_file()]
    found.sort(key=lambda t: _natural(t[0]))
    return [t for t in found if not names or any(n in t[0] for n in names)]


def _nets_with_violations(report: Path) -> int:
    nets: set[str] = set()
    for line in report.read_text().splitlines()[1:]:
        nets.update(w for w in line.split()[6:] if NET_NAME.fullmatch(w))
    return len(nets)


def bench_one(name: str, lef: Path, args: argparse.Namespace, work: Path) -> dict:
    row: dict = {"tech": name, "cells": args.cells}
    folder = work / f"{name}_gen{args.cells}_s{args.seed}"
    gen = xroute_command("make-testcase", "--lef", str(lef), "--cells", str(args.cells), "--seed", str(args.seed),
                         "--out", str(folder))
    if args.utilization is not None:
        gen += ["--utilization", str(args.utilization)]
    made = run_process(gen, timeout=args.timeout)
    row["gen_s"] = made.wall_s
    if made.returncode != 0:
        row["note"] = "generation failed: " + made.last_line
        return row
    out = folder / "out"
    stem = folder / folder.name
    route = xroute_command("route", "--lef", str(lef), "--def", f"{stem}.def", "--guide", f"{stem}.guide",
                           "--threads", str(args.threads), "--seed", str(args.seed), "--quiet", "--out", str(out))
    routed = run_process(route, timeout=args.timeout, metrics_dir=out)
    row.update(route_wall_s=routed.wall_s, route_cpu_s=routed.cpu_s, rss_mb=routed.peak_rss_mb)
    if routed.returncode not in (0, 1) or routed.metrics is None:
        row["note"] = f"route failed (exit {routed.returncode}): {routed.last_line}"
        return row
    final = routed.metrics["final"]
    row.update(nets=final["nets"], violations=final["violations"], by_type=final["violations_by_type"],
               opens=final["open_nets"], wl_um=final["wirelength_um"], vias=final["vias"],
               route_s=final["route_seconds"], bad_nets=_nets_with_violations(out / f"{folder.name}.drc.rpt"))
    row["floors"] = (row["opens"] == 0 and row["bad_nets"] <= FLOOR_NETS_SHARE * row["nets"]
                     and row["route_s"] < FLOOR_ROUTE_S)
    return row


HEADER = ("technology", "cells", "nets", "violations by type", "viol", "nets w/ viol", "opens", "WL um", "vias",
          "route s", "wall s", "CPU s", "RSS MB", "gen s", "floors")


def format_row(r: dict) -> tuple[str, ...]:
    if "nets" not in r:
        return (r["tech"], str(r["cells"]), "-", r.get("note", ""), "", "", "", "", "", "", "", "", "",
                f"{r['gen_s']:.1f}", "no")
    types = " ".join(f"{SHORT.get(k, k)}:{v}" for k, v in r["by_type"].items() if v) or "-"
    share = 100.0 * r["bad_nets"] / max(1, r["nets"])
    return (r["tech"], f"{r['cells']:,}", f"{r['nets']:,}", types, f"{r['violations']:,}",
            f"{r['bad_nets']:,} ({share:.2f}%)", str(r["opens"]), f"{r['wl_um']:,.0f}", f"{r['vias']:,}",
            f"{r['route_s']:.1f}", f"{r['route_wall_s']:.1f}", f"{r['route_cpu_s']:.1f}", f"{r['rss_mb']:.0f}",
            f"{r['gen_s']:.1f}", "met" if r["floors"] else "MISSED")


def print_table(rows: list[dict]) -> None:
    lines = [HEADER] + [format_row(r) for r in rows]
    widths = [max(len(line[i]) for line in lines) for i in range(len(HEADER))]
    for k, line in enumerate(lines):
        print("| " + " | ".join(c.ljust(w) for c, w in zip(line, widths)) + " |")
        if k == 0:
            print("|" + "|".join("-" * (w + 2) for w in widths) + "|")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="keep the technologies whose name contains one of these")
    ap.add_argument("--cells", type=int, default=5000)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--utilization", type=float, default=None, help="default: make-testcase's (0.75)")
    ap.add_argument("--techs", type=Path, default=SHARED / "techs")
    ap.add_argument("--testcases", type=Path, default=SHARED / "testcases")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per child process")
    ap.add_argument("--keep", type=Path, default=None, help="write the designs and routes here (else a temp dir)")
    args = ap.parse_args()
    techs = technologies(args.techs, args.testcases, args.names)
    if not techs:
        sys.exit(f"techs_bench: no LEF found in {args.techs} or {args.testcases}")
    print(f"# {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {args.cells} cells, seed {args.seed}, "
          f"{args.threads} threads, load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs", flush=True)
    rows = []
    with tempfile.TemporaryDirectory(prefix="techs_bench_") as tmp:
        work = args.keep if args.keep is not None else Path(tmp)
        for name, lef in techs:
            rows.append(bench_one(name, lef, args, work))
            print(f"# done {name}: " + " ".join(format_row(rows[-1])[2:]), file=sys.stderr, flush=True)
    print_table(rows)
    met = sum(1 for r in rows if r.get("floors"))
    print(f"# floors met on {met} of {len(rows)}; load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
