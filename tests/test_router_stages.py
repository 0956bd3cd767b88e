"""The router's stages on tiny drawn designs, with the exact path expected (DBU).

The technology (UNITS 1000: 1 DBU = 1 nm): M1 horizontal, M2 vertical, M3 horizontal; on every
layer tracks every 200 from 100 in x and y, wires 60 wide, spacing 70; vias V12 and V23 with a
60 x 60 cut, metal 100 x 60 along the horizontal layers and 60 x 100 along M2. The cell PIN1
(200 x 200) has one pin A: a 60 x 60 M1 square at its centre, so a cell placed at (x, y) has its
pin on the track crossing (x + 100, y + 100). Die 4000 x 4000, GCells of 1000.

Stages (engine_cpp): maze search (route/maze), the grid footprint of fixed shapes
(grid/footprint), minimum-area repair (route/min_area_fix), clipping of a net's routing at a
region's boundary (region/clip) and the crossings that join regions (loop/crossings). Regions are
opened and routed net by net through ``_engine.RoutingSession(db).open_region(box)``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from drawn import shape_rows, write_design
from lef_text import Rect, library, macro, pin, stack
from xroute import _engine
from xroute.check import check_design
from xroute.design import load_design

AREA = "AREA 0.02 ;"  # 20000 nm^2: a 60 wide wire needs 334 nm


def drawn(tmp_path: Path, comps: dict[str, tuple[int, ...]], nets: dict[str, list[str]], extra: str = "",
          m1_area: bool = False, m2_area: bool = False, m2_rules: str = "", macros: str = "",
          m1_rules: str = "", guide: str = "") -> Any:
    """A loaded Design: cells at the given locations (N; PIN1 unless a third item names a macro
    from `macros`, more LEF MACROs), nets of their pins A, `extra` DEF statements (BLOCKAGES)
    after the components, `m1_rules` / `m2_rules` more LEF statements of M1 / M2, and the
    route guide text `guide` (none when empty)."""
    comp_lines = "".join(f"- {c} {m[0] if m else 'PIN1'} + PLACED ( {x} {y} ) N ;\n"
                         for c, (x, y, *m) in comps.items())
    net_lines = "".join(f"- {n} " + " ".join(f"( {c} A )" for c in cs) + " ;\n" for n, cs in nets.items())
    def_text = (
        'VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN stages ;\nUNITS DISTANCE MICRONS 1000 ;\n'
        "DIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
        "TRACKS Y 100 DO 20 STEP 200 LAYER M1 M2 M3 ;\n"
        "TRACKS X 100 DO 20 STEP 200 LAYER M1 M2 M3 ;\n"
        "GCELLGRID X 0 DO 5 STEP 1000 ;\nGCELLGRID Y 0 DO 5 STEP 1000 ;\n"
        f"COMPONENTS {len(comps)} ;\n{comp_lines}END COMPONENTS\n{extra}"
        f"NETS {len(nets)} ;\n{net_lines}END NETS\nEND DESIGN\n"
    )
    rules = {"M1": [AREA] * m1_area + [m1_rules] * bool(m1_rules), "M2": [AREA] * m2_area + [m2_rules] * bool(m2_rules)}
    lef_text = library(stack(rules=rules), cell("PIN1", (0.07, 0.07, 0.13, 0.13)), macros)
    lef, def_ = write_design(tmp_path, lef_text, def_text, stem="stages")
    if not guide:
        return load_design(lef=lef, def_=def_)
    (tmp_path / "stages.guide").write_text(guide)
    return load_design(lef=lef, def_=def_, guide=tmp_path / "stages.guide")


def blockage(layer: str, rect: tuple[int, int, int, int]) -> str:
    x0, y0, x1, y1 = rect
    return f"BLOCKAGES 1 ;\n- LAYER {layer} RECT ( {x0} {y0} ) ( {x1} {y1} ) ;\nEND BLOCKAGES\n"


def route_die(design: Any) -> tuple[Any, list[dict[str, Any]], dict[str, Any]]:
    """Opens the whole die as one region, routes every candidate in order and commits:
    (the session, each route_net result, the region's metrics)."""
    session = _engine.RoutingSession(design.engine)
    region = session.open_region(tuple(int(v) for v in design.die_area))
    results = [region.route_net(i) for i in range(len(region.candidates))]
    metrics = region.metrics()
    region.commit()
    return session, results, metrics


# Two cells whose pins lie on the M1 track y = 1100, 2000 apart.
ROW = {"u1": (400, 1000), "u2": (2400, 1000)}


def test_a_two_pin_net_on_one_track_is_one_straight_wire(tmp_path: Path) -> None:
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]})
    session = _engine.RoutingSession(d.engine)
    region = session.open_region((0, 0, 4000, 4000))
    # net, pins, terminals, access points, bounding box of the access points, pins of the net,
    # crossings, the guide span (no guides: the region box), grid nodes new routing uses in the bbox
    assert region.candidates.tolist() == [[0, 2, 2, 2, 500, 1100, 2500, 1100, 2, 0, 0, 0, 4000, 4000, 0]]
    assert region.route_net(0) == {"net": 0, "routed": True, "wirelength_dbu": 2000, "vias": 0, "unreached": 0}
    assert region.metrics()["violations"] == 0
    region.commit()
    assert d.net_routing(0) == {"wires": [("M1", 500, 1100, 2500, 1100, 0, -1, -1)], "vias": [], "patches": []}
    assert d.engine.check_connectivity()["open_nets"] == 0


