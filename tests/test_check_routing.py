"""Database.check_routing: opens, markers, wirelength, vias and the contest
scorer's routing-preference figures (wrong-way, off-track, out-of-guide) on a
drawn routed design with tracks and guides, and on the reference route."""

from __future__ import annotations

import gzip
from pathlib import Path

import pytest

from drawn import write_design
from test_drc_rules import TECH_LEF
from xroute import _engine

# M1 HORIZONTAL, M2 VERTICAL (test_drc_rules' technology), 1000 DBU/um.
# Tracks on both layers, both orientations: lines at 100 + 200 k.
#
#   y=1300 . . . . . . . . . . . . . . . . . x V12 (2150,1300): off track
#                                            |   (x=2150 on no M2 X line)
#                                            | M2 (2150,300)-(2150,1300)
#                                            |   off track, 1000 long;
#   y=300          +------ M1 -------------- x V12 (2100,300): on track
#                  | M1 wrong way (200)        M1 (1100,300)-(2100,300)
#   y=100  +--M1---+                           M1 (100,100)-(1100,100)
#         x=100   x=1100                   x=2100
#
# Guides of n1: M1 (0,0)-(1200,400) and (2000,200)-(2200,400);
#               M2 (2000,200)-(2300,1000).
# Out of guide: M1 (1100..2100 at y=300) outside [0,1200] and [2000,2200]:
# 800; M2 (y 300..1300 at x=2150) outside [200,1000]: 300; total 1100.
# Via (2100,300) is in an M1 and an M2 guide; via (2150,1300) is in none: 1.
DEF = """\
VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN tiny ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 10000 10000 ) ;
TRACKS Y 100 DO 50 STEP 200 LAYER M1 ;
TRACKS X 100 DO 50 STEP 200 LAYER M1 ;
TRACKS X 100 DO 50 STEP 200 LAYER M2 ;
TRACKS Y 100 DO 50 STEP 200 LAYER M2 ;
NETS 1 ;
- n1
  + ROUTED M1 ( 100 100 ) ( 1100 100 )
    NEW M1 ( 1100 100 ) ( 1100 300 )
    NEW M1 ( 1100 300 ) ( 2100 300 ) V12
    NEW M2 ( 2150 300 ) ( 2150 1300 ) V12 ;
END NETS
END DESIGN
"""

GUIDE = """\
n1
(
0 0 1200 400 M1
2000 200 2200 400 M1
2000 200 2300 1000 M2
)
"""


def test_check_routing_figures_of_a_drawn_design(tmp_path):
    lef, def_ = write_design(tmp_path, TECH_LEF, DEF)
    guide = tmp_path / "tiny.guide"
    guide.write_text(GUIDE)
    db = _engine.load([str(lef)], str(def_), str(guide))
    r = db.check_routing()
    assert r["opens"] == 0 and r["connectivity"]["open_nets"] == 0
    assert r["markers"] == db.check_drc()
    assert (r["wirelength_dbu"], r["vias"]) == (3200, 2)
    assert r["wirelength_um"] == pytest.approx(3.2)
    assert (r["wrong_way_wirelength_dbu"], r["wrong_way_wirelength_um"]) == (200, pytest.approx(0.2))
    assert (r["off_track_wirelength_dbu"], r["off_track_vias"]) == (1000, 1)
    assert r["has_guides"] is True
    assert r["scorer_pitch_dbu"] == 200  # M2's PITCH 0.2 um: the contest score's unit
    assert (r["out_of_guide_wirelength_dbu"], r["out_of_guide_vias"]) == (1100, 1)
    assert r["out_of_guide_wirelength_um"] == pytest.approx(1.1)

    # Without a guide file the guide figures are None, the others unchanged.
    r = _engine.load([str(lef)], str(def_)).check_routing()
    assert r["has_guides"] is False
    assert (r["out_of_guide_wirelength_dbu"], r["out_of_guide_wirelength_um"], r["out_of_guide_vias"]) == (None, None, None)
    assert (r["wrong_way_wirelength_dbu"], r["off_track_wirelength_dbu"], r["off_track_vias"]) == (200, 1000, 1)


REFERENCE = Path(__file__).resolve().parents[1].parent / "shared" / "reference_routes"
TESTCASES = Path(__file__).resolve().parents[1].parent / "shared" / "testcases"


@pytest.mark.parametrize("name", ["ispd18_test1", "ispd19_test1"])
def test_reference_route_has_no_marker(name, tmp_path):
    """TritonRoute reports 0 violations on its routes; so does our checker (drc/README.md, Readings)."""
    gz = REFERENCE / f"{name}.tritonroute.def.gz"
    base = TESTCASES / name / f"{name}.input"
    if not gz.exists() or not Path(str(base) + ".lef").exists():
        pytest.skip(f"{name} reference route not available")
    def_ = tmp_path / f"{name}.def"
    def_.write_bytes(gzip.decompress(gz.read_bytes()))
    db = _engine.load([str(base) + ".lef"], str(def_), str(base) + ".guide")
    r = db.check_routing()
    assert r["opens"] == 0
    assert r["markers"] == []
