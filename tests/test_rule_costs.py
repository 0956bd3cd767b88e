"""Rule-aware routing costs and the repair inside a region: drawn cases where the footprint
(grid/footprint.cpp) must follow the layer's spacing table, and the sample where the
old footprint made the router short a pad pin."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conftest import require_testcase
from drawn import write_design
from lef_text import cut, library, macro, pin, routing, stack_via, via
from xroute import _engine, load_design

# M2 (vertical) has a wide-metal row: 0.07 um for short parallel runs, 0.5 um once a
# shape at least 1 um wide runs parallel for more than 0.5 um. The macro's M2
# obstruction is 2 um x 2 um at (0.6..2.6, 0.95..2.95).
WIDE_LAYERS = (
    routing("M1", "HORIZONTAL", 0.2, 0.06, 0.07),
    cut("V1", 0.06, 0.08),
    routing("M2", "VERTICAL", 0.2, 0.06, rules=["SPACINGTABLE", "  PARALLELRUNLENGTH 0.0 0.5", "  WIDTH 0.0 0.07 0.07",
                                               "  WIDTH 1.0 0.07 0.5 ;"]),
    stack_via("V12", "M1", "V1", "M2", True, 0.06, metal_length=0.1),
)
WIDE_LEF = library(
    *WIDE_LAYERS,
    macro("BIG", 2.0, 2.0, pin("P", "INPUT", [("M1", (0.0, 0.0, 0.2, 0.06))]), obs=[("M2", (0.0, 0.0, 2.0, 2.0))],
          klass="BLOCK"),
)

WIDE_DEF = """\
VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN wide ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 4000 4000 ) ;
TRACKS Y 100 DO 20 STEP 200 LAYER M1 ;
TRACKS X 100 DO 20 STEP 200 LAYER M2 ;
COMPONENTS 1 ;
- u1 BIG + PLACED ( 600 950 ) N ;
END COMPONENTS
NETS 1 ;
- a ( u1 P ) ;
END NETS
END DESIGN
"""


def fixed_owner_at(tmp_path: Path, x: int, y: int, z: int) -> int:
    lef, def_ = write_design(tmp_path, WIDE_LEF, WIDE_DEF, "wide")
    db = load_design(lef=lef, def_=def_).engine
    region = _engine.RoutingSession(db).open_region((0, 0, 4000, 4000))
    g = region.grid()
    xs, ys = np.asarray(g["xs"]).tolist(), np.asarray(g["ys"]).tolist()
    return int(g["fixed_owner"][z, ys.index(y), xs.index(x)])


def test_wide_obstruction_blocks_its_sides_with_the_wide_spacing(tmp_path: Path) -> None:
    # 0.3 um left of the 2 um tall obstruction: a vertical M2 wire there runs parallel to it
    # for up to 2 um and needs 0.5 um.
    assert fixed_owner_at(tmp_path, 300, 1500, 1) == -2


def test_wire_ending_below_a_wide_obstruction_needs_only_the_short_run_spacing(tmp_path: Path) -> None:
    # 0.22 um below it (y = 0.7), a vertical M2 wire meets it end-on (parallel run = its own width):
    # 0.07 um is enough. The old footprint used the 0.5 um row all around and forbade it.
    assert fixed_owner_at(tmp_path, 1500, 700, 1) == -1
    # At y = 0.9 the wire end (0.93) is 0.02 um away: still forbidden.
    assert fixed_owner_at(tmp_path, 1500, 900, 1) == -2


def _route(name: str, threads: int = 1, **settings: int) -> tuple[Any, dict[str, Any]]:
    require_testcase(name)
    d = load_design(name)
    out = _engine.route(d.engine, settings=_engine.RouterSettings(threads=threads, **settings))
    return d, out


def test_pad_pins_of_ispd19_sample4_are_reached_without_shorts() -> None:
    # The pad pins sit in a notch at the pad's edge; with the wide-metal row applied all
    # around the pad every way in looked forbidden and the router went through the pad's
    # Metal6 obstruction (2 shorts, 2 cut shorts; 6 violations left after 10 iterations).
    _, out = _route("ispd19_sample4")
    last = out["iterations"][-1]
    assert last["violations"] == 0, last["violations_by_type"]


def test_repair_inside_the_region_lowers_the_first_iterations_markers() -> None:
    # Iteration 0 alone: the region's own check-and-reroute rounds (off by default in
    # iteration 0) leave fewer markers than routing each net once. Regions of 3 GCells: at the
    # default 10, iteration 0 leaves none (since open line ends across the tracks are in the
    # footprint; it left some before).
    require_testcase("ispd19_sample4")
    counts = []
    for rounds in (0, 3):
        d = load_design("ispd19_sample4")
        settings = _engine.RouterSettings(first_repair_rounds=rounds, region_size=3, iterations=1)
        one = _engine.route(d.engine, settings=settings)
        counts.append(one["iterations"][0]["violations"])
    assert counts[1] < counts[0]


@pytest.mark.parametrize("name", ["ispd19_sample4", pytest.param("ispd18_sample3", marks=pytest.mark.slow)])
def test_repair_rounds_do_not_depend_on_the_thread_count(tmp_path: Path, name: str) -> None:
    defs = []
    for threads in (1, 2):
        require_testcase(name)
        d = load_design(name)
        settings = _engine.RouterSettings(first_repair_rounds=2, repair_rounds=2, threads=threads, iterations=3)
        _engine.route(d.engine, settings=settings)
        path = tmp_path / f"{name}.{threads}.def"
        d.engine.write_def(str(path))
        defs.append(path.read_bytes())
    assert defs[0] == defs[1]


# A cell's M1 pin at (500, 1500), 0.07 um left of the wide M2 obstruction: its via's M2 pad (0.1 um
# along the track) needs only the short-run spacing, a vertical M2 wire beside the obstruction the
# 0.5 um one. Net a joins it to a pin far above; net b joins two pins far right.
LANDING_LEF = library(
    *WIDE_LAYERS,
    macro("BIG", 2.0, 2.0, obs=[("M2", (0.0, 0.0, 2.0, 2.0))], klass="BLOCK"),
    macro("C", 0.2, 0.2, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.13))])),
)

LANDING_DEF = WIDE_DEF.replace("COMPONENTS 1 ;\n- u1 BIG + PLACED ( 600 950 ) N ;\n", (
    "COMPONENTS 5 ;\n- u1 BIG + PLACED ( 600 950 ) N ;\n- c1 C + PLACED ( 400 1400 ) N ;\n"
    "- c2 C + PLACED ( 400 3400 ) N ;\n- c3 C + PLACED ( 3400 3400 ) N ;\n- c4 C + PLACED ( 3400 400 ) N ;\n")).replace(
    "NETS 1 ;\n- a ( u1 P ) ;\n", "NETS 2 ;\n- a ( c1 A ) ( c2 A ) ;\n- b ( c3 A ) ( c4 A ) ;\n")


def drawn_region(tmp_path: Path, lef_text: str, def_text: str, name: str) -> tuple[Any, Any, dict[str, Any], Any]:
    """(database, the whole die opened as one region, its grid, node(x, y, z) -> flat node index)."""
    lef, def_ = write_design(tmp_path, lef_text, def_text, name)
    db = load_design(lef=lef, def_=def_).engine
    region = _engine.RoutingSession(db).open_region((0, 0, 4000, 4000))
    g = region.grid()
    xs, ys = np.asarray(g["xs"]).tolist(), np.asarray(g["ys"]).tolist()
    _, ny, nx = g["flags"].shape

    def node(x: int, y: int, z: int) -> int:
        return (z * ny + ys.index(y)) * nx + xs.index(x)

    return db, region, g, node


def test_a_wire_into_the_nets_own_access_via_landing_pays_no_wire_footprint(tmp_path: Path) -> None:
    # The step from (300, 1500) east into the landing above pin c1/A, on M2 (wrong way: 200 x 4).
    # For net a it costs the wire alone: it ends on its own via's pad, which pin access checked.
    # For net b it is another net's landing and a forbidden wire (landing and fixed penalties). The
    # old maze charged net a the fixed penalty too, and its route went up a layer and down again.
    _, region, g, node = drawn_region(tmp_path, LANDING_LEF, LANDING_DEF, "landing")
    xs, ys = np.asarray(g["xs"]).tolist(), np.asarray(g["ys"]).tolist()
    landing = node(500, 1500, 1)
    assert g["fixed_owner"][1, ys.index(1500), xs.index(500)] == -2  # no M2 wire may run there
    assert g["flags"][1, ys.index(1500), xs.index(500)] & 8  # the landing of pin access's via
    east = 4
    nets = region.candidates[:, 0].tolist()
    costs = _engine.MazeCosts()
    # Each pin here has one via point, so the landing is also its pin's sole landing (flag 64) and
    # the default charges other nets the sole-landing penalty there: 8,000 (soleLandingCosts).
    assert g["flags"][1, ys.index(1500), xs.index(500)] & 64
    landing_cost = max(costs.landing_penalty, 8000)
    for net, expected in ((0, 800), (1, 800 + landing_cost + costs.fixed_penalty)):
        neighbours, step = region.moves(nets.index(net), node(300, 1500, 1))
        assert (neighbours[east], step[east]) == (landing, expected), net


# M1 is vertical with an end-of-line rule (0.12 um within 0.05 of an end narrower than 0.12). Pin P
# is a bar along x, 0.1 um tall: its end at x = 1.0 is a line end across the tracks. In BARHELD a
# 0.06 um wide rect of the pin runs up from that end, so the end is no line end.
EOL_LAYERS = (
    routing("M1", "VERTICAL", 0.2, 0.06, 0.06, rules=["SPACING 0.12 ENDOFLINE 0.12 WITHIN 0.05 ;"]),
    cut("V1", 0.06, 0.08),
    routing("M2", "HORIZONTAL", 0.2, 0.06, 0.06),
    stack_via("V12", "M1", "V1", "M2", False, 0.06, metal_length=0.1),
)
EOL_LEF = library(
    *EOL_LAYERS,
    macro("BAR", 2.0, 2.0, pin("P", "INPUT", [("M1", (0.4, 0.95, 1.0, 1.05))])),
    macro("BARHELD", 2.0, 2.0, pin("P", "INPUT", [("M1", (0.4, 0.95, 1.0, 1.05)), ("M1", (0.94, 0.95, 1.0, 1.6))])),
)


def eol_owners(tmp_path: Path, cell: str, points: list[tuple[int, int]]) -> list[tuple[int, int]]:
    """(fixed_owner, via_fixed_owner) on M1 at each (x, y) around cell u1 placed at the origin."""
    def_ = WIDE_DEF.replace("DESIGN wide", "DESIGN eol").replace(
        "u1 BIG + PLACED ( 600 950 )", f"u1 {cell} + PLACED ( 0 0 )").replace(
        "TRACKS Y 100 DO 20 STEP 200 LAYER M1 ;\nTRACKS X 100 DO 20 STEP 200 LAYER M2 ;",
        "TRACKS X 100 DO 20 STEP 200 LAYER M1 ;\nTRACKS Y 100 DO 20 STEP 200 LAYER M2 ;")
    lef, def_path = write_design(tmp_path, EOL_LEF, def_, "eol")
    db = load_design(lef=lef, def_=def_path).engine
    g = _engine.RoutingSession(db).open_region((0, 0, 4000, 4000)).grid()
    xs, ys = np.asarray(g["xs"]).tolist(), np.asarray(g["ys"]).tolist()
    return [(int(g["fixed_owner"][0, ys.index(y), xs.index(x)]), int(g["via_fixed_owner"][0, ys.index(y), xs.index(x)]))
            for x, y in points]


def test_an_open_line_end_of_a_fixed_pin_claims_its_end_of_line_window(tmp_path: Path) -> None:
    # A via's M1 pad at (1.1, 1.1) (0.06 x 0.1) is 0.07 um from the open end: enough for the
    # spacing (0.06), not for the end of line (0.12), and it lies within 0.05 of the end. The old
    # footprint claimed cross ends of routed metal only, and the router put another net's via
    # there (the EndOfLine markers that stayed on ispd19_test1 beside cells' B0 pins).
    net_a = 0
    assert eol_owners(tmp_path, "BAR", [(1100, 1100), (1300, 1100), (1100, 1300)]) == [
        (net_a, net_a),  # the pin's own net may go there, no other
        (-1, -1),  # 0.27 um from the end: free
        (-1, -1),  # beyond the within band: free
    ]


def test_a_held_end_of_a_fixed_pin_claims_only_the_spacing(tmp_path: Path) -> None:
    # The rect running up from the end makes it an edge of the pin's outline: the pad 0.07 um away
    # keeps the spacing.
    assert eol_owners(tmp_path, "BARHELD", [(1100, 1100)]) == [(-1, -1)]


# Two default vias up from M1 (vertical, end of line 0.12 within 0.05): V12 with its M1 pad along
# the tracks (the one the grid's footprints assume) and V12H with it across. Pin A is a bar 0.1 x
# 0.06 at (1.02..1.12, 1.07..1.13) of cell u1: V12H at (1.1, 1.1) leaves less metal outside it, so
# pin access chooses it, and its pad's end sticks out 0.05 to x = 1.17. Net b runs a vertical M1
# wire on x = 1.3 (its metal from 1.27): 0.1 from that end, enough for the spacing (0.06) and for
# V12's pad, not for the end of line.
VARIANT_LEF = library(
    routing("M1", "VERTICAL", 0.2, 0.06, 0.06, rules=["SPACING 0.12 ENDOFLINE 0.12 WITHIN 0.05 ;"]),
    cut("V1", 0.06, 0.08),
    routing("M2", "HORIZONTAL", 0.2, 0.06, 0.06),
    via("V12", [("M1", (-0.03, -0.07, 0.03, 0.07)), ("V1", (-0.03, -0.03, 0.03, 0.03)),
                ("M2", (-0.07, -0.03, 0.07, 0.03))]),
    via("V12H", [("M1", (-0.07, -0.03, 0.07, 0.03)), ("V1", (-0.03, -0.03, 0.03, 0.03)),
                 ("M2", (-0.07, -0.03, 0.07, 0.03))]),
    macro("BARA", 2.0, 2.0, pin("A", "INPUT", [("M1", (1.02, 1.07, 1.12, 1.13))])),
    macro("POST", 0.4, 0.4, pin("P", "INPUT", [("M1", (0.07, 0.1, 0.13, 0.3))])),
)

VARIANT_DEF = WIDE_DEF.replace("DESIGN wide", "DESIGN variant").replace(
    "TRACKS Y 100 DO 20 STEP 200 LAYER M1 ;\nTRACKS X 100 DO 20 STEP 200 LAYER M2 ;",
    "TRACKS X 100 DO 20 STEP 200 LAYER M1 ;\nTRACKS Y 100 DO 20 STEP 200 LAYER M2 ;").replace(
    "COMPONENTS 1 ;\n- u1 BIG + PLACED ( 600 950 ) N ;\n", (
        "COMPONENTS 4 ;\n- u1 BARA + PLACED ( 0 0 ) N ;\n- u4 BARA + PLACED ( 2000 2000 ) N ;\n"
        "- u2 POST + PLACED ( 1200 300 ) N ;\n- u3 POST + PLACED ( 1200 1500 ) N ;\n")).replace(
    "NETS 1 ;\n- a ( u1 P ) ;\n", "NETS 2 ;\n- a ( u1 A ) ( u4 A ) ;\n- b ( u2 P ) ( u3 P ) ;\n")


def test_an_access_via_of_another_variant_is_judged_as_placed(tmp_path: Path) -> None:
    # The via step down into net a's access point at (1.1, 1.1) costs use_penalty more once net b's
    # wire is there: V12H's pad end faces it. The grid's footprints, made for V12's pad, see no
    # conflict, and the old maze charged nothing for a via that breaks the end-of-line rule.
    db, region, g, node = drawn_region(tmp_path, VARIANT_LEF, VARIANT_DEF, "variant")
    xs, ys = np.asarray(g["xs"]).tolist(), np.asarray(g["ys"]).tolist()
    nets = region.candidates[:, 0].tolist()
    a, b = nets.index(0), nets.index(1)
    assert g["flags"][0, ys.index(1100), xs.index(1100)] & 16  # pin access's via up at (1.1, 1.1)
    access = db.pin_access()
    chosen = [access["via_names"][v] for p, v in zip(access["points"].tolist(), access["via"].tolist())
              if p[:2] == [1100, 1100]]
    assert chosen == ["V12H"]
    down = 1
    before = region.moves(a, node(1100, 1100, 1))
    assert before[0][down] == node(1100, 1100, 0)
    region.route_net(b)
    assert g["routed_net"][0, ys.index(1100), xs.index(1300)] == 1  # b's M1 wire passes (1.3, 1.1)
    after = region.moves(a, node(1100, 1100, 1))
    assert after[1][down] - before[1][down] == _engine.MazeCosts().use_penalty
