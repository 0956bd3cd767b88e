"""Command-line options shared by the routing commands (route, evaluate, batch).

Routing flags default to None, meaning "not given": the value then comes from ``--config``
(see :mod:`xroute.config`), and from the defaults in configs/default.yaml without one.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.defaults import MAX_SEARCH_BUDGET, SEARCH_BUDGET
from xroute.net_order import BUILTIN_POLICIES
from xroute.router import DEFAULT_ITERATIONS, DEFAULT_REGION_SIZE, MAX_ITERATIONS

ConfigOption = Annotated[
    Path | None,
    typer.Option("--config", "-c", help="YAML config (see configs/default.yaml); flags given here override its values.",
                 show_default=False),
]
OutOption = Annotated[
    Path | None,
    typer.Option("--out", help="Output folder (created if needed). Default: ./out/<design>.", show_default=False),
]
RegionSizeOption = Annotated[
    int | None,
    typer.Option("--region-size",
                 help="Region side in GCells (0: auto, 10 or more while the regions' grids stay small, "
                      "down to 5 where they are large at 10). Default: 0.",
                 show_default=False),
]
IterationsOption = Annotated[
    int | None,
    typer.Option("--iterations",
                 help=f"Iteration limit (1..{MAX_ITERATIONS}); stops early at 0 violations. Default: {DEFAULT_ITERATIONS}.",
                 show_default=False),
]
ThreadsOption = Annotated[
    int | None,
    typer.Option("--threads", help="Worker threads (the result does not depend on it). Default: 1.", show_default=False),
]
RepairRoundsOption = Annotated[
    int | None,
    typer.Option("--repair-rounds", help="Check-and-reroute rounds inside each region before it is committed "
                 "(iterations after the first; more rounds, fewer violations, more time). Default: 0.",
                 show_default=False),
]
PolicyOption = Annotated[
    str | None,
    typer.Option("--policy",
                 help=f"Net-order policy: {', '.join(BUILTIN_POLICIES)}, best-of-K (search: fewer violations "
                      "for more time, see --search-budget), or a policy file (.py defining order(region, features) "
                      "or next_net(region, features)). "
                      "Default: heuristic.", show_default=False),
]
NetRouterOption = Annotated[
    Path | None,
    typer.Option("--net-router",
                 help="A net-router ONNX model (policies/models/net_router_dqn.onnx): it routes each net step by step, "
                      "A* taking over every net it does not connect. Not with --policy.", show_default=False),
]
SearchBudgetOption = Annotated[
    int | None,
    typer.Option("--search-budget", min=1, max=MAX_SEARCH_BUDGET,
                 help=f"Trial routings per region of the rollout and victims policies (and bestof's K). Default: {SEARCH_BUDGET}.",
                 show_default=False),
]
SeedOption = Annotated[int | None, typer.Option("--seed", help="Seed of the random policy and of the victims and best-of-K searches' random orders. Default: 1.", show_default=False)]
JsonOption = Annotated[bool, typer.Option("--json", help="Print one JSON document on stdout, nothing else.")]
QuietOption = Annotated[bool, typer.Option("--quiet", "-q", help="Print only the final line.")]
SchedulePolicyOption = Annotated[
    str | None,
    typer.Option("--schedule-policy",
                 help="Each iteration's plan (region size and offset, repair rounds, marker / history / other-net "
                      "weights, or stop): rule (the settings' own plans), a .py file defining "
                      "plan(history, rule), or a .json schedule model (xroute train-schedule). Default: rule.", show_default=False),
]
ScheduleOption = Annotated[
    str | None,
    typer.Option("--schedule", help="Per-iteration region size and offset in GCells, cycled: e.g. '5:0,5:2,7:3' "
                 "(overrides --region-size and the config's iteration_schedule). Default: --region-size with "
                 "offsets 0, C/3, 2C/3.", show_default=False),
]
