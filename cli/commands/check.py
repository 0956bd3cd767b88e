"""``xroute check``: judge any routed DEF, ours or another router's.

``xroute check --lef L.lef --def routed.def [--guide G.guide]``, or ``xroute check TESTCASE
--def routed.def`` (the testcase's LEF and guide). Prints opens, violations by type, wirelength,
vias, the wrong-way / off-track / out-of-guide figures and the contest score before violations
(:mod:`xroute.check`); writes ``<stem>.check.json``, ``<stem>.drc.rpt`` and ``<stem>.lyrdb``
(a KLayout marker database) into ``--out``. Exit status 1 when a net is open, 2 for bad input.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.markup import escape
from rich.table import Table

from xroute.cli.console import print_json, print_read_warnings, stdout_console
from xroute.cli.options import JsonOption, QuietOption
from xroute.glossary import SCORE_NAME, score_line

EXIT_OPENS = 1


def _stem(def_path: Path) -> str:
    """The output stem: the DEF's name less .routed.def / .def, made safe (xroute.safe_paths)."""
    from xroute.safe_paths import safe_stem

    name = def_path.name
    for suffix in (".routed.def", ".def"):
        if name.lower().endswith(suffix):
            name = name[: -len(suffix)]
            break
    return safe_stem(name)


def _table(r) -> Table:  # noqa: ANN001 - a CheckResult
    table = Table(title=f"Check of {escape(r.design)}", show_header=False, title_justify="left")
    table.add_column("item", style="bold")
    table.add_column("value", justify="right")
    table.add_row("nets (with >= 2 pins)", f"{r.nets_checked:,}")
    table.add_row("open nets", str(r.opens), style="red" if r.opens else None)
    table.add_row("violations", f"{r.violations:,}")
    for kind, count in r.violations_by_type.items():
        table.add_row(f"  {kind}", f"{count:,}")
    table.add_row("wirelength (µm)", f"{r.wirelength_um:,.2f}")
    table.add_row("vias", f"{r.vias:,}")
    table.add_row("wrong-way wire (µm)", f"{r.wrong_way_wirelength_um:,.2f}")
    table.add_row("off-track wire (µm)", f"{r.off_track_wirelength_um:,.2f}")
    table.add_row("off-track vias", f"{r.off_track_vias:,}")
    if r.out_of_guide_wirelength_um is not None:
        table.add_row("out-of-guide wire (µm)", f"{r.out_of_guide_wirelength_um:,.2f}")
        table.add_row("out-of-guide vias", f"{r.out_of_guide_vias:,}")
    if r.score is not None:
        table.add_row(f"{SCORE_NAME} (before violations)", f"{r.score:,.1f}")
    return table


def check(
    testcase: Annotated[str | None, typer.Argument(help="Testcase whose LEF (and guide) to use.",
                                                   show_default=False)] = None,
    def_: Annotated[Path | None, typer.Option("--def", help="The routed DEF to check.", show_default=False)] = None,
    lef: Annotated[list[Path] | None, typer.Option("--lef", help="LEF file (repeatable, in order); instead of a "
                                                   "testcase.", show_default=False)] = None,
    guide: Annotated[Path | None, typer.Option("--guide", help="Route guide file: out-of-guide figures and the "
                                               "contest score.", show_default=False)] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Folder for <stem>.check.json, .drc.rpt and .lyrdb. "
                                             "Default: ./out/check-<stem>.", show_default=False)] = None,
    as_json: JsonOption = False,
    quiet: QuietOption = False,
) -> None:
    """Check a routed DEF: opens, design rules, wirelength, vias, guide and track figures.

    Give the routed DEF with --def and either a testcase name (its LEF and guide are used) or
    --lef files (and --guide for the out-of-guide figures). Exit status 1 when a net is open.
    """
    from xroute.check import check_to_outputs
    from xroute.design import load_design
    from xroute.testcases.registry import find_testcase

    if def_ is None:
        raise typer.BadParameter("give the routed DEF to check", param_hint="--def")
    if testcase is not None and lef:
        raise typer.BadParameter("give a testcase name or --lef files, not both", param_hint="TESTCASE")
    if testcase is None and not lef:
        raise typer.BadParameter("give a testcase name or --lef files", param_hint="TESTCASE")
    if testcase is not None:
        found = find_testcase(testcase)
        lef = [found.lef]
        if guide is None and found.guide is not None:
            guide = found.guide
    design = load_design(lef=[str(p) for p in lef or []], def_=str(def_), guide=str(guide) if guide else None)
    print_read_warnings(design)
    stem = _stem(def_)
    out_dir = out if out is not None else Path("out") / f"check-{stem}"
    result, paths = check_to_outputs(design, out_dir, stem)  # published as one set

    if as_json:
        print_json(result.to_dict())
    else:
        if not quiet:
            stdout_console().print(_table(result))
            if result.score is not None:
                typer.echo(score_line())
        for item in result.not_checked:  # also under --quiet: a count of 0 claims nothing of these
            typer.echo(f"not checked: {item['rule']} on {', '.join(item['layers'])}")
        typer.echo(f"{result.design}: {result.opens} open, {result.violations} violations, "
                   f"WL {result.wirelength_um:,.1f} um, {result.vias:,} vias"
                   + (f", {SCORE_NAME} {result.score:,.1f}" if result.score is not None else "")
                   + f" -> {paths['json'].parent}")
    if result.opens:
        for o in result.open_nets[:20]:
            typer.echo(f"open net {o['net']}: {o['pin_groups']} unconnected pin groups", err=True)
        raise typer.Exit(EXIT_OPENS)
