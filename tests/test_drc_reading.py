"""How the checker reads MinArea and LEF58_CORNERSPACING (the counts
must be true). Each case is drawn; drc/README.md gives the reading and why.
Technology and helpers: test_drc_rules.py (M1: AREA 0.05 = 50000 DBU^2;
M5: CORNERSPACING CONVEXCORNER EXCEPTEOL 0.15, width >= 0: 150,
width >= 300: 250; 1000 DBU per micron)."""

from __future__ import annotations

from test_drc_rules import PIN, VIA, WIRE, check, db  # noqa: F401  (db is a fixture)


# ----------------------------------------------------------- MinArea, M1 --


def test_min_area_pin_sticking_out_of_its_via_pad_is_the_inputs(db):
    # The ispd18_test1 case: a library pin smaller than AREA, a via pad on it
    # that sticks out. Union 30000 + 20000 - 16000 (overlap) = 34000 < 50000.
    #
    #   y=300 +--+-------+--+
    #         |  |overlap|  |       pin (0,0)-(100,300), fixed
    #   y=100 |  +-------+--+       pad (20,100)-(120,300), a via's
    #         |   pin    |
    #   y=0   +----------+
    #        x=0 x=20  x=100 x=120
    pin = ("M1", 0, 0, 100, 300, 1)
    pad = ("M1", 20, 100, 120, 300, 1)
    shapes, origins = [pin, pad], [PIN, VIA]
    # Part of the outline is the pin's: the violation is the input's (fixed),
    # reported only when fixed violations are asked for.
    assert check(db, shapes, origins=origins, skip_fixed_pairs=True) == []
    assert check(db, shapes, origins=origins, skip_fixed_pairs=False) == [
        ("MinArea", "M1", (0, 0, 120, 300), (1, -1))
    ]


def test_min_area_pin_covered_by_routing_is_checked(db):
    # The routing covers the whole pin: the outline is all routing, and
    # 100x400 = 40000 < 50000 is the router's violation.
    #   +--wire--+  (0,0)-(100,400)
    #   |  [pin] |  pin (0,100)-(100,200) inside it
    #   +--------+
    shapes = [("M1", 0, 100, 100, 200, 1), ("M1", 0, 0, 100, 400, 1)]
    assert check(db, shapes, origins=[PIN, WIRE], skip_fixed_pairs=True) == [
        ("MinArea", "M1", (0, 0, 100, 400), (1, -1))
    ]
    # Large enough with its pin counted once: nothing.
    shapes = [("M1", 0, 100, 100, 200, 1), ("M1", 0, 0, 100, 500, 1)]
    assert check(db, shapes, origins=[PIN, WIRE], skip_fixed_pairs=True) == []


def test_min_area_routing_alone_still_checked(db):
    # A via pad and a stub of routing on no pin: 200x200 = 40000 < 50000.
    shapes = [("M1", 0, 0, 200, 200, 1), ("M1", 50, 50, 150, 150, 1)]
    assert check(db, shapes, origins=[WIRE, VIA], skip_fixed_pairs=True) == [
        ("MinArea", "M1", (0, 0, 200, 200), (1, -1))
    ]


# --------------------------------------------------- CornerSpacing, M5 --


def test_corner_spacing_ignores_metal_with_a_parallel_run(db):
    # The ispd19_test1 case: B's via pad lies in A's corner quadrant, but B's
    # wire continues left over A's top edge, so B's merged metal has no
    # convex corner facing A's corner (its lower-left one is left of A's
    # corner; (1050,1200) is concave): a parallel run, plain spacing 100 >= 100.
    #
    #              +--B pad--+      B pad (1050,1100)-(1300,1300)
    #     +--------+---------+      B wire (900,1100)-(1250,1200)
    #     +---B wire---------+
    #  +------A------+ (1000,1000)  A (0,0)-(1000,1000)
    a = ("M5", 0, 0, 1000, 1000, 1)
    wire, pad = ("M5", 900, 1100, 1250, 1200, 2), ("M5", 1050, 1100, 1300, 1300, 2)
    assert check(db, [a, wire, pad]) == []
    # Without the wire the pad's lower-left corner faces A's corner:
    # max(50, 100) < 250.
    assert check(db, [a, pad]) == [("CornerSpacing", "M5", (1000, 1000, 1050, 1100), (1, 2))]


