"""``xroute train-schedule``: fit a schedule model (:mod:`xroute.schedule_model`) on training designs.

Training designs: generated ones (``--lef TECH.lef`` per technology, ``--cells N``, ``--seeds 1,2``: a
placed design per technology and seed, as ``make-testcase --lef`` writes it) and testcases by name
(``--testcase NAME``). Every design is routed with the default and with each candidate of the grid
(:func:`xroute.policies.schedule_train.default_grid`, 20 candidates, or the ``--candidate`` ones), ``--jobs``
routes at once. Everything goes
under ``--out DIR``: the designs (``DIR/designs``), the runs (``DIR/runs``) and the model
(``DIR/schedule.json``), which ``xroute route --schedule-policy DIR/schedule.json`` uses.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from xroute.cli.console import stdout_console

if TYPE_CHECKING:
    from xroute.schedule_model import SwitchSchedule


def _seeds(text: str) -> list[int]:
    try:
        seeds = [int(s) for s in text.split(",") if s.strip()]
    except ValueError:
        raise typer.BadParameter(f"expected integers separated by commas, got '{text}'", param_hint="--seeds") from None
    if not seeds:
        raise typer.BadParameter("give at least one seed", param_hint="--seeds")
    return seeds


def _candidate(text: str) -> SwitchSchedule:
    from xroute.schedule_model import SwitchSchedule

    parts = text.split(":")
    try:
        if len(parts) != 4:
            raise ValueError("four fields")
        size, ratio, patience, budget = int(parts[0]), float(parts[1]), int(parts[2]), int(parts[3])
        return SwitchSchedule(size, ratio, patience, late_budget=budget)
    except ValueError as exc:
        detail = f": {exc}" if str(exc) else ""
        raise typer.BadParameter(f"expected SIZE:RATIO:PATIENCE:BUDGET (e.g. 5:0.1:0:4), got '{text}'{detail}",
                                 param_hint="--candidate") from None


def train_schedule(
    out: Annotated[Path, typer.Option("--out", help="Output folder: designs, runs and schedule.json.")],
    lef: Annotated[
        list[Path] | None,
        typer.Option("--lef", help="Generate training designs on this technology LEF (repeatable).", show_default=False),
    ] = None,
    testcase: Annotated[
        list[str] | None,
        typer.Option("--testcase", help="Train on this testcase too (repeatable; a name on the search path).",
                     show_default=False),
    ] = None,
    cells: Annotated[int, typer.Option("--cells", help="Cells of each generated design.")] = 1500,
    seeds: Annotated[str, typer.Option("--seeds", help="Generator seeds, comma-separated.")] = "1,2",
    utilization: Annotated[
        float | None, typer.Option("--utilization", help="Row utilisation of the generated designs \\[default: 0.75].",
                                   show_default=False)
    ] = None,
    candidate: Annotated[
        list[str] | None,
        typer.Option("--candidate", help="A candidate SIZE:RATIO:PATIENCE:BUDGET (late region size, switch ratio, "
                     "patience, late search budget; repeatable) instead of the default grid of 20.", show_default=False),
    ] = None,
    jobs: Annotated[int, typer.Option("--jobs", help="Routes at once (child processes).", min=1, max=256)] = 2,
    threads: Annotated[int, typer.Option("--threads", help="Threads of each route.", min=1, max=256)] = 1,
    iterations: Annotated[
        int | None, typer.Option("--iterations", help="Iteration limit of every route \\[default: the router's].",
                                 min=1, max=64, show_default=False)
    ] = None,
    band: Annotated[float, typer.Option("--band", help="Largest wirelength and via growth over the default allowed "
                                        "on any training design (0.005 = 0.5%).", min=0.0, max=1.0)] = 0.005,
    time_weight: Annotated[float, typer.Option("--time-weight", help="Weight of log CPU time against log "
                                               "violations in the score.", min=0.0, max=100.0)] = 1.0,
) -> None:
    """Fit a schedule model: the rule's plans until the run converges, then smaller regions, and a stop on a
    stall, with the switch point, region size and patience that do best on the training designs."""
    from xroute.atomic_files import atomic_write_text
    from xroute.policies.schedule_train import TrainCase, generate_cases, train
    from xroute.testcases.registry import find_testcase

    console = stdout_console()
    if not lef and not testcase:
        raise typer.BadParameter("give at least one --lef or --testcase", param_hint="--lef/--testcase")
    seed_list = _seeds(seeds)
    grid = [_candidate(c) for c in candidate] if candidate else None
    cases = generate_cases(lef or [], cells, seed_list, utilization, out / "designs") if lef else []
    for name in testcase or []:
        found = find_testcase(name)
        cases.append(TrainCase(found.name, (str(found.lef),), str(found.def_),
                               str(found.guide) if found.guide else None))
    console.print(f"training on {len(cases)} design(s): {', '.join(c.name for c in cases)}")
    route_args = ["--iterations", str(iterations)] if iterations is not None else []
    doc = train(cases, out, grid=grid, jobs=jobs, threads=threads, band=band, time_weight=time_weight, route_args=route_args,
                progress=lambda line: console.print(f"  {line}", markup=False, highlight=False))
    model = out / "schedule.json"
    atomic_write_text(model, json.dumps(doc, indent=1) + "\n")
    chosen = doc["parameters"]
    if chosen is None:
        console.print("no candidate beat the default on the training designs: the model keeps the rule")
    else:
        console.print(f"chosen: {chosen} (mean score {doc['chosen_score']})")
    console.print(f"-> {model}", markup=False, highlight=False)
