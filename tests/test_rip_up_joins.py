"""What a rip-up must join again, and what routing joins nothing (engine_cpp/region/clip.cpp
``keptConductors``, loop/dangling.cpp), on tiny drawn designs with the exact routing expected (DBU).

Technology: the drawn stack of ``lef_text.stack`` (M1 and M3 horizontal, M2 vertical; tracks every
200 from 100, wires 60 wide, default vias V12 and V23). Two cells of one 60 x 60 M1 pin each.
"""

from __future__ import annotations

from pathlib import Path

from drawn import load_drawn
from lef_text import library, macro, pin, stack
from xroute import _engine

CELL = macro("PIN1", 0.2, 0.2, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.13))]))


def design(tmp_path: Path, routing: str, third: tuple[int, int] | None = None):
    """Net n1 joins the pins at (300, 300) and (1700, 300), and a third cell's pin at `third` + (100,
    100) if given, routed as `routing` says."""
    cells = [(200, 200), (1600, 200)] + ([third] if third else [])
    components = "".join(f"- u{k + 1} PIN1 + PLACED ( {x} {y} ) N ;\n" for k, (x, y) in enumerate(cells))
    pins = " ".join(f"( u{k + 1} A )" for k in range(len(cells)))
    def_text = (
        'VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN joins ;\nUNITS DISTANCE MICRONS 1000 ;\n'
        "DIEAREA ( 0 0 ) ( 2000 2000 ) ;\n"
        "TRACKS Y 100 DO 10 STEP 200 LAYER M1 M2 M3 ;\n"
        "TRACKS X 100 DO 10 STEP 200 LAYER M1 M2 M3 ;\n"
        "GCELLGRID X 0 DO 3 STEP 1000 ;\nGCELLGRID Y 0 DO 3 STEP 1000 ;\n"
        f"COMPONENTS {len(cells)} ;\n{components}"
        f"END COMPONENTS\nNETS 1 ;\n- n1 {pins}\n" + routing + " ;\nEND NETS\nEND DESIGN\n")
    return load_drawn(tmp_path, library(stack(layers=3), CELL), def_text, stem="joins")


# A U: up on M2 from each pin, across on M3 at y = 1500.
U_ROUTE = ("  + ROUTED M1 ( 300 300 ) V12\n  NEW M1 ( 1700 300 ) V12\n"
           "  NEW M2 ( 300 300 ) ( 300 1500 ) V23\n  NEW M2 ( 1700 300 ) ( 1700 1500 ) V23\n"
           "  NEW M3 ( 300 1500 ) ( 1700 1500 )")


def test_a_net_passing_a_region_twice_is_not_joined_again_inside_it(tmp_path: Path) -> None:
    # The band y 500..900 cuts both legs of the U. Kept outside it: each pin's stub up to y = 500,
    # and the U's top from y = 900 up and across. Of the four boundary terminals, the two at y = 900
    # are one conductor already (the top): the band must join the three conductors, which the two
    # straight legs do (800 of M2, no via). Joining all four as if apart, as the rip-up did, also
    # bridged the legs inside the band: 1,400 of M3 more and two vias.
    db = design(tmp_path, U_ROUTE)
    assert db.check_connectivity()["open_nets"] == 0
    region = _engine.RoutingSession(db).open_region((0, 500, 2000, 900))
    region.route_rest("heuristic")
    m = region.metrics()
    assert (m["wirelength_dbu"], m["vias"], m["unreached"]) == (800, 0, 0)
    region.commit()
    assert db.check_connectivity()["open_nets"] == 0
    wires = sorted(tuple(w[1:5]) for w in db.net_routing(0)["wires"])
    assert (300, 500, 300, 900) in wires or (300, 900, 300, 500) in wires
    assert (1700, 500, 1700, 900) in wires or (1700, 900, 1700, 500) in wires
    assert db.metrics()["wirelength_dbu"] == 1200 * 2 + 1400