def test_corner_spacing_region_is_a_square(db):
    # dx = 200, dy = 240: Euclidean 312 >= 250, but max(dx, dy) = 240 < 250.
    #            +--B--
    #            |
    #   ---A---+ (1000,1000)
    a = ("M5", 0, 0, 1000, 1000, 1)
    assert check(db, [a, ("M5", 1200, 1240, 1700, 1740, 2)]) == [
        ("CornerSpacing", "M5", (1000, 1000, 1200, 1240), (1, 2))
    ]
    assert check(db, [a, ("M5", 1200, 1250, 1700, 1750, 2)]) == []  # dy = 250


def test_corner_spacing_needs_a_facing_convex_corner(db):
    # B's edge, not its corner, is nearest: B's lower-left corner is left of
    # A's corner, so B runs over A's corner (a parallel run, plain spacing).
    #   +-----B------+          B (900,1150)-(1400,1650)
    #  ---A---+ (1000,1000)
    a = ("M5", 0, 0, 1000, 1000, 1)
    assert check(db, [a, ("M5", 900, 1150, 1400, 1650, 2)]) == []
    # B's corner facing away from A (its lower-right one, beside A) is not a
    # corner-to-corner pair either: B (500,1100)-(1000,1600) sits straight above.
    assert check(db, [a, ("M5", 500, 1100, 1000, 1600, 2)]) == []


def test_corner_spacing_except_eol_on_either_corner(db):
    # A is wide (no line end); B is a 100-wide wire whose bottom edge (100 <
    # 150, two convex corners) is a line end: B's corner is exempt, so is the pair.
    #      |B|
    #      +-+ (1100,1100) line end
    #   -A-+ (1000,1000)
    a = ("M5", 0, 0, 1000, 1000, 1)
    assert check(db, [a, ("M5", 1100, 1100, 1200, 2000, 2)]) == []
    # A 200-wide B (no line end) at the same place: max(100, 100) < 250.
    assert check(db, [a, ("M5", 1100, 1100, 1300, 2000, 2)]) == [
        ("CornerSpacing", "M5", (1000, 1000, 1100, 1100), (1, 2))
    ]


def test_corner_spacing_between_pins_is_the_inputs(db):
    # Two pins' corners face each other 100 x 100 apart (< 250): the library's
    # geometry. Routing joined to each pin away from the corners does not make
    # it the router's (as for EndOfLine): fixed, dropped by skip_fixed_pairs.
    #              +--pin B--+--wire B
    #              |         |
    #   wire A--+--+ (1100,1100)
    #   +-pin A-+ (1000,1000)
    pin_a, wire_a = ("M5", 0, 0, 1000, 1000, 1), ("M5", -500, 400, 0, 600, 1)
    pin_b, wire_b = ("M5", 1100, 1100, 2100, 2100, 2), ("M5", 2100, 1500, 2600, 1700, 2)
    shapes, origins = [pin_a, wire_a, pin_b, wire_b], [PIN, WIRE, PIN, WIRE]
    marker = ("CornerSpacing", "M5", (1000, 1000, 1100, 1100), (1, 2))
    assert check(db, shapes, origins=origins, skip_fixed_pairs=True) == []
    assert check(db, shapes, origins=origins, skip_fixed_pairs=False) == [marker]
    # A via pad on pin B's corner: the corner is the router's too.
    pad = ("M5", 1100, 1100, 1300, 1300, 2)
    assert check(db, [*shapes, pad], origins=[*origins, VIA], skip_fixed_pairs=True) == [marker]
