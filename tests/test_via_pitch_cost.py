"""The maze's costs against the pitch (route/maze.hpp ``pitchCosts``), read through the region's
moves on drawn stacks.

A via costs at least ``via_pitches`` pitches of the second routing layer: the contest scorer weighs a
via as 4 of them (pitch 0.4 um, 400 DBU: 4 pitches are 1,600, above via_cost's 1,200; 0.2 um: 800,
via_cost stays). A DBU of wire costs one unit where the pitch is 200 DBU or more, and 200 / pitch
units (rounded) where it is finer.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from drawn import load_drawn
from lef_text import library, macro, pin, stack
from xroute import _engine

CELL = macro("PIN1", 0.4, 0.4, pin("A", "INOUT", [("M1", (0.17, 0.17, 0.23, 0.23))]))


def via_step(tmp_path: Path, pitch_um: float, costs: _engine.MazeCosts | None = None) -> int:
    """The cost of the via up from the first pin's access point, a two-pin net on the drawn stack."""
    p = round(pitch_um * 1000)
    def_text = (
        'VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN pitch ;\nUNITS DISTANCE MICRONS 1000 ;\n'
        "DIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
        f"TRACKS Y {p // 2} DO {4000 // p} STEP {p} LAYER M1 M2 M3 ;\n"
        f"TRACKS X {p // 2} DO {4000 // p} STEP {p} LAYER M1 M2 M3 ;\n"
        "COMPONENTS 2 ;\n- u1 PIN1 + PLACED ( 0 0 ) N ;\n- u2 PIN1 + PLACED ( 2400 0 ) N ;\nEND COMPONENTS\n"
        "NETS 1 ;\n- n1 ( u1 A ) ( u2 A ) ;\nEND NETS\nEND DESIGN\n")
    db = load_drawn(tmp_path, library(stack(pitch=pitch_um, layers=3), CELL), def_text, stem="pitch")
    session = _engine.RoutingSession(db) if costs is None else _engine.RoutingSession(db, costs=costs)
    region = session.open_region((0, 0, 4000, 4000))
    grid = region.grid()
    xs, ys = [int(v) for v in grid["xs"]], [int(v) for v in grid["ys"]]
    node = ys.index(200) * len(xs) + xs.index(200)  # u1's pin centre on M1 (z 0)
    nodes, step = region.moves(0, node)
    assert nodes[0] == node + len(xs) * len(ys)  # the node above, on M2
    return int(step[0])


def test_defaults() -> None:
    costs = _engine.MazeCosts()
    assert (costs.via_cost, costs.via_pitches) == (1200, 4)


@pytest.mark.parametrize(("pitch_um", "costs", "expected"), [
    (0.4, None, 4 * 400),  # the scorer's weight is above via_cost
    (0.4, _engine.MazeCosts(via_pitches=0), 1200),  # via_cost alone
    (0.4, _engine.MazeCosts(via_cost=2000), 2000),  # via_cost above the weight
    (0.2, None, 1200),  # 4 x 200 = 800 is below via_cost
    (0.2, _engine.MazeCosts(via_pitches=7), 7 * 200),
])
def test_via_cost_is_at_least_the_scorers_weight(tmp_path: Path, pitch_um: float,
                                                 costs: _engine.MazeCosts | None, expected: int) -> None:
    assert via_step(tmp_path, pitch_um, costs) == expected


def wire_step(tmp_path: Path, pitch_um: float) -> tuple[int, int]:
    """(cost, length in DBU) of the step east along M1 from a free node in the middle of the die."""
    p = round(pitch_um * 1000)
    n = 4000 // p
    def_text = (
        'VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN pitch ;\nUNITS DISTANCE MICRONS 1000 ;\n'
        "DIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
        f"TRACKS Y {p // 2} DO {n} STEP {p} LAYER M1 M2 M3 ;\n"
        f"TRACKS X {p // 2} DO {n} STEP {p} LAYER M1 M2 M3 ;\n"
        "COMPONENTS 2 ;\n- u1 PIN1 + PLACED ( 0 0 ) N ;\n- u2 PIN1 + PLACED ( 2400 0 ) N ;\nEND COMPONENTS\n"
        "NETS 1 ;\n- n1 ( u1 A ) ( u2 A ) ;\nEND NETS\nEND DESIGN\n")
    fine = dict(width=0.02, spacing=0.02, cut_width=0.02, cut_spacing=0.02, via_metal_length=0.03)
    db = load_drawn(tmp_path, library(stack(pitch=pitch_um, layers=3, **fine), CELL), def_text, stem="pitch")
    region = _engine.RoutingSession(db).open_region((0, 0, 4000, 4000))
    grid = region.grid()
    xs, ys = [int(v) for v in grid["xs"]], [int(v) for v in grid["ys"]]
    x = min(range(len(xs)), key=lambda i: abs(xs[i] - 1600))  # between the cells
    y = min(range(len(ys)), key=lambda i: abs(ys[i] - 2000))  # above them: no pin, no other net
    nodes, step = region.moves(0, y * len(xs) + x)
    east = 4  # MazeDirection kMoveEast
    assert nodes[east] == y * len(xs) + x + 1
    return int(step[east]), xs[x + 1] - xs[x]


@pytest.mark.parametrize(("pitch_um", "unit"), [
    (0.4, 1), (0.2, 1),  # the ISPD technologies' pitches: a DBU of wire is a cost unit
    (0.1, 2), (0.045, 4), (0.036, 6),  # finer: 200 / pitch units a DBU, rounded
])
def test_wire_counts_at_the_200_dbu_pitch(tmp_path: Path, pitch_um: float, unit: int) -> None:
    """Penalties are cost units a node or a shape, set where the pitch is 200-400 DBU; where it is
    finer a DBU of wire counts 200 / pitch units, so that a penalty spans as many tracks as there."""
    cost, length = wire_step(tmp_path, pitch_um)
    assert length > 0
    assert cost == length * unit
