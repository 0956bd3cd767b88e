"""Design-rule checker: drawn cases, one rule family at a time.

Every case draws a few shapes in a tiny technology (UNITS 1000: 1 DBU = 1 nm)
and asserts the exact list of markers (type, layer, box, nets). The drawings
are not to scale; x grows to the right, y upwards.
"""

from __future__ import annotations

import numpy as np
import pytest

from drawn import shape_rows
from lef_text import cut, library, routing, stack_via
from xroute import _engine

EOL = "SPACING 0.12 ENDOFLINE 0.15 WITHIN 0.05"
TECH = (
    routing("M1", "HORIZONTAL", 0.2, 0.1, rules=["AREA 0.05 ;", "SPACINGTABLE", "  PARALLELRUNLENGTH 0.0 0.5",
                                                 "  WIDTH 0.0   0.10 0.10", "  WIDTH 0.2   0.10 0.20",
                                                 "  WIDTH 0.4   0.30 0.40 ;"]),
    cut("V1", 0.1, 0.1, rules=["SPACING 0.15 ADJACENTCUTS 3 WITHIN 0.2 ;"]),
    routing("M2", "VERTICAL", 0.2, 0.1, 0.1, rules=["SPACING 0.2 RANGE 0.3 1.0 ;", f"{EOL} ;"]),
    cut("V2", 0.1, rules=["SPACING 0.2 CENTERTOCENTER ;", "SPACING 0.05 SAMENET ;"]),
    routing("M3", "HORIZONTAL", 0.2, 0.1, 0.1, rules=[f"{EOL} PARALLELEDGE 0.12 WITHIN 0.1 ;"]),
    cut("V3", 0.1, 0.1),
    routing("M4", "VERTICAL", 0.2, 0.1, 0.1, rules=[f"{EOL} PARALLELEDGE 0.12 WITHIN 0.1 TWOEDGES ;"]),
    cut("V4", 0.1, 0.1),
    routing("M5", "HORIZONTAL", 0.2, 0.1, 0.1, rules=[
        'PROPERTY LEF58_CORNERSPACING "CORNERSPACING CONVEXCORNER EXCEPTEOL 0.15 WIDTH 0.0 SPACING 0.15 '
        'WIDTH 0.3 SPACING 0.25 ;" ;']),
    stack_via("V12", "M1", "V1", "M2", True, 0.1),
)


def tech_lef(*more: str) -> str:
    """The rules' technology (five layers, one via), then ``more`` LEF parts (sites, macros)."""
    return library(*TECH, *more, header=["CLEARANCEMEASURE EUCLIDEAN ;"])


TECH_LEF = tech_lef()

LAYERS = ["M1", "V1", "M2", "V2", "M3", "V3", "M4", "V4", "M5"]
WIRE, VIA, PIN, OBS, SPECIAL = 0, 1, 2, 3, 4


@pytest.fixture(scope="module")
def db(tmp_path_factory):
    path = tmp_path_factory.mktemp("drc") / "tech.lef"
    path.write_text(TECH_LEF)
    return _engine.load_lef([str(path)])


def check(db, shapes, origins=None, skip_fixed_pairs=False, window=None):
    """shapes: (layer name, xlo, ylo, xhi, yhi, net) rows -> [(type, layer, box, nets)]."""
    rows = shape_rows([[LAYERS.index(s[0]), *s[1:]] for s in shapes])
    org = None if origins is None else np.array(origins, dtype=np.int8)
    markers = _engine.check_shapes(db, rows, org, skip_fixed_pairs=skip_fixed_pairs, window=window)
    return [(m["type"], m["layer"], m["box"], m["nets"]) for m in markers]


def test_technology_as_written(db):
    m1 = db.layers()[0]
    assert m1["spacing_table"] == {"prls": [0, 500], "widths": [0, 200, 400], "spacing": [[100, 100], [100, 200], [300, 400]]}
    assert m1["min_area"] == 50000


# --------------------------------------------------------------- shorts --


