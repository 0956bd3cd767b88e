"""A picture of a routing region for ``render()`` (numpy only: no matplotlib, no CLI).

:func:`render_grid` draws the region grid (the engine Region's ``grid()`` views) seen from above,
one square of ``scale`` pixels per (x, y) node, y upwards, each pixel the top-most thing on any
layer at that node, in this order of precedence (later wins):

============================  ==================================================================
white                          no node on any layer
light grey                     a track node
dark grey                      a blockage (a fixed shape no net may touch)
pale colour of the layer       where a wire would violate metal routed before (other nets' routing)
colour of the layer            a node on the path of a net routed in this region (higher layers on top)
black                          a pin access point of a candidate net
red                            a boundary terminal (where a net's routing outside the region ends)
============================  ==================================================================

Layer colours cycle through :data:`LAYER_COLOURS` (the lowest routing layer first). The output is
``uint8[H, W, 3]`` with ``H = ny * scale``, ``W = nx * scale`` (the picture the gymnasium
``rgb_array`` render mode returns).
"""

from __future__ import annotations

from typing import Any

import numpy as np

LAYER_COLOURS: np.ndarray = np.array([
    (31, 119, 180), (214, 39, 40), (44, 160, 44), (148, 103, 189), (255, 127, 14),
    (23, 190, 207), (140, 86, 75), (227, 119, 194), (188, 189, 34),
], dtype=np.uint8)
"""RGB per routing layer (cycled): blue, red, green, purple, orange, cyan, brown, pink, olive."""

_WHITE = (255, 255, 255)
_TRACK = (225, 225, 225)
_BLOCKED = (110, 110, 110)
_ACCESS_POINT = (0, 0, 0)
_BOUNDARY = (230, 0, 0)
# Grid flag bits (engine_cpp/grid/region_grid.hpp NodeFlag) and the fixed-owner value of a blockage.
_ON_TRACK, _ACCESS, _BOUNDARY_BIT = 1, 2, 4
_BLOCKAGE = -2


def _pale(rgb: np.ndarray) -> np.ndarray:
    return (255 - (255 - rgb.astype(np.int32)) * 35 // 100).astype(np.uint8)


def render_grid(grid: dict[str, np.ndarray], scale: int = 4) -> np.ndarray:
    """uint8[ny * scale, nx * scale, 3]: the region grid seen from above (see the module docstring)."""
    if scale < 1:
        raise ValueError(f"scale must be >= 1, got {scale}")
    flags = np.asarray(grid["flags"])
    nz, ny, nx = flags.shape
    img = np.empty((ny, nx, 3), dtype=np.uint8)
    img[:] = _WHITE
    img[(flags & _ON_TRACK).any(axis=0) != 0] = _TRACK
    img[(np.asarray(grid["fixed_owner"]) == _BLOCKAGE).any(axis=0)] = _BLOCKED
    wire_use = np.asarray(grid["wire_use"])
    routed = np.asarray(grid["routed_net"])
    for z in range(nz):
        img[wire_use[z] > 0] = _pale(LAYER_COLOURS[z % len(LAYER_COLOURS)])
    for z in range(nz):
        img[routed[z] >= 0] = LAYER_COLOURS[z % len(LAYER_COLOURS)]
    img[((flags & _ACCESS) != 0).any(axis=0)] = _ACCESS_POINT
    img[((flags & _BOUNDARY_BIT) != 0).any(axis=0)] = _BOUNDARY
    img = img[::-1]  # row 0 of the picture is the top (highest y)
    if scale > 1:
        img = np.repeat(np.repeat(img, scale, axis=0), scale, axis=1)
    return np.ascontiguousarray(img)


def render_region(region: Any, scale: int = 4) -> np.ndarray:
    """The picture of an engine Region (``xroute.session.Region``) as it is now."""
    return render_grid(region.grid(), scale)


def blank_picture(scale: int = 4) -> np.ndarray:
    """What an env renders with no region open: one white square of 16 x 16 nodes."""
    return np.full((16 * scale, 16 * scale, 3), 255, dtype=np.uint8)
