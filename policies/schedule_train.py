"""Train a schedule model (:mod:`xroute.schedule_model`): route training designs with every candidate of a
grid and keep the one that does best against the default, within a wirelength and via band.

Each run is a child process ``python -m xroute route ... --threads T --quiet`` (``--jobs`` at once);
its figures come from its metrics JSON and its CPU seconds from ``wait4`` (all its threads). For a
candidate c on a design d, with the default's figures as reference:

    score(c, d) = log((violations_c + 1) / (violations_default + 1)) + time_weight * log(cpu_c / cpu_default)

A candidate is feasible when on every design it leaves no open net and its wirelength and vias are
within ``band`` of the default's; the model is the feasible candidate with the lowest mean score, or
the rule itself (null parameters) when none scores below ``-min_gain`` (0.05: 5% better than the
default, above the run-to-run noise of CPU seconds). CPU seconds vary from run to run: when
two candidates score within that noise, another training run may keep the other; the document lists
every candidate's figures so that this shows.
"""

from __future__ import annotations

import json
import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Callable, Sequence

from xroute.atomic_files import atomic_write_text
from xroute.errors import XrouteError
from xroute.route_process import run_process, xroute_command
from xroute.schedule_model import SwitchSchedule, model_document

LATE_SIZES = (5, 10)  # 10: the rule's own size (its offsets too)
LATE_BUDGETS = (0, 4)
SWITCH_RATIOS = (1.0, 0.3, 0.1)
PATIENCES = (0, 3)


@dataclass(frozen=True)
class TrainCase:
    """A design to train on: its LEF files, DEF and guide (None: the built-in global router)."""

    name: str
    lef: tuple[str, ...]
    def_file: str
    guide: str | None


@dataclass(frozen=True)
class RunFigures:
    violations: int
    opens: int
    wirelength_um: float
    vias: int
    cpu_s: float
    iterations: int


def default_grid() -> list[SwitchSchedule]:
    """The candidates: late region size x late search budget x switch ratio x patience, less those
    that only differ in a switch that changes nothing (size 10 without a search: the rule): 20."""
    grid = []
    for size in LATE_SIZES:
        for budget in LATE_BUDGETS:
            for ratio in SWITCH_RATIOS:
                if size == 10 and budget == 0 and ratio != SWITCH_RATIOS[0]:
                    continue
                grid += [SwitchSchedule(size, ratio, patience, late_budget=budget) for patience in PATIENCES]
    return grid


def generate_cases(lefs: Sequence[Path], cells: int, seeds: Sequence[int], utilization: float | None,
                   folder: Path) -> list[TrainCase]:
    """One generated design per technology LEF and seed (``make-testcase --lef``), written under ``folder``."""
    from xroute.testcases.real_generator import DEFAULT_UTILIZATION, make_real_testcase

    cases = []
    for lef in lefs:
        stem = lef.name.split(".")[0]
        for seed in seeds:
            name = f"{stem}_c{cells}_s{seed}"
            out = make_real_testcase([lef], cells, seed, folder / name,
                                     DEFAULT_UTILIZATION if utilization is None else utilization)
            cases.append(TrainCase(name, (str(lef),), str(out / f"{name}.def"), str(out / f"{name}.guide")))
    return cases


def _route(case: TrainCase, model: Path | None, threads: int, out: Path, route_args: Sequence[str]) -> RunFigures:
    cmd = xroute_command("route", "--def", case.def_file, "--threads", str(threads), "--quiet", "--out", str(out),
                         *route_args)
    for lef in case.lef:
        cmd += ["--lef", lef]
    if case.guide:
        cmd += ["--guide", case.guide]
    if model is not None:
        cmd += ["--schedule-policy", str(model)]
    run = run_process(cmd, env={"CI": "true"}, metrics_dir=out)
    if run.returncode != 0:
        raise XrouteError(f"training run on {case.name} failed: {run.last_line}")
    if run.metrics is None:
        raise XrouteError(f"training run on {case.name} wrote no metrics JSON in {out}")
    m = run.metrics
    f = m["final"]
    return RunFigures(int(f["violations"]), int(f["open_nets"]), float(f["wirelength_um"]), int(f["vias"]),
                      round(run.cpu_s, 2), len(m["iterations"]))