def test_short_overlap(db):
    #   +--------+          net 2: (500,50)-(1500,150)
    # +-|---+    |          net 1: (0,0)-(1000,100)
    # | +---|----+          overlap (500,50)-(1000,100)
    # +-----+
    assert check(db, [("M1", 0, 0, 1000, 100, 1), ("M1", 500, 50, 1500, 150, 2)]) == [
        ("Short", "M1", (500, 50, 1000, 100), (1, 2))
    ]


def test_short_abutting_edges_and_one_dbu_apart(db):
    # +------++------+     abutting at x = 1000: a short (zero-width box)
    # |  1   ||  2   |
    # +------++------+
    assert check(db, [("M1", 0, 0, 1000, 100, 1), ("M1", 1000, 0, 2000, 100, 2)]) == [
        ("Short", "M1", (1000, 0, 1000, 100), (1, 2))
    ]
    # One DBU apart: no short, but 1 < 100 spacing.
    assert check(db, [("M1", 0, 0, 1000, 100, 1), ("M1", 1001, 0, 2001, 100, 2)]) == [
        ("MetalSpacing", "M1", (1000, 0, 1001, 100), (1, 2))
    ]


def test_short_same_net_obstruction_and_obstruction_pairs(db):
    a = ("M1", 0, 0, 1000, 100, 1)
    assert check(db, [a, ("M1", 500, 50, 1500, 150, 1)]) == []  # same net: one conductor
    assert check(db, [a, ("M1", 500, 50, 1500, 150, -1)]) == [("Short", "M1", (500, 50, 1000, 100), (1, -1))]
    assert check(db, [("M1", 0, 0, 1000, 100, -1), ("M1", 500, 50, 1500, 150, -1)]) == []


def test_short_markers_of_one_region_merge(db):
    # net 1 is an L of two rects; the net 2 square overlaps both: one marker.
    # |1|
    # |1|+--+
    # |##|2 |      overlaps (0,0)-(250,100) and (0,0)-(100,250)
    # |##1111111
    shapes = [("M1", 0, 0, 1000, 100, 1), ("M1", 0, 0, 100, 1000, 1), ("M1", 0, 0, 250, 250, 2)]
    assert check(db, shapes) == [("Short", "M1", (0, 0, 250, 250), (1, 2))]


def test_cut_short(db):
    assert check(db, [("V1", 0, 0, 100, 100, 1), ("V1", 50, 0, 150, 100, 2)]) == [
        ("CutShort", "V1", (50, 0, 100, 100), (1, 2))
    ]


# -------------------------------------------------- PRL spacing table, M1 --
# widths rows 0 / 200 / 400, PRL columns 0 / 500:
#            PRL>0   PRL>500
#   w>0       100     100
#   w>200     100     200
#   w>400     300     400


def two_wires(width_a, gap, prl, x0=0):
    """Wire A (net 1) of height width_a at the bottom, wire B (net 2, 150 high) above it."""
    return [("M1", 0, 0, 2000, width_a, 1), ("M1", x0, width_a + gap, x0 + prl, width_a + gap + 150, 2)]


def test_prl_narrow_wires(db):
    # +----------B----------+
    #        gap 100 / 99
    # +----------A----------+
    assert check(db, two_wires(100, 100, 2000)) == []
    assert check(db, two_wires(100, 99, 2000)) == [("MetalSpacing", "M1", (0, 100, 2000, 199), (1, 2))]


def test_prl_width_row_boundary(db):
    # width exactly 200 is not "> 200": row 0, 100 is enough.
    assert check(db, two_wires(200, 100, 2000)) == []
    # width 201: row 1, PRL 2000 > 500: needs 200.
    assert check(db, two_wires(201, 100, 2000)) == [("MetalSpacing", "M1", (0, 201, 2000, 301), (1, 2))]
    assert check(db, two_wires(201, 200, 2000)) == []
    assert check(db, two_wires(201, 199, 2000)) == [("MetalSpacing", "M1", (0, 201, 2000, 400), (1, 2))]


def test_prl_column_boundary(db):
    #   +-B-+ (PRL 500 or 501)
    #   gap 100
    # +--------A (width 300, row 1)--------+
    assert check(db, two_wires(300, 100, 500)) == []  # PRL 500 is not "> 500": 100
    assert check(db, two_wires(300, 100, 501)) == [("MetalSpacing", "M1", (0, 300, 501, 400), (1, 2))]


