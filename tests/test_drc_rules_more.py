"""Design-rule checker, drawn cases continued: cuts, minimum area, corner
spacing, and whole checks (order independence, window, fixed shapes, bad
input). Technology and helpers: test_drc_rules.py."""

from __future__ import annotations

import random

import numpy as np
import pytest

from test_drc_rules import OBS, PIN, SPECIAL, VIA, WIRE, check, db  # noqa: F401  (db is a fixture)
from xroute import _engine


# ----------------------------------------------------------- cuts, V1/V2 --


def test_cut_spacing(db):
    a = ("V1", 0, 0, 100, 100, 1)
    assert check(db, [a, ("V1", 200, 0, 300, 100, 2)]) == []
    assert check(db, [a, ("V1", 199, 0, 299, 100, 2)]) == [("CutSpacing", "V1", (100, 0, 199, 100), (1, 2))]
    # Plain cut spacing applies to same-net cuts too; an identical cut is the same cut.
    assert check(db, [a, ("V1", 199, 0, 299, 100, 1)]) == [("CutSpacing", "V1", (100, 0, 199, 100), (1, 1))]
    assert check(db, [a, a]) == []
    # Diagonal, Euclidean: 71/71 is 100.4 away, 70/70 is 99.0.
    assert check(db, [a, ("V1", 171, 171, 271, 271, 2)]) == []
    assert check(db, [a, ("V1", 170, 170, 270, 270, 2)]) == [("CutSpacing", "V1", (100, 100, 170, 170), (1, 2))]
    assert check(db, [a, ("V1", 150, 0, 250, 100, -1)]) == [("CutSpacing", "V1", (100, 0, 150, 100), (1, -1))]


def test_cut_spacing_center_to_center_and_samenet(db):
    # V2: 0.2 centre to centre; same-net cuts: 0.05 edge to edge instead.
    a = ("V2", 0, 0, 100, 100, 1)
    assert check(db, [a, ("V2", 200, 0, 300, 100, 2)]) == []  # centres 200 apart
    assert check(db, [a, ("V2", 199, 0, 299, 100, 2)]) == [("CutSpacing", "V2", (100, 0, 199, 100), (1, 2))]
    assert check(db, [a, ("V2", 199, 0, 299, 100, 1)]) == []  # same net: 99 >= 50
    assert check(db, [a, ("V2", 150, 0, 250, 100, 1)]) == []
    assert check(db, [a, ("V2", 149, 0, 249, 100, 1)]) == [("CutSpacing", "V2", (100, 0, 149, 100), (1, 1))]


def test_adjacent_cuts(db):
    # V1: SPACING 0.15 ADJACENTCUTS 3 WITHIN 0.2. X has three neighbours 120
    # away (< 200), so it needs 150 to each: three markers. T also has three
    # neighbours (X at 120, L and R at 169.7) but is >= 150 from L and R.
    #       [T]
    #  [L]  [X]  [R]
    x = ("V1", 0, 0, 100, 100, 1)
    left, right, top = ("V1", -220, 0, -120, 100, 1), ("V1", 220, 0, 320, 100, 1), ("V1", 0, 220, 100, 320, 1)
    assert check(db, [x, left, right, top]) == [
        ("AdjacentCuts", "V1", (-120, 0, 0, 100), (1, 1)),
        ("AdjacentCuts", "V1", (0, 100, 100, 220), (1, 1)),
        ("AdjacentCuts", "V1", (100, 0, 220, 100), (1, 1)),
    ]
    assert check(db, [x, left, right]) == []  # two neighbours only
    spread = [x, ("V1", -250, 0, -150, 100, 1), ("V1", 250, 0, 350, 100, 1), ("V1", 0, 250, 100, 350, 1)]
    assert check(db, spread) == []  # 150 away: enough


# ------------------------------------------------------------ min area, M1 --


def test_min_area(db):
    assert check(db, [("M1", 0, 0, 500, 100, 1)]) == []  # exactly 50000
    assert check(db, [("M1", 0, 0, 499, 100, 1)]) == [("MinArea", "M1", (0, 0, 499, 100), (1, -1))]


