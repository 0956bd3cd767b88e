"""Headroom of the schedule decisions against today's default: what could a learned plan gain?

    python -m experiments.schedule.headroom menu   DESIGN --out OUT [--threads 2] [--cutoff-ratio 1.5]
    python -m experiments.schedule.headroom search DESIGN --out OUT [--depth 3] [--threads 2]
    python -m experiments.schedule.headroom early  DESIGN --out OUT [--threads 2]
    python -m experiments.schedule.headroom plans  DESIGN --out OUT --prefixes "rule,size8;size10"
    python -m experiments.schedule.headroom table  OUT/*.jsonl

DESIGN is a testcase on the search path (``ispd18_test1_4x4`` is made on first use with
``xroute make-testcase --tile ispd18_test1 --by 4x4`` into OUT/tiles, which is put on the search path).

* ``menu``: the default, then the hand-written settings (victims 2/4/8, best-of-4, repair 1/3,
  sizes 5/7, 10 then 5, the shipped switch schedule); every run after the default is stopped once
  it has spent ``--cutoff-ratio`` times the default's CPU seconds (a run stopped there cannot be
  faster). CPU seconds, not wall, decide: on a shared machine they move far less with the load.
* ``search``: the best per-iteration plan sequence by greedy search with rollouts: for the first
  ``--depth`` iterations in turn, every action of :data:`ACTIONS` is tried at that iteration, with the
  best prefix found so far before it and the rule after it; the action whose run ends at 0
  violations soonest (CPU seconds; wire and vias within 0.3% of the default's) is kept.
* ``plans``: the default, then each named prefix of :data:`ACTIONS` (``;`` between prefixes, ``,``
  between iterations) with the rule after it: the sequences the greedy search would reach deeper.
* ``early``: the decisions that move iteration 1's cost: routes of two iterations, iteration 1
  with each action; prints iteration 1's seconds, regions, net routes and violations after it.

Every run is ``xroute route DESIGN --quiet --threads T`` in a fresh process (wall, CPU and peak RSS
from wait4), then ``xroute check`` on its routed DEF (contest score, opens). One JSON line per run
in OUT/<command>-<design>.jsonl; ``table`` prints them as markdown.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

XROUTE = (sys.executable, "-m", "xroute")
HERE = Path(__file__).resolve().parent
REPLAY = HERE / "replay_plans.py"
STALE_MODEL = HERE.parents[1] / "policies" / "models" / "schedule_switch.json"


def _bench_menu() -> list[tuple[str, list[str]]]:
    """bench/schedule_menu.py's menu (one list of the hand-written settings), loaded from its file."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("schedule_menu", HERE.parents[1] / "bench" / "schedule_menu.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return list(module.MENU)


MENU: list[tuple[str, list[str]]] = [*_bench_menu(), ("stale_model", ["--schedule-policy", str(STALE_MODEL)])]

# Changes to one iteration's plan (replay_plans.py's entries).
ACTIONS: dict[str, dict[str, Any]] = {
    "rule": {},
    "size5": {"region_size": 5},
    "size8": {"region_size": 8},
    "size10": {"region_size": 10},
    "size12": {"region_size": 12},
    "size24": {"region_size": 24},
    "repair1": {"repair_rounds": 1},
    "weights0.5": {"weights": 0.5},
    "weights2": {"weights": 2.0},
    "victims2": {"search_budget": 2},
    "victims4": {"search_budget": 4},
    # the shipped switch schedule's late plan: size 5 with the victims search at 4 trials
    "late5b4": {"region_size": 5, "search_budget": 4},
}
BAND = 0.003  # contest score within 0.3% of the default's


