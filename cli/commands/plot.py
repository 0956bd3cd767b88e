"""``xroute plot``: a picture of a whole routed design (violations by type, wire per GCell, out-of-guide wire)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer


def plot(
    run_dir: Annotated[Path, typer.Argument(help="A route output folder (routed DEF, metrics JSON, DRC report).",
                                            show_default=False)],
    out: Annotated[Path, typer.Option("--out", help="Picture to write: .png or .svg.")] = Path("design.png"),
) -> None:
    """Draw a whole routed design as a PNG or SVG picture.

    Wire per GCell as a grey heat map, wire outside its net's route guides in magenta (when the
    guide file the run read, named in its metrics JSON, is still there), and the design-rule
    markers of the run's DRC report as points, one colour and shape per type, beside a bar chart
    of the violations by type with their counts. Axes in µm. Needs matplotlib
    (pip install 'xroute\\[plot]').

    Example: xroute plot out/ispd19_test1 --out ispd19_test1.png
    """
    from xroute.atomic_files import atomic_write_bytes
    from xroute.cli.plot_data import picture_format, read_drc_report, run_files
    from xroute.cli.plot_design import measure, render
    from xroute.design import load_design

    fmt = picture_format(out)
    if not run_dir.is_dir():
        from xroute.errors import InputError

        raise InputError("not a folder: give a route output folder", str(run_dir), 0)
    files = run_files(run_dir)
    design = load_design(lef=files.lef, def_=files.def_path, guide=files.guide)
    markers = read_drc_report(files.drc) if files.drc is not None else []
    pic = measure(design, markers, with_guides=files.guide is not None)
    picture = render(design, pic, f"{design.name} ({files.def_path.name})", fmt)
    if out.parent != Path(""):
        out.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(out, picture)
    guide = "no guide file" if pic.out_of_guide_um is None else f"{pic.out_of_guide_um:,.1f} um out of guide"
    typer.echo(f"plot: {design.name}: {len(markers):,} violations, {guide} -> {out}")
