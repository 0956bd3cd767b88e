"""A large design's whole check runs in horizontal bands of about ``band_shapes`` shapes
(drc/design_check.hpp), each band judged from the shapes near it with every conductor near it
whole. The markers must be the whole check's however the design is cut: here small designs are
cut into many thin bands, so that band edges cross wires, pins and markers everywhere."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import available
from xroute import RouterSettings, prepare_design, route_design

# No use penalty and one iteration: the routing keeps shorts, spacing and end-of-line markers.
FIRST_PASS = dict(costs=RouterSettings().costs.replace(use_penalty=0), region_size=5, iterations=1, threads=2)


@pytest.mark.parametrize("name", available("ispd18_sample2", "ispd19_sample4"))
def test_bands_give_the_whole_checks_markers(name: str) -> None:
    design = prepare_design(name)
    route_design(design, settings=RouterSettings(**FIRST_PASS))
    whole = design.engine.check_drc(band_shapes=0)
    assert whole, "the first pass should leave markers to compare"
    shapes = len(design.engine.drc_shapes())
    for band in (shapes // 3, 2_000, 300):
        assert design.engine.check_drc(band_shapes=band, threads=2) == whole, band


def routed(name: str, tmp: Path, band_shapes: int, share: float, region_size: int = 5) -> tuple[bytes, list, list[int]]:
    design = prepare_design(name)
    settings = RouterSettings(threads=2, region_size=region_size, check_band_shapes=band_shapes, partial_check_share=share,
                              costs=RouterSettings().costs.replace(use_penalty=0))
    result = route_design(design, settings=settings)
    out = tmp / f"{name}-{band_shapes}-{share}.def"
    design.write_def(out)
    return out.read_bytes(), [it.violations_by_type for it in result.iterations], [it.checked_shapes for it in result.iterations]


@pytest.mark.parametrize("name", available("ispd18_sample2"))
def test_the_router_routes_the_same_with_banded_checks(name: str, tmp_path: Path) -> None:
    # Every check whole (no partial checks), in bands or at once: the same markers after every
    # iteration, so the same routed DEF.
    whole_def, whole_markers, whole_checked = routed(name, tmp_path, 0, 0.0)
    band_def, band_markers, band_checked = routed(name, tmp_path, 300, 0.0)
    assert len(whole_markers) >= 2
    assert band_markers == whole_markers
    assert band_def == whole_def
    # A shape near two bands is looked at by both: more shapes checked is the sign that bands ran.
    assert all(b > w for b, w in zip(band_checked, whole_checked))


@pytest.mark.parametrize("name", available("ispd18_sample2", "ispd19_sample4"))
def test_partial_checks_in_bands_give_the_whole_checks_markers(name: str, tmp_path: Path) -> None:
    # Every check after the first partial (a share of 1): where more than a band's share of the nets
    # changed, the zone is judged band by band, each changed net's MinArea markers in one band.
    # At region size 2 ispd19_sample4 keeps MinArea markers on rerouted nets after an iteration.
    whole_def, whole_markers, _ = routed(name, tmp_path, 0, 0.0, region_size=2)
    band_def, band_markers, band_checked = routed(name, tmp_path, 300, 1.0, region_size=2)
    assert len(whole_markers) >= 2
    assert band_markers == whole_markers
    assert band_def == whole_def
    assert all(0 < c for c in band_checked)


def test_the_band_size_is_checked() -> None:
    from xroute.errors import RouteArgumentError

    design = prepare_design(available("ispd18_sample")[0])
    with pytest.raises(ValueError, match="band_shapes must be >= 0"):
        design.engine.check_drc(band_shapes=-1)
    with pytest.raises(RouteArgumentError, match="check_band_shapes"):
        route_design(design, settings=RouterSettings(check_band_shapes=-1))
