"""The built-in global router (engine_cpp/groute): capacities counted exactly on a drawn grid, a
2-pin net detouring around a blocked GCell edge, guides that round-trip through the guide
reader, determinism, ispd18_sample routed with built-in guides (0 opens), a global route of
ispd19_test3 without overflow, and the ``xroute global-route`` command.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from typer.testing import CliRunner

from conftest import pick, require_testcase
from drawn import write_design
from lef_text import library, macro, pin, stack
from xroute import _engine
from xroute.cli.app import app
from xroute.design import load_design
from xroute.groute import GlobalRouteArgumentError, global_route

# ---------------------------------------------------------------------------
# A drawn grid (UNITS 1000). Three routing layers M1 (horizontal), M2 (vertical), M3
# (horizontal), all with tracks every 100 from 50 in x and y, width 60, spacing 70: a shape
# blocks the tracks within 30 + 70 = 100 of it. GCELLGRID every 200: 5 x 5 GCells, two
# tracks per GCell row or column, GCell centres at 100, 300, 500, 700, 900.
#
#   row 2 (y 400..600):  [A]  .   #   .  [B]     A in u1 at GCell (0, 2), B in u2 at (4, 2)
#                              x 400..600 on M3: the blockage "#"
#
# The M3 blockage (400, 400)-(600, 600), grown by 100, covers y 300..700 and x 300..700: the
# tracks y = 350, 450, 550, 650 between the centres 300-500 and 500-700 (edges 1 and 2).
# Row 2 loses both tracks there (capacity 0), rows 1 and 3 one each (capacity 1).
# ---------------------------------------------------------------------------

LEF = library(stack(pitch=0.1), macro("CELL", 0.2, 0.2, pin("A", "INOUT", [("M1", (0.07, 0.07, 0.13, 0.13))])))

DEF = """\
VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN grid ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 1000 1000 ) ;
TRACKS Y 50 DO 10 STEP 100 LAYER M1 ;
TRACKS X 50 DO 10 STEP 100 LAYER M1 ;
TRACKS X 50 DO 10 STEP 100 LAYER M2 ;
TRACKS Y 50 DO 10 STEP 100 LAYER M2 ;
TRACKS Y 50 DO 10 STEP 100 LAYER M3 ;
TRACKS X 50 DO 10 STEP 100 LAYER M3 ;
GCELLGRID X 0 DO 6 STEP 200 ;
GCELLGRID Y 0 DO 6 STEP 200 ;
COMPONENTS 2 ;
- u1 CELL + PLACED ( 0 400 ) N ;
- u2 CELL + PLACED ( 800 400 ) N ;
END COMPONENTS
{blockages}NETS 1 ;
- a ( u1 A ) ( u2 A ) ;
END NETS
END DESIGN
"""

BLOCKAGE = "BLOCKAGES 1 ;\n- LAYER M3\n  RECT ( 400 400 ) ( 600 600 ) ;\nEND BLOCKAGES\n"


def drawn(tmp_path: Path, blocked: bool = True) -> Any:
    lef, def_ = write_design(tmp_path, LEF, DEF.format(blockages=BLOCKAGE if blocked else ""), stem="grid")
    return load_design(lef=lef, def_=def_)


def test_capacity_counts_blocked_tracks_exactly(tmp_path: Path) -> None:
    design = drawn(tmp_path)
    cap = _engine.gcell_capacity(design.engine)
    assert cap["xs"].tolist() == cap["ys"].tolist() == [0, 200, 400, 600, 800, 1000]
    assert cap["layers"] == ["M1", "M2", "M3"] and cap["horizontal"] == [True, False, True]
    m3 = np.full((5, 5), 2, np.int32)
    m3[:, 4] = 0  # no edge to the right of the last column
    m3[2, 1:3] = 0
    m3[1, 1:3] = m3[3, 1:3] = 1
    assert cap["capacity"][2].tolist() == m3.tolist()
    all_tracks = np.full((5, 5), 2, np.int32)
    all_tracks[:, 4] = 0
    assert cap["tracks"][2].tolist() == all_tracks.tolist()
    # M2 (vertical): nothing blocks it; no edge above the top row.
    m2 = np.full((5, 5), 2, np.int32)
    m2[4, :] = 0
    assert cap["capacity"][1].tolist() == m2.tolist()
    # M1: the pins (x 70..130 at y 470..530, x 870..930) grown by 100 block the tracks
    # y 450 and 550 (row 2) between the centres they reach: edge 0 (u1) and edge 3 (u2).
    m1 = all_tracks.copy()
    m1[2, 0] = m1[2, 3] = 0
    assert cap["capacity"][0].tolist() == m1.tolist()


def guide_rows(design: Any, net: str) -> list[tuple[str, int, int, int, int]]:
    rects, layers = design.net_guides(net)
    names = [layer.name for layer in design.layers]
    return [(names[int(z)], *map(int, r)) for r, z in zip(rects, layers)]


def test_two_pin_net_detours_around_the_blocked_edges(tmp_path: Path) -> None:
    (tmp_path / "open").mkdir()
    open_design = drawn(tmp_path / "open", blocked=False)
    stats = global_route(open_design, capacity_percent=100)  # the drawn capacities, all of them
    assert (stats.nets, stats.wirelength_gcells, stats.overflow) == (1, 4, 0)
    # Straight along row 2 on M3, pins on M1 with M2 above, via stacks up to M3 at both ends.
    assert ("M3", 0, 400, 1000, 600) in guide_rows(open_design, "a")

    design = drawn(tmp_path)
    stats = global_route(design, capacity_percent=100)
    assert stats.initial_overflow == 2  # the straight pattern route crosses two full edges
    assert (stats.overflow, stats.overflow_3d, stats.wirelength_gcells) == (0, 0, 6)
    assert stats.iterations >= 1 and stats.reroutes >= 1
    rows = guide_rows(design, "a")
    for name, xlo, ylo, xhi, yhi in rows:
        if name == "M3" and (ylo, yhi) == (400, 600):
            assert not (xlo < 400 and xhi > 400) and not (xlo < 600 and xhi > 600), "crosses the blocked edges"
    # Every pin GCell has guides on M1 and M2.
    for box in ((0, 400, 200, 600), (800, 400, 1000, 600)):
        assert ("M1", *box) in rows and ("M2", *box) in rows


SAMPLE = pick("ispd18_sample")  # or its generated stand-in when the contest data is missing
NO_GUIDE = pick("ispd19_test3")  # or a generated design without guide


@pytest.fixture(scope="module")
def sample_guides(tmp_path_factory: pytest.TempPathFactory) -> tuple[Any, Path]:
    require_testcase(SAMPLE)
    design = load_design(SAMPLE, use_guide=False)
    path = tmp_path_factory.mktemp("groute") / "sample.guide"
    global_route(design, path)
    return design, path


def test_guide_file_round_trips_through_the_reader(sample_guides: tuple[Any, Path]) -> None:
    design, path = sample_guides
    text = path.read_text()
    assert text.startswith(design.net_names[0] + "\n(\n") and text.endswith(")\n")
    reread = load_design(lef=design.lef_paths, def_=design.def_path, guide=path)
    assert reread.guide_source == "file" and design.guide_source == "built-in"
    assert np.array_equal(reread.guide_start, design.guide_start)
    assert np.array_equal(reread.guide_rects, design.guide_rects)
    assert np.array_equal(reread.guide_layers, design.guide_layers)
    assert design.counts()["guides"] == int(design.guide_start[-1]) > 0


def test_global_route_is_deterministic(sample_guides: tuple[Any, Path], tmp_path: Path) -> None:
    design, path = sample_guides
    again = load_design(SAMPLE, use_guide=False)
    global_route(again, tmp_path / "again.guide")
    assert (tmp_path / "again.guide").read_bytes() == path.read_bytes()


def test_sample_routes_with_built_in_guides_without_opens(tmp_path: Path) -> None:
    require_testcase(SAMPLE)
    from xroute.outputs import write_route_outputs
    from xroute.router import route_design

    design = load_design(SAMPLE, use_guide=False)
    assert design.guide_source == "none"
    global_route(design)
    outputs = write_route_outputs(design, route_design(design), tmp_path)
    assert outputs.open_nets == 0
    assert outputs.final["nets_checked"] == int((design.pins_per_net() >= 2).sum()) > 0
    assert outputs.metrics["guide"] == "built-in"
    assert outputs.metrics["global_route"]["overflow"] == 0


def test_ispd19_test3_global_route_has_no_overflow(tmp_path: Path) -> None:
    require_testcase(NO_GUIDE)
    design = load_design(NO_GUIDE)
    assert not design.has_guides
    stats = global_route(design, tmp_path / "t3.guide")
    if NO_GUIDE == "ispd19_test3":
        assert stats.gcells == (130, 130) and stats.layers == 9
        assert stats.nets > 7000
    else:  # the generated design: 6 layers, its GCELLGRID
        assert stats.gcells == (len(design.gcell_lines("x")) - 1, len(design.gcell_lines("y")) - 1)
        assert stats.layers == 6 and stats.nets > 10
    assert stats.overflow == 0
    # Every net with two or more pins has guides.
    starts = design.guide_start
    multi = np.flatnonzero(design.pins_per_net() >= 2)
    assert (starts[multi + 1] > starts[multi]).all()


def test_bad_settings_are_refused(tmp_path: Path) -> None:
    design = drawn(tmp_path)
    with pytest.raises(GlobalRouteArgumentError, match="capacity_percent"):
        global_route(design, capacity_percent=0)
    with pytest.raises(GlobalRouteArgumentError, match="slack"):
        global_route(design, slack=-1)
    with pytest.raises(GlobalRouteArgumentError, match="congestion_cost"):
        global_route(design, congestion_cost=-1.0)
    assert not design.has_guides


runner = CliRunner()


def test_cli_global_route_testcase_and_file_forms(tmp_path: Path) -> None:
    found = require_testcase(SAMPLE)
    out1 = tmp_path / "a.guide"
    r = runner.invoke(app, ["global-route", SAMPLE, "--out", str(out1)])
    assert r.exit_code == 0, r.output
    assert f"{SAMPLE}:" in r.output and str(out1) in r.output
    out2 = tmp_path / "b.guide"
    r = runner.invoke(app, ["global-route", str(found.def_), str(found.lef), "--out", str(out2), "--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.output)
    assert data["guide"] == str(out2) and data["overflow"] == 0
    assert out1.read_bytes() == out2.read_bytes()


def test_cli_global_route_bad_input_is_one_line(tmp_path: Path) -> None:
    lef = tmp_path / "x.lef"
    lef.write_text(LEF)
    r = runner.invoke(app, ["global-route", str(tmp_path / "missing.def"), str(lef), "--out", str(tmp_path / "g")])
    assert r.exit_code == 2
    assert r.output.strip().count("\n") == 0 and "DEF file not found" in r.output
    assert not (tmp_path / "g").exists()


def test_cli_route_without_guide_runs_the_global_router(tmp_path: Path) -> None:
    found = require_testcase(SAMPLE)
    r = runner.invoke(app, ["route", "--lef", str(found.lef), "--def", str(found.def_), "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    assert "guides from the built-in global router" in r.output
    metrics = json.loads((tmp_path / f"{SAMPLE}.metrics.json").read_text())
    assert metrics["guide"] == "built-in" and metrics["inputs"]["guide"] is None
    assert metrics["final"]["open_nets"] == 0


def test_built_in_guides_cost_nothing_to_leave(tmp_path: Path) -> None:
    # No scorer counts wire outside the built-in global router's guides: the maze's out-of-guide factor
    # is built_in_guide_factor (1) there, out_of_guide_factor (3) for guides read from a file.
    from xroute.testcases.generator import make_testcase

    folder = make_testcase(800, 3, tmp_path / "gen")
    lef, def_ = sorted(folder.glob("*.lef")), folder / "gen.def"

    def routed(guide: Path | None, costs: Any = None) -> bytes:
        design = load_design(lef=lef, def_=def_, guide=guide, use_guide=guide is not None)
        if guide is None:
            global_route(design)
        settings = _engine.RouterSettings(iterations=2, costs=costs or _engine.MazeCosts())
        _engine.route(design.engine, settings=settings)
        out = tmp_path / f"r{len(list(tmp_path.glob('r*.def')))}.def"
        design.engine.write_def(str(out))
        return out.read_bytes()

    global_route(load_design(lef=lef, def_=def_, use_guide=False), tmp_path / "built_in.guide")
    from_file = routed(tmp_path / "built_in.guide")  # the same guides, read from a file
    assert routed(None, _engine.MazeCosts(built_in_guide_factor=_engine.MazeCosts().out_of_guide_factor)) == from_file
    built_in = routed(None)
    assert built_in != from_file
    assert routed(None, _engine.MazeCosts(out_of_guide_factor=5)) == built_in  # the file's factor is not used
    assert routed(tmp_path / "built_in.guide", _engine.MazeCosts(out_of_guide_factor=1)) == built_in
