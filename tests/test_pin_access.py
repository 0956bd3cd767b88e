"""Pin access (engine_cpp/pa): access points of every net pin.

A drawn case with the exact points chosen, then the contest designs: every
pin has a point inside its metal, every via cut lies in the pin's metal (or
its via's metal stays inside the cell, away from its edges), the
classes give the same points as computing each component on its own, threads
do not change the result, and the chosen vias add no design-rule marker to
the pins and obstructions around them.
"""

from __future__ import annotations

import collections
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from conftest import available, pick
from drawn import shape_rows, write_design
from lef_text import Rect, library, macro, pin, stack
from xroute import _engine
from xroute.design import load_design

UP, EAST, WEST, NORTH, SOUTH = 1, 2, 4, 8, 16

# ---------------------------------------------------------------------------
# A drawn case (UNITS 1000: 1 DBU = 1 nm). M1 horizontal, M2 vertical, tracks
# every 200 from 100 in x and y on both layers. V12 has a 60x60 cut, a
# 100x60 M1 enclosure and a 60x100 M2 one. M1 spacing is 70.
#
#   y=700  +-------+       +-------+
#          |   A   |  80   |   B   |      A: x 100..260, B: x 340..500
#   y=300  +-------+       +-------+      (cell CELL at (0, 0) N, die 0..2000)
#          x=100 260      340     500
#
# A: x tracks 100 (edge: the cut would stick out), half track 200, centre
# 180, enclosed edges 130 / 230; y track 500 (300 / 700 are edges).
# On track, (100, 500), the cut sticks out of A onto the via's own M1, which
# would reach x = 50, closer to the cell's edge than M1's spacing (70): not
# taken. So (200, 500) costs 1, (180, 500) 2, then cost 3: (130, 500) and
# (230, 500) at the same distance, 130 first (x order); (230, 500) would
# also be illegal: its enclosure ends at 280, 60 from B. The three x differ,
# so all three are taken. B: x track 500 is its right edge; the cut sticks
# out onto the via's M1 (450..550, well inside the cell), so B has on-track
# via points, (500, 500) and, at its ends, (500, 300) and (500, 700), and
# offers only those.
# Planar stubs (60 wide, 200 long): towards the other pin they hit it (or
# come within 70), and west of x = 200 they leave the die.
# ---------------------------------------------------------------------------

def tiny_lef(a_rect: Rect = (0.10, 0.30, 0.26, 0.70)) -> str:
    """M1 (horizontal), V1, M2 (vertical) and V12; CELL (1 x 1 um) with pins A (M1 ``a_rect``) and B."""
    return library(stack(layers=2), macro("CELL", 1.0, 1.0, pin("A", "INPUT", [("M1", a_rect)]),
                                          pin("B", "OUTPUT", [("M1", (0.34, 0.30, 0.50, 0.70))])))


TINY_LEF = tiny_lef()

TINY_DEF = """\
VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN tiny ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( {die} {die} ) ;
TRACKS Y 100 DO {tracks} STEP 200 LAYER M1 ;
TRACKS X 100 DO {tracks} STEP 200 LAYER M1 ;
TRACKS X 100 DO {tracks} STEP 200 LAYER M2 ;
TRACKS Y 100 DO {tracks} STEP 200 LAYER M2 ;
COMPONENTS {count} ;
{components}END COMPONENTS
NETS {net_count} ;
{nets}END NETS
END DESIGN
"""


def tiny_def(components: list[str], nets: list[str], die: int = 2000) -> str:
    """TINY_DEF with these component and net lines, tracks every 200 over a die of `die` DBU."""
    return TINY_DEF.format(die=die, tracks=die // 200, count=len(components), net_count=len(nets),
                           components="".join(c + "\n" for c in components), nets="".join(n + "\n" for n in nets))