def test_two_pins_on_one_column_join_on_the_vertical_layer(tmp_path: Path) -> None:
    d = drawn(tmp_path, {"u1": (400, 1000), "u2": (400, 2400)}, {"n1": ["u1", "u2"]})
    _, results, metrics = route_die(d)
    assert results[0]["wirelength_dbu"] == 1400 and results[0]["vias"] == 2 and metrics["violations"] == 0
    assert d.net_routing(0) == {
        "wires": [("M2", 500, 1100, 500, 2500, 0, -1, -1)],
        "vias": [("V12", 500, 1100), ("V12", 500, 2500)],
        "patches": [],
    }


def test_a_blocked_track_forces_a_detour_with_two_vias(tmp_path: Path) -> None:
    # M2 blocked over x 0..600 between the pins: the M2 tracks x = 100, 300 and 500 are closed
    # there, so the net steps on M1 to the next free track, x = 700, at both pins.
    d = drawn(tmp_path, {"u1": (400, 1000), "u2": (400, 2400)}, {"n1": ["u1", "u2"]},
              blockage("M2", (0, 1400, 600, 2000)))
    _, results, metrics = route_die(d)
    assert results[0]["wirelength_dbu"] == 200 + 1400 + 200 and results[0]["vias"] == 2
    assert metrics["violations"] == 0
    assert d.net_routing(0) == {
        "wires": [("M1", 500, 1100, 700, 1100, 0, -1, -1), ("M2", 700, 1100, 700, 2500, 0, -1, -1),
                  ("M1", 700, 2500, 500, 2500, 0, -1, -1)],
        "vias": [("V12", 700, 1100), ("V12", 700, 2500)],
        "patches": [],
    }


def test_a_blocked_horizontal_track_sends_the_net_up_to_the_next_horizontal_layer(tmp_path: Path) -> None:
    # M1 blocked between the pins (x 640..2360, the whole height: no way round on M1, and M1
    # costs as much as M3 per length); M2 is vertical: the straight path is on M3, reached by a
    # via stack (V12, V23) on each pin, with no extra wirelength.
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, blockage("M1", (640, 0, 2360, 4000)))
    _, results, metrics = route_die(d)
    assert results[0]["wirelength_dbu"] == 2000 and results[0]["vias"] == 4 and metrics["violations"] == 0
    assert d.net_routing(0) == {
        "wires": [("M3", 500, 1100, 2500, 1100, 0, -1, -1)],
        "vias": [("V12", 500, 1100), ("V23", 500, 1100), ("V23", 2500, 1100), ("V12", 2500, 1100)],
        "patches": [],
    }


def test_a_short_wire_gets_a_centred_min_area_patch(tmp_path: Path) -> None:
    # M1 AREA 0.02 um^2 = 20000 nm^2. The wire (500,1100)-(700,1100) with its half-width
    # extensions is 260 x 60 = 15600 (the pins lie inside it). A 60 wide patch needs
    # ceil(20000 / 60) = 334: it grows the piece by 74, 37 on each side, along M1 (horizontal):
    # x 470 - 37 = 433 .. 730 + 37 = 767, as wide as the wire.
    d = drawn(tmp_path, {"u1": (400, 1000), "u2": (600, 1000)}, {"n1": ["u1", "u2"]}, m1_area=True)
    _, results, metrics = route_die(d)
    assert results[0]["wirelength_dbu"] == 200 and metrics["violations"] == 0
    r = d.net_routing(0)
    assert r["wires"] == [("M1", 500, 1100, 700, 1100, 0, -1, -1)]
    assert r["patches"] == [("M1", 433, 1070, 767, 1130)]
    (_, x0, y0, x1, y1), = r["patches"]
    assert (x1 - x0) * (y1 - y0) >= 20000 > (x1 - x0 - 2) * (y1 - y0)  # the shortest on the manufacturing grid
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_via_stacks_get_min_area_patches_on_the_middle_layer(tmp_path: Path) -> None:
    # M2 AREA 0.02 um^2; the M2 metal of each via stack (V12 top and V23 bottom, both 60 x 100 at
    # the pin) is 6000 nm^2 alone: each grows along M2 (vertical) by 234, 117 on each side:
    # y 1050 - 117 = 933 .. 1150 + 117 = 1267, 60 wide around x = 500 and x = 2500.
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, blockage("M1", (640, 0, 2360, 4000)), m2_area=True)
    _, _, metrics = route_die(d)
    assert metrics["violations"] == 0
    r = d.net_routing(0)
    assert r["wires"] == [("M3", 500, 1100, 2500, 1100, 0, -1, -1)]
    assert r["patches"] == [("M2", 470, 933, 530, 1267), ("M2", 2470, 933, 2530, 1267)]


