"""``xroute make-testcase``: generate a testcase (``--cells N --seed S``) or tile a real one (``--tile NAME --by RxC``).

The output folder's name is the testcase's name: ``--out DIR`` writes ``DIR/<DIR name>.{lef,def,guide}``
(generated) or ``DIR/<DIR name>.input.{lef,def,guide}`` (tiled, the contest naming of the original).
Default folders: ``./gen<N>_s<S>`` and ``./<NAME>_<R>x<C>``. The written files are loaded back once to
check them and to print their counts.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.console import print_json


def make_testcase(
    cells: Annotated[
        int | None, typer.Option("--cells", help="Generate a testcase with this many logic cells.", show_default=False)
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the generator (same seed, same files).")] = 1,
    tile: Annotated[
        str | None,
        typer.Option("--tile", help="Tile this testcase (a name on the search path) instead.", show_default=False),
    ] = None,
    by: Annotated[str, typer.Option("--by", help="Tiling: ROWSxCOLS copies, e.g. 4x4.")] = "2x2",
    out: Annotated[
        Path | None,
        typer.Option("--out", help="Output folder; its name is the testcase's name.", show_default=False),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the result as JSON, nothing else.")] = False,
) -> None:
    """Write a testcase: a generated one (--cells N [--seed S]: our own 45 nm-like technology LEF, a placed
    DEF, guides) or R x C renamed copies of a real one (--tile NAME --by RxC). Route it with
    `xroute route --lef DIR/X.lef --def DIR/X.def --guide DIR/X.guide` (tiled: X.input.lef, ...), or by
    name with DIR's parent folder in XROUTE_TESTCASES."""
    if (cells is None) == (tile is None):
        raise typer.BadParameter("give exactly one of --cells N or --tile TESTCASE", param_hint="--cells/--tile")

    from xroute.design import load_design

    if cells is not None:
        from xroute.testcases.generator import make_testcase as generate

        folder = generate(cells, seed, out if out is not None else Path(f"gen{cells}_s{seed}"))
    else:
        from xroute.testcases.tiling import parse_by, tile_testcase

        rows, cols = parse_by(by)
        folder = tile_testcase(tile, rows, cols, out if out is not None else Path(f"{tile}_{rows}x{cols}"))
    name = folder.resolve().name
    infix = "" if cells is not None else ".input"
    files = {ext: folder / f"{name}{infix}.{ext}" for ext in ("lef", "def", "guide")}
    guide = files["guide"] if files["guide"].is_file() else None
    design = load_design(lef=[str(files["lef"])], def_=str(files["def"]), guide=str(guide) if guide else None)
    counts = design.counts()
    result = {
        "name": name,
        "folder": str(folder),
        "files": {k: str(v) for k, v in files.items() if v.is_file()},
        "components": counts["components"],
        "nets": counts["nets"],
        "io_pins": counts["io_pins"],
        "guides": counts["guides"],
        "die_area": list(design.die_area),
    }
    if as_json:
        print_json(result)
        return
    x0, y0, x1, y1 = design.die_area
    dbu = design.dbu_per_micron
    typer.echo(f"wrote {name}: {counts['components']:,} components, {counts['nets']:,} nets, "
               f"{counts['io_pins']:,} IO pins, {counts['guides']:,} guides, die {(x1 - x0) / dbu:g} x "
               f"{(y1 - y0) / dbu:g} um -> {folder}")
    guide_opt = f" --guide {files['guide']}" if guide else ""
    typer.echo(f"route it: xroute route --lef {files['lef']} --def {files['def']}{guide_opt}")
