"""A region routed net by net from Python (what the learning environments drive).

``_engine.RoutingSession(db).open_region(box)`` gives a Region: candidate nets
with their features, live numpy views of the region grid, ``route_net(i)`` in
any order, ``metrics()``, and ``commit()`` into the design.
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import pick, require_testcase

# The contest samples, or their generated stand-ins when the contest data is missing.
SAMPLE, SAMPLE2 = pick("ispd18_sample"), pick("ispd18_sample2")


def fresh(name: str):
    from xroute import load_design

    require_testcase(name)
    return load_design(name)


def whole_die(design) -> tuple[int, int, int, int]:
    return tuple(int(v) for v in design.die_area)


def test_a_region_over_the_whole_sample_routes_every_net_without_opens() -> None:
    from xroute import _engine

    d = fresh(SAMPLE)
    session = _engine.RoutingSession(d.engine)
    region = session.open_region(whole_die(d))
    cands = region.candidates
    # Every net of ispd18_sample (and of its stand-in) has all its pins, two or more, inside the die:
    # all are candidates, each with its pins as terminals.
    assert cands.shape == (d.num_nets, len(_engine.POLICY_FEATURES))
    assert sorted(cands[:, 0].tolist()) == list(range(d.num_nets))
    if SAMPLE == "ispd18_sample":
        assert (cands[:, 1] == 2).all() and (cands[:, 2] == 2).all()
    ppn = d.pins_per_net()[cands[:, 0]]
    assert (ppn >= 2).all() and (cands[:, 1] == ppn).all() and (cands[:, 2] == ppn).all()
    assert region.unrouted() == list(range(d.num_nets))

    for i in reversed(range(len(cands))):
        result = region.route_net(i)
        assert result["routed"] and result["unreached"] == 0
        assert result["wirelength_dbu"] > 0 or result["vias"] > 0
    assert region.unrouted() == []
    with pytest.raises(ValueError, match="already routed"):
        region.route_net(0)
    with pytest.raises(IndexError):
        region.route_net(len(cands))

    m = region.metrics()
    assert m["nets_routed"] == d.num_nets and m["unreached"] == 0
    region.commit()
    with pytest.raises(RuntimeError, match="committed"):
        region.route_net(0)
    conn = d.engine.check_connectivity()
    assert conn["open_nets"] == 0 and conn["unrouted_nets"] == 0
    # The region's metrics are the design's once committed.
    totals = d.engine.metrics()
    assert totals["wirelength_dbu"] == m["wirelength_dbu"]
    assert totals["vias"] == m["vias"]


def test_grid_views_are_live_and_shaped_z_y_x() -> None:
    from xroute import _engine

    d = fresh(SAMPLE)
    region = _engine.RoutingSession(d.engine).open_region(whole_die(d))
    g = region.grid()
    nz = len(d.routing_layers)
    shape = (nz, len(g["ys"]), len(g["xs"]))
    for key in ("flags", "fixed_owner", "wire_use", "access_net", "routed_net", "marker_cost"):
        assert g[key].shape == shape, key
    assert np.all(np.diff(g["xs"]) > 0) and np.all(np.diff(g["ys"]) > 0)
    types = region.node_type()
    assert types.shape == shape
    # Access points are where the candidates' pins are reached.
    assert int((types == 3).sum()) == int(((g["flags"] & 2) > 0).sum()) > 0
    assert set(np.unique(g["access_net"][g["access_net"] >= 0]).tolist()) <= set(range(d.num_nets))
    assert (g["routed_net"] == -1).all()
    first = int(region.candidates[0, 0])
    region.route_net(0)
    # The same array object now shows the routed net's nodes.
    assert (g["routed_net"] == first).any()


def test_any_order_connects_every_net_and_repeats_byte_for_byte() -> None:
    from xroute import _engine

    def run(order_key):
        d = fresh(SAMPLE2)
        region = _engine.RoutingSession(d.engine).open_region(whole_die(d))
        for i in order_key(len(region.candidates)):
            region.route_net(int(i))
        region.commit()
        return d.def_text(), d.engine.check_connectivity()["open_nets"]

    forward, opens_f = run(lambda n: range(n))
    again, _ = run(lambda n: range(n))
    backward, opens_b = run(lambda n: reversed(range(n)))
    assert forward == again
    assert opens_f == opens_b == 0


def test_a_routed_region_reopened_rips_up_and_reroutes_its_nets() -> None:
    from xroute import _engine

    d = fresh(SAMPLE)
    session = _engine.RoutingSession(d.engine)
    box = whole_die(d)
    first = session.open_region(box)
    first.route_rest("heuristic")
    first.commit()
    wirelength = d.engine.metrics()["wirelength_dbu"]
    again = session.open_region(box)
    # Every net is routed now: reopening the box rips them up (their pins are the terminals).
    assert len(again.candidates) == d.num_nets
    again.route_rest("heuristic")
    again.commit()
    assert d.engine.check_connectivity()["open_nets"] == 0
    assert d.engine.metrics()["wirelength_dbu"] == wirelength


def test_a_region_of_ispd18_test1_connects_every_net_it_holds_whole() -> None:
    from xroute import _engine

    name = pick("ispd18_test1")  # without the contest data: the stand-in (7 x 7 GCells)
    d = fresh(name)
    session = _engine.RoutingSession(d.engine)
    xs, ys = session.gcell_lines
    lo, hi = (30, 35) if name == "ispd18_test1" else (1, 6)  # 5 x 5 GCells in the middle of the die
    box = (int(xs[lo]), int(ys[lo]), int(xs[hi]), int(ys[hi]))
    region = session.open_region(box)
    cands = region.candidates
    assert len(cands) > (50 if name == "ispd18_test1" else 10)
    region.route_rest("heuristic")
    m = region.metrics()
    assert m["nets_routed"] == len(cands) and m["unreached"] == 0
    region.commit()

    # Nets whose every pin has an access point in the box are routed whole here (the
    # region's terminals are the pins' points inside it): none may be open.
    pa = d.engine.pin_access()
    start = d.net_pin_start

    def in_box(p: int) -> bool:
        pts = pa["points"][pa["start"][p]:pa["start"][p + 1]]
        return any(box[0] <= x <= box[2] and box[1] <= y <= box[3] for x, y, *_ in pts.tolist())

    inside = set()
    for n in cands[:, 0].tolist():
        if all(in_box(p) for p in range(start[n], start[n + 1])):
            inside.add(d.net_names[n])
    assert len(inside) > (10 if name == "ispd18_test1" else 1)
    open_names = {o["net"] for o in d.engine.check_connectivity()["opens"]}
    assert not (inside & open_names)
    # The rest of the die is unrouted: every other multi-pin net is still open.
    assert len(open_names) == int((d.pins_per_net() >= 2).sum()) - len(inside)
