"""A marker that outlasts its nets' reroutes costs more each check, as far as a via's landing pad
reaches, and keeps its age when it turns into another rule's marker between the same two nets."""

from __future__ import annotations

import pytest

from conftest import contest_found
from xroute import prepare_design, route_design


@pytest.mark.slow
def test_ispd19_test1_at_16_gcells_routes_to_zero() -> None:
    if not contest_found("ispd19_test1"):
        pytest.skip("ispd19_test1 is not on the search path (../shared/testcases)")
    # Before: one Metal1 EndOfLine between two nets' access-via pads (net1185 x net411, at
    # 157450,70500) lasted from iteration 4 to the last; its cost stayed the flat marker penalty.
    design = prepare_design("ispd19_test1")
    result = route_design(design, region_size=16, threads=2)
    assert result.region_size == 16
    assert result.violations == 0 and len(result.iterations) < 16
    conn = design.engine.check_connectivity()
    assert (conn["open_nets"], conn["unrouted_nets"]) == (0, 0)