def test_prl_widest_row(db):
    assert check(db, two_wires(400, 300, 2000)) == []  # 400 is row 1 -> 200
    assert check(db, two_wires(401, 400, 2000)) == []  # row 2, PRL > 500 -> 400
    assert check(db, two_wires(401, 399, 2000)) == [("MetalSpacing", "M1", (0, 401, 2000, 800), (1, 2))]
    # Row 2 with a short run (PRL 400 <= 500): 300.
    assert check(db, two_wires(401, 300, 400)) == []
    assert check(db, two_wires(401, 299, 400)) == [("MetalSpacing", "M1", (0, 401, 400, 700), (1, 2))]


def test_prl_diagonal_is_euclidean(db):
    #                 +---B---+   dx = 60, dy = 80: exactly 100 away
    #          (dx,dy)
    # +---A---+
    a = ("M1", 0, 0, 1000, 100, 1)
    assert check(db, [a, ("M1", 1060, 180, 2060, 280, 2)]) == []
    assert check(db, [a, ("M1", 1059, 180, 2059, 280, 2)]) == [("MetalSpacing", "M1", (1000, 100, 1059, 180), (1, 2))]


def test_prl_zero_run_length_corner_line(db):
    # B starts exactly where A ends (x = 1000), 50 above: PRL 0, distance 50.
    assert check(db, [("M1", 0, 0, 1000, 100, 1), ("M1", 1000, 150, 2000, 250, 2)]) == [
        ("MetalSpacing", "M1", (1000, 100, 1000, 150), (1, 2))
    ]


def test_prl_same_net_and_obstruction(db):
    a = ("M1", 0, 0, 2000, 100, 1)
    assert check(db, [a, ("M1", 0, 150, 2000, 250, 1)]) == []  # same net: not checked
    # A wide obstruction counts as min-width (USEMINSPACING OBS ON): 100, not 400.
    obs = ("M1", 0, 0, 2000, 1000, -1)
    assert check(db, [obs, ("M1", 0, 1100, 2000, 1200, 1)]) == []
    assert check(db, [obs, ("M1", 0, 1099, 2000, 1199, 1)]) == [("MetalSpacing", "M1", (0, 1000, 2000, 1099), (1, -1))]
    # A wire as wide as that obstruction uses its real width: 400.
    assert check(db, [("M1", 0, 0, 2000, 1000, 2), ("M1", 0, 1100, 2000, 1200, 1)]) == [
        ("MetalSpacing", "M1", (0, 1000, 2000, 1100), (1, 2))
    ]


def test_plain_spacing_and_range(db):
    # M2: SPACING 0.1, and 0.2 for widths in [0.3, 1.0]; wires side by side.
    #  |A| gap |B|
    a = ("M2", 0, 0, 100, 1000, 1)
    assert check(db, [a, ("M2", 200, 0, 300, 1000, 2)]) == []
    assert check(db, [a, ("M2", 199, 0, 299, 1000, 2)]) == [("MetalSpacing", "M2", (100, 0, 199, 1000), (1, 2))]
    wide = ("M2", 0, 0, 300, 1000, 1)  # width 300: in the RANGE
    assert check(db, [wide, ("M2", 500, 0, 600, 1000, 2)]) == []
    assert check(db, [wide, ("M2", 499, 0, 599, 1000, 2)]) == [("MetalSpacing", "M2", (300, 0, 499, 1000), (1, 2))]
    narrower = ("M2", 0, 0, 299, 1000, 1)  # width 299: below the RANGE
    assert check(db, [narrower, ("M2", 399, 0, 499, 1000, 2)]) == []


# ------------------------------------------------------ end of line, M2 --
# SPACING 0.12 ENDOFLINE 0.15 WITHIN 0.05: the top of a 100-wide wire is a
# line end; its window is x in (-50, 150), y in (1000, 1120).

A_M2 = ("M2", 0, 0, 100, 1000, 1)


