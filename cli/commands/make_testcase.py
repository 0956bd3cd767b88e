"""``xroute make-testcase``: generate a testcase (``--cells N --seed S``, on our technology or on real
``--lef`` files) or tile a real one (``--tile NAME --by RxC``).

The output folder's name is the testcase's name: ``--out DIR`` writes ``DIR/<DIR name>.{lef,def,guide}``
(generated), ``DIR/<DIR name>.{def,guide}`` (generated on ``--lef`` files, which stay where they are) or
``DIR/<DIR name>.input.{lef,def,guide}`` (tiled, the contest naming of the original). Default folders:
``./gen<N>_s<S>``, ``./<LEF stem>_gen<N>_s<S>`` and ``./<NAME>_<R>x<C>``. The written files are loaded
back once to check them and to print their counts.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.console import print_json


def _generate_on_lef(lef: list[Path], cells: int, seed: int, utilization: float | None, out: Path | None,
                     ndr_nets: int) -> Path:
    from xroute.testcases.real_generator import DEFAULT_UTILIZATION, make_real_testcase

    stem = lef[-1].name.split(".")[0]
    return make_real_testcase(lef, cells, seed, out if out is not None else Path(f"{stem}_gen{cells}_s{seed}"),
                              DEFAULT_UTILIZATION if utilization is None else utilization, ndr_nets)


def make_testcase(
    cells: Annotated[
        int | None, typer.Option("--cells", help="Generate a testcase with this many logic cells.", show_default=False)
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the generator (same seed, same files).")] = 1,
    lef: Annotated[
        list[Path] | None,
        typer.Option("--lef", help="Generate on this technology/cell LEF (repeatable) instead of ours.",
                     show_default=False),
    ] = None,
    utilization: Annotated[
        float | None,
        typer.Option("--utilization", help="With --lef: share of the row area the cells fill \\[default: 0.75].",
                     show_default=False),
    ] = None,
    ndr_nets: Annotated[
        int,
        typer.Option("--ndr-nets", help="With --lef: give this many nets a NONDEFAULTRULE of twice the width and "
                     "spacing above the pin layer."),
    ] = 0,
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
    DEF, guides; with --lef FILE, a placed DEF and guides on that real technology and its core cells)
    or R x C renamed copies of a real one (--tile NAME --by RxC). Route it with
    `xroute route --lef DIR/X.lef --def DIR/X.def --guide DIR/X.guide` (tiled: X.input.lef, ...; --lef:
    the same LEF files), or by name with DIR's parent folder in XROUTE_TESTCASES."""
    if (cells is None) == (tile is None):
        raise typer.BadParameter("give exactly one of --cells N or --tile TESTCASE", param_hint="--cells/--tile")
    if (lef or utilization is not None) and cells is None:
        raise typer.BadParameter("--lef and --utilization go with --cells N", param_hint="--lef")
    if ndr_nets and not lef:
        raise typer.BadParameter("--ndr-nets needs --lef", param_hint="--ndr-nets")
    if utilization is not None and not lef:
        raise typer.BadParameter("--utilization needs --lef (our technology's is fixed)", param_hint="--utilization")

    from xroute.design import load_design

    if cells is not None and lef:
        folder = _generate_on_lef(lef, cells, seed, utilization, out, ndr_nets)
    elif cells is not None:
        from xroute.testcases.generator import make_testcase as generate

        folder = generate(cells, seed, out if out is not None else Path(f"gen{cells}_s{seed}"))
    else:
        from xroute.testcases.tiling import parse_by, tile_testcase

        rows, cols = parse_by(by)
        folder = tile_testcase(tile, rows, cols, out if out is not None else Path(f"{tile}_{rows}x{cols}"))
    name = folder.resolve().name
    infix = "" if cells is not None else ".input"
    files = {ext: folder / f"{name}{infix}.{ext}" for ext in ("lef", "def", "guide")}
    lef_paths = [str(p) for p in lef] if lef else [str(files["lef"])]
    guide = files["guide"] if files["guide"].is_file() else None
    design = load_design(lef=lef_paths, def_=str(files["def"]), guide=str(guide) if guide else None)
    counts = design.counts()
    result = {
        "name": name,
        "folder": str(folder),
        "files": {k: str(v) for k, v in files.items() if v.is_file()},
        "lef": lef_paths,
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
    lef_opts = " ".join(f"--lef {p}" for p in lef_paths)
    typer.echo(f"route it: xroute route {lef_opts} --def {files['def']}{guide_opt}")
