"""Design-rule checks of whole designs: shape collection from a drawn DEF, and
the contest designs (pins and obstructions only, unrouted)."""

from __future__ import annotations

import collections
import time
from pathlib import Path

import pytest

from conftest import available, pick
from drawn import load_contest, load_drawn
from lef_text import macro, pin, site
from test_drc_rules import tech_lef

CELL_LEF = site("core", 0.2, 1.0) + macro(
    "INV", 1.0, 1.0,
    pin("A", "INPUT", [("M1", (0.1, 0.4, 0.3, 0.6))]),
    pin("Y", "OUTPUT", [("M1", (0.7, 0.4, 0.9, 0.6))]),
    pin("VDD", "INOUT", [("M1", (0.0, 0.9, 1.0, 1.1))], use="POWER"),
    site_name="core", obs=[("M1", (0.4, 0.3, 0.6, 0.7))],
)

#   u1 at (1000,1000) N, u2 at (2000,1000) FS (mirrored about the x axis).
#   Net n1 joins u1/Y and u2/A with an M1 wire and a V12 via at its end; in
#   the dirty variant a second piece runs into u1's OBS.
DEF_TEMPLATE = """\
VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN tiny ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 10000 10000 ) ;
COMPONENTS 2 ;
- u1 INV + PLACED ( 1000 1000 ) N ;
- u2 INV + PLACED ( 2000 1000 ) FS ;
END COMPONENTS
BLOCKAGES 1 ;
- LAYER M2 RECT ( 5000 5000 ) ( 6000 6000 ) ;
END BLOCKAGES
SPECIALNETS 1 ;
- VDD ( u1 VDD )
  + ROUTED M1 200 ( 1000 3000 ) ( 3000 3000 ) ;
END SPECIALNETS
NETS 1 ;
- n1 ( u1 Y ) ( u2 A )
  + ROUTED M1 ( 1800 1500 ) ( 2200 1500 ) V12{extra} ;
END NETS
END DESIGN
"""

M1, V1, M2 = 0, 1, 2
WIRE, VIA, PIN, OBS, SPECIAL = 0, 1, 2, 3, 4


def load(tmp_path: Path, extra: str = ""):
    return load_drawn(tmp_path, tech_lef(CELL_LEF), DEF_TEMPLATE.format(extra=extra))


def test_collected_shapes(tmp_path):
    db = load(tmp_path)
    # Net ids: n1 = 0, special VDD = 1, then pins on no net: u1/A = 2,
    # u2/Y = 3, u2/VDD = 4 (a POWER pin on no net: one id per pin name).
    assert sorted(db.drc_shapes()) == sorted([
        (M1, 1100, 1400, 1300, 1600, 2, PIN),      # u1/A
        (M1, 1700, 1400, 1900, 1600, 0, PIN),      # u1/Y
        (M1, 1000, 1900, 2000, 2100, 1, PIN),      # u1/VDD, on the special net
        (M1, 1400, 1300, 1600, 1700, -1, OBS),     # u1 OBS
        (M1, 2100, 1400, 2300, 1600, 0, PIN),      # u2/A (FS: y -> 1000 - y)
        (M1, 2700, 1400, 2900, 1600, 3, PIN),      # u2/Y
        (M1, 2000, 900, 3000, 1100, 4, PIN),       # u2/VDD
        (M1, 2400, 1300, 2600, 1700, -1, OBS),     # u2 OBS
        (M2, 5000, 5000, 6000, 6000, -1, OBS),     # DEF blockage
        (M1, 1000, 2900, 3000, 3100, 1, SPECIAL),  # special wire, flush ends
        (M1, 1750, 1450, 2250, 1550, 0, WIRE),     # wire + half width at both ends
        (M1, 2150, 1450, 2250, 1550, 0, VIA),      # V12 at (2200, 1500)
        (V1, 2150, 1450, 2250, 1550, 0, VIA),
        (M2, 2150, 1450, 2250, 1550, 0, VIA),
    ])