def test_min_area_counts_the_union_once(db):
    # Two overlapping rects, 30000 + 29900 DBU^2, but their union is 49900.
    assert check(db, [("M1", 0, 0, 300, 100, 1), ("M1", 200, 0, 499, 100, 1)]) == [
        ("MinArea", "M1", (0, 0, 499, 100), (1, -1))
    ]
    assert check(db, [("M1", 0, 0, 300, 100, 1), ("M1", 200, 0, 500, 100, 1)]) == []


def test_min_area_pin_metal_counts_and_gaps_split(db):
    # A wire abutting its pin: one conductor of 50000.
    assert check(db, [("M1", 0, 0, 300, 100, 1), ("M1", 300, 0, 500, 100, 1)], origins=[WIRE, PIN]) == []
    # Same net with a gap: two conductors, each too small.
    assert check(db, [("M1", 0, 0, 300, 100, 1), ("M1", 400, 0, 600, 100, 1)]) == [
        ("MinArea", "M1", (0, 0, 300, 100), (1, -1)),
        ("MinArea", "M1", (400, 0, 600, 100), (1, -1)),
    ]
    # Touching at a corner point only is not a connection.
    assert check(db, [("M1", 0, 0, 300, 100, 1), ("M1", 300, 100, 600, 200, 1)]) == [
        ("MinArea", "M1", (0, 0, 300, 100), (1, -1)),
        ("MinArea", "M1", (300, 100, 600, 200), (1, -1)),
    ]
    assert check(db, [("M1", 0, 0, 100, 100, -1)]) == []  # obstructions have no area rule


# -------------------------------------------------------- corner spacing, M5 --
# CONVEXCORNER EXCEPTEOL 0.15, width >= 0: 150, width >= 300: 250.


def test_corner_spacing_wide(db):
    #            +--B--+     B's lower-left corner dx = dy from A's upper-right;
    #            +-----+     the spacing region is a square: max(dx, dy) < 250
    # +---A---+
    # | 1000  |
    # +-------+
    a = ("M5", 0, 0, 1000, 1000, 1)
    assert check(db, [a, ("M5", 1250, 1250, 1750, 1750, 2)]) == []  # 250 away
    assert check(db, [a, ("M5", 1249, 1249, 1749, 1749, 2)]) == [
        ("CornerSpacing", "M5", (1000, 1000, 1249, 1249), (1, 2))
    ]
    assert check(db, [a, ("M5", 1249, 1249, 1749, 1749, -1)]) == [
        ("CornerSpacing", "M5", (1000, 1000, 1249, 1249), (1, -1))
    ]


def test_corner_spacing_narrow_and_except_eol(db):
    a = ("M5", 0, 0, 200, 1000, 1)  # width 200: 150; its 200-long top edge is no line end
    assert check(db, [a, ("M5", 350, 1150, 550, 1650, 2)]) == []  # 150 away
    assert check(db, [a, ("M5", 349, 1100, 549, 1600, 2)]) == [("CornerSpacing", "M5", (200, 1000, 349, 1100), (1, 2))]
    # 100-wide wires: both corners belong to line ends, exempt.
    assert check(db, [("M5", 0, 0, 100, 1000, 1), ("M5", 200, 1100, 300, 1600, 2)]) == []


# ----------------------------------------------------------- whole checks --


CLEAN = [
    ("M1", 0, 0, 2000, 100, 1),
    ("M1", 0, 200, 2000, 300, 2),
    ("V1", 1900, 200, 2000, 300, 2),
    ("M2", 1900, 200, 2000, 1200, 2),
    ("M2", 1600, 0, 1700, 1200, 3),
    ("M3", 0, 2000, 3000, 2100, 4),
    ("M5", 0, 0, 1000, 1000, 5),
    ("M5", 1300, 1300, 1800, 1800, 6),
]


