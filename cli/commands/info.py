"""``xroute info``: a summary of one design (files, units, counts, grid, guides, layers)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from xroute.cli.console import (
    DefOption,
    GuideOption,
    LefOption,
    TestcaseArg,
    check_design_args,
    load_design_args,
    print_json,
    stdout_console,
)

if TYPE_CHECKING:
    from xroute.design import Design

# Buckets of the pins-per-net histogram: label -> (min pins, max pins), inclusive.
PIN_BUCKETS: dict[str, tuple[int, int]] = {
    "0-1": (0, 1),
    "2": (2, 2),
    "3": (3, 3),
    "4-10": (4, 10),
    ">10": (11, 2**31 - 1),
}


def _microns(dbu: int, dbu_per_micron: int) -> float:
    return round(dbu / dbu_per_micron, 4) if dbu_per_micron else 0.0


def pin_histogram(pins_per_net: Any) -> dict[str, int]:
    """Number of nets per bucket of :data:`PIN_BUCKETS`."""
    return {
        label: int(((pins_per_net >= lo) & (pins_per_net <= hi)).sum()) for label, (lo, hi) in PIN_BUCKETS.items()
    }


def summarize(design: Design) -> dict[str, Any]:
    """Everything ``xroute info`` shows, as plain JSON-ready data (lengths in DBU unless named _um)."""
    counts = design.counts()
    dbu = design.dbu_per_micron
    xlo, ylo, xhi, yhi = design.die_area
    ppn = design.pins_per_net()
    nx, ny = design.gcell_grid_size()
    layers = [
        {
            "index": layer.index,
            "name": layer.name,
            "type": layer.type,
            "direction": layer.direction,
            "pitch": list(layer.pitch),
            "width": layer.width,
            "min_width": layer.min_width,
            "min_spacing": layer.min_spacing,
            "min_area": layer.min_area,
        }
        for layer in design.layers
    ]
    return {
        "design": design.name,
        "testcase": design.testcase,
        "files": {"lef": design.lef_paths, "def": design.def_path, "guide": design.guide_path},
        "dbu_per_micron": dbu,
        "die_area": {
            "dbu": [xlo, ylo, xhi, yhi],
            "um": [_microns(v, dbu) for v in (xlo, ylo, xhi, yhi)],
            "width_um": _microns(xhi - xlo, dbu),
            "height_um": _microns(yhi - ylo, dbu),
        },
        "components": counts["components"],
        "macros": counts["macros"],
        "nets": counts["nets"],
        "pins": {
            "total": counts["net_pins"],
            "max_per_net": int(ppn.max()) if len(ppn) else 0,
            "histogram": pin_histogram(ppn),
        },
        "io_pins": counts["io_pins"],
        "special_nets": counts["special_nets"],
        "blockages": counts["blockages"],
        "rows": counts["rows"],
        "tracks": counts["tracks"],
        "gcell_grid": [nx, ny] if nx and ny else None,
        "guides": counts["guides"] if design.guide_path else None,
        "routing_layers": counts["routing_layers"],
        "layers": layers,
        "warnings": design.warning_count,
        "warning_messages": list(design.engine.warnings()),
        "skipped_statements": design.skipped_statements(),
        "not_modelled_rules": design.unjudged_rules(),
        "counts": counts,
    }


def _pitch(pitch: list[int]) -> str:
    if not any(pitch):
        return "-"
    return str(pitch[0]) if pitch[0] == pitch[1] else f"{pitch[0]} x {pitch[1]}"


def _design_table(s: dict[str, Any]) -> Table:
    table = Table(title=f"Design {escape(s['design'])}", show_header=False, title_justify="left")
    table.add_column("item", style="bold")
    table.add_column("value")
    die = s["die_area"]
    hist = "  ".join(f"{k}: {v}" for k, v in s["pins"]["histogram"].items() if k != "0-1" or v)
    rows: list[tuple[str, Any]] = [
        ("design", s["design"]),
        ("testcase", s["testcase"] or "-"),
        ("LEF", "\n".join(s["files"]["lef"])),
        ("DEF", s["files"]["def"]),
        ("guide file", s["files"]["guide"] or "none"),
        ("DBU per micron", s["dbu_per_micron"]),
        ("die area (DBU)", "({}, {}) - ({}, {})".format(*die["dbu"])),
        ("die area (µm)", f"{die['width_um']:g} x {die['height_um']:g}"),
        ("components", s["components"]),
        ("macros (LEF)", s["macros"]),
        ("nets", s["nets"]),
        ("pins", f"{s['pins']['total']} total, max {s['pins']['max_per_net']} per net"),
        ("pins per net", hist),
        ("IO pins", s["io_pins"]),
        ("special nets", s["special_nets"]),
        ("blockages", s["blockages"]),
        ("rows", s["rows"]),
        ("tracks", s["tracks"]),
        ("GCell grid", "{} x {}".format(*s["gcell_grid"]) if s["gcell_grid"] else "none"),
        ("guides", s["guides"] if s["guides"] is not None else "no guide file"),
        ("warnings", s["warnings"]),
    ]
    for item, value in rows:
        table.add_row(item, escape(str(value)))
    return table


def _layer_table(s: dict[str, Any]) -> Table:
    table = Table(title="Layers (lengths in DBU, area in DBU²)", title_justify="left")
    for col in ("#", "name", "type", "direction", "pitch", "width", "min spacing", "min area"):
        table.add_column(col, justify="right" if col in ("#", "pitch", "width", "min spacing", "min area") else "left")
    for layer in s["layers"]:
        table.add_row(
            str(layer["index"]),
            escape(layer["name"]),
            layer["type"],
            layer["direction"] or "-",
            _pitch(layer["pitch"]),
            str(layer["width"] or "-"),
            str(layer["min_spacing"] or "-"),
            str(layer["min_area"] or "-"),
        )
    return table


def _skipped_table(skipped: dict[str, int]) -> Table:
    table = Table(title="Skipped statements (not understood, counted)", title_justify="left")
    table.add_column("keyword")
    table.add_column("count", justify="right")
    for keyword, count in sorted(skipped.items()):
        table.add_row(escape(keyword), str(count))
    return table


def _not_modelled_table(rules: list[dict]) -> Table:
    table = Table(title="Rules stated and not modelled (xroute check does not judge them)", title_justify="left")
    table.add_column("rule")
    table.add_column("layers")
    for item in rules:
        table.add_row(escape(item["rule"]), escape(", ".join(item["layers"])))
    return table


def info(
    testcase: TestcaseArg = None,
    lef: LefOption = None,
    def_: DefOption = None,
    guide: GuideOption = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the summary as JSON on stdout, nothing else.")] = False,
) -> None:
    """Read a design (a testcase name, or --lef and --def files, optionally --guide) and print a summary of it."""
    check_design_args(testcase, lef, def_, guide)
    design = load_design_args(testcase, lef, def_, guide)
    summary = summarize(design)
    if as_json:
        print_json(summary)
        return
    console = stdout_console()
    console.print(_design_table(summary))
    console.print(_layer_table(summary))
    if summary["skipped_statements"]:
        console.print(_skipped_table(summary["skipped_statements"]))
    if summary["not_modelled_rules"]:
        console.print(_not_modelled_table(summary["not_modelled_rules"]))
    for message in summary["warning_messages"]:
        typer.echo(f"warning: {message}")
