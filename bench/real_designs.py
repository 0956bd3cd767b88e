"""Placed designs from open flows (OpenROAD's test data on Nangate45, sky130, asap7), routed and judged.

    python bench/real_designs.py [--manifest bench/real_designs.tsv] [--root DIR] [--git-dir GIT]
                                 [--only ID,ID] [--contest NAME,NAME] [--threads 2] [--out DIR]
                                 [--timeout S] [--json FILE]

The manifest (``real_designs.tsv``) names each design's repository, commit and paths; the files
are never in this repository. They are read from ``--root`` (default ``$XROUTE_REAL_DESIGNS``, else
``~/.cache/xroute/real_designs``), where ``<root>/<path>`` is the file at the manifest's commit; with
``--git-dir`` (a clone, bare or not, of the repository) a file missing there is first written into
the root from the clone (``git show COMMIT:PATH``, symbolic links followed). A design whose files are
missing is skipped with the reason.

Each design is routed by ``python -m xroute route`` in its own process (the router's defaults,
``--threads``, the guide when the manifest gives one, else the built-in global router), then the
routed DEF is judged by ``python -m xroute check``. Printed per design: nets, first-pass violations
(after iteration 0) and per net, iterations, violations by type and opens of the written DEF, wire
(um) and vias, the whole process's wall seconds, milliseconds per net, the router's peak RSS, and the
rules the LEFs state that the checker does not judge. ``--contest`` routes contest testcases by name
in the same run (ispd18_test1, ispd19_test3: the per-net yardsticks). OpenROAD's own routed DEFs of a
placement (manifest column ``openroad``) are judged by ``xroute check`` too and printed beside ours,
with our wire and vias over theirs (``wire_ratio``, ``via_ratio`` in the JSON).
Exit status 1 when a route fails or leaves violations or opens.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
COLUMNS = ("id", "pdk", "repo", "commit", "def", "lefs", "guide", "openroad", "note")


def read_manifest(path: Path) -> list[dict[str, str]]:
    """The manifest's rows; a malformed line is an error naming the file and line."""
    rows: list[dict[str, str]] = []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            fields = line.rstrip("\n").split("\t")
            if fields[0] == "id":
                continue
            if len(fields) != len(COLUMNS):
                raise SystemExit(f"error: {path}:{number}: {len(fields)} fields, expected {len(COLUMNS)}")
            rows.append(dict(zip(COLUMNS, fields)))
    return rows


def paths_of(row: dict[str, str]) -> list[str]:
    extra = [] if row["guide"] == "-" else [row["guide"]]
    routed = [] if row["openroad"] == "-" else row["openroad"].split(";")
    return [row["def"], *row["lefs"].split(";"), *extra, *routed]


def git_blob(git_dir: Path, commit: str, path: str) -> bytes | None:
    """The file at commit:path in the clone, symbolic links followed, in the folders on the path too
    (None when absent)."""
    def entry(p: str) -> tuple[str, bytes] | None:
        listing = subprocess.run(["git", f"--git-dir={git_dir}", "ls-tree", commit, "--", p],
                                 capture_output=True, text=True)
        if listing.returncode != 0 or not listing.stdout.strip():
            return None
        mode, kind = listing.stdout.split()[:2]
        if kind != "blob":
            return mode, b""
        blob = subprocess.run(["git", f"--git-dir={git_dir}", "show", f"{commit}:{p}"], capture_output=True)
        return (mode, blob.stdout) if blob.returncode == 0 else None

    todo, done, links = path.split("/"), [], 0
    while todo:
        here = "/".join([*done, todo.pop(0)])
        found = entry(here)
        if found is None:
            return None
        mode, data = found
        if mode == "120000":  # a link: go on from its target
            links += 1
            if links > 16:
                return None
            target = os.path.normpath(os.path.join(os.path.dirname(here), data.decode().strip()))
            if target.startswith(".."):
                return None
            done, todo = [], target.split("/") + todo
        elif not todo:
            return data if data or mode != "040000" else None
        else:
            done = here.split("/")
    return None


