"""The default region size (region_size 0): 10 GCells, or more while most regions' grids stay within a node
budget and the region does not yet cover the die; fewer, down to 5, while they are over it at 10."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import contest_found
from xroute import _engine
from xroute.config import load_config
from xroute.defaults import LEAST_REGION_GCELLS, REGION_GRID_NODES
from xroute.design import load_design
from xroute.errors import XrouteError
from xroute.router import RouteArgumentError, region_size_for, route_design, router_settings


def generated(tmp_path: Path, split: int, cells: int = 120, merge: int = 1) -> Path:
    """A generated design (GCells of 5.7 x 5.6 um; 120 cells: 6 x 6 GCells, 2,000 cells: 24 x 24) with
    every GCell cut into split x split, or merge x merge GCells made one; its DEF's path."""
    from xroute.testcases.generator import make_testcase

    folder = make_testcase(cells, 3, tmp_path / "small_gcells")
    def_path = folder / "small_gcells.def"
    text = def_path.read_text()

    def finer(m: re.Match[str]) -> str:
        axis, start, count, step = m.group(1), int(m.group(2)), int(m.group(3)), int(m.group(4))
        assert step % split == 0 and (count - 1) % merge == 0
        return f"GCELLGRID {axis} {start} DO {(count - 1) * split // merge + 1} STEP {step * merge // split} ;"

    text, n = re.subn(r"GCELLGRID ([XY]) (\d+) DO (\d+) STEP (\d+) ;", finer, text)
    assert n == 2
    def_path.write_text(text)
    return def_path


def load(def_path: Path) -> object:
    return load_design(lef=sorted(def_path.parent.glob("*.lef")), def_=def_path, use_guide=False)


def test_the_default_region_follows_the_grid_not_the_gcells(tmp_path: Path) -> None:
    # 2,000 cells, 24 GCells across: regions of 17 GCells keep three in four grids within the budget
    assert region_size_for(load(generated(tmp_path / "a", 1, cells=2000)), 0) == 17
    # the same design with every GCell cut in four: the same region boxes, twice the GCells a side
    design = load(generated(tmp_path / "b", 2, cells=2000))
    assert region_size_for(design, 0) == 34
    assert region_size_for(design, 4) == 4  # a size given is kept


def test_the_default_region_stops_where_it_covers_the_die(tmp_path: Path) -> None:
    # 120 cells: 6 x 6 GCells, so 10 (the least) covers the die; cut in four, 12 x 12 GCells
    assert region_size_for(load(generated(tmp_path / "a", 1)), 0) == 10
    assert region_size_for(load(generated(tmp_path / "b", 2)), 0) == 12


def test_the_default_region_shrinks_where_ten_gcells_are_over_the_budget(tmp_path: Path) -> None:
    # 2,000 cells with 3 x 3 GCells made one: 8 GCells across, so 10 cover the whole die, whose grid
    # is over the budget (17 of the small GCells are the most that stay within it): 5 (15 small)
    design = load(generated(tmp_path, 1, cells=2000, merge=3))
    size = region_size_for(design, 0)

    def nodes(s: int) -> float:
        return _engine.region_grid_nodes(design.engine, s)

    assert nodes(10) > REGION_GRID_NODES
    assert size == LEAST_REGION_GCELLS == 5
    assert nodes(5) <= REGION_GRID_NODES < nodes(6)


def test_a_run_at_the_default_routes_with_the_resolved_region(tmp_path: Path) -> None:
    design = load(generated(tmp_path, 2))
    result = route_design(design, iterations=2)
    assert result.settings.region_size == 0
    assert [it.region_size for it in result.iterations] == [12] * len(result.iterations)
    assert result.region_size == 12
    given = route_design(load(generated(tmp_path / "given", 2)), iterations=1, region_size=6)
    assert given.iterations[0].region_size == 6 and given.region_size == 6


def test_a_negative_region_size_is_refused(tmp_path: Path) -> None:
    with pytest.raises(RouteArgumentError, match="at least 1 GCell"):
        router_settings(region_size=-1)
    config = tmp_path / "c.yaml"
    config.write_text("region:\n  region_size: 0\n")
    assert load_config(config).region.region_size == 0
    config.write_text("region:\n  region_size: -1\n")
    with pytest.raises(XrouteError, match=r"c.yaml:2: .*region_size"):
        load_config(config)


@pytest.mark.parametrize(("name", "size"), [("ispd18_test1", 15), ("ispd19_test1", 16), pytest.param("ispd19_test3", 10, marks=pytest.mark.slow)])
def test_contest_designs_default_region_sizes(name: str, size: int) -> None:
    if not contest_found(name):
        pytest.skip(f"{name} is not on the search path (../shared/testcases)")
    # ispd18_test1: GCells of 3 x 2.85 um, tracks 0.2 / 0.19 um; ispd19_test1: 1 um, 0.1 um;
    # ispd19_test3: 1.5 um, 0.1 um, and a grid line through many off-track access points
    assert region_size_for(load_design(name), 0) == size
