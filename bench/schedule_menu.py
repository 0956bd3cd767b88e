"""The menu of hand-written settings beside a learned schedule, one design at a time, in one run.

    python bench/schedule_menu.py [DESIGN ...] [--learned MODEL.json ...] [--only NAME,...] [--skip NAME,...]
                                  [--threads 2] [--jsonl OUT] [--cutoff S] [--table-from JSONL]

Per design (default: ispd18_test1, ispd19_test1, ispd19_test3), one fresh process per setting,
sequentially: `xroute route DESIGN --quiet --threads T FLAGS`. The menu: default; victims at budgets
2, 4 and 8; best-of-4; repair rounds 1 and 3; region sizes 5 and 7; size 10 for the first iteration
then 5; then each `--learned` model (`--schedule-policy MODEL`, named after its file). Wall and CPU
seconds (all threads) and peak RSS come from wait4; violations, wirelength and vias from the run's
metrics JSON. `--cutoff` skips the settings of a design once that many seconds went to it (the
default's run always happens first).

Printed per design: each setting's final violations, wirelength and vias (and their change from the
default's), wall and CPU seconds (and wall / default wall), peak RSS, whether it lies in the 1% band
(wirelength and vias within 1% of the default's), the violations per iteration; then, for each learned
setting, its verdict against the menu, by wall time and by CPU time: the in-band menu settings that dominate it
(fewer-or-equal violations and less-or-equal time), and whether it reaches (a) 30% fewer violations
than the default at <= 1.2x its time or (b) the default's violations or fewer at <= 0.75x. The machine's load average is
printed before and after each run: on a shared machine wall times grow with it, CPU times less.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

TEN_THEN_FIVE = "10:0,5:1,5:3,5:0,5:1,5:3,5:0,5:1,5:3,5:0"
MENU: list[tuple[str, list[str]]] = [
    ("default", []),
    ("victims2", ["--policy", "victims", "--search-budget", "2"]),
    ("victims4", ["--policy", "victims", "--search-budget", "4"]),
    ("victims8", ["--policy", "victims", "--search-budget", "8"]),
    ("bestof4", ["--policy", "bestof", "--search-budget", "4"]),
    ("repair1", ["--repair-rounds", "1"]),
    ("repair3", ["--repair-rounds", "3"]),
    ("size5", ["--region-size", "5"]),
    ("size7", ["--region-size", "7"]),
    ("size10then5", ["--schedule", TEN_THEN_FIVE]),
]
DESIGNS = ["ispd18_test1", "ispd19_test1", "ispd19_test3"]
BAND = 0.01  # wirelength and vias within 1% of the default's


def run(design: str, name: str, flags: list[str], threads: int, out_root: Path) -> dict:
    """One route in a fresh process: its figures, wall/CPU seconds and peak RSS."""
    from xroute.route_process import run_process, xroute_command

    run_dir = out_root / f"{design}-{name}"
    proc = run_process(xroute_command("route", design, "--quiet", "--threads", str(threads), "--out", str(run_dir),
                                      *flags), env={"CI": "true"}, metrics_dir=run_dir)
    row: dict = {"design": design, "setting": name, "flags": flags, "threads": threads, "rc": proc.returncode,
                 "wall_s": round(proc.wall_s, 2), "cpu_s": round(proc.cpu_s, 2),
                 "peak_rss_mb": round(proc.peak_rss_mb, 1), "load1": round(os.getloadavg()[0], 2)}
    if proc.returncode != 0 or proc.metrics is None:
        row["error"] = [proc.last_line]
        return row
    m = proc.metrics
    f = m["final"]
    row.update(violations=f["violations"], violations_by_type=f["violations_by_type"], wirelength_um=f["wirelength_um"],
               vias=f["vias"], open_nets=f["open_nets"], per_iteration=[it["violations"] for it in m["iterations"]])
    return row


def in_band(row: dict, ref: dict) -> bool:
    return (row.get("open_nets") == 0 and row["wirelength_um"] <= ref["wirelength_um"] * (1 + BAND)
            and row["vias"] <= ref["vias"] * (1 + BAND))


def verdict(learned: dict, rows: list[dict], ref: dict) -> list[str]:
    """The floors of one learned setting against the menu's rows of the same design, by wall
    time and, since a shared machine's load moves wall times, by CPU time too."""
    menu = [r for r in rows if r["setting"] in dict(MENU) and "error" not in r and in_band(r, ref)]
    lines = [f"  {learned['setting']}: in the 1% band: {'yes' if in_band(learned, ref) else 'NO'}"]
    for clock in ("wall_s", "cpu_s"):
        dominating = [r["setting"] for r in menu
                      if r["violations"] <= learned["violations"] and r[clock] <= learned[clock]]
        ratio = learned[clock] / ref[clock]
        a = ref["violations"] > 0 and learned["violations"] <= 0.7 * ref["violations"] and ratio <= 1.2
        b = learned["violations"] <= ref["violations"] and ratio <= 0.75
        lines.append(f"    by {clock[:-2]} time ({ratio:.2f}x the default's): dominated by in-band menu settings: "
                     f"{', '.join(dominating) or 'none'}; (a) <= 70% of the default's violations at <= 1.2x: "
                     f"{'met' if a else 'not met'}; (b) <= its violations at <= 0.75x: {'met' if b else 'not met'}")
    return lines