def run(design: str, flags: list[str], threads: int, out: Path, env: dict[str, str],
        timeout: float | None = None) -> dict[str, Any]:
    """One route in a fresh process (stopped past ``timeout`` CPU seconds), then its check; the figures as a dict."""
    from xroute.route_process import run_process

    proc = run_process([*XROUTE, "route", design, "--quiet", "--threads", str(threads), "--out", str(out), *flags],
                       env=env, cpu_limit=timeout, metrics_dir=out)
    stopped = proc.stopped
    row: dict[str, Any] = {"wall_s": round(proc.wall_s, 2), "cpu_s": round(proc.cpu_s, 2),
                           "rss_mb": round(proc.peak_rss_mb), "rc": proc.returncode, "stopped": stopped}
    if stopped or proc.metrics is None:
        row["error"] = "stopped at the cutoff" if stopped else (proc.stdout + proc.stderr)[-1000:]
        return row
    data = proc.metrics
    final = data["final"]
    row.update(violations=final["violations"], wirelength_um=final["wirelength_um"], vias=final["vias"],
               route_s=round(final["route_seconds"], 2),
               iterations=[{"seconds": round(it["seconds"], 2), "violations": it["violations"],
                            "regions": it["regions"], "net_routes": it["net_routes"],
                            "region_size": it["region_size"]} for it in data["iterations"]])
    chk = subprocess.run([*XROUTE, "check", design, "--def", str(out / f"{design}.routed.def"), "--out",
                          str(out / "check"), "--json"], capture_output=True, text=True, env=env)
    if chk.returncode in (0, 1):
        doc = json.loads(chk.stdout)
        row.update(score=doc["score"], opens=doc["opens"], check_violations=doc["violations"])
    else:
        row["check_error"] = chk.stderr.strip()[-500:]
    return row


def environment(out: Path, design: str) -> dict[str, str]:
    env = {**os.environ, "CI": "true"}
    tiles = out / "tiles"
    if design.endswith("_4x4"):
        folder = tiles / design
        if not folder.exists():
            folder.parent.mkdir(parents=True, exist_ok=True)
            subprocess.run([*XROUTE, "make-testcase", "--tile", design[:-4], "--by", "4x4", "--out", str(folder)],
                           check=True, env=env)
    if tiles.exists():
        env["XROUTE_TESTCASES"] = os.pathsep.join(p for p in (env.get("XROUTE_TESTCASES", ""), str(tiles)) if p)
    return env


def record(path: Path, row: dict[str, Any]) -> None:
    with path.open("a") as f:
        f.write(json.dumps(row) + "\n")
    its = row.get("iterations") or []
    print(f"{row['design']} {row['setting']}: viol={row.get('violations')} score={row.get('score')} "
          f"wall={row['wall_s']} cpu={row['cpu_s']} iters={len(its)} "
          f"per-iteration s={[it['seconds'] for it in its]}", flush=True)


def replay_flags(out: Path, name: str, plans: list[dict[str, Any]], env: dict[str, str]) -> list[str]:
    path = out / "plans" / f"{name}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(plans))
    env["XROUTE_REPLAY_PLANS"] = str(path)
    return ["--schedule-policy", str(REPLAY)]


def menu(args: argparse.Namespace, out: Path, env: dict[str, str]) -> None:
    log = out / f"menu-{args.design}.jsonl"
    default_cpu: float | None = None
    for name, flags in MENU:
        if args.only and name not in args.only.split(","):
            continue
        timeout = None if default_cpu is None else args.cutoff_ratio * default_cpu
        row = {"design": args.design, "setting": name, "flags": flags, "threads": args.threads,
               **run(args.design, flags, args.threads, out / "runs" / f"{args.design}-{name}", env, timeout)}
        if name == "default":
            default_cpu = row["cpu_s"]
        record(log, row)


def feasible(row: dict[str, Any], base: dict[str, Any]) -> bool:
    return (row.get("violations") == 0 and row.get("opens") == 0 and row.get("score") is not None
            and row["score"] <= base["score"] * (1 + BAND))