def ensure_files(row: dict[str, str], root: Path, git_dir: Path | None) -> str | None:
    """None when every file of the row is under root (written from git_dir if need be), else why not."""
    for rel in paths_of(row):
        dest = root / rel
        if dest.is_file():
            continue
        data = git_blob(git_dir, row["commit"], rel) if git_dir is not None else None
        if data is None:
            return f"{rel} not under {root}" + (f" nor in {git_dir}" if git_dir else " (give --git-dir)")
        dest.parent.mkdir(parents=True, exist_ok=True)
        tmp = dest.with_name(dest.name + ".part")
        tmp.write_bytes(data)
        tmp.replace(dest)
    return None


def run(cmd: list[str], timeout: float) -> tuple[int, float, str]:
    start = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return 124, time.perf_counter() - start, f"still running after {timeout:.0f} s"
    return p.returncode, time.perf_counter() - start, (p.stderr.strip().splitlines() or [""])[-1]


def check(lefs: list[Path], def_path: Path, guide: Path | None, timeout: float) -> dict:
    cmd = [sys.executable, "-m", "xroute", "check", "--json", "--def", str(def_path)]
    for lef in lefs:
        cmd += ["--lef", str(lef)]
    if guide is not None:
        cmd += ["--guide", str(guide)]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        return json.loads(p.stdout)
    except (subprocess.TimeoutExpired, json.JSONDecodeError) as e:
        return {"error": str(e)}


def route_one(name: str, lefs: list[Path], def_path: Path | None, guide: Path | None, args, out: Path) -> dict:
    """Route one design (files, or a testcase name when def_path is None) and judge the written DEF."""
    cmd = [sys.executable, "-m", "xroute", "route", "--threads", str(args.threads), "--out", str(out)]
    if def_path is None:
        cmd.append(name)
    else:
        cmd += ["--def", str(def_path)] + [a for lef in lefs for a in ("--lef", str(lef))]
        if guide is not None:
            cmd += ["--guide", str(guide)]
    rc, wall, last = run(cmd, args.timeout)
    metrics = sorted(out.glob("*.metrics.json"))
    if rc not in (0, 1) or not metrics:
        return {"id": name, "error": f"route exit {rc}: {last}", "wall_s": wall}
    m = json.loads(metrics[0].read_text())
    final, its = m["final"], m["iterations"]
    row = {"id": name, "nets": final["nets"], "first_pass": its[0]["violations"] if its else None,
           "iterations": final["iterations_run"], "wirelength_um": final["wirelength_um"], "vias": final["vias"],
           "wall_s": round(wall, 1), "route_s": round(final["route_seconds"], 1), "peak_rss_mb": final["peak_rss_mb"],
           "iteration_s": [round(i["seconds"], 2) for i in its]}
    routed = sorted(out.glob("*.routed.def"))
    if def_path is not None and routed:
        judged = check(lefs, routed[0], guide, args.timeout)
        row.update(violations=judged.get("violations"), by_type=judged.get("violations_by_type"),
                   opens=judged.get("opens"), not_checked=judged.get("not_checked"), check_error=judged.get("error"))
    else:
        row.update(violations=final["violations"],
                   by_type={k: v for k, v in final["violations_by_type"].items() if v}, opens=final["open_nets"])
    return row


def fmt(row: dict) -> str:
    if "error" in row:
        return f"| {row['id']} | failed: {row['error']} |"
    nets = row["nets"] or 1
    types = ", ".join(f"{k} {v}" for k, v in (row.get("by_type") or {}).items() if v) or "-"
    rules = row.get("not_checked")
    named = "; ".join(f"{r['rule']} ({len(r['layers'])})" for r in rules) if rules else "-"
    return (f"| {row['id']} | {row.get('pdk', '')} | {row['nets']:,} | {row['first_pass']:,} "
            f"({row['first_pass'] / nets:.2f}) | {row['iterations']} | {row['violations']} ({types}) | "
            f"{row['opens']} | {row['wirelength_um']:,.1f} | {row['vias']:,} | {row['wall_s']:.1f} | "
            f"{1000 * row['wall_s'] / nets:.1f} | {row['peak_rss_mb']:,.0f} | {named} |")