def test_a_min_area_patch_beside_another_nets_wire_at_legal_spacing(tmp_path: Path) -> None:
    # As above, with a second net n2 on the M2 track x = 700 from (700, 300) to (700, 1900), beside
    # n1's left via stack, and an M2 end-of-line spacing of 0.18 um: the patch's spacing halo
    # (30 + 180 each side of x = 500) reaches the node of n2's wire on the next track. That wire
    # (670..730) is 140 from the patch (470..530), beside it and not beyond its ends: 70 is
    # enough. The patch scorer used to refuse any patch whose halo held a node another net's
    # wire makes unusable, so this stack kept its MinArea marker.
    eol = "SPACING 0.18 ENDOFLINE 0.07 WITHIN 0.025 ;"
    comps = {**ROW, "u3": (600, 200), "u4": (600, 1800)}
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"]},
              blockage("M1", (640, 400, 2360, 1800)), m2_area=True, m2_rules=eol)
    region = _engine.RoutingSession(d.engine).open_region((0, 0, 4000, 4000))
    region.route_net(1)  # n2 first: its wire is there when n1's patches are placed
    region.route_net(0)
    assert region.metrics()["violations"] == 0
    region.commit()
    assert d.net_routing(1)["wires"] == [("M2", 700, 300, 700, 1900, 0, -1, -1)]
    r = d.net_routing(0)
    assert r["wires"] == [("M3", 500, 1100, 2500, 1100, 0, -1, -1)]
    assert r["patches"] == [("M2", 470, 933, 530, 1267), ("M2", 2470, 933, 2530, 1267)]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_a_min_area_patch_leaves_the_landing_of_another_nets_access_via_free(tmp_path: Path) -> None:
    # As the via-stack case, with n2's pin right above n1's left stack, at (500, 1300), boxed in
    # on M1 by blockages (west ending 70 from its via's M1 metal, north, and the one east), so
    # its only way out is its access via, whose M2 landing is 470..530 x 1250..1350. n1 is
    # routed first. Its centred patch (y 933..1267) would overlap that landing, and n2 had to
    # short it; the patch now pays for crowding another net's access landing and grows all
    # towards low: y 1050 - 2 * 117 = 816 .. 1150, 100 below the landing.
    comps = {**ROW, "u3": (400, 1200), "u4": (400, 2400)}
    rects = [("M1", (640, 0, 2360, 4000)), ("M1", (0, 1200, 380, 1400)), ("M1", (0, 1400, 640, 1600))]
    extra = f"BLOCKAGES {len(rects)} ;\n" + "".join(
        f"- LAYER {layer} RECT ( {a} {b} ) ( {c} {e} ) ;\n" for layer, (a, b, c, e) in rects) + "END BLOCKAGES\n"
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"]}, extra, m2_area=True)
    region = _engine.RoutingSession(d.engine).open_region((0, 0, 4000, 4000))
    region.route_net(0)  # n1 first: its patches are placed before n2's via is there
    region.route_net(1)
    assert region.metrics()["violations"] == 0
    region.commit()
    assert d.net_routing(0)["patches"] == [("M2", 470, 816, 530, 1150), ("M2", 2470, 933, 2530, 1267)]
    assert ("V12", 500, 1300) in d.net_routing(1)["vias"]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_a_wire_keeps_out_of_the_end_of_line_window_of_a_patch_across_the_tracks(tmp_path: Path) -> None:
    # M2 (vertical) end-of-line spacing 0.25 um for line ends under 0.07 um. n1's left via stack
    # (M2 landing 470..530 x 1050..1150) has M2 blockages on its track (y 700..800, 1400..1500): a
    # patch along the track would end 133 from them, too close for its line ends, so it lies
    # across: 333..667 x 1070..1130, whose left end (60 tall) needs 250, down to x = 83, 47
    # into the metal of the M2 track x = 100. n2 (pins at
    # (100, 300) and (100, 1900)) is routed after n1; its straight M2 wire on x = 100 broke that
    # rule: the footprint modelled line ends along the tracks only. Open line ends across them
    # now claim the nodes in their window, and n2 keeps out.
    eol = "SPACING 0.25 ENDOFLINE 0.07 WITHIN 0.025 ;"
    comps = {**ROW, "u3": (0, 200), "u4": (0, 1800)}
    rects = [("M1", (640, 0, 2360, 4000)), ("M2", (460, 700, 540, 800)), ("M2", (460, 1400, 540, 1500))]
    extra = f"BLOCKAGES {len(rects)} ;\n" + "".join(
        f"- LAYER {layer} RECT ( {a} {b} ) ( {c} {e} ) ;\n" for layer, (a, b, c, e) in rects) + "END BLOCKAGES\n"
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"]}, extra, m2_area=True, m2_rules=eol)
    region = _engine.RoutingSession(d.engine).open_region((0, 0, 4000, 4000))
    region.route_net(0)
    g = region.grid()
    xs, ys = list(g["xs"]), list(g["ys"])
    assert g["wire_use"][1, ys.index(1100), xs.index(100)] == 1  # in front of the patch's left end
    assert g["wire_use"][1, ys.index(900), xs.index(100)] == 0
    region.route_net(1)
    assert region.metrics()["violations"] == 0
    region.commit()
    assert ("M2", 333, 1070, 667, 1130) in d.net_routing(0)["patches"]
    assert ("M2", 100, 300, 100, 1900, 0, -1, -1) not in d.net_routing(1)["wires"]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_a_via_stack_boxed_in_on_its_track_gets_a_thicker_shorter_patch(tmp_path: Path) -> None:
    # As the via-stack case, with M2 blockages around the left stack: on its track below and
    # above it (y 800..900 and 1300..1400), so a wire-wide patch along the track (334 long)
    # cannot keep spacing 70 to both (970..1230 is 260), and on the tracks beside it (x 260..340
    # and 660..740), so a wire-wide patch across (334 long in x) cannot either. A patch 90 wide
    # (x 455..545, 115 from the side blockages) needs 223 along the track: it fits. The repair
    # used to try wire-wide patches only.
    rects = [(460, 800, 540, 900), (460, 1300, 540, 1400), (260, 1000, 340, 1200), (660, 1000, 740, 1200)]
    blocks = "".join(f"- LAYER M2 RECT ( {a} {b} ) ( {c} {e} ) ;\n" for a, b, c, e in rects)
    extra = f"BLOCKAGES 5 ;\n- LAYER M1 RECT ( 640 0 ) ( 2360 4000 ) ;\n{blocks}END BLOCKAGES\n"
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, extra, m2_area=True)
    _, _, metrics = route_die(d)
    assert metrics["violations"] == 0
    r = d.net_routing(0)
    assert r["wires"] == [("M3", 500, 1100, 2500, 1100, 0, -1, -1)]
    (_, x0, y0, x1, y1), right = r["patches"]
    assert right == ("M2", 2470, 933, 2530, 1267)
    assert x1 - x0 > 60 and 970 <= y0 and y1 <= 1230 and (x1 - x0) * (y1 - y0) >= 20000
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def cell(name: str, pin_rect: Rect, obs: Rect | None = None) -> str:
    """A 0.2 x 0.2 um LEF MACRO like PIN1: pin A one M1 RECT `pin_rect` (um), and an M1
    obstruction RECT `obs` if given."""
    return macro(name, 0.2, 0.2, pin("A", "INOUT", [("M1", pin_rect)]), obs=[("M1", obs)] if obs else [])


