"""``xroute plot-region``: a picture of the routing in a box (layers coloured, pins, labelled DRC markers)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.console import GuideOption, LefOption
from xroute.errors import XrouteError

EXIT_EMPTY = 2  # a box with nothing in it: a warning, no picture


def plot_region(
    source: Annotated[Path, typer.Argument(help="A route output folder (routed DEF, metrics JSON, DRC report), "
                                                "or a DEF file (with --lef).", show_default=False)],
    box: Annotated[str | None, typer.Option("--box", help="Region in DBU: xlo,ylo,xhi,yhi.", show_default=False)] = None,
    gcell: Annotated[str | None, typer.Option("--gcell", help="Lower-left GCell of the region: X,Y (with --size).",
                                              show_default=False)] = None,
    size: Annotated[int, typer.Option("--size", help="Region side in GCells (with --gcell).", min=1)] = 1,
    lef: LefOption = None,
    guide: GuideOption = None,
    drc: Annotated[Path | None, typer.Option("--drc", help="DRC report whose markers to draw "
                                             "Default: the run folder's <design>.drc.rpt.", show_default=False)] = None,
    net: Annotated[str | None, typer.Option("--net", help="Net to highlight (drawn bold and labelled; the "
                                            "others dimmed).", show_default=False)] = None,
    dbu: Annotated[bool, typer.Option("--dbu", help="Axes in DBU instead of µm.")] = False,
    out: Annotated[Path, typer.Option("--out", help="Picture to write: .png or .svg.")] = Path("region.png"),
) -> None:
    """Draw a region's routing as a PNG or SVG picture.

    Wires, vias and patches in one colour per layer and per via layer, pins hatched, design-rule
    markers in red labelled with their type, layer and nets, and the nets a marker names labelled
    on their shapes; --net NAME highlights one net. Axes in µm (--dbu: DBU). Give the region as
    --box xlo,ylo,xhi,yhi (DBU) or as --gcell X,Y --size C (GCells of the router's grid: the DEF's
    GCELLGRID, else the guides' most common size). A box with nothing in it is a warning and exit
    status 2, no picture. Needs matplotlib (pip install 'xroute\\[plot]').

    Example: xroute plot-region out/ispd18_test1 --gcell 35,43 --size 1 --out region1.png
    Example: xroute plot-region out/ispd18_test1 --box 100000,120000,104000,123000 --net net1234 --out n.svg
    """
    from xroute.design import load_design
    from xroute.atomic_files import atomic_write_bytes
    from xroute.cli.plot_data import describe, gcell_box, parse_ints, picture_format, picture_inputs, read_drc_report
    from xroute.cli.plot_region import region_content, render

    fmt = picture_format(out)

    if (box is None) == (gcell is None):
        raise typer.BadParameter("give either --box xlo,ylo,xhi,yhi or --gcell X,Y", param_hint="--box/--gcell")
    lef_paths, def_path, guide_path, drc = picture_inputs(source, lef, guide, drc)
    if box is not None:
        region = parse_ints(box, 4, "--box")
        if region[0] >= region[2] or region[1] >= region[3]:
            raise typer.BadParameter("xlo < xhi and ylo < yhi are needed", param_hint="--box")
    design = load_design(lef=lef_paths, def_=def_path, guide=guide_path)
    if gcell is not None:
        gx, gy = parse_ints(gcell, 2, "--gcell")
        region = gcell_box(design, gx, gy, size)
    highlight = None
    if net is not None:
        if net not in design.net_names:
            raise XrouteError(f"{def_path}: no net named '{net}' (--net)")
        highlight = design.net_names.index(net)
    markers = read_drc_report(drc) if drc is not None else []
    content = region_content(design, region, markers)
    if content.empty:
        typer.echo(f"warning: {def_path}: nothing in the box {describe(region)} (no wire, via, pin or marker): "
                   "no picture written", err=True)
        raise typer.Exit(EXIT_EMPTY)
    picture = render(design, region, content, f"{design.name} {describe(region)}", highlight, dbu, fmt)
    if out.parent != Path(""):
        out.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(out, picture)
    typer.echo(f"plot-region: {design.name} {describe(region)} -> {out}")

