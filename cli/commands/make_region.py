"""``xroute make-region``: write one routing region of a testcase as a small self-contained design.

The region is ``--size`` x ``--size`` GCells from the GCell ``--location X,Y`` (its lower-left),
or a ``--box xlo,ylo,xhi,yhi`` in DBU, or one of the XRoute paper's static regions
(``--paper-region 1``..``10``). The folder (``--out``) gets region.lef, region.def,
region.guide and region.yaml (see :mod:`xroute.testcases.regions`), written atomically; the
``xroute/StaticRegion-v0`` environment loads it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Optional

import typer

from xroute.testcases.regions import RegionError, make_region, paper_region_box
from xroute.cli.console import print_json, stdout_console


def _ints(text: str, count: int, what: str) -> tuple[int, ...]:
    try:
        values = tuple(int(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != count:
        raise RegionError(f"{what} must be {count} comma-separated integers, got {text!r}")
    return values


def make_region_command(
    testcase: Annotated[Optional[str], typer.Argument(help="Testcase name (e.g. ispd18_test1).", show_default=False)] = None,
    out: Annotated[Path, typer.Option("--out", help="Region folder to write (replaced if it holds a region).")] = Path("region"),
    location: Annotated[Optional[str], typer.Option("--location", help="X,Y: GCell column and row of the region's lower-left.")] = None,
    size: Annotated[int, typer.Option("--size", help="Region side in GCells (with --location).")] = 1,
    box: Annotated[Optional[str], typer.Option("--box", help="xlo,ylo,xhi,yhi in DBU (instead of --location).")] = None,
    paper_region: Annotated[Optional[int], typer.Option("--paper-region", help="The XRoute paper's static region 1..10.")] = None,
    json: Annotated[bool, typer.Option("--json", help="Print region.yaml's content as JSON only.")] = False,
) -> None:
    """Write a static region (clipped LEF/DEF/guide + region.yaml) of a testcase."""
    given = [v is not None for v in (location, box, paper_region)]
    if sum(given) != 1:
        raise typer.BadParameter("give exactly one of --location, --box or --paper-region", param_hint="--location")
    if paper_region is not None:
        name, paper_box = paper_region_box(paper_region)
        if testcase is not None and testcase != name:
            raise RegionError(f"paper region {paper_region} is on {name}, not {testcase}")
        testcase = name
        summary = make_region(testcase, out, box=paper_box)
    else:
        if testcase is None:
            raise typer.BadParameter("a testcase name is required", param_hint="TESTCASE")
        if location is not None:
            x, y = _ints(location, 2, "--location")
            summary = make_region(testcase, out, location=(x, y), size=size)
        else:
            summary = make_region(testcase, out, box=_ints(box or "", 4, "--box"))
    data = summary.to_yaml()
    if json:
        print_json(data)
        return
    stdout_console().print(
        f"{summary.out_dir}: {data['testcase']} box {tuple(data['box'])}, {data['nets']} nets, {data['pins']} pins, "
        f"{data['boundary_pins']} boundary pins, sparsity {data['sparsity']} nodes/net"
    )