# PIN1 with an M1 obstruction ending 70 left of the pin's metal (x -0.1..0.0; placed at x = 400: 300..400).
PINOBS = cell("PINOBS", (0.07, 0.07, 0.13, 0.13), (-0.1, 0.07, 0.0, 0.13))


def test_no_via_at_an_access_point_that_pin_access_left_planar(tmp_path: Path) -> None:
    # u1's obstruction ends 70 left of its pin's point (500, 1100): a wire there (metal
    # 470..530) keeps spacing 70, a V12 (M1 metal 450..550) would be 50 away. Pin access offers
    # the point for planar exits only; the maze used to put the via there anyway (it trusted
    # every via at the net's own access points).
    d = drawn(tmp_path, {"u1": (400, 1000, "PINOBS"), "u2": (400, 2400)}, {"n1": ["u1", "u2"]}, macros=PINOBS)
    pa = d.engine.pin_access()
    first = np.asarray(pa["points"])[pa["start"][0]]
    assert first[:2].tolist() == [500, 1100] and not first[3] & 1  # no ACCESS_UP there
    _, _, metrics = route_die(d)
    assert metrics["violations"] == 0
    assert ("V12", 500, 1100) not in d.net_routing(0)["vias"]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_an_access_via_too_close_to_the_next_cells_pin_loses_its_via_exit(tmp_path: Path) -> None:
    # u1's pin point (500, 1100): its V12 (M1 metal 450..550) would be 50 from the pin of the
    # cell placed right of it at x = 600 (metal 600..660), a wire there (470..530) 70. Pin access
    # computes u1's class alone, where the via is legal; checked among the neighbours it loses
    # the via exit, and the router joins the pin with a planar step first.
    edge = cell("EDGEPIN", (0.0, 0.07, 0.06, 0.13))  # pin A at the cell's left edge
    d = drawn(tmp_path, {"u1": (400, 1000), "u2": (600, 1000, "EDGEPIN"), "u3": (400, 2400)},
              {"n1": ["u1", "u3"]}, macros=edge)
    pa = d.engine.pin_access()
    points = np.asarray(pa["points"])[pa["start"][0]:pa["start"][1]]
    assert [500, 1100] in points[:, :2].tolist()
    assert all(not p[3] & 1 for p in points if p[:2].tolist() == [500, 1100])  # no ACCESS_UP there
    _, _, metrics = route_die(d)
    assert metrics["violations"] == 0
    assert ("V12", 500, 1100) not in d.net_routing(0)["vias"]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_the_route_leaves_an_access_point_only_where_pin_access_allows(tmp_path: Path) -> None:
    # M1 end-of-line spacing 0.12 um for line ends under 0.07 um. u1's pin is 485..515 x
    # 1060..1140 (its 80 tall sides are no line ends), its obstruction ends 105 left of it
    # (x 300..380). A wire leaving the pin's point (500, 1100) east has its west end at 470, a
    # 60 tall line end 90 from the obstruction; pin access allows only north and south (and
    # no via: its cut would stick out of the pin). The maze used to take the straight M1 wire
    # east to u2 anyway (it trusted every step at the net's own access points).
    eol = "SPACING 0.12 ENDOFLINE 0.07 WITHIN 0.025 ;"
    west = cell("PINWEST", (0.085, 0.06, 0.115, 0.14), (-0.1, 0.07, -0.02, 0.13))
    d = drawn(tmp_path, {"u1": (400, 1000, "PINWEST"), "u2": (2400, 1000)}, {"n1": ["u1", "u2"]},
              macros=west, m1_rules=eol)
    pa = d.engine.pin_access()
    points = np.asarray(pa["points"])[pa["start"][0]:pa["start"][1]]
    assert points[:, 0].tolist() == [500] * len(points)
    assert all(p[3] == _engine.ACCESS_NORTH | _engine.ACCESS_SOUTH for p in points)
    _, _, metrics = route_die(d)
    assert metrics["violations"] == 0
    assert ("M1", 500, 1100, 2500, 1100, 0, -1, -1) not in d.net_routing(0)["wires"]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_a_reopened_region_clips_the_net_at_its_boundary(tmp_path: Path) -> None:
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]})
    session, _, _ = route_die(d)
    # The left half: u1's pin inside, the routed wire leaves the box at x = 2000, where the part
    # kept outside ends: a boundary terminal on M1 at (2000, 1100).
    region = session.open_region((0, 0, 2000, 2000))
    # pins inside 1, terminals 2 (the pin and the boundary point, one crossing), their bounding box
    assert region.candidates.tolist() == [[0, 1, 2, 2, 500, 1100, 2000, 1100, 2, 1, 0, 0, 2000, 2000, 0]]
    assert region.route_net(0) == {"net": 0, "routed": True, "wirelength_dbu": 1500, "vias": 0, "unreached": 0}
    # routed_nearby: the new wire's grid nodes on y = 1100 from x = 500 to 2000, all inside the bbox
    xs = [int(x) for x in region.grid()["xs"] if 500 <= x <= 2000]
    assert region.candidates[0, -1] == len(xs) > 1
    region.commit()
    assert d.net_routing(0) == {
        "wires": [("M1", 2000, 1100, 2500, 1100, 0, -1, -1), ("M1", 500, 1100, 2000, 1100, 0, -1, -1)],
        "vias": [],
        "patches": [],
    }
    assert d.engine.check_connectivity()["open_nets"] == 0
    assert d.engine.metrics()["wirelength_dbu"] == 2000