def same_routing(run: RunFigures, ref: RunFigures) -> bool:
    """Whether two runs ended alike (violations, wirelength, vias, iterations): the same routing, as far
    as the figures tell; their CPU seconds then differ by noise only."""
    return (run.violations, run.wirelength_um, run.vias, run.iterations) == (
        ref.violations, ref.wirelength_um, ref.vias, ref.iterations)


def score(run: RunFigures, ref: RunFigures, time_weight: float) -> float:
    """0 for a run that ended like the default's (its time difference is noise), else the log ratios."""
    if same_routing(run, ref):
        return 0.0
    return math.log((run.violations + 1) / (ref.violations + 1)) + time_weight * math.log(run.cpu_s / max(ref.cpu_s, 1e-3))


def feasible(run: RunFigures, ref: RunFigures, band: float) -> bool:
    return (run.opens == 0 and run.wirelength_um <= ref.wirelength_um * (1 + band)
            and run.vias <= ref.vias * (1 + band))


def choose(grid: Sequence[SwitchSchedule], refs: dict[str, RunFigures], runs: Sequence[dict[str, RunFigures]],
           band: float, time_weight: float, min_gain: float) -> tuple[SwitchSchedule | None, float, list[dict]]:
    """(the chosen candidate or None, its mean score, one row per candidate): the feasible candidate
    with the lowest mean score below ``-min_gain``; of equal scores the earlier in the grid."""
    table = []
    best, best_score = None, -min_gain  # a candidate must beat the default by more than the timing noise
    for cand, per_design in zip(grid, runs):
        ok = all(feasible(per_design[n], refs[n], band) for n in refs)
        mean = sum(score(per_design[n], refs[n], time_weight) for n in refs) / len(refs)
        table.append({"parameters": cand.parameters(), "feasible": ok, "mean_score": round(mean, 4),
                      "runs": {n: asdict(f) for n, f in per_design.items()}})
        if ok and mean < best_score - 1e-9:
            best, best_score = cand, mean
    return best, best_score, table


def train(cases: Sequence[TrainCase], folder: Path, grid: Sequence[SwitchSchedule] | None = None, jobs: int = 2,
          threads: int = 1, band: float = 0.005, time_weight: float = 1.0, min_gain: float = 0.05,
          route_args: Sequence[str] = (), progress: Callable[[str], None] | None = None) -> dict:
    """Route every case with the default and every candidate (``route_args``: more ``xroute route``
    options for every run, e.g. ``["--iterations", "3"]``); the model document (parameters and figures)."""
    if not cases:
        raise XrouteError("no training designs")
    grid = list(default_grid() if grid is None else grid)
    folder.mkdir(parents=True, exist_ok=True)
    models = []
    for k, cand in enumerate(grid):
        path = folder / f"candidate{k:02d}.json"
        atomic_write_text(path, json.dumps(model_document(cand)))
        models.append(path)
    work = [(c, None, -1) for c in cases] + [(c, models[k], k) for k in range(len(grid)) for c in cases]

    def run(item: tuple[TrainCase, Path | None, int]) -> tuple[str, int, RunFigures]:
        case, model, k = item
        figures = _route(case, model, threads, folder / "runs" / f"{case.name}-{'default' if k < 0 else k}", route_args)
        if progress:
            progress(f"{case.name} {'default' if k < 0 else grid[k].parameters()}: {figures.violations} violations, "
                     f"{figures.cpu_s} CPU s")
        return case.name, k, figures

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        results = list(pool.map(run, work))
    figures = {(name, k): f for name, k, f in results}
    refs = {c.name: figures[(c.name, -1)] for c in cases}
    runs = [{c.name: figures[(c.name, k)] for c in cases} for k in range(len(grid))]
    best, best_score, table = choose(grid, refs, runs, band, time_weight, min_gain)
    return model_document(
        best,
        trained_on=[{"name": c.name, "lef": [Path(f).name for f in c.lef], "guide": c.guide is not None,
                     "default": asdict(figures[(c.name, -1)])} for c in cases],
        objective={"score": "log((violations+1)/(violations_default+1)) + time_weight*log(cpu/cpu_default)",
                   "time_weight": time_weight, "band": band, "min_gain": min_gain, "threads": threads,
                   "route_args": list(route_args)},
        chosen_score=round(best_score, 4) if best is not None else None,
        candidates=table,
    )
