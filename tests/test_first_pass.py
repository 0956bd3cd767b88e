"""The first pass kept for replay (``xroute.session.first_pass``, engine_cpp/loop/first_pass.*): regions
opened in context are in the state the flow routed them in, on a generated design (no contest data)."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import require_testcase

DESIGN = "standin_sample4"  # generated: 120 cells, several regions at region size 2
SIZE = 2


@pytest.fixture(scope="module")
def pass_and_design():
    from xroute import load_design
    from xroute.session import first_pass, open_session

    require_testcase(DESIGN)
    design = load_design(DESIGN)
    session = open_session(design)
    fp = first_pass(session, SIZE)
    return fp, session, design


def test_replaying_every_region_in_context_gives_the_flows_first_pass(pass_and_design) -> None:
    """Each region opened in context and routed in the heuristic order routes what the flow routed there:
    their wirelength and vias add up exactly to iteration 0 of route_design."""
    from xroute import load_design
    from xroute.router import route_design

    fp, _, design = pass_and_design
    colours = {c for _, _, c, _ in fp.regions}
    assert len(fp.regions) >= 8 and colours == {0, 1, 2, 3}
    assert [c for _, _, c, _ in fp.regions] == sorted(c for _, _, c, _ in fp.regions)  # the flow's order
    wl = vias = 0
    for i in range(len(fp.regions)):
        r = fp.open_region(i)
        r.route_rest("heuristic")
        m = r.metrics()
        wl, vias = wl + m["wirelength_dbu"], vias + m["vias"]
    flow = route_design(load_design(DESIGN), region_size=SIZE, iterations=1).iterations[0]
    assert (wl, vias) == (flow.wirelength_dbu, flow.vias) == (fp.report["wirelength_dbu"], fp.report["vias"])
    assert fp.report["violations"] == flow.violations
    assert wl > 0


def test_restore_puts_back_the_routing_before_a_colour(pass_and_design) -> None:
    fp, _, design = pass_and_design
    fp.restore(0)
    assert design.counts()["route_wires"] == 0 and design.counts()["route_vias"] == 0
    counts = []
    for colour in range(1, 5):
        fp.restore(colour)
        counts.append(design.counts()["route_vias"])
    assert counts == sorted(counts) and counts[0] > 0  # each colour adds routing
    assert counts[-1] == fp.report["vias"]
    with pytest.raises(IndexError):
        fp.open_region(len(fp.regions))


def test_neighbours_routing_is_present_in_an_opened_region(pass_and_design) -> None:
    """In context, a region of a later colour sees its earlier neighbours' routing (other nets' metal
    near its edges, crossing points already chosen), which the same box opened on the unrouted design
    does not; a region of colour 0 sees none."""
    fp, session, _ = pass_and_design

    def routed_metal(region) -> int:
        return int((np.asarray(region.grid()["wire_use"]) > 0).sum())

    seen = {}
    for i, (_, box, colour, _) in enumerate(fp.regions):
        in_context = routed_metal(fp.open_region(i))
        fp.restore(0)
        alone = routed_metal(session.open_region(tuple(box)))
        assert alone == 0
        seen.setdefault(colour, []).append(in_context)
    assert max(seen[0]) == 0
    assert all(max(seen[c]) > 0 for c in (1, 2, 3))
    assert sum(v > 0 for c in (1, 2, 3) for v in seen[c]) >= len(fp.regions) // 2


def test_first_pass_bad_arguments() -> None:
    from xroute import load_design
    from xroute.session import first_pass, open_session

    require_testcase(DESIGN)
    session = open_session(load_design(DESIGN))
    with pytest.raises(ValueError, match="region_size"):
        first_pass(session, -1)
    with pytest.raises(ValueError, match="unknown policy"):
        first_pass(session, 2, policy="nope")


def test_region_markers_are_the_violations_metrics_counts(pass_and_design) -> None:
    """``Region.markers()`` lists the markers ``metrics()['violations']`` counts: inside the box, naming
    the region's candidate nets (or -1, an obstruction or pin on no net)."""
    fp, _, design = pass_and_design
    seen = 0
    for i in range(len(fp.regions)):
        r = fp.open_region(i)
        r.route_rest("random", 3)
        markers = r.markers()
        assert len(markers) == r.metrics()["violations"]
        nets = set(np.asarray(r.candidates)[:, 0].tolist())
        xlo, ylo, xhi, yhi = r.box
        for m in markers:
            bx = m["box"]
            assert bx[0] <= xhi and bx[2] >= xlo and bx[1] <= yhi and bx[3] >= ylo, (m, r.box)
            assert m["layer"] in {layer.name for layer in design.layers}, m
            assert any(n in nets for n in m["nets"]), (m, sorted(nets))
            assert all(n in nets or n < 0 or n >= design.num_nets for n in m["nets"]), m
        seen += len(markers)
    assert seen > 0  # a random order on this crowded generated design leaves some
