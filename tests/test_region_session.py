"""A region routed net by net from Python (what the learning environments drive).

``_engine.RoutingSession(db).open_region(box)`` gives a Region: candidate nets
with their features, live numpy views of the region grid, ``route_net(i)`` in
any order, ``metrics()``, and ``commit()`` into the design.
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import require_testcase


def fresh(name: str):
    from xroute import load_design

    require_testcase(name)
    return load_design(name)


def whole_die(design) -> tuple[int, int, int, int]:
    return tuple(int(v) for v in design.die_area)


def test_a_region_over_the_whole_sample_routes_every_net_without_opens() -> None:
    from xroute import _engine

    d = fresh("ispd18_sample")
    session = _engine.RoutingSession(d.engine)
    region = session.open_region(whole_die(d))
    cands = region.candidates
    # Every net of ispd18_sample has two pins inside the die: all are candidates.
    assert cands.shape == (d.num_nets, len(_engine.POLICY_FEATURES))
    assert sorted(cands[:, 0].tolist()) == list(range(d.num_nets))
    assert (cands[:, 1] == 2).all() and (cands[:, 2] == 2).all()
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

    d = fresh("ispd18_sample")
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
        d = fresh("ispd18_sample2")
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

    d = fresh("ispd18_sample")
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

    d = fresh("ispd18_test1")
    session = _engine.RoutingSession(d.engine)
    xs, ys = session.gcell_lines
    box = (int(xs[30]), int(ys[30]), int(xs[35]), int(ys[35]))  # 5 x 5 GCells in the middle of the die
    region = session.open_region(box)
    cands = region.candidates
    assert len(cands) > 50
    region.route_rest("heuristic")
    m = region.metrics()
    assert m["nets_routed"] == len(cands) and m["unreached"] == 0
    region.commit()

    # Nets whose pins all lie in the box are routed whole here: none may be open.
    pa = d.engine.pin_access()
    start = d.net_pin_start
    inside = set()
    for n in cands[:, 0].tolist():
        pts = [pa["points"][pa["start"][p]] for p in range(start[n], start[n + 1])]
        if all(box[0] <= x <= box[2] and box[1] <= y <= box[3] for x, y, *_ in pts):
            inside.add(d.net_names[n])
    assert len(inside) > 10
    open_names = {o["net"] for o in d.engine.check_connectivity()["opens"]}
    assert not (inside & open_names)
    # The rest of the die is unrouted: every other multi-pin net is still open.
    assert len(open_names) == int((d.pins_per_net() >= 2).sum()) - len(inside)