def test_a_boundary_terminal_on_the_pins_access_point_is_reached_without_a_path(tmp_path: Path) -> None:
    # The box's right edge x = 500 runs through u1's access point (500, 1100), where the wire kept
    # outside the box ends: the boundary terminal and the pin share their only grid node. The tree
    # starts on the pin, so the boundary terminal is already in it (once counted as unreached).
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]})
    session, _, _ = route_die(d)
    region = session.open_region((0, 0, 500, 2000))
    assert region.candidates.tolist() == [[0, 1, 2, 2, 500, 1100, 500, 1100, 2, 1, 0, 0, 500, 2000, 0]]
    assert region.route_net(0) == {"net": 0, "routed": True, "wirelength_dbu": 0, "vias": 0, "unreached": 0}


def test_out_of_guide_cost_is_the_same_both_ways_across_the_guide_edge(tmp_path: Path) -> None:
    # n1's only guide: M1 left of x = 2000. The contest scorer counts the part of a wire's centre
    # line outside its layer's guide, and a via whose centre lies outside the guide of either of its
    # layers; the maze charges a step that crosses the guide edge half the out-of-guide factor
    # (3 by default) either way, and a via the factor when either end is outside.
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, guide="n1\n(\n0 0 2000 4000 M1\n)\n")
    session = _engine.RoutingSession(d.engine)
    region = session.open_region((0, 0, 4000, 4000))
    grid = region.grid()
    xs, ys = [int(v) for v in grid["xs"]], [int(v) for v in grid["ys"]]

    def node(x: int, y: int, z: int) -> int:
        return (z * len(ys) + ys.index(y)) * len(xs) + xs.index(x)

    inside, outside, above = node(1900, 1100, 0), node(2100, 1100, 0), node(1900, 1100, 1)
    up, east, west = 0, 4, 5
    assert _engine.MazeCosts().out_of_guide_factor == 3
    nodes, costs = region.moves(0, inside)
    assert (nodes[east], costs[east]) == (outside, 400)  # 200 DBU: half in, half out (1 and 3)
    assert costs[west] == 200  # inside both ends
    assert (nodes[up], costs[up]) == (above, 3600)  # M2 has no guide: the via costs 3 x 1200
    nodes, costs = region.moves(0, outside)
    assert (nodes[west], costs[west]) == (inside, 400)
    assert costs[east] == 600  # outside both ends
    nodes, costs = region.moves(0, above)
    assert (nodes[1], costs[1]) == (inside, 3600)  # down onto the guide: the via is still out of M2's


def claimed(grid: dict[str, Any], key: str, z: int) -> dict[tuple[int, int], int]:
    """{(x, y): owner} of the nodes on routing layer z whose `key` field has an owner."""
    xs, ys, field = grid["xs"], grid["ys"], grid[key][z]
    return {(int(xs[x]), int(ys[y])): int(field[y, x]) for y, x in np.argwhere(field != -1)}


def test_footprint_of_a_blockage_and_of_pins(tmp_path: Path) -> None:
    # A 200 x 200 M1 blockage at (1400,1000)-(1600,1200) on the pins' track (owner -2: an
    # obstruction; the pins' nodes are owned by their net, 0). Spacing 70:
    # * a wire node (60 x 60 of metal) is claimed when closer than 70: only (1500, 1100); at
    #   (1300, 1100) the metal ends at 1330, exactly 70 away;
    # * a via landing (100 x 60 on M1) at (1300, 1100) or (1700, 1100) comes within 50: claimed;
    #   at (1500, 900) its metal ends at y = 930, 70 below the blockage: free.
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, blockage("M1", (1400, 1000, 1600, 1200)))
    region = _engine.RoutingSession(d.engine).open_region((0, 0, 4000, 4000))
    g = region.grid()
    assert claimed(g, "fixed_owner", 0) == {(500, 1100): 0, (1500, 1100): -2, (2500, 1100): 0}
    assert claimed(g, "via_fixed_owner", 0) == {(500, 1100): 0, (1300, 1100): -2, (1500, 1100): -2,
                                                (1700, 1100): -2, (2500, 1100): 0}
    for z in (1, 2):
        assert claimed(g, "fixed_owner", z) == {} and claimed(g, "via_fixed_owner", z) == {}
    # node types: the blocked node and the two access points
    types = region.node_type()
    assert types[0][list(g["ys"]).index(1100)][list(g["xs"]).index(1500)] == 1
    assert {(int(g["xs"][x]), int(g["ys"][y])) for z, y, x in np.argwhere(types == 3)} == {(500, 1100), (2500, 1100)}