def write_tiny(tmp_path: Path, components: list[str], more: str = "") -> Any:
    lef, def_ = write_design(tmp_path, TINY_LEF, tiny_def(components, ["- a ( u1 A ) ;", f"- b ( u1 B ) {more} ;"]))
    return load_design(lef=lef, def_=def_).engine


def points_of(result: dict[str, Any], ref: int) -> list[list[int]]:
    s = result["start"]
    return result["points"][s[ref]:s[ref + 1]].tolist()


def test_drawn_case_exact_points(tmp_path: Path) -> None:
    db = write_tiny(tmp_path, ["- u1 CELL + PLACED ( 0 0 ) N ;"])
    r = db.pin_access(max_points_per_pin=3)  # the expected points below are the best three
    assert r["fallback_pins"] == 0
    assert r["classes"] == 1
    assert r["via_names"] == ["V12"]
    # (x, y, z, dirs, cost), best first.
    assert points_of(r, 0) == [
        [200, 500, 0, UP | WEST | NORTH | SOUTH, 1],
        [180, 500, 0, UP | NORTH | SOUTH, 2],
        [130, 500, 0, UP | NORTH | SOUTH, 3],
    ]
    assert points_of(r, 1) == [
        [500, 500, 0, UP | EAST | NORTH | SOUTH, 0],
        [500, 300, 0, UP | EAST | NORTH | SOUTH, 0],
        [500, 700, 0, UP | EAST | NORTH | SOUTH, 0],
    ]
    assert r["via"].tolist() == [0] * 6


def test_drawn_case_max_points_and_translation(tmp_path: Path) -> None:
    # Tracks repeat every 200 in x and y. u2 and u3 sit at the same track
    # phase, away from the die edge: one class, the same points moved. u1
    # touches the die edge (its stubs would leave the die): a class of its
    # own. u4 is 100 off the phase in x: the tracks cross its pin B elsewhere.
    db = write_tiny(
        tmp_path,
        [
            "- u1 CELL + PLACED ( 0 0 ) N ;",
            "- u2 CELL + PLACED ( 400 400 ) N ;",
            "- u3 CELL + PLACED ( 800 0 ) N ;",
            "- u4 CELL + PLACED ( 1100 1000 ) N ;",
        ],
        more="( u2 B ) ( u3 B ) ( u4 B )",
    )
    r = db.pin_access(max_points_per_pin=1)
    assert np.diff(r["start"]).tolist() == [1] * 5
    assert points_of(r, 0) == [[200, 500, 0, UP | WEST | NORTH | SOUTH, 1]]  # u1 A
    assert points_of(r, 1) == [[500, 500, 0, UP | EAST | NORTH | SOUTH, 0]]  # u1 B
    assert points_of(r, 2) == [[900, 900, 0, UP | EAST | NORTH | SOUTH, 0]]  # u2 B
    assert points_of(r, 3) == [[1300, 500, 0, UP | EAST | NORTH | SOUTH, 0]]  # u3 B
    # u4 B spans x 1440..1600, y 1300..1700: track x 1500 and track y 1500.
    assert points_of(r, 4) == [[1500, 1500, 0, UP | EAST | NORTH | SOUTH, 0]]
    assert r["classes"] == 3


def test_drawn_case_blocked_pin_falls_back(tmp_path: Path) -> None:
    # Pin A is 40 wide at the die's left edge: no 60 cut fits, and every
    # planar stub (60 wide, centred on x = 20) leaves the die. The fallback
    # point is the pin's centre snapped to the tracks (no x track crosses
    # it; y 500), cost 100, exit up through V12.
    lef = tiny_lef(a_rect=(0.00, 0.30, 0.04, 0.70))
    lef_path, def_path = write_design(
        tmp_path, lef, tiny_def(["- u1 CELL + PLACED ( 0 0 ) N ;"], ["- a ( u1 A ) ;", "- b ( u1 B ) ;"])
    )
    db = load_design(lef=lef_path, def_=def_path).engine
    r = db.pin_access()
    assert r["fallback_pins"] == 1
    assert points_of(r, 0) == [[20, 500, 0, UP, 100]]
    assert r["via"][0] == 0