def test_reaching_one_end_of_a_kept_conductor_reaches_the_other(tmp_path: Path) -> None:
    # The U of the test above with a third pin at (1500, 700) inside the band, joined to the right leg
    # by an M1 stub. The band's route starts at that pin and reaches the top's conductor first at its
    # right end, (1700, 900). Its left end, (300, 900), is then part of the tree as well: the left leg
    # joins from there (400 of M2). When the maze marked only the terminal it hit, it joined the
    # left leg by an M1 bridge from the pin (1,200) and a via: 2,000 and 2 vias in all.
    db = design(tmp_path, U_ROUTE + "\n  NEW M1 ( 1500 700 ) ( 1700 700 ) V12", third=(1400, 600))
    assert db.check_connectivity()["open_nets"] == 0
    region = _engine.RoutingSession(db).open_region((0, 500, 2000, 900))
    region.route_rest("heuristic")
    m = region.metrics()
    assert (m["wirelength_dbu"], m["vias"], m["unreached"]) == (200 + 400 + 400, 1, 0)
    region.commit()
    assert db.check_connectivity()["open_nets"] == 0
    wires = {tuple(sorted([tuple(w[1:3]), tuple(w[3:5])])) for w in db.net_routing(0)["wires"]}
    assert ((300, 500), (300, 900)) in wires and ((1500, 700), (1700, 700)) in wires
    assert not any(a[1] == b[1] == 700 and a[0] <= 300 for a, b in wires)  # no bridge to the left leg


def test_terminals_joined_only_through_the_box_are_joined_again(tmp_path: Path) -> None:
    # The box x 0..1000, y 500..1700 holds the left leg's upper part and the top's left half. Kept:
    # the left pin's stub up to y = 500 and the top's right half with the right leg. Their two
    # boundary terminals, (300, 500) on M2 and (1000, 1500) on M3, are joined only through the box:
    # two conductors, and the route joins them.
    db = design(tmp_path, U_ROUTE)
    region = _engine.RoutingSession(db).open_region((0, 500, 1000, 1700))
    region.route_rest("heuristic")
    m = region.metrics()
    assert m["unreached"] == 0 and m["wirelength_dbu"] >= 700 + 1000
    region.commit()
    assert db.check_connectivity()["open_nets"] == 0


def test_routing_that_joins_nothing_is_cut_back(tmp_path: Path) -> None:
    # The pins joined on M2 / M3 / M2 as above (without the U's height: across at y = 700), plus:
    # the left leg running on past the M3 corner to y = 1300 (600 that join nothing); a V23 on the
    # right leg's middle with nothing on M3 above it; and an M3 wire from (1700, 700) to
    # (1900, 700) past the corner (200).
    db = design(tmp_path, "  + ROUTED M1 ( 300 300 ) V12\n  NEW M1 ( 1700 300 ) V12\n"
                          "  NEW M2 ( 300 300 ) ( 300 1300 )\n  NEW M2 ( 300 700 ) V23\n"
                          "  NEW M2 ( 1700 300 ) ( 1700 700 ) V23\n  NEW M2 ( 1700 500 ) V23\n"
                          "  NEW M3 ( 300 700 ) ( 1900 700 )")
    assert db.check_connectivity()["open_nets"] == 0
    before = db.metrics()
    counts = db.trim_dangling()
    assert counts == {"wires": 0, "shortened": 2, "vias": 1, "patches": 0, "length_dbu": 600 + 200}
    after = db.metrics()
    assert after["wirelength_dbu"] == before["wirelength_dbu"] - 800
    assert after["vias"] == before["vias"] - 1
    assert db.check_connectivity()["open_nets"] == 0
    wires = sorted(tuple(w[1:5]) for w in db.net_routing(0)["wires"])
    assert wires == [(300, 300, 300, 700), (300, 700, 1700, 700), (1700, 300, 1700, 700)]
    # Nothing is left to cut.
    assert db.trim_dangling() == {"wires": 0, "shortened": 0, "vias": 0, "patches": 0, "length_dbu": 0}


def test_a_wire_ending_in_a_pin_shape_is_held(tmp_path: Path) -> None:
    # A routed net whose every end is on a pin or on another piece: nothing to cut.
    db = design(tmp_path, U_ROUTE)
    assert db.trim_dangling()["length_dbu"] == 0
    assert db.metrics()["vias"] == 4
