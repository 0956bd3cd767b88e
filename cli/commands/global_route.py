"""``xroute global-route``: route guides for a placed design with the built-in global router.

``xroute global-route DEF LEF... --out X.guide`` reads the DEF and the LEF files (the DEF is
the argument ending in ``.def``, else the first), or ``xroute global-route TESTCASE`` a testcase
by name; any guide the testcase has is ignored. The guides are written atomically in the ISPD
guide format (default ``./out/<design>/<design>.guide``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.console import print_json
from xroute.groute import DEFAULT_CAPACITY_PERCENT, DEFAULT_ITERATIONS


def _split_inputs(inputs: list[str]) -> tuple[str | None, str | None, list[str]]:
    """(testcase, DEF, LEFs) from the positional arguments."""
    if len(inputs) == 1 and not inputs[0].lower().endswith((".def", ".lef")) and not Path(inputs[0]).is_file():
        return inputs[0], None, []
    if len(inputs) < 2:
        raise typer.BadParameter("give a testcase name, or a DEF file and at least one LEF file", param_hint="INPUTS")
    defs = [i for i, p in enumerate(inputs) if p.lower().endswith(".def")]
    at = defs[0] if len(defs) == 1 else 0
    return None, inputs[at], inputs[:at] + inputs[at + 1 :]


def global_route(
    inputs: Annotated[
        list[str],
        typer.Argument(help="A testcase name, or a DEF file and its LEF files (in reading order).", show_default=False,
                       metavar="INPUTS"),
    ],
    out: Annotated[
        Path | None,
        typer.Option("--out", help="Guide file to write. Default: ./out/<design>/<design>.guide.", show_default=False),
    ] = None,
    iterations: Annotated[
        int, typer.Option("--iterations", help="Rip-up-and-reroute rounds at most (stops at zero overflow).")
    ] = DEFAULT_ITERATIONS,
    capacity: Annotated[
        int, typer.Option("--capacity", help="Percent of each GCell edge's free tracks the router may fill (1..100).")
    ] = DEFAULT_CAPACITY_PERCENT,
    slack: Annotated[int, typer.Option("--slack", help="GCells every guide rectangle is grown by.")] = 0,
    as_json: Annotated[bool, typer.Option("--json", help="Print the statistics as JSON on stdout, nothing else.")] = False,
) -> None:
    """Global-route a placed design and write its route guides (ISPD guide format)."""
    from xroute.cli.commands.route import global_route_summary
    from xroute.design import load_design
    from xroute.groute import global_route as run_global_route

    from xroute.regular_files import check_output

    if out is not None:
        check_output(out, "guide file")
    testcase, def_, lefs = _split_inputs(inputs)
    if testcase is not None:
        design = load_design(testcase, use_guide=False)
    else:
        design = load_design(lef=lefs, def_=def_)
    from xroute.safe_paths import safe_stem

    path = out if out is not None else Path("out") / safe_stem(design.name) / f"{safe_stem(design.name)}.guide"
    path.parent.mkdir(parents=True, exist_ok=True)
    check_output(path, "guide file")  # never replace a folder, FIFO or device (checked before routing)
    stats = run_global_route(design, path, iterations=iterations, capacity_percent=capacity, slack=slack)
    if as_json:
        print_json({"design": design.name, "guide": str(path), **stats.to_dict()})
    else:
        typer.echo(f"{design.name}: {global_route_summary(stats)} -> {path}")