def test_drawn_pin_with_an_on_track_point_offers_only_on_track_points(tmp_path: Path) -> None:
    # u4's pin B spans x 1440..1600, y 1300..1700: track x 1500 and track y 1500
    # cross inside it with room for the cut (1300 and 1700, its ends, with the
    # cut sticking out onto the via's metal). The old choice spread the three
    # points over distinct x (1500, then off-track 1520 and 1570); now a pin
    # with a legal on-track via point offers on-track points only. u1's pin A
    # has none (see the drawn case): it keeps its off-track points.
    db = write_tiny(tmp_path, ["- u1 CELL + PLACED ( 0 0 ) N ;", "- u4 CELL + PLACED ( 1100 1000 ) N ;"], more="( u4 B )")
    r = db.pin_access(max_points_per_pin=3)
    on = UP | EAST | NORTH | SOUTH
    assert points_of(r, 2) == [[1500, 1500, 0, on, 0], [1500, 1300, 0, on, 0], [1500, 1700, 0, on, 0]]
    assert [p[4] for p in points_of(r, 0)] == [1, 2, 3]


ROUTE_DEF = tiny_def(["- u1 CELL + PLACED ( 1100 1000 ) N ;", "- u2 CELL + PLACED ( 1100 2400 ) N ;"],
                     ["- n ( u1 B ) ( u2 B ) ;"], die=4000)


def test_drawn_route_uses_on_track_access_vias(tmp_path: Path) -> None:
    # Two B pins stacked 1.4 um apart, each crossed by track x 1500 and by
    # track y 1500 / 2900 with room for the cut. With off-track points on
    # offer the router reached u2 a half-track y off M1's tracks (100
    # shorter); with only the on-track points both vias sit on track
    # crossings. The pins' ends are 1,000 apart: at 800 a wrong-way M1 wire
    # (4 x 800) costs what two vias and the M2 wire cost (2 x 1200 + 800),
    # and the maze may take either.
    lef, def_ = write_design(tmp_path, TINY_LEF, ROUTE_DEF)
    db = load_design(lef=lef, def_=def_).engine
    _engine.route(db)
    c = db.check_routing()
    assert (c["opens"], c["markers"], c["vias"]) == (0, [], 2)
    assert c["off_track_vias"] == 0
    vias = db.net_routing(0)["vias"]
    assert len(vias) == 2
    for _, x, y in vias:
        assert (x - 100) % 200 == 0 and (y - 100) % 200 == 0, (x, y)


# ---------------------------------------------------------------------------
# Contest designs.
# ---------------------------------------------------------------------------

# The contest designs found, each missing one replaced by its generated stand-in (conftest.available).
DESIGNS = available("ispd18_sample", "ispd18_test1", "ispd19_test1", "ispd19_sample4")
SAMPLE = pick("ispd18_sample")

_results: dict[str, dict[str, Any]] = {}


def access(loaded_design: Any, name: str) -> tuple[Any, dict[str, Any]]:
    db = loaded_design(name).engine
    if name not in _results:
        # The counts below are for three per pin, as the classes give them (no neighbours).
        _results[name] = db.pin_access(max_points_per_pin=3, check_in_context=False)
    return db, _results[name]


def pin_shapes(db: Any) -> dict[int, list[tuple[int, int, int, int, int]]]:
    """pinRef -> [(routing index, xlo, ylo, xhi, yhi)] of its routing-layer shapes."""
    routing = {i: l["routing_index"] for i, l in enumerate(db.layers())}
    start = np.asarray(db.net_pin_start)
    out: dict[int, list[tuple[int, int, int, int, int]]] = collections.defaultdict(list)
    for net in range(len(start) - 1):
        for local, layer, xlo, ylo, xhi, yhi in db.net_pin_shapes(net).tolist():
            if routing[layer] >= 0:
                out[int(start[net]) + local].append((routing[layer], xlo, ylo, xhi, yhi))
    return out