def add_source_args(ap: argparse.ArgumentParser) -> None:
    """--manifest, --root and --git-dir: where the manifest's files are found (ensure_files)."""
    ap.add_argument("--manifest", type=Path, default=HERE / "real_designs.tsv")
    ap.add_argument("--root", type=Path, default=Path(os.environ.get(
        "XROUTE_REAL_DESIGNS", Path.home() / ".cache" / "xroute" / "real_designs")))
    ap.add_argument("--git-dir", type=Path, default=None)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_source_args(ap)
    ap.add_argument("--only", default="", help="comma-separated ids")
    ap.add_argument("--contest", default="", help="comma-separated testcase names routed in the same run")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=3600.0)
    ap.add_argument("--out", type=Path, default=Path("/tmp/xroute-real-designs"))
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args(argv)

    rows = read_manifest(args.manifest)
    only = {s for s in args.only.split(",") if s}
    unknown = only - {r["id"] for r in rows}
    if unknown:
        raise SystemExit(f"error: --only: no design {', '.join(sorted(unknown))} in {args.manifest}")
    results, failed = [], False
    print("| design | PDK | nets | first pass (per net) | iterations | violations | opens | wire um | vias | "
          "wall s | ms/net | peak MB | not checked (layers) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        if only and row["id"] not in only:
            continue
        why = ensure_files(row, args.root, args.git_dir)
        if why is not None:
            print(f"| {row['id']} | skipped: {why} |", flush=True)
            continue
        lefs = [args.root / p for p in row["lefs"].split(";")]
        guide = None if row["guide"] == "-" else args.root / row["guide"]
        res = route_one(row["id"], lefs, args.root / row["def"], guide, args, args.out / row["id"])
        res["pdk"] = row["pdk"]
        res["openroad"] = []
        if row["openroad"] != "-":
            for rel in row["openroad"].split(";"):
                judged = check(lefs, args.root / rel, None, args.timeout)
                res["openroad"].append({"def": rel, **{k: judged.get(k) for k in (
                    "violations", "violations_by_type", "opens", "wirelength_um", "vias", "error")}})
        results.append(res)
        failed |= "error" in res or bool(res.get("violations")) or bool(res.get("opens"))
        print(fmt(res), flush=True)
    for name in [s for s in args.contest.split(",") if s]:
        res = route_one(name, [], None, None, args, args.out / name)
        res["pdk"] = "contest"
        results.append(res)
        failed |= "error" in res or bool(res.get("violations")) or bool(res.get("opens"))
        print(fmt(res), flush=True)
    for res in results:
        for o in res.get("openroad", []):
            types = ", ".join(f"{k} {v}" for k, v in (o.get("violations_by_type") or {}).items() if v) or "-"
            ratio = ""
            if o.get("wirelength_um") and o.get("vias") and res.get("wirelength_um") is not None:
                o["wire_ratio"] = round(res["wirelength_um"] / o["wirelength_um"], 4)
                o["via_ratio"] = round(res["vias"] / o["vias"], 4)
                ratio = f"; ours / OpenROAD's: wire {o['wire_ratio']:.3f}, vias {o['via_ratio']:.3f}"
            print(f"OpenROAD's {o['def']} by xroute check: {o['violations']} violations ({types}), "
                  f"{o['opens']} opens, {o['wirelength_um']} um, {o['vias']} vias (ours: {res.get('violations')}, "
                  f"{res.get('wirelength_um')} um, {res.get('vias')} vias{ratio})")
    if args.json:
        args.json.write_text(json.dumps({"date": time.strftime("%Y-%m-%d"), "threads": args.threads,
                                         "results": results}, indent=1) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