def test_footprint_of_a_blockage_on_the_vertical_layer(tmp_path: Path) -> None:
    # The same blockage on M2 (vertical): via landings there are 60 x 100 (V12 top, V23 bottom):
    # they reach 50 towards it from (1500, 900) and (1500, 1300), but from (1300, 1100) end 70 away.
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, blockage("M2", (1400, 1000, 1600, 1200)))
    g = _engine.RoutingSession(d.engine).open_region((0, 0, 4000, 4000)).grid()
    assert claimed(g, "fixed_owner", 1) == {(1500, 1100): -2}
    assert claimed(g, "via_fixed_owner", 1) == {(1500, 900): -2, (1500, 1100): -2, (1500, 1300): -2}
    assert claimed(g, "fixed_owner", 0) == {(500, 1100): 0, (2500, 1100): 0}


def test_a_net_crossing_two_regions_meets_at_the_shared_edge(tmp_path: Path) -> None:
    from xroute.groute import global_route
    from xroute.router import route_design

    # Region size 2 GCells: the die is 2 x 2 regions of 2000; the net's pins lie in the two lower
    # ones. The global route's guides cross their shared edge x = 2000 on M3 only (M1 and M2 only
    # in the pins' GCells), so the crossing is on M3, on the pins' track y = 1100: each region
    # routes its half to that point, on the same layer.
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]})
    global_route(d, tmp_path / "built_in.guide")
    rects, layers = d.net_guides(0)
    crossing = [(tuple(r), z) for r, z in zip(rects.tolist(), layers.tolist()) if r[0] < 2000 < r[2]]
    assert crossing == [((0, 1000, 3000, 2000), 4)]  # layer 4: M3 (M1 V1 M2 V2 M3)
    # Read from a file, wire outside them costs twice (built-in ones cost nothing to leave)
    d = drawn(tmp_path, ROW, {"n1": ["u1", "u2"]}, guide=(tmp_path / "built_in.guide").read_text())
    result = route_design(d, region_size=2, iterations=1)
    assert [(it.regions, it.net_routes) for it in result.iterations] == [(2, 2)]
    r = d.net_routing(0)
    meet = [w for w in r["wires"] if (2000, 1100) in {(w[1], w[2]), (w[3], w[4])}]
    assert [w[0] for w in meet] == ["M3", "M3"]  # one layer on both sides of the edge
    assert [{(w[1], w[2]), (w[3], w[4])} for w in meet] == [{(900, 1100), (2000, 1100)}, {(2100, 1100), (2000, 1100)}]
    assert d.engine.metrics()["wirelength_dbu"] == 2000
    assert d.engine.check_connectivity()["open_nets"] == 0 and result.violations == 0


@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_two_nets_on_neighbouring_tracks_stay_straight_in_either_order(tmp_path: Path, order: tuple[int, int]) -> None:
    # Tracks 200 apart hold two 60 wide wires 140 apart (> 70): no net disturbs the other.
    comps = {**ROW, "u3": (400, 1200), "u4": (2400, 1200)}
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"]})
    region = _engine.RoutingSession(d.engine).open_region((0, 0, 4000, 4000))
    for i in order:
        region.route_net(i)
    assert region.metrics()["violations"] == 0
    region.commit()
    assert d.net_routing(d.net_id("n1"))["wires"] == [("M1", 500, 1100, 2500, 1100, 0, -1, -1)]
    assert d.net_routing(d.net_id("n2"))["wires"] == [("M1", 500, 1300, 2500, 1300, 0, -1, -1)]


def test_a_guide_touching_a_region_edge_from_one_side_links_nothing(tmp_path: Path) -> None:
    # One region per GCell. n1's guide leaves A's GCell (0, 0) to the right and comes back to B's
    # GCell (0, 2) through column 1; nothing of it lies in GCell (0, 1). Its rows touch GCell
    # (0, 1)'s edges from below and above, and the crossing planner once linked the regions there:
    # the net went straight up through (0, 1), 2,000 DBU out of its guide. Links need a guide on
    # both sides of the edge, so the net follows the guide: 0 out-of-guide wire.
    guide = "n1\n(\n0 0 2000 1000 M1\n1000 0 2000 3000 M2\n0 2000 2000 3000 M1\n)\n"
    d = drawn(tmp_path, {"a": (400, 400), "b": (400, 2400)}, {"n1": ["a", "b"]}, guide=guide)
    _engine.route(d.engine, settings=_engine.RouterSettings(region_size=1))
    r = check_design(d)
    assert (r.opens, r.violations) == (0, 0)
    assert r.out_of_guide_wirelength_um == 0
    assert r.wirelength_um == pytest.approx(3.2)  # around: 600 + 2,000 + 600 DBU (M2 at x = 1,100), not 2,000 straight up


def test_a_net_whose_guide_passes_a_region_twice_has_two_parts_there(tmp_path: Path) -> None:
    # Regions of 3 x 3 GCells: [0, 3000) and [3000, 4000) along x. n1's guide runs from A (GCell
    # (0, 0)) right along row 0 into the second region, up column 3 past C, and back left along
    # row 2 to B (GCell (0, 2)). In the first region the guide is two pieces, joined only through
    # the second. The net is routed there as two parts, each tied to its own crossing, so it stays
    # in the guide; routed as one (the planner's region tree before), A and B were joined straight
    # up column 0, out of the guide.
    guide = ("n1\n(\n0 0 4000 1000 M1\n0 2000 4000 3000 M1\n3000 1000 4000 2000 M1\n"
             "3000 0 4000 3000 M2\n)\n")
    d = drawn(tmp_path, {"a": (400, 400), "b": (400, 2400), "c": (3400, 1400)}, {"n1": ["a", "b", "c"]},
              guide=guide)
    first = _engine.FirstPass(_engine.RoutingSession(d.engine), 3, "heuristic")
    at_origin = [i for i, row in enumerate(first.regions) if row[0] == (0, 0)]
    assert first.open_region(at_origin[0]).candidates[:, 0].tolist() == [0, 0]  # n1 twice
    _engine.route(d.engine, settings=_engine.RouterSettings(region_size=3))
    r = check_design(d)
    assert (r.opens, r.violations) == (0, 0)
    assert r.out_of_guide_wirelength_um == 0