def covered(rect: tuple[int, int, int, int], metal: list[tuple[int, int, int, int]]) -> bool:
    """Is the rect covered by the union of `metal` (coordinate-compressed grid)?"""
    xlo, ylo, xhi, yhi = rect
    parts = [(max(a, xlo), max(b, ylo), min(c, xhi), min(d, yhi)) for a, b, c, d in metal]
    parts = [p for p in parts if p[0] < p[2] and p[1] < p[3]]
    xs = sorted({xlo, xhi, *[p[0] for p in parts], *[p[2] for p in parts]})
    ys = sorted({ylo, yhi, *[p[1] for p in parts], *[p[3] for p in parts]})
    for x0, x1 in zip(xs, xs[1:]):
        for y0, y1 in zip(ys, ys[1:]):
            if not any(p[0] <= x0 and p[1] <= y0 and p[2] >= x1 and p[3] >= y1 for p in parts):
                return False
    return True


@pytest.mark.parametrize("name", DESIGNS)
def test_points_lie_in_pin_metal(loaded_design: Any, name: str) -> None:
    db, r = access(loaded_design, name)
    start, points, vias = r["start"], r["points"], r["via"]
    refs = len(np.asarray(db.pin_refs))
    assert len(start) == refs + 1 and start[0] == 0 and start[-1] == len(points) == len(vias)
    counts = np.diff(start)
    assert counts.min() >= 1 and counts.max() <= 3

    layers = db.layers()
    routing_of = {l["name"]: l["routing_index"] for l in layers}
    cut_of: dict[int, tuple[int, list[tuple[int, int, int, int]]]] = {}
    for v in set(vias.tolist()) - {-1}:
        info = db.via(r["via_names"][v])
        cut = [tuple(s[1:]) for s in info["shapes"] if s[0] == info["cut"]]
        cut_of[v] = (routing_of[info["bottom"]], cut)

    shapes = pin_shapes(db)
    cells = cell_boxes(db)
    margin = {l["routing_index"]: keep_in_margin(l) for l in layers if l["routing_index"] >= 0}
    bottom_metal = {
        v: [tuple(s[1:]) for s in db.via(r["via_names"][v])["shapes"] if s[0] == db.via(r["via_names"][v])["bottom"]]
        for v in cut_of
    }
    for ref in range(refs):
        mine = shapes[ref]
        pts = points[start[ref]:start[ref + 1]]
        assert len({(int(p[0]), int(p[1]), int(p[2])) for p in pts}) == len(pts)  # distinct
        assert list(pts[:, 4]) == sorted(pts[:, 4])  # best first
        for k, (x, y, z, dirs, cost) in enumerate(pts.tolist()):
            metal = [s[1:] for s in mine if s[0] == z]
            assert any(a <= x <= c and b <= y <= d for a, b, c, d in metal), (ref, x, y, z)
            assert dirs != 0
            v = int(vias[start[ref] + k])
            if dirs & UP:
                bottom, cuts = cut_of[v]
                assert bottom == z
                if all(covered((a + x, b + y, c + x, d + y), metal) for a, b, c, d in cuts):
                    continue
                # A cut sticking out of the pin: a component's pin, the via's metal
                # on the pin's layer inside the cell by the layer's keep-in margin.
                assert ref in cells, (ref, x, y, r["via_names"][v])
                cx0, cy0, cx1, cy1 = cells[ref]
                m = margin[z]
                for a, b, c, d in bottom_metal[v]:
                    assert cx0 + m <= a + x and cy0 + m <= b + y and c + x <= cx1 - m and d + y <= cy1 - m, (ref, x, y)
            else:
                assert v == -1


def keep_in_margin(layer: dict[str, Any]) -> int:
    """How far inside its cell a via's metal must stay when its cut sticks out of the pin: the
    layer's min spacing or largest end-of-line space."""
    return max([layer["min_spacing"], *[e["space"] for e in layer["eol_rules"]]])