def test_clean_layout_has_no_marker(db):
    assert check(db, CLEAN) == []


DIRTY = [
    ("M1", 0, 0, 1000, 100, 1), ("M1", 500, 50, 1500, 150, 2),        # short
    ("M1", 0, 5000, 2000, 5201, 1), ("M1", 0, 5301, 2000, 5401, 2),    # spacing
    ("M1", 9000, 0, 9499, 100, 3),                                     # min area
    ("M2", 0, 0, 100, 1000, 1), ("M2", -500, 1119, 600, 1219, 2),      # EOL
    ("V1", 0, 0, 100, 100, 1), ("V1", 170, 170, 270, 270, 2),          # cut spacing
    ("V1", 5000, 0, 5100, 100, 4), ("V1", 4780, 0, 4880, 100, 4),
    ("V1", 5220, 0, 5320, 100, 4), ("V1", 5000, 220, 5100, 320, 4),    # adjacent cuts
    ("M5", 0, 0, 1000, 1000, 1), ("M5", 1176, 1176, 1676, 1676, 2),    # corner
]


def test_dirty_layout_markers_do_not_depend_on_input_order(db):
    expected = check(db, DIRTY)
    assert [m[0] for m in expected] == [
        "Short", "MetalSpacing", "EndOfLine", "CutSpacing", "AdjacentCuts", "AdjacentCuts", "AdjacentCuts",
        "MinArea", "CornerSpacing",
    ]
    rng = random.Random(7)
    for _ in range(5):
        shuffled = DIRTY[:]
        rng.shuffle(shuffled)
        assert check(db, shuffled) == expected


def test_window_keeps_markers_that_touch_it(db):
    everything = check(db, DIRTY)
    inside = check(db, DIRTY, window=(8000, -1000, 10000, 1000))
    assert inside == [("MinArea", "M1", (9000, 0, 9499, 100), (3, -1))]
    # The short's box (500,50)-(1000,100) touches this window at one corner.
    assert check(db, DIRTY, window=(1000, 100, 1100, 200)) == [m for m in everything if m[0] == "Short"]
    assert check(db, DIRTY, window=(1001, 101, 1100, 200)) == []


def test_skip_fixed_pairs(db):
    pins = [("M1", 0, 0, 1000, 100, 1), ("M1", 500, 50, 1500, 150, 2)]
    assert check(db, pins, origins=[PIN, PIN], skip_fixed_pairs=True) == []
    assert check(db, pins, origins=[PIN, OBS], skip_fixed_pairs=True) == []
    assert check(db, pins, origins=[PIN, SPECIAL], skip_fixed_pairs=True) == []
    assert check(db, pins, origins=[PIN, WIRE], skip_fixed_pairs=True) == [("Short", "M1", (500, 50, 1000, 100), (1, 2))]
    small = [("M1", 0, 0, 100, 100, 1)]
    assert check(db, small, origins=[PIN], skip_fixed_pairs=True) == []
    assert check(db, small, origins=[VIA], skip_fixed_pairs=True) == [("MinArea", "M1", (0, 0, 100, 100), (1, -1))]
    # A wire covering a small pin makes the conductor new: reported (a pin
    # sticking out of its wire exempts the conductor: test_drc_reading.py).
    joined = [("M1", 0, 0, 100, 100, 1), ("M1", 0, 0, 200, 100, 1)]
    assert check(db, joined, origins=[PIN, WIRE], skip_fixed_pairs=True) == [("MinArea", "M1", (0, 0, 200, 100), (1, -1))]


def test_bad_input_is_refused(db):
    with pytest.raises(ValueError):
        _engine.check_shapes(db, np.zeros((2, 5), dtype=np.int32))
    with pytest.raises(IndexError):
        _engine.check_shapes(db, np.array([[99, 0, 0, 10, 10, 1]], dtype=np.int32))
    with pytest.raises(ValueError):
        _engine.check_shapes(db, np.array([[0, 0, 0, 10, 10, 1]], dtype=np.int32), np.array([9], dtype=np.int8))
    assert _engine.check_shapes(db, np.zeros((0, 6), dtype=np.int32)) == []


