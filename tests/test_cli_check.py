"""``xroute check`` on DEFs we did not route: a hand-written routed DEF with known violations, an
open net and known guide/track figures (exact markers), and the KLayout marker database."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import make_runner
from lef_text import cut, library, routing
from xroute.cli.app import app

LEF = library(routing("M1", "HORIZONTAL", 0.2, 0.1, 0.1), cut("V1", 0.1), routing("M2", "VERTICAL", 0.2, 0.1, 0.1),
              grid=None)

# Drawn in DBU (1000 per µm); M1 wires are 100 wide and extend 50 past their ends.
#
#   y=1250  b ======================== (off track: M1 tracks are y = 100 + 200k)
#   y=1100  a ==================================|==      a and b 50 apart: MetalSpacing
#                                               |  d   d runs down M1 (wrong way) and
#   y= 300                                      d      overlaps a: Short
#   c: two pins at y=2500, no routing: open
def _pin(name: str, net: str, x: int, y: int) -> str:
    return (f"- {name} + NET {net} + DIRECTION INPUT + USE SIGNAL\n"
            f"  + LAYER M1 ( -50 -50 ) ( 50 50 ) + PLACED ( {x} {y} ) N ;\n")


DEF = (
    "VERSION 5.8 ;\nDESIGN handmade ;\nUNITS DISTANCE MICRONS 1000 ;\nDIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
    "TRACKS Y 100 DO 20 STEP 200 LAYER M1 ;\nTRACKS X 100 DO 20 STEP 200 LAYER M2 ;\n"
    "PINS 8 ;\n"
    + _pin("a1", "a", 300, 1100) + _pin("a2", "a", 3300, 1100)
    + _pin("b1", "b", 300, 1250) + _pin("b2", "b", 2300, 1250)
    + _pin("c1", "c", 300, 2500) + _pin("c2", "c", 2300, 2500)
    + _pin("d1", "d", 3000, 300) + _pin("d2", "d", 3000, 700)
    + "END PINS\nNETS 4 ;\n"
    "- a ( PIN a1 ) ( PIN a2 ) + ROUTED M1 ( 300 1100 ) ( 3300 1100 ) ;\n"
    "- b ( PIN b1 ) ( PIN b2 ) + ROUTED M1 ( 300 1250 ) ( 2300 1250 ) ;\n"
    "- c ( PIN c1 ) ( PIN c2 ) ;\n"
    "- d ( PIN d1 ) ( PIN d2 ) + ROUTED M1 ( 3000 300 ) ( 3000 1100 ) ;\n"
    "END NETS\nEND DESIGN\n"
)

# A guide for every net; d's guide stops at y=700, so 400 DBU of its wire is out of guide.
GUIDE = """\
a
(
0 1000 3400 1200 M1
)
b
(
0 1200 2400 1300 M1
)
c
(
0 2400 2400 2600 M1
)
d
(
2900 200 3100 700 M1
)
"""


@pytest.fixture
def handmade(tmp_path: Path) -> tuple[Path, Path, Path]:
    lef, def_, guide = tmp_path / "h.lef", tmp_path / "handmade.def", tmp_path / "h.guide"
    lef.write_text(LEF)
    def_.write_text(DEF)
    guide.write_text(GUIDE)
    return lef, def_, guide


def test_check_finds_the_drawn_violations_and_the_open(handmade: tuple[Path, Path, Path], tmp_path: Path) -> None:
    lef, def_, guide = handmade
    out = tmp_path / "chk"
    result = make_runner().invoke(app, ["check", "--lef", str(lef), "--def", str(def_), "--guide", str(guide),
                                        "--out", str(out), "--json"])
    assert result.exit_code == 1, result.output  # c is open
    doc = json.loads(result.stdout)
    assert doc["opens"] == 1 and doc["open_nets"] == [{"net": "c", "pin_groups": 2}]
    assert doc["violations_by_type"] == {"MetalSpacing": 1, "Short": 1}
    markers = json.loads((out / "handmade.check.json").read_text())["markers"]
    got = sorted((m["type"], m["layer"], tuple(m["box"]), tuple(m["nets"])) for m in markers)
    assert got == [
        ("MetalSpacing", "M1", (250, 1150, 2350, 1200), (0, 1)),  # a's and b's wires (and pins) 50 apart
        ("Short", "M1", (2950, 1050, 3050, 1150), (0, 3)),  # d's wire over a's
    ]
    assert doc["wirelength_um"] == pytest.approx((3000 + 2000 + 800) / 1000)
    assert doc["vias"] == 0
    assert doc["wrong_way_wirelength_um"] == pytest.approx(0.8)  # d: vertical on horizontal M1
    assert doc["off_track_wirelength_um"] == pytest.approx(2.0)  # b at y=1250
    assert doc["out_of_guide_wirelength_um"] == pytest.approx(0.4)  # d above y=700
    assert doc["out_of_guide_vias"] == 0
    # Contest score: M2 pitch 200 DBU; 0.5*29 pitches of wire + 1*2 out of guide + 0.5*10 off track + 1*4 wrong way.
    assert doc["m2_pitch_dbu"] == 200
    assert doc["score"] == pytest.approx(0.5 * 29 + 2 + 0.5 * 10 + 4)
    assert (out / "handmade.drc.rpt").read_text().count("MetalSpacing") >= 1


def test_check_without_guide_has_no_guide_figures(handmade: tuple[Path, Path, Path], tmp_path: Path) -> None:
    lef, def_, _ = handmade
    result = make_runner().invoke(app, ["check", "--lef", str(lef), "--def", str(def_), "--out", str(tmp_path),
                                        "--json"])
    doc = json.loads(result.stdout)
    assert doc["out_of_guide_wirelength_um"] is None and doc["score"] is None


def test_lyrdb_loads_in_klayout_with_one_item_per_marker(handmade: tuple[Path, Path, Path], tmp_path: Path) -> None:
    rdb = pytest.importorskip("klayout.rdb", reason="the klayout package (test group) reads marker databases")
    lef, def_, guide = handmade
    make_runner().invoke(app, ["check", "--lef", str(lef), "--def", str(def_), "--out", str(tmp_path), "--quiet"])
    db = rdb.ReportDatabase("check")
    db.load(str(tmp_path / "handmade.lyrdb"))
    assert db.num_items() == 2
    names = sorted(c.name() for c in db.each_category())
    assert names == ["MetalSpacing", "Short"]
    boxes = sorted(str(v) for item in db.each_item() for v in item.each_value() if v.is_box())
    assert boxes == ["box: (0.25,1.15;2.35,1.2)", "box: (2.95,1.05;3.05,1.15)"]


def test_check_a_testcase_with_our_routed_def(tmp_path: Path) -> None:
    """Routed by us, checked by the command: the figures agree with the route's metrics."""
    runner = make_runner()
    routed = runner.invoke(app, ["route", "demo", "--out", str(tmp_path / "r"), "--json"])
    assert routed.exit_code == 0, routed.output
    final = json.loads(routed.stdout)["final"]
    result = runner.invoke(app, ["check", "demo", "--def", str(tmp_path / "r" / "demo.routed.def"),
                                 "--out", str(tmp_path / "c"), "--json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert (doc["opens"], doc["violations"], doc["vias"]) == (0, final["violations"], final["vias"])
    assert doc["wirelength_um"] == pytest.approx(final["wirelength_um"])
    assert doc["score"] is not None and doc["score"] > 0
    # the table names the figure as every command does and says what it is (xroute.glossary)
    shown = runner.invoke(app, ["check", "demo", "--def", str(tmp_path / "r" / "demo.routed.def"),
                                "--out", str(tmp_path / "c2")])
    assert shown.exit_code == 0, shown.output
    assert "contest score = 0.5·WL + 2·vias + 1·out-of-guide WL" in shown.stdout
    assert shown.stdout.rstrip().endswith(f"contest score {doc['score']:,.1f} -> {tmp_path / 'c2'}")


def test_check_needs_a_def_and_one_source_of_lef(tmp_path: Path) -> None:
    runner = make_runner()
    assert runner.invoke(app, ["check", "demo"]).exit_code == 2
    assert runner.invoke(app, ["check", "--def", str(tmp_path / "x.def")]).exit_code == 2
    missing = runner.invoke(app, ["check", "demo", "--def", str(tmp_path / "missing.def")])
    assert missing.exit_code == 2 and "missing.def" in missing.stderr