def cell_boxes(db: Any) -> dict[int, tuple[int, int, int, int]]:
    """pinRef -> its component's placed box (SIZE, rotated by the orientation); IO pins absent."""
    start = np.asarray(db.net_pin_start)
    out: dict[int, tuple[int, int, int, int]] = {}
    for net in range(len(start) - 1):
        for local, (comp, _) in enumerate(db.net_pins(net)):
            if comp == "PIN":
                continue
            c = db.component(comp)
            w, h = db.macro(c["macro"])["size"]
            if c["orient"] in ("E", "W", "FE", "FW"):
                w, h = h, w
            x, y = c["location"]
            out[int(start[net]) + local] = (x, y, x + w, y + h)
    return out


@pytest.mark.parametrize(("name", "fallback", "classes"), [("ispd18_sample", 0, 20), ("ispd18_test1", 0, 219)])
def test_fallback_and_class_counts(loaded_design: Any, name: str, fallback: int, classes: int) -> None:
    _, r = access(loaded_design, name)
    assert r["fallback_pins"] == fallback
    assert r["classes"] == classes
    assert (r["points"][:, 4] < 100).all()


def test_one_class_same_relative_points(loaded_design: Any) -> None:
    # Components of one macro and orientation at the same track phase
    # (ispd18_test1: x tracks every 400, y every 380; its stand-in: x every 380,
    # y every 280), away from the die edge, have the same points relative to
    # their location.
    name = pick("ispd18_test1")
    db, r = access(loaded_design, name)
    px, py, margin, enough = (400, 380, 5000, 100) if name == "ispd18_test1" else (380, 280, 3000, 5)
    start, points, vias = r["start"], r["points"], r["via"]
    die = db.die_area
    comps: dict[str, dict[str, Any]] = {}
    groups: dict[tuple[Any, ...], list[tuple[Any, ...]]] = collections.defaultdict(list)
    net_start = np.asarray(db.net_pin_start)
    for net in range(len(net_start) - 1):
        for local, (comp, pin) in enumerate(db.net_pins(net)):
            ref = int(net_start[net]) + local
            if comp == "PIN":  # an IO pin (the stand-in has some; ispd18_test1 none)
                continue
            c = comps.setdefault(comp, db.component(comp))
            x, y = c["location"]
            if not (die[0] + margin < x < die[2] - 2 * margin and die[1] + margin < y < die[3] - 2 * margin):
                continue
            key = (c["macro"], c["orient"], pin, x % px, y % py)
            rel = tuple(
                (int(p[0]) - x, int(p[1]) - y, *map(int, p[2:]), int(vias[start[ref] + k]))
                for k, p in enumerate(points[start[ref]:start[ref + 1]])
            )
            groups[key].append(rel)
    shared = [g for g in groups.values() if len(g) >= 2]
    assert len(shared) > enough
    for g in shared:
        assert all(rel == g[0] for rel in g)


@pytest.mark.parametrize("name", available("ispd18_sample", "ispd19_sample4"))
def test_classes_match_components_computed_alone(loaded_design: Any, name: str) -> None:
    db, r = access(loaded_design, name)
    alone = db.pin_access(max_points_per_pin=3, share_classes=False, check_in_context=False)
    for key in ("start", "points", "via"):
        assert np.array_equal(r[key], alone[key])
    assert alone["classes"] >= r["classes"]


def test_threads_give_the_same_table(loaded_design: Any) -> None:
    db, _ = access(loaded_design, pick("ispd18_test1"))
    r = db.pin_access(max_points_per_pin=3)  # with the check among the neighbours
    two = db.pin_access(max_points_per_pin=3, threads=2)
    for key in ("start", "points", "via"):
        assert np.array_equal(r[key], two[key])
    assert (two["fallback_pins"], two["classes"]) == (r["fallback_pins"], r["classes"])