def test_random_rects_match_a_brute_force_pair_check(db):
    # Every rect its own net on M1, so each violating pair is one marker.
    # Reference: all pairs, the LEF 5.8 table lookup written out again.
    widths, prls, table = [0, 200, 400], [0, 500], [[100, 100], [100, 200], [300, 400]]

    def need(w, prl):
        row = max(i for i, v in enumerate(widths) if i == 0 or w > v)
        col = max(j for j, v in enumerate(prls) if j == 0 or prl > v)
        return table[row][col]

    rng = random.Random(11)
    rects = []
    for net in range(150):
        x, y = rng.randrange(0, 6000), rng.randrange(0, 6000)
        rects.append((x, y, x + rng.randrange(50, 700), y + rng.randrange(50, 700)))
    expected = set()
    for i, a in enumerate(rects):
        for j in range(i + 1, len(rects)):
            b = rects[j]
            dx = max(0, b[0] - a[2], a[0] - b[2])
            dy = max(0, b[1] - a[3], a[1] - b[3])
            if dx == 0 and dy == 0:
                expected.add(("Short", (i, j)))
                continue
            prl = max(min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1]))
            w = max(min(a[2] - a[0], a[3] - a[1]), min(b[2] - b[0], b[3] - b[1]))
            if dx * dx + dy * dy < need(w, prl) ** 2:
                expected.add(("MetalSpacing", (i, j)))
    got = {(m[0], m[3]) for m in check(db, [("M1", *r, n) for n, r in enumerate(rects)]) if m[0] != "MinArea"}
    assert len(expected) > 50
    assert got == expected


# ------------------------------------------- overlapping shifted copies --
# Thousands of copies of one wire, each shifted by 1 DBU, overlap into a band
# (`check` once took 46 s on 50,000 of them). They are checked as the
# rects they are (each copy its own width and run length), through the
# crowded-layer index, the boundary sweep and the collinear joins; the
# markers are those of the geometry, in any order.

def test_copies_shifted_across_a_wire(db):
    #  +--N2--+                     N2 = (500,2149)-(1100,2249): 50 above the band
    #  ====band====                 2,000 copies of (0,i)-(1000,100+i), net 1: (0,0)-(1000,2099)
    #     [N3]                      N3 = (200,1000)-(800,1100): inside the band
    band = [("M1", 0, i, 1000, 100 + i, 1) for i in range(2000)]
    shapes = band + [("M1", 500, 2149, 1100, 2249, 2), ("M1", 200, 1000, 800, 1100, 3)]
    expected = [
        ("Short", "M1", (200, 1000, 800, 1100), (1, 3)),
        # Per rect (drc/README.md): the copies just below and above N3 that do not touch it are
        # closer than the 100 the table asks for 100-wide metal; so are copies i >= 1950 to N2.
        ("MetalSpacing", "M1", (200, 901, 800, 1000), (1, 3)),
        ("MetalSpacing", "M1", (200, 1100, 800, 1199), (1, 3)),
        ("MetalSpacing", "M1", (500, 2050, 1000, 2149), (1, 2)),
    ]
    assert check(db, shapes) == expected
    assert check(db, random.Random(7).sample(shapes, len(shapes))) == expected


def test_copies_shifted_along_a_wire(db):
    # 2,000 copies of (0,i)-(100,1000+i) on M2, net 1: one wire (0,0)-(100,2999) whose top is a
    # line end (100 < 150) with B in its window (as test_eol_window_outward, 1,999 higher).
    band = [("M2", 0, i, 100, 1000 + i, 1) for i in range(2000)]
    b = ("M2", -500, 3118, 600, 3218, 2)
    assert check(db, band + [b]) == [("EndOfLine", "M2", (-50, 3118, 150, 3119), (1, 2))]
    assert check(db, band + [b[:2] + (3119,) + b[3:]]) == []  # 120 away: legal
