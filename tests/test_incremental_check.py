"""After the first iteration the loop checks again only what each iteration changed (when few enough
nets changed; here always); its markers are a whole check's. Routed with and without it, a design
must give the same routed DEF and the same markers after every iteration: any marker the partial
check got wrong would steer the next iteration's rip-up elsewhere."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import available, contest_found
from xroute import RouterSettings, prepare_design, route_design


def routed(name: str, tmp: Path, incremental: bool, **settings: object) -> tuple[bytes, list, list[int]]:
    # A share of 1: every check after the first is partial, however many nets changed; 0: all whole.
    share = 1.0 if incremental else 0.0
    design = prepare_design(name)
    result = route_design(design, settings=RouterSettings(threads=2, partial_check_share=share, **settings))
    out = tmp / f"{name}-{incremental}.def"
    design.write_def(out)
    per_iteration = [it.violations_by_type for it in result.iterations]
    checked = [it.checked_shapes for it in result.iterations]
    return out.read_bytes(), per_iteration, checked


def same_with_and_without(name: str, tmp: Path, **settings: object) -> list[int]:
    whole_def, whole_markers, whole_checked = routed(name, tmp, False, **settings)
    part_def, part_markers, part_checked = routed(name, tmp, True, **settings)
    assert part_markers == whole_markers
    assert part_def == whole_def
    # The first check is whole either way; a later partial one looks at fewer shapes than the whole one.
    assert part_checked[0] == whole_checked[0]
    assert all(p < w for p, w in zip(part_checked[1:], whole_checked[1:]))
    return part_checked


@pytest.mark.parametrize("name", available("ispd18_sample2", "ispd19_sample4"))
def test_partial_checks_give_the_whole_checks_markers(name: str, tmp_path: Path) -> None:
    # No use penalty in the first pass: it leaves shorts for the later iterations to mend.
    costs = RouterSettings().costs.replace(use_penalty=0)
    checked = same_with_and_without(name, tmp_path, costs=costs, region_size=5)
    assert len(checked) >= 2
    assert all(0 < c < checked[0] for c in checked[1:])


def test_the_marked_standin_over_several_iterations(testcase, tmp_path: Path) -> None:
    # Its violations go 15 -> 21 -> 0 at region size 2: markers between two nets, rip-ups of neighbours.
    testcase("standin_marked")
    checked = same_with_and_without("standin_marked", tmp_path, region_size=2)
    assert len(checked) >= 3


@pytest.mark.slow
def test_ispd18_test1_routes_the_same_with_partial_checks(tmp_path: Path) -> None:
    if not contest_found("ispd18_test1"):
        pytest.skip("ispd18_test1 is not on the search path (../shared/testcases)")
    checked = same_with_and_without("ispd18_test1", tmp_path)
    assert len(checked) >= 3


def test_the_share_is_checked() -> None:
    from xroute.errors import RouteArgumentError

    for bad in (-0.1, 1.5, float("nan")):
        with pytest.raises(RouteArgumentError, match="partial_check_share must be in 0..1"):
            route_design(prepare_design(available("ispd18_sample")[0]),
                         settings=RouterSettings(partial_check_share=bad))