def test_design_check(tmp_path):
    db = load(tmp_path)
    # Only fixed shapes break rules: the two 200 x 200 pins on no net are
    # below the 50000 DBU^2 minimum area; the V12 pad alone on M2 has no rule.
    assert db.check_drc(skip_fixed_pairs=True) == []
    markers = db.check_drc(skip_fixed_pairs=False)
    assert [(m["type"], m["layer"], m["box"], m["nets"]) for m in markers] == [
        ("MinArea", "M1", (1100, 1400, 1300, 1600), (2, -1)),
        ("MinArea", "M1", (2700, 1400, 2900, 1600), (3, -1)),
    ]


def test_design_check_finds_a_routed_short(tmp_path):
    # A second piece from (1800,1500) left to (1500,1500) runs into u1's OBS
    # (1400,1300)-(1600,1700): the wire (1450,1450)-(1850,1550) overlaps it.
    db = load(tmp_path, extra=" NEW M1 ( 1800 1500 ) ( 1500 1500 )")
    got = [(m["type"], m["layer"], m["box"], m["nets"]) for m in db.check_drc()]
    assert got == [("Short", "M1", (1450, 1450, 1600, 1550), (0, -1))]
    # A window away from it sees nothing.
    assert db.check_drc(window=(4000, 4000, 4100, 4100)) == []


def contest(name: str):
    return load_contest(name)


@pytest.mark.parametrize("name", available("ispd18_sample", "ispd18_sample2", "ispd18_test1"))
def test_unrouted_contest_design_has_no_new_violation(name):
    db = contest(name)
    # Unrouted: every shape is a pin, an OBS or special wiring.
    assert db.check_drc(skip_fixed_pairs=True) == []


def test_ispd18_sample_pins_of_different_nets_do_not_short():
    db = contest(pick("ispd18_sample"))  # or its generated stand-in without the contest data
    markers = db.check_drc(skip_fixed_pairs=False)
    assert not [m for m in markers if m["type"] == "Short" and m["nets"][1] >= 0]


def test_ispd18_test1_counts(capsys):
    db = contest("ispd18_test1")
    t0 = time.perf_counter()
    markers = db.check_drc(skip_fixed_pairs=False)
    seconds = time.perf_counter() - t0
    counts = collections.Counter((m["type"], m["layer"]) for m in markers)
    with capsys.disabled():
        print(f"\nispd18_test1 (pins + OBS): {len(db.drc_shapes())} shapes, {dict(counts)}, {seconds:.2f} s")
    # No pin of one net overlaps a pin of another.
    assert not [m for m in markers if m["type"] == "Short" and m["nets"][1] >= 0]


def test_the_markers_do_not_depend_on_the_checks_threads(tmp_path, testcase):
    """Layers are checked side by side: any thread count gives the same markers, report and counts.
    The stand-in is routed one iteration at region size 2, which leaves markers on several layers."""
    from xroute.design import load_design
    from xroute.router import route_design

    found = testcase("standin_marked")
    design = load_design(lef=[str(found.lef)], def_=str(found.def_), guide=str(found.guide))
    route_design(design, region_size=2, iterations=1)
    one = design.engine.check_routing(report_path=str(tmp_path / "one.rpt"), threads=1)
    assert len({m["layer"] for m in one["markers"]}) >= 2, "the test needs markers on several layers"
    for threads in (2, 3, 16):
        many = design.engine.check_routing(report_path=str(tmp_path / f"{threads}.rpt"), threads=threads)
        assert many["markers"] == one["markers"]
        assert (tmp_path / f"{threads}.rpt").read_bytes() == (tmp_path / "one.rpt").read_bytes()
        assert design.engine.write_drc_report(str(tmp_path / "w.rpt"), threads=threads) == \
            design.engine.write_drc_report(str(tmp_path / "w1.rpt"), threads=1)