def search(args: argparse.Namespace, out: Path, env: dict[str, str]) -> None:
    log = out / f"search-{args.design}.jsonl"
    base = run(args.design, [], args.threads, out / "runs" / f"{args.design}-search-default", env)
    record(log, {"design": args.design, "setting": "default", "prefix": [], **base})
    prefix: list[str] = []
    best = base
    for depth in range(args.depth):
        if depth >= len(best.get("iterations") or []):
            break
        options = []
        for action in ACTIONS:
            if action == "rule":
                options.append((action, best))
                continue
            plans = [ACTIONS[a] for a in [*prefix, action]]
            name = "-".join([*prefix, action])
            flags = replay_flags(out, f"{args.design}-{name}", plans, env)
            row = run(args.design, flags, args.threads, out / "runs" / f"{args.design}-search-{name}", env,
                      args.cutoff_ratio * base["cpu_s"])
            record(log, {"design": args.design, "setting": name, "prefix": [*prefix, action], **row})
            options.append((action, row))
        ok = [(r["cpu_s"], a, r) for a, r in options if feasible(r, base)]
        if not ok:
            break
        _, action, best = min(ok, key=lambda t: t[0])
        prefix.append(action)
        print(f"depth {depth}: keep {action} (cpu {best['cpu_s']} s, wall {best['wall_s']} s)", flush=True)
    record(log, {"design": args.design, "setting": "best", "prefix": prefix, **best})


def plans(args: argparse.Namespace, out: Path, env: dict[str, str]) -> None:
    log = out / f"plans-{args.design}.jsonl"
    base = run(args.design, [], args.threads, out / "runs" / f"{args.design}-plans-default", env)
    record(log, {"design": args.design, "setting": "default", "prefix": [], **base})
    for text in (args.prefixes or "").split(";"):
        prefix = [a.strip() for a in text.split(",") if a.strip()]
        unknown = [a for a in prefix if a not in ACTIONS]
        if unknown or not prefix:
            raise SystemExit(f"error: --prefixes: unknown or empty prefix {text!r} (actions: {', '.join(ACTIONS)})")
        name = "-".join(prefix)
        flags = replay_flags(out, f"{args.design}-{name}", [ACTIONS[a] for a in prefix], env)
        row = run(args.design, flags, args.threads, out / "runs" / f"{args.design}-plans-{name}", env,
                  args.cutoff_ratio * base["cpu_s"])
        record(log, {"design": args.design, "setting": name, "prefix": prefix, **row})


def early(args: argparse.Namespace, out: Path, env: dict[str, str]) -> None:
    log = out / f"early-{args.design}.jsonl"
    for action, change in ACTIONS.items():
        flags = ["--iterations", "2", *replay_flags(out, f"{args.design}-early-{action}", [{}, change], env)]
        row = run(args.design, flags, args.threads, out / "runs" / f"{args.design}-early-{action}", env)
        record(log, {"design": args.design, "setting": f"iteration 1: {action}", **row})


def table(paths: list[str]) -> None:
    print("| design | setting | violations | score | wall s | CPU s | peak RSS | per-iteration s (violations) |")
    print("|---|---|---:|---:|---:|---:|---:|---|")
    for p in paths:
        for line in Path(p).read_text().splitlines():
            r = json.loads(line)
            its = ", ".join(f"{it['seconds']:.1f} ({it['violations']})" for it in r.get("iterations") or [])
            viol = r.get("violations", "stopped" if r.get("stopped") else "failed")
            score = f"{r['score']:,.0f}" if r.get("score") is not None else "—"
            print(f"| {r['design']} | {r['setting']} | {viol} | {score} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} | "
                  f"{r['rss_mb']} MB | {its} |")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["menu", "search", "early", "plans", "table"])
    ap.add_argument("design", nargs="+")
    ap.add_argument("--out", default="runs/headroom")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--cutoff-ratio", type=float, default=1.5)
    ap.add_argument("--depth", type=int, default=3)
    ap.add_argument("--only", default=None, help="menu: comma-separated setting names")
    ap.add_argument("--prefixes", default=None, help="plans: prefixes of actions, ';' between, ',' inside")
    args = ap.parse_args()
    if args.command == "table":
        table(args.design)
        return 0
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    for design in args.design:
        args.design = design
        env = environment(out, design)
        {"menu": menu, "search": search, "early": early, "plans": plans}[args.command](args, out, env)
    return 0


if __name__ == "__main__":
    sys.exit(main())
