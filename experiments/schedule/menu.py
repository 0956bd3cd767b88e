"""Run the menu of hand-written settings on the contest designs in parallel, one JSON line per job.

    python -m experiments.schedule.menu --out OUT [--cores N] [--cutoff S] [--only NAME]
                                        [--src CHECKOUT] [--data TESTCASES]

Without --src it runs the installed `xroute`; with --src, the package in CHECKOUT/src (whose
src/xroute must hold a compiled _engine module, as on a borrowed machine without pip access).
--data sets XROUTE_TESTCASES.

Each job is `python -m xroute route DESIGN --quiet --threads T FLAGS`; its wall and CPU seconds
(wait4, all threads) and its metrics JSON's final and per-iteration figures are appended to
OUT/menu.jsonl when it ends. Jobs start longest-first while free cores allow; none starts after
--cutoff seconds.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import sys
import time
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from xroute.route_process import ProcessRun


def _bench_menu() -> list[tuple[str, list[str]]]:
    """The menu of bench/schedule_menu.py (one list of settings for both runners)."""
    path = Path(__file__).resolve().parents[2] / "bench" / "schedule_menu.py"
    spec = importlib.util.spec_from_file_location("xroute_bench_schedule_menu", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.MENU


# Cost of each setting relative to the default at one thread (orders the parallel jobs).
COST = {"default": 1.0, "victims2": 1.8, "victims4": 2.5, "victims8": 4.0, "bestof4": 3.0, "repair1": 2.0,
        "repair3": 4.8, "size5": 0.65, "size7": 0.7, "size10then5": 0.7}
MENU = [(name, flags, COST[name]) for name, flags in _bench_menu()]
EXTRA = [
    ("size5_victims4", ["--region-size", "5", "--policy", "victims", "--search-budget", "4"], 2.0),
    ("size5_repair1", ["--region-size", "5", "--repair-rounds", "1"], 1.5),
    ("size3", ["--region-size", "3"], 0.8),
    ("size15", ["--region-size", "15"], 1.2),
]
DESIGNS = {"ispd18_test1": 16.0, "ispd19_test1": 83.0, "ispd19_test3": 140.0}


def jobs(only: str | None) -> list[dict]:
    out = []
    for design, unit in DESIGNS.items():
        for rank, table in ((0, MENU), (1, EXTRA)):
            for name, flags, rel in table:
                if only and only not in (name, design, f"{design}:{name}"):
                    continue
                cost = unit * rel
                threads = 4 if cost > 300 else 2
                out.append({"design": design, "setting": name, "flags": flags, "cost": cost,
                            "threads": threads, "extra": rank})
    # The menu before the extras, each longest first.
    return sorted(out, key=lambda j: (j["extra"], -j["cost"]))


def summary(job: dict, run: ProcessRun) -> dict:
    row = {k: job[k] for k in ("design", "setting", "flags", "threads")}
    row.update(rc=run.returncode, wall_s=round(run.wall_s, 2), cpu_s=round(run.cpu_s, 2))
    if run.returncode != 0 or run.metrics is None:
        row["error"] = (run.stdout + run.stderr)[-2000:]
        return row
    data = run.metrics
    final = data["final"]
    row.update({k: final.get(k) for k in (
        "violations", "violations_by_type", "wirelength_um", "vias", "opens", "open_nets",
        "iterations_run", "route_seconds", "runtime_seconds", "peak_rss_mb")})
    row["iterations"] = [{k: it.get(k) for k in (
        "iteration", "region_size", "offset", "regions", "violations", "violations_by_type",
        "wirelength_um", "vias", "seconds")} for it in data["iterations"]]
    return row


def run_job(job: dict, env: dict[str, str]) -> dict:
    """One job in a child process (xroute.route_process), summarised."""
    from xroute.route_process import run_process, xroute_command

    run_dir = Path("/tmp/menu_runs") / f"{job['design']}-{job['setting']}"
    cmd = xroute_command("route", job["design"], "--quiet", "--threads", str(job["threads"]), "--out", str(run_dir),
                         *job["flags"])
    return summary(job, run_process(cmd, env=env, metrics_dir=run_dir))


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--src", default=None)
    ap.add_argument("--data", default=None)
    ap.add_argument("--out", required=True)
    ap.add_argument("--cores", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--cutoff", type=float, default=330.0)
    ap.add_argument("--only", default=None)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    env = {"CI": "true", "PYTHONUNBUFFERED": "1"}
    if args.src:  # the children's package, and the runner's (xroute.route_process) in this process
        env["PYTHONPATH"] = str(Path(args.src) / "src")
        sys.path.insert(0, env["PYTHONPATH"])
    if args.data:
        env["XROUTE_TESTCASES"] = args.data
    pending = jobs(args.only)
    for job in pending:  # a job never asks for more threads than there are cores
        job["threads"] = min(job["threads"], args.cores)
    free = args.cores
    start = time.monotonic()
    log = (out / "menu.jsonl").open("a")
    # One thread per running job, each waiting for its own child: jobs start while free cores allow.
    with ThreadPoolExecutor(max_workers=args.cores) as pool:
        running: dict[Future, dict] = {}
        while pending or running:
            for job in list(pending):
                if job["threads"] <= free and time.monotonic() - start < args.cutoff:
                    running[pool.submit(run_job, job, env)] = job
                    free -= job["threads"]
                    pending.remove(job)
                    print(f"[{time.monotonic() - start:6.1f}s] start {job['design']} {job['setting']}"
                          f" threads={job['threads']}", flush=True)
            if not running:
                break
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            for future in done:
                job = running.pop(future)
                free += job["threads"]
                row = future.result()
                log.write(json.dumps(row) + "\n")
                log.flush()
                print(f"[{time.monotonic() - start:6.1f}s] done {job['design']} {job['setting']}: rc={row['rc']} "
                      f"viol={row.get('violations')} wl={row.get('wirelength_um')} vias={row.get('vias')} "
                      f"wall={row['wall_s']} cpu={row['cpu_s']}", flush=True)
    skipped = [f"{j['design']}:{j['setting']}" for j in pending]
    print("not started (cutoff):", ", ".join(skipped) or "none", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