def test_bad_arguments(loaded_design: Any) -> None:
    db = loaded_design(SAMPLE).engine
    with pytest.raises(ValueError):
        db.pin_access(max_points_per_pin=0)
    with pytest.raises(ValueError):
        db.pin_access(threads=0)


# ---------------------------------------------------------------------------
# Design-rule check of the chosen vias against every pin and obstruction.
# ---------------------------------------------------------------------------


def via_rows(db: Any, r: dict[str, Any], which: str) -> list[tuple[int, list[tuple[int, ...]]]]:
    """(x // 1, [shape rows]) for the vias of the first (or every) point of each pin, net ids as drc_shapes."""
    layer_index = {l["name"]: i for i, l in enumerate(db.layers())}
    net_start = np.asarray(db.net_pin_start)
    net_of = np.repeat(np.arange(len(net_start) - 1), np.diff(net_start))
    start, points, vias = r["start"], r["points"], r["via"]
    shapes = {v: db.via(r["via_names"][v])["shapes"] for v in set(vias.tolist()) - {-1}}
    out = []
    for ref in range(len(start) - 1):
        last = start[ref + 1] if which == "all" else start[ref] + 1
        for k in range(start[ref], last):
            if vias[k] < 0:
                continue
            x, y = int(points[k][0]), int(points[k][1])
            rows = [(layer_index[l], a + x, b + y, c + x, d + y, int(net_of[ref])) for l, a, b, c, d in shapes[int(vias[k])]]
            out.append(((x, y), rows))
    return out


def new_markers(db: Any, rows: list[tuple[int, ...]], near: int | None = None) -> list[dict[str, Any]]:
    """Markers that the rows (vias, stubs) add to the design's shapes. With
    `near`, only design shapes within `near` DBU of some row take part (the
    same ones with and without the rows)."""
    base = db.drc_shapes()
    base_rows = np.array([s[:6] for s in base], dtype=np.int32)
    base_origins = np.array([s[6] for s in base], dtype=np.int32)
    if near is not None:
        keep = np.zeros(len(base_rows), dtype=bool)
        for _, xlo, ylo, xhi, yhi, _ in rows:
            keep |= (
                (base_rows[:, 1] <= xhi + near)
                & (base_rows[:, 3] >= xlo - near)
                & (base_rows[:, 2] <= yhi + near)
                & (base_rows[:, 4] >= ylo - near)
            )
        base_rows, base_origins = base_rows[keep], base_origins[keep]
    shapes = np.concatenate([base_rows, shape_rows(rows)])
    origins = np.concatenate([base_origins, np.ones(len(rows), dtype=np.int32)])
    before = {(m["type"], m["layer"], m["box"], m["nets"]) for m in _engine.check_shapes(db, base_rows, base_origins)}
    after = _engine.check_shapes(db, shapes, origins, skip_fixed_pairs=True)
    # Min area is the router's wire's business; pin-pin markers (already
    # there without the vias) are not the vias' doing.
    return [m for m in after if m["type"] != "MinArea" and (m["type"], m["layer"], m["box"], m["nets"]) not in before]


def test_best_vias_together_add_no_marker(loaded_design: Any) -> None:
    db, r = access(loaded_design, SAMPLE)
    rows = [row for _, rs in via_rows(db, r, "first") for row in rs]
    if SAMPLE == "ispd18_sample":
        assert len(rows) == 3 * 22
    assert rows and len(rows) % 3 == 0
    assert new_markers(db, rows) == []


def test_every_via_adds_no_marker(loaded_design: Any) -> None:
    # Every point's via of ispd18_sample (or its stand-in), in batches of vias at
    # least 1.5 um apart (the points of one pin, close together, are alternatives,
    # not meant to coexist).
    db, r = access(loaded_design, SAMPLE)
    batches: list[list[tuple[int, ...]]] = []
    placed: list[list[tuple[int, int]]] = []
    for (x, y), rs in via_rows(db, r, "all"):
        for b, where in enumerate(placed):
            if all(abs(x - px) + abs(y - py) >= 3000 for px, py in where):
                batches[b] += rs
                where.append((x, y))
                break
        else:
            batches.append(list(rs))
            placed.append([(x, y)])
    # ispd18_sample: 22 pins, 54 via points (a pin with an on-track via point offers only on-track ones).
    assert sum(len(b) for b in batches) == (3 * 54 if SAMPLE == "ispd18_sample" else 3 * len(via_rows(db, r, "all")))
    for rows in batches:
        assert new_markers(db, rows) == []


