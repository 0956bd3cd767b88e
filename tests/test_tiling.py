"""Tiling a testcase R x C (``xroute.testcases.tiling``, ``xroute make-testcase --tile``)."""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest

from conftest import pick
from xroute.testcases import DEMO
from xroute.testcases.tiling import _point_offset, parse_by, tile_testcase
from xroute.errors import XrouteError

SCALED = ("components", "nets", "net_pins", "guides", "io_pins", "blockages")


def _load(folder: Path):
    from xroute.design import load_design

    n = folder.name
    guide = folder / f"{n}.input.guide"
    return load_design(lef=[str(folder / f"{n}.input.lef")], def_=str(folder / f"{n}.input.def"),
                       guide=str(guide) if guide.is_file() else None)


def _markers(design) -> Counter:
    return Counter((m["type"], m["layer"]) for m in design.engine.check_drc(skip_fixed_pairs=False))


def test_point_offset_moves_absolute_points_only() -> None:
    tokens = "- n1 ( u1 A ) + ROUTED Metal2 ( 10 20 ) ( * 90 ) ( 5 6 7 ) RECT ( -1 -2 3 4 ) ;".split()
    moved = _point_offset(tokens, 100, 1000, 5)
    assert " ".join(moved) == "- n1 ( u1 A ) + ROUTED Metal2 ( 110 1020 ) ( * 1090 ) ( 105 1006 7 ) RECT ( -1 -2 3 4 ) ;"


@pytest.mark.parametrize("text, expected", [("2x2", (2, 2)), ("4X1", (4, 1)), ("1x64", (1, 64))])
def test_parse_by(text: str, expected: tuple[int, int]) -> None:
    assert parse_by(text) == expected


@pytest.mark.parametrize("text", ["0x2", "2", "2x", "x2", "ax2", "65x1", "2x2x2"])
def test_parse_by_rejects(text: str) -> None:
    with pytest.raises(XrouteError):
        parse_by(text)


def test_sample_2x2_is_four_renamed_copies_and_routes(testcase, tmp_path: Path) -> None:
    sample = pick("ispd18_sample")  # or its generated stand-in without the contest data
    found = testcase(sample)
    from xroute.design import load_design
    from xroute.outputs import write_route_outputs
    from xroute.router import route_design

    base = load_design(sample)
    tiled = _load(tile_testcase(sample, 2, 2, tmp_path / "s22"))
    a, b = base.counts(), tiled.counts()
    assert {k: b[k] for k in SCALED} == {k: 4 * a[k] for k in SCALED}
    assert b["rows"] == 4 * a["rows"] and b["special_nets"] == a["special_nets"]
    assert sorted(tiled.net_names) == sorted(f"{n}_r{i}_c{j}" for n in base.net_names for i in range(2) for j in range(2))
    # Copy (0, 0) sits where the original does; every component of copy (1, 1) moved by one offset.
    def loc(d, name: str) -> tuple[int, int]:
        return d.component(name)["location"]

    moves = set()
    if sample == "ispd18_sample":
        names = ("inst2015", "inst2591", "inst7234")
    else:  # the first three components of the stand-in's DEF
        names = tuple(re.findall(r"^- (\S+) ", found.def_.read_text().split("\nCOMPONENTS ")[1], re.M)[:3])
    for name in names:
        assert loc(tiled, f"{name}_r0_c0") == loc(base, name)
        (x1, y1), (x0, y0) = loc(tiled, f"{name}_r1_c1"), loc(base, name)
        moves.add((x1 - x0, y1 - y0))
    assert len(moves) == 1 and min(moves.pop()) > 0
    # No rule broken between copies: exactly four times the original's markers.
    assert _markers(tiled) == Counter({k: 4 * v for k, v in _markers(base).items()})
    result = route_design(tiled, threads=1)
    outputs = write_route_outputs(tiled, result, tmp_path / "out")
    assert outputs.open_nets == 0 and outputs.final["nets_routed"] == 4 * a["nets"]


def test_demo_1x2_keeps_io_pins_merges_rails_and_routes(tmp_path: Path) -> None:
    """The shipped demo has IO pins and power special nets; runs without contest data."""
    from xroute.design import load_design
    from xroute.outputs import write_route_outputs
    from xroute.router import route_design

    base = load_design(DEMO)
    tiled = _load(tile_testcase(DEMO, 1, 2, tmp_path / "demo_1x2"))
    a, b = base.counts(), tiled.counts()
    assert {k: b[k] for k in SCALED} == {k: 2 * a[k] for k in SCALED}
    assert b["special_nets"] == a["special_nets"] == 2
    vdd, vdd_tiled = base.special_net("VDD"), tiled.special_net("VDD")
    assert len(vdd_tiled["rects"]) == 2 * len(vdd["rects"])
    assert tiled.io_pin("io0_r0_c1")["net"] == base.io_pin("io0")["net"] + "_r0_c1"
    assert _markers(base) == Counter() and _markers(tiled) == Counter()
    outputs = write_route_outputs(tiled, route_design(tiled, threads=2), tmp_path / "out")
    assert outputs.open_nets == 0 and outputs.final["nets_routed"] == 2 * a["nets"]


def test_tiling_refuses_what_it_cannot_move(tmp_path: Path) -> None:
    from xroute.testcases.def_text import read_def_text
    from xroute.testcases.tiling import tile_def

    path = tmp_path / "a.def"
    path.write_text("VERSION 5.8 ;\nDESIGN a ;\nDIEAREA ( 0 0 ) ( 10 0 ) ( 10 10 ) ;\nEND DESIGN\n")
    with pytest.raises(XrouteError, match="rectangular DIEAREA"):
        tile_def(read_def_text(path), [], 2, 2, "a_2x2")
    path.write_text("DESIGN a ;\nDIEAREA ( 0 0 ) ( 10 10 ) ;\nGROUPS 1 ;\n- g1 u1 ;\nEND GROUPS\nEND DESIGN\n")
    with pytest.raises(XrouteError, match="GROUPS"):
        tile_def(read_def_text(path), [], 2, 2, "a_2x2")
