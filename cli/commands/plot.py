"""``xroute plot``: a picture of a whole routed design (violations by type, wire per GCell, out-of-guide wire)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.console import GuideOption, LefOption


def plot(
    source: Annotated[Path, typer.Argument(help="A route output folder (routed DEF, metrics JSON, DRC report), "
                                                "or a DEF file (with --lef).", show_default=False)],
    lef: LefOption = None,
    guide: GuideOption = None,
    drc: Annotated[Path | None, typer.Option("--drc", help="DRC report whose markers to draw. "
                                             "Default: the run folder's <design>.drc.rpt.", show_default=False)] = None,
    out: Annotated[Path, typer.Option("--out", help="Picture to write: .png or .svg.")] = Path("design.png"),
) -> None:
    """Draw a whole routed design as a PNG or SVG picture.

    Wire per GCell as a grey heat map, wire outside its net's route guides in magenta (when the
    guide file the run read, named in its metrics JSON, is still there), and the design-rule
    markers of the run's DRC report as points, one colour and shape per type, beside a bar chart
    of the violations by type with their counts. Axes in µm. Another router's DEF: give it with
    --lef (and --guide, --drc when there are). Needs matplotlib
    (pip install 'xroute\\[plot]').

    Example: xroute plot out/ispd19_test1 --out ispd19_test1.png
    Example: xroute plot other.def --lef tech.lef --guide design.guide --out other.png
    """
    from xroute.atomic_files import atomic_write_bytes
    from xroute.cli.plot_data import picture_format, picture_inputs, read_drc_report
    from xroute.cli.plot_design import measure, render
    from xroute.design import load_design

    fmt = picture_format(out)
    lef_paths, def_path, guide_path, drc = picture_inputs(source, lef, guide, drc)
    design = load_design(lef=lef_paths, def_=def_path, guide=guide_path)
    markers = read_drc_report(drc) if drc is not None else []
    pic = measure(design, markers, with_guides=guide_path is not None)
    picture = render(design, pic, f"{design.name} ({def_path.name})", fmt)
    if out.parent != Path(""):
        out.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(out, picture)
    outside = "no guide file" if pic.out_of_guide_um is None else f"{pic.out_of_guide_um:,.1f} um out of guide"
    typer.echo(f"plot: {design.name}: {len(markers):,} violations, {outside} -> {out}")