def test_eol_window_outward(db):
    #  +------------B------------+   y = 1120 (legal) / 1119
    #        ....window....
    #          |A|
    assert check(db, [A_M2, ("M2", -500, 1120, 600, 1220, 2)]) == []
    assert check(db, [A_M2, ("M2", -500, 1119, 600, 1219, 2)]) == [("EndOfLine", "M2", (-50, 1119, 150, 1120), (1, 2))]


def test_eol_window_sideways(db):
    #            |B|   B starts at x = 150 (legal) / 149, y = 1090
    #  .window.
    #    |A|
    assert check(db, [A_M2, ("M2", 150, 1090, 250, 2000, 2)]) == []
    # At x = 149 B enters A's window, and A enters the window of B's bottom
    # end (x in (99, 299), y in (970, 1090)).
    assert check(db, [A_M2, ("M2", 149, 1090, 249, 2000, 2)]) == [
        ("EndOfLine", "M2", (99, 970, 100, 1000), (2, 1)),
        ("EndOfLine", "M2", (149, 1090, 150, 1120), (1, 2)),
    ]


def test_eol_exemptions(db):
    b = ("M2", -500, 1119, 600, 1219, 2)
    # Same net, not connected: not checked.
    assert check(db, [A_M2, b[:5] + (1,)]) == []
    # A 200-wide top edge is not a line end (and 119 >= 100 spacing).
    assert check(db, [("M2", 0, 0, 200, 1000, 1), b]) == []
    # A's top edge continues into a same-net bar: the merged edge is 900 long.
    #  +----B----+
    #  ===A2===      A2 = (-400,900)-(500,1000), same net as A
    #     |A|
    assert check(db, [A_M2, ("M2", -400, 900, 500, 1000, 1), b]) == []


def test_eol_needs_two_convex_corners(db):
    #  +--B--+               B = (-400,1101)-(-40,1200): in A's EOL window
    #          +--A3--+      A3 = (100,990)-(300,1100), same net as A
    #        |A|             A's top edge then ends in a concave corner
    b = ("M2", -400, 1101, -40, 1200, 2)
    assert check(db, [A_M2, b]) == [("EndOfLine", "M2", (-50, 1101, -40, 1120), (1, 2))]
    assert check(db, [A_M2, ("M2", 100, 990, 300, 1100, 1), b]) == []


def test_eol_obstruction(db):
    assert check(db, [A_M2, ("M2", -500, 1119, 600, 1219, -1)]) == [("EndOfLine", "M2", (-50, 1119, 150, 1120), (1, -1))]


# ------------------------------------------- EOL with PARALLELEDGE, M3/M4 --
# PARALLELEDGE 0.12 WITHIN 0.1: metal within 120 of a side of A, from 100
# below the line end to 50 beyond it: x in (100, 220), y in (900, 1050).


def test_eol_paralleledge(db):
    a = ("M3", 0, 0, 100, 1000, 1)
    b = ("M3", -500, 1119, 600, 1219, 2)
    assert check(db, [a, b]) == []  # no parallel metal: the rule does not apply
    #   +------B------+
    #  |A|  |P|           P = (219, 0)-(319, 950), net 3
    assert check(db, [a, b, ("M3", 219, 0, 319, 950, 3)]) == [("EndOfLine", "M3", (-50, 1119, 150, 1120), (1, 2))]
    assert check(db, [a, b, ("M3", 220, 0, 320, 950, 3)]) == []  # exactly 120 away
    assert check(db, [a, b, ("M3", 219, 0, 319, 900, 3)]) == []  # ends exactly 100 below
    assert check(db, [a, b, ("M3", 219, 0, 319, 901, 3)]) == [("EndOfLine", "M3", (-50, 1119, 150, 1120), (1, 2))]


def test_eol_paralleledge_twoedges(db):
    a = ("M4", 0, 0, 100, 1000, 1)
    b = ("M4", -500, 1119, 600, 1219, 2)
    right = ("M4", 219, 0, 319, 950, 3)
    left = ("M4", -219, 0, -119, 950, 4)
    assert check(db, [a, b, right]) == []
    assert check(db, [a, b, left]) == []
    assert check(db, [a, b, left, right]) == [("EndOfLine", "M4", (-50, 1119, 150, 1120), (1, 2))]