@pytest.mark.parametrize("pin_ylo", [1070, 1080])
def test_a_wire_leaving_a_pin_does_not_extend_beyond_the_pins_inner_edge(tmp_path: Path, pin_ylo: int) -> None:
    # M1 end-of-line spacing 0.17 um for line ends under 0.07 um. Two facing pins of different
    # nets, 180 apart: u1's (x 1470..1510) and u2's (1690..1730), each too narrow for a via's
    # cut, so pin access offers planar exits only, the nearest at their centres x = 1490 and
    # 1710 on the track y = 1100. n1 leaves u1 west (to u3), n2 leaves u2 east (to u4). A wire
    # end's usual half-width extension (30) stuck out of each pin: line ends at 1520 and 1680,
    # 160 apart, two EndOfLine markers. A wire end at a point inside its pin, where the pin
    # reaches into the wire, now stops at the point (extension 0): the metal ends at the pins'
    # own edges. The pins are as tall as the wire (y 1070..1130), or 10 shorter (1080..1130):
    # the end edge's bare 10 meets the pin at a concave corner, no line end.
    pin_y = (pin_ylo - 1000) / 1000
    left = cell("LEFTPIN", (0.07, pin_y, 0.11, 0.13))
    right = cell("RIGHTPIN", (0.09, pin_y, 0.13, 0.13))
    comps = {"u3": (400, 1000), "u1": (1400, 1000, "LEFTPIN"), "u2": (1600, 1000, "RIGHTPIN"), "u4": (2600, 1000)}
    eol = "SPACING 0.17 ENDOFLINE 0.07 WITHIN 0.025 ;"
    d = drawn(tmp_path, comps, {"n1": ["u3", "u1"], "n2": ["u2", "u4"]}, macros=left + right, m1_rules=eol)
    _, _, metrics = route_die(d)
    assert metrics["violations"] == 0
    assert d.net_routing(0)["wires"] == [("M1", 500, 1100, 1490, 1100, 0, -1, 0)]
    assert d.net_routing(1)["wires"] == [("M1", 1710, 1100, 2700, 1100, 0, 0, -1)]
    assert d.engine.check_drc(skip_fixed_pairs=False) == []
    # The same wires with the usual extensions (metal 470..1520 and 1680..2730): both ends face.
    # Each marker: the other net's metal inside the line end's window (n2's end at 1680 reaches
    # 1510, n1's extension 1510..1520 is in it; and the mirror image).
    m1 = [i for i, layer in enumerate(d.engine.layers()) if layer["name"] == "M1"][0]
    pins = [(m1, 1470, pin_ylo, 1510, 1130, 0), (m1, 1690, pin_ylo, 1730, 1130, 1),
            (m1, 470, 1070, 530, 1130, 0), (m1, 2670, 1070, 2730, 1130, 1)]
    old = shape_rows(pins + [(m1, 470, 1070, 1520, 1130, 0), (m1, 1680, 1070, 2730, 1130, 1)])
    markers = _engine.check_shapes(d.engine, old)
    assert sorted((m["type"], m["box"], m["nets"]) for m in markers) == [
        ("EndOfLine", (1510, 1070, 1520, 1130), (1, 0)), ("EndOfLine", (1680, 1070, 1690, 1130), (0, 1))]


@pytest.mark.parametrize("penalty", [None, 20000])
def test_a_routed_pins_unused_via_landings_stop_costing_other_nets(tmp_path: Path, penalty: int | None) -> None:
    # u1's pin is a tall M1 bar (x 470..530, y 1070..1530) with three access points, (500, 1100),
    # (500, 1300) and (500, 1500), each with a via up whose M2 landing is reserved for n1. n1
    # joins u1 and u2 on M1 without a via. n2 (pins at (500, 300) and (500, 2500)) runs on the
    # M2 track x = 500 right over those landings. Before n1 is routed a step onto one costs the
    # landing penalty; once n1's pin is joined its landings are released (flag 32) and cost n2
    # nothing more, so n2 runs straight: one M2 wire, two vias. With the engine's costs (penalty
    # None; the landing penalty is 0 since 2026-11-27) the step costs the same before and after.
    tall = macro("TALL", 0.2, 0.6, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.53))]))
    comps = {"u1": (400, 1000, "TALL"), "u2": (2400, 1000), "u3": (400, 200), "u4": (400, 2400)}
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"]}, macros=tall)
    costs = _engine.MazeCosts() if penalty is None else _engine.MazeCosts(landing_penalty=penalty)
    region = _engine.RoutingSession(d.engine, costs=costs).open_region((0, 0, 4000, 4000))
    g = region.grid()
    xs, ys = list(g["xs"]), list(g["ys"])
    nx, ny = len(xs), len(ys)
    landings = [ys.index(y) for y in (1100, 1300, 1500)]
    assert [int(g["flags"][1, y, xs.index(500)]) for y in landings] == [9, 9, 9]  # on track, landing

    def north_step_cost(y: int) -> int:  # n2's step on M2 from (500, ys[y - 1]) onto (500, ys[y])
        nodes, costs = region.moves(1, (1 * ny + y - 1) * nx + xs.index(500))
        assert nodes[2] == (1 * ny + y) * nx + xs.index(500)
        return int(costs[2])

    before = [north_step_cost(y) for y in landings]
    assert region.route_net(0) == {"net": 0, "routed": True, "wirelength_dbu": 2000, "vias": 0, "unreached": 0}
    assert [int(g["flags"][1, y, xs.index(500)]) for y in landings] == [41, 41, 41]  # + released
    after = [north_step_cost(y) for y in landings]
    assert [b - a for a, b in zip(after, before)] == [costs.landing_penalty] * 3
    region.route_net(1)
    assert region.metrics()["violations"] == 0
    region.commit()
    assert d.net_routing(1) == {"wires": [("M2", 500, 300, 500, 2500, 0, -1, -1)],
                                "vias": [("V12", 500, 300), ("V12", 500, 2500)], "patches": []}
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