def exit_rows(db: Any, r: dict[str, Any], k: int, net: int) -> list[tuple[int, ...]]:
    """Every exit of point k: its via's shapes, and its planar stubs (min width,
    one preferred pitch long, from the point), as drc shape rows on `net`."""
    layers = db.layers()
    lef_of = {l["routing_index"]: i for i, l in enumerate(layers) if l["routing_index"] >= 0}
    index_of = {l["name"]: i for i, l in enumerate(layers)}
    rows: list[tuple[int, ...]] = []
    x, y, z, dirs, _ = map(int, r["points"][k])
    if dirs & UP:
        for l, a, b, c, d in db.via(r["via_names"][int(r["via"][k])])["shapes"]:
            rows.append((index_of[l], a + x, b + y, c + x, d + y, net))
    info = layers[lef_of[z]]
    w = info["min_width"] or info["width"]
    h = w // 2
    length = stub_length(db, info)
    for bit, rect in (
        (EAST, (x - h, y - h, x + length, y - h + w)),
        (WEST, (x - length, y - h, x - h + w, y - h + w)),
        (NORTH, (x - h, y - h, x - h + w, y + length)),
        (SOUTH, (x - h, y - length, x - h + w, y - h + w)),
    ):
        if dirs & bit:
            rows.append((lef_of[z], *rect, net))
    return rows


def stub_length(db: Any, info: dict[str, Any]) -> int:
    """The smallest step between the layer's preferred tracks (its pitch when none)."""
    axis = "Y" if info["direction"] == "HORIZONTAL" else "X"
    steps = [t["step"] for t in db.tracks() if t["layer"] == info["name"] and t["axis"] == axis and t["count"] > 1]
    return min(steps) if steps else max(info["pitch"])


@pytest.mark.parametrize(("name", "io_pins"), [("ispd18_sample3", 5), pytest.param("ispd19_test3", 57, marks=pytest.mark.slow), ("standin_noguide", None)])
def test_io_pin_exits_add_no_marker(loaded_design: Any, name: str, io_pins: int) -> None:
    # IO pins are checked against the design around them (pad cells, rings):
    # every exit of every point, vias and planar stubs, adds no marker.
    db = loaded_design(name, use_guide=False).engine
    r = db.pin_access()
    refs = np.asarray(db.pin_refs)
    net_start = np.asarray(db.net_pin_start)
    net_of = np.repeat(np.arange(len(net_start) - 1), np.diff(net_start))
    io = [ref for ref in range(len(refs)) if refs[ref][0] < 0]
    if io_pins is None:  # a generated design: its PINS on nets
        io_pins = loaded_design(name, use_guide=False).counts()["io_pins"]
        assert io_pins > 0
    assert len(io) == io_pins
    batches: list[list[tuple[int, ...]]] = []
    placed: list[list[tuple[int, int]]] = []
    for ref in io:
        for k in range(r["start"][ref], r["start"][ref + 1]):  # alternatives: never in one batch
            x, y = (int(v) for v in r["points"][k][:2])
            rows = exit_rows(db, r, k, int(net_of[ref]))
            assert rows
            for b, where in enumerate(placed):
                if all(abs(x - px) + abs(y - py) >= 5000 for px, py in where):
                    batches[b] += rows
                    where.append((x, y))
                    break
            else:
                batches.append(rows)
                placed.append([(x, y)])
    for rows in batches:
        assert new_markers(db, rows, near=3000) == []