def table(design: str, rows: list[dict]) -> list[str]:
    ref = next((r for r in rows if r["setting"] == "default" and "error" not in r), None)
    lines = [f"## {design}", "",
             "| setting | violations | WL um (vs default) | vias (vs default) | wall s (x default) | CPU s | RSS MB "
             "| 1% band | per iteration |",
             "|---|---:|---:|---:|---:|---:|---:|---|---|"]
    for r in rows:
        if "error" in r:
            lines.append(f"| {r['setting']} | failed: {r['error'][0]} | | | | | | | |")
            continue
        d_wl = f" ({100 * (r['wirelength_um'] / ref['wirelength_um'] - 1):+.2f}%)" if ref else ""
        d_v = f" ({100 * (r['vias'] / ref['vias'] - 1):+.2f}%)" if ref else ""
        x = f" ({r['wall_s'] / ref['wall_s']:.2f}x)" if ref else ""
        band = ("yes" if in_band(r, ref) else "no") if ref else "?"
        lines.append(f"| {r['setting']} | {r['violations']} | {r['wirelength_um']:,.1f}{d_wl} | {r['vias']:,}{d_v} "
                     f"| {r['wall_s']:.1f}{x} | {r['cpu_s']:.1f} | {r['peak_rss_mb']:.0f} | {band} "
                     f"| {', '.join(map(str, r['per_iteration']))} |")
    if ref:
        for r in rows:
            if r["setting"] not in dict(MENU) and "error" not in r:
                lines += verdict(r, rows, ref)
    return lines + [""]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("designs", nargs="*", default=DESIGNS)
    ap.add_argument("--learned", action="append", default=[], help="a schedule model (.json) or policy (.py)")
    ap.add_argument("--only", default="", help="settings to run, comma-separated (default: all)")
    ap.add_argument("--skip", default="", help="settings to leave out, comma-separated")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--jsonl", default=None, help="append one JSON line per run to this file")
    ap.add_argument("--cutoff", type=float, default=None, help="seconds per design after which settings are skipped")
    ap.add_argument("--runs", default="/tmp/xroute_schedule_menu", help="folder for the runs' outputs")
    ap.add_argument("--table-from", default=None, metavar="JSONL",
                    help="route nothing: print the tables of the runs a --jsonl file holds (the last run of each "
                         "design and setting)")
    args = ap.parse_args()
    if args.table_from:
        rows: dict[tuple[str, str], dict] = {}
        for line in Path(args.table_from).read_text().splitlines():
            row = json.loads(line)
            rows[(row["design"], row["setting"])] = row
        for design in dict.fromkeys(d for d, _ in rows):
            ordered = sorted((r for (d, _), r in rows.items() if d == design), key=lambda r: r["setting"] != "default")
            print("\n".join(table(design, ordered)))
        return 0
    settings = list(MENU) + [(Path(m).stem, ["--schedule-policy", str(Path(m).resolve())]) for m in args.learned]
    only = {s for s in args.only.split(",") if s}
    skip = {s for s in args.skip.split(",") if s}
    settings = [(n, f) for n, f in settings if n == "default" or ((not only or n in only) and n not in skip)]
    for design in args.designs:
        rows, start = [], time.monotonic()
        for name, flags in settings:
            if args.cutoff is not None and name != "default" and time.monotonic() - start > args.cutoff:
                print(f"[{design}] {name}: skipped (cutoff)", flush=True)
                continue
            print(f"[{design}] {name}: load {os.getloadavg()[0]:.2f} ...", end=" ", flush=True)
            row = run(design, name, flags, args.threads, Path(args.runs))
            rows.append(row)
            print(f"{row.get('violations', 'failed')} violations, {row['wall_s']} s wall, {row['cpu_s']} s CPU, "
                  f"load {row['load1']:.2f}", flush=True)
            if args.jsonl:
                with open(args.jsonl, "a") as f:
                    f.write(json.dumps(row) + "\n")
        print("\n".join(table(design, rows)), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
