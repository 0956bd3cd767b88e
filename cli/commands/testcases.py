"""``xroute testcases``: the known testcases, their published sizes, where each was found, and the static regions."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from xroute.cli.console import print_json, stdout_console

CONTEST_SITES = {
    "ISPD-2018": "http://www.ispd.cc/contests/18/",
    "ISPD-2019": "http://www.ispd.cc/contests/19/",
}


def _num(value: int | None) -> str:
    return "—" if value is None else str(value)


def _die_um(die_mm: tuple[float, float] | None) -> str:
    return "—" if die_mm is None else f"{die_mm[0] * 1000:g} x {die_mm[1] * 1000:g}"


def collect() -> dict[str, Any]:
    """What ``xroute testcases`` shows, as JSON-ready data."""
    from xroute.testcases import ENV_VAR, STATIC_REGIONS, locate_all, search_path

    located = locate_all()
    found_names = {known.name for known, found in located if found is not None}
    rows = []
    for known, found in located:
        rows.append(
            {
                "name": known.name,
                "contest": known.contest,
                "sample": known.sample,
                "components": known.components,
                "macros": known.macros,
                "nets": known.nets,
                "io_pins": known.io_pins,
                "metal_layers": known.metal_layers,
                "tech_node": known.tech_node,
                "die_mm": list(known.die_mm) if known.die_mm else None,
                "has_guide": known.has_guide,
                "source": known.source,
                "found": str(found.folder) if found else None,
                "files": (
                    {"lef": str(found.lef), "def": str(found.def_), "guide": str(found.guide) if found.guide else None}
                    if found
                    else None
                ),
            }
        )
    regions = [
        {
            "name": r.name,
            "testcase": r.testcase,
            "size_gcells": list(r.size_gcells),
            "lower_left": list(r.lower_left),
            "upper_right": list(r.upper_right),
            "testcase_found": r.testcase in found_names,
        }
        for r in STATIC_REGIONS
    ]
    return {
        "env_var": ENV_VAR,
        "search_path": [str(p) for p in search_path()],
        "testcases": rows,
        "static_regions": regions,
    }


def _testcase_table(data: dict[str, Any]) -> Table:
    table = Table(title="Known testcases (published sizes; — = not published or not confirmed)", title_justify="left")
    numeric = ("components", "macros", "nets", "IO pins", "layers")
    for col in ("name", *numeric, "node", "die (µm)", "guide"):
        table.add_column(col, justify="right" if col in numeric else "left", no_wrap=True)
    table.add_column("found under", overflow="fold")
    for row in data["testcases"]:
        found = row["found"]
        guide = "yes" if row["has_guide"] else "no"
        if row["files"] is not None:
            guide = "yes" if row["files"]["guide"] else "no"
        table.add_row(
            row["name"],
            _num(row["components"]),
            _num(row["macros"]),
            _num(row["nets"]),
            _num(row["io_pins"]),
            _num(row["metal_layers"]),
            row["tech_node"] or "—",
            _die_um(row["die_mm"]),
            guide,
            escape(str(Path(found).parent)) if found else "[dim]not found[/dim]",
        )
    return table


def _region_table(data: dict[str, Any]) -> Table:
    table = Table(title="Static regions of the XRoute paper (DBU)", title_justify="left")
    for col in ("region", "testcase", "GCells", "lower-left", "upper-right", "testcase found"):
        table.add_column(col)
    for r in data["static_regions"]:
        table.add_row(
            r["name"],
            r["testcase"],
            "{} x {}".format(*r["size_gcells"]),
            "({}, {})".format(*r["lower_left"]),
            "({}, {})".format(*r["upper_right"]),
            "yes" if r["testcase_found"] else "no",
        )
    return table


def _footer(data: dict[str, Any]) -> str:
    roots = "\n".join(f"  {i}. {escape(p)}" for i, p in enumerate(data["search_path"], 1))
    sites = ", ".join(f"{contest}: {url}" for contest, url in CONTEST_SITES.items())
    return (
        f"Search path (first match wins):\n{roots}\n"
        f"To add an ISPD testcase: download it from the contest site ({sites}), then put "
        f"<name>/<name>.input.lef, .def and .guide under ../shared/testcases beside the project, "
        f"or under any folder you list in ${data['env_var']} (separated by '{os.pathsep}')."
    )


def testcases(
    as_json: Annotated[bool, typer.Option("--json", help="Print the list as JSON on stdout, nothing else.")] = False,
) -> None:
    """List the known ISPD-2018/2019 testcases, their published sizes and where each was found."""
    data = collect()
    if as_json:
        print_json(data)
        return
    console = stdout_console()
    console.print(_testcase_table(data))
    console.print(_footer(data), highlight=False)
    console.print()
    console.print(_region_table(data))
