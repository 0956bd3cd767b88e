"""Observations for learning policies (policies/rl/observation.py): alignment and channels."""

from __future__ import annotations

import numpy as np
import pytest

from xroute.policies.rl.observation import (
    ALIGNED_SHAPE,
    NET_CHANNELS,
    NET_FEATURES,
    align,
    net_features,
    observe_arrays,
)


def test_align_pools_by_ceil_stride_and_pads_at_the_high_end() -> None:
    g = np.zeros((9, 5, 130), dtype=np.uint8)
    g[0, 0, 0] = 1
    g[4, 2, 64] = 1  # z stride 3 -> 1, y stride 1 -> 2, x stride ceil(130/64) = 3 -> 21
    g[8, 4, 129] = 1  # -> (2, 4, 43)
    a = align(g)
    assert a.shape == ALIGNED_SHAPE and a.dtype == np.float32
    assert np.argwhere(a).tolist() == [[0, 0, 0], [1, 2, 21], [2, 4, 43]]
    assert a.sum() == 3


def test_align_keeps_leading_axes_and_any_one_in_a_window_survives() -> None:
    g = np.zeros((2, 4, 3, 128, 64))
    g[1, 3, 1, 127, 63] = 1
    a = align(g)
    assert a.shape == (2, 4) + ALIGNED_SHAPE
    # 3 layers -> stride 1; 128 rows -> stride 2 (127 -> 63); 64 columns -> stride 1.
    assert np.argwhere(a).tolist() == [[1, 3, 1, 63, 63]]


def test_align_of_a_tiny_grid_is_zero_padded() -> None:
    a = align(np.ones((1, 2, 3)))
    expected = np.zeros(ALIGNED_SHAPE, dtype=np.float32)
    expected[0, :2, :3] = 1
    assert np.array_equal(a, expected)
    with pytest.raises(ValueError, match="at least 3 axes"):
        align(np.ones((4, 4)))


def _tiny_grid() -> dict[str, np.ndarray]:
    """A 2-layer, 3 x 4 grid: net 7 has a pin (pinRef 0) with access points at (z0, y1, x1) and
    (z0, y1, x2), and a boundary terminal at (z1, y0, x3); net 9 has one access point at
    (z0, y2, x0) (pinRef 5); a blockage at (z1, y2, x2); net 9 has routed through (z1, y1, x0)."""
    shape = (2, 3, 4)
    g = {
        "flags": np.ones(shape, dtype=np.uint8),
        "fixed_owner": np.full(shape, -1, dtype=np.int32),
        "wire_use": np.zeros(shape, dtype=np.uint16),
        "routed_net": np.full(shape, -1, dtype=np.int32),
        "access_net": np.full(shape, -1, dtype=np.int32),
        "access_pin": np.full(shape, -1, dtype=np.int32),
    }
    for z, y, x, net, pin in ((0, 1, 1, 7, 0), (0, 1, 2, 7, 0), (0, 2, 0, 9, 5)):
        g["flags"][z, y, x] |= 2
        g["access_net"][z, y, x] = net
        g["access_pin"][z, y, x] = pin
        g["fixed_owner"][z, y, x] = net
    g["flags"][1, 0, 3] |= 4
    g["access_net"][1, 0, 3] = 7
    g["fixed_owner"][1, 2, 2] = -2
    g["flags"][0, 0, 3] = 0  # a node that does not exist
    g["fixed_owner"][0, 0, 3] = -2
    g["routed_net"][1, 1, 0] = 9
    return g


# net, pins, terminals, access_points, bbox (xlo, ylo, xhi, yhi), net_pins
ROWS = np.array([[7, 1, 2, 3, 100, 0, 300, 100, 4], [9, 1, 1, 1, 0, 200, 0, 200, 2]], dtype=np.int32)
BOX = (0, 0, 400, 200)


def test_channels_of_a_hand_made_region() -> None:
    g = _tiny_grid()
    obs = observe_arrays(g, ROWS, np.array([True, False]), BOX)
    assert obs.nets.shape == (2, NET_CHANNELS) + ALIGNED_SHAPE
    assert obs.net_ids.tolist() == [7, 9] and obs.mask.tolist() == [True, False]
    # Channel 0: terminals (access points and the boundary terminal) of each net.
    assert np.argwhere(obs.nets[0, 0]).tolist() == [[0, 1, 1], [0, 1, 2], [1, 0, 3]]
    assert np.argwhere(obs.nets[1, 0]).tolist() == [[0, 2, 0]]
    # +x: (0,1,1) has its pin's access point to the right; -x: (0,1,2) to the left; no others.
    assert np.argwhere(obs.nets[0, 1]).tolist() == [[0, 1, 1]]
    assert np.argwhere(obs.nets[0, 2]).tolist() == [[0, 1, 2]]
    assert obs.nets[0, 3:].sum() == 0 and obs.nets[1, 1:].sum() == 0
    # Obstacles: the blockage, net 9's route and its (routed) access point; not the missing node,
    # not net 7's own (unrouted) pin.
    assert np.argwhere(obs.obstacle).tolist() == [[0, 2, 0], [1, 1, 0], [1, 2, 2]]


def test_same_grid_with_both_nets_unrouted_has_no_pin_obstacle() -> None:
    g = _tiny_grid()
    g["routed_net"][:] = -1
    g["wire_use"][0, 0, 0] = 3
    obs = observe_arrays(g, ROWS, np.array([True, True]), BOX)
    assert np.argwhere(obs.obstacle).tolist() == [[0, 0, 0], [1, 2, 2]]


def test_net_features_exact_values() -> None:
    f = net_features(ROWS, np.array([True, False]), BOX)
    assert f.shape == (2, len(NET_FEATURES)) and f.dtype == np.float32
    col = {name: i for i, name in enumerate(NET_FEATURES)}
    assert f[0, col["pins"]] == pytest.approx(1 / 6)  # log2(2) / 6
    assert f[0, col["access_points"]] == pytest.approx(2 / 6)  # log2(4) / 6
    assert f[0, col["boundary_terminals"]] == pytest.approx(1 / 6)
    assert f[1, col["boundary_terminals"]] == 0
    assert f[0, col["bbox_width"]] == pytest.approx(0.5) and f[0, col["bbox_height"]] == pytest.approx(0.5)
    # Net 9's box (a point at (0, 200)) does not touch net 7's (100..300, 0..100).
    assert f[:, col["overlap"]].tolist() == [0.0, 0.0]
    # Heuristic: net 9 (half perimeter 0) first.
    assert f[:, col["heuristic_rank"]].tolist() == [1.0, 0.0]