@pytest.mark.parametrize("sole", [8000, 0, -1])
def test_the_landing_above_a_pins_only_via_point_costs_other_nets(tmp_path: Path, sole: int) -> None:
    # u1's pin (PIN1, a 60 x 60 M1 square at (500, 1100)) has one access point with a via up; u5's
    # (the tall bar, y 1470..1930) has three, at y 1500, 1700 and 1900. Every landing above them on
    # the M2 track x = 500 is reserved for its net (flags 9: on track, landing); u1's alone is also
    # its pin's sole landing (+ 64). n2 (pins at (500, 300) and (500, 2500)) would run over all of
    # them: a step onto the sole landing costs the sole-landing penalty, the others nothing more.
    # Routed before n1 with a penalty, n2 leaves the node to n1's via; n1 and n3 then route and the
    # region has no violation. Without (0), n2 runs over it. -1 (the default) is 8,000 here: five of
    # the six pins have one via point.
    tall = macro("TALL", 0.2, 0.6, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.53))]))
    comps = {"u1": (400, 1000), "u2": (2400, 1000), "u3": (400, 200), "u4": (400, 2400),
             "u5": (400, 1400, "TALL"), "u6": (2400, 2000)}
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"], "n3": ["u5", "u6"]}, macros=tall)
    costs = _engine.MazeCosts(sole_landing_penalty=sole)
    region = _engine.RoutingSession(d.engine, costs=costs).open_region((0, 0, 4000, 4000))
    free = _engine.RoutingSession(d.engine, costs=_engine.MazeCosts(sole_landing_penalty=0)).open_region((0, 0, 4000, 4000))
    g = region.grid()
    xs, ys = list(g["xs"]), list(g["ys"])
    nx, ny = len(xs), len(ys)
    landings = [ys.index(y) for y in (1100, 1500, 1700, 1900)]
    assert [int(g["flags"][1, y, xs.index(500)]) for y in landings] == [73, 9, 9, 9]

    def north_step_cost(r: Any, y: int) -> int:  # n2's step on M2 from (500, ys[y - 1]) onto (500, ys[y])
        nodes, step_costs = r.moves(1, (1 * ny + y - 1) * nx + xs.index(500))
        assert nodes[2] == (1 * ny + y) * nx + xs.index(500)
        return int(step_costs[2])

    extra = [north_step_cost(region, y) - north_step_cost(free, y) for y in landings]
    assert extra == [8000 if sole else 0, 0, 0, 0]
    region.route_net(1)
    assert (int(g["routed_net"][1, landings[0], xs.index(500)]) == 1) == (sole == 0)  # n2 on the sole landing
    if sole:
        region.route_net(0)
        region.route_net(2)
        assert region.metrics()["violations"] == 0
    # The whole flow reports the penalty it used, the default resolved.
    used = _engine.route(d.engine, settings=_engine.RouterSettings(costs=costs))["sole_landing_penalty"]
    assert used == (8000 if sole else 0)


def test_the_sole_landing_penalty_is_off_where_most_pins_have_more_via_points(tmp_path: Path) -> None:
    # The same three nets with u2, u3, u4 and u6 tall too: two pins in six have one via point, so the
    # default (-1) charges nothing on u1's sole landing; 8,000 set by hand still does.
    tall = macro("TALL", 0.2, 0.6, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.53))]))
    comps = {"u1": (400, 1000), "u2": (2400, 1000, "TALL"), "u3": (400, 200), "u4": (400, 2400, "TALL"),
             "u5": (400, 1400, "TALL"), "u6": (2400, 2000, "TALL")}
    d = drawn(tmp_path, comps, {"n1": ["u1", "u2"], "n2": ["u3", "u4"], "n3": ["u5", "u6"]}, macros=tall)
    box = (0, 0, 4000, 4000)
    auto = _engine.RoutingSession(d.engine).open_region(box)
    free = _engine.RoutingSession(d.engine, costs=_engine.MazeCosts(sole_landing_penalty=0)).open_region(box)
    charged = _engine.RoutingSession(d.engine, costs=_engine.MazeCosts(sole_landing_penalty=8000)).open_region(box)
    g = auto.grid()
    xs, ys = list(g["xs"]), list(g["ys"])
    nx, ny = len(xs), len(ys)
    y = ys.index(1100)
    assert int(g["flags"][1, y, xs.index(500)]) == 73  # u1's landing: still its pin's sole landing

    def north_step_cost(r: Any) -> int:
        nodes, step_costs = r.moves(1, (1 * ny + y - 1) * nx + xs.index(500))
        assert nodes[2] == (1 * ny + y) * nx + xs.index(500)
        return int(step_costs[2])

    assert north_step_cost(auto) == north_step_cost(free)
    assert north_step_cost(charged) - north_step_cost(free) == 8000
    assert _engine.route(d.engine)["sole_landing_penalty"] == 0
