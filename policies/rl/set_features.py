"""Compact per-candidate features for the set scorer (numpy only; no engine, no torch at import).

One row of :data:`SET_FEATURES` per candidate net, computed once when a region opens: the ten
columns of :func:`~xroute.policies.rl.observation.net_features` (counts, box shares, overlaps,
heuristic rank), where the net's terminal box lies in the region (its four edges as shares of
the region box, and its half perimeter), how crowded that box is (share of the region's 2D cells
under the box that hold an obstacle of :func:`~xroute.policies.rl.observation.obstacle_grid`;
share of the other candidates' terminal nodes inside it) and the region's size (candidate count).
About 80 bytes per candidate, against 344 KiB for the grids of :mod:`observation`; the relations
between nets are left to the scorer's attention over the set (it sees every box).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from xroute.policies.rl.observation import NET_FEATURES, net_features, obstacle_grid

SET_FEATURES: tuple[str, ...] = NET_FEATURES + (
    "box_xlo",  # terminal box edges as shares of the region box (0 = its low edge, 1 = its high edge)
    "box_ylo",
    "box_xhi",
    "box_yhi",
    "half_perimeter",  # (bbox_width + bbox_height) / 2
    "boundary_share",  # boundary terminals / terminals
    "obstacle_density",  # share of 2D grid cells under the terminal box holding an obstacle on any layer
    "terminal_density",  # share of the other candidates' terminal nodes inside this net's terminal box
    "candidates",  # log2(1 + N) / 6, the same on every row
)
"""Columns of :func:`set_features`."""

_NET, _PINS, _TERMINALS, _APS, _XLO, _YLO, _XHI, _YHI, _NET_PINS = range(9)


def _box_cells(coords: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Index range [a, b) of the sorted grid ``coords`` inside each closed interval [lo, hi]."""
    a = np.searchsorted(coords, lo, side="left")
    b = np.searchsorted(coords, hi, side="right")
    return a, np.maximum(a, b)


def set_features(grid: dict[str, np.ndarray], rows: np.ndarray, mask: np.ndarray,
                 box: tuple[int, int, int, int]) -> np.ndarray:
    """float32[N, len(SET_FEATURES)] from a region's grid views (:meth:`Region.grid`), its candidate
    rows (int32[N, C], the engine's feature columns; the first 9 are read, which keep their place
    as columns are added), the unrouted mask and the region box (DBU)."""
    mask = np.asarray(mask, dtype=bool)
    r = np.asarray(rows, dtype=np.int64).reshape(len(mask), -1)[:, :9]
    n = len(r)
    out = np.zeros((n, len(SET_FEATURES)), dtype=np.float32)
    if n == 0:
        return out
    base = net_features(r, mask, box)
    k = len(NET_FEATURES)
    out[:, :k] = base
    x0, y0, x1, y1 = (int(v) for v in box)
    w, h = max(1, x1 - x0), max(1, y1 - y0)
    out[:, k + 0] = np.clip((r[:, _XLO] - x0) / w, -1, 2)
    out[:, k + 1] = np.clip((r[:, _YLO] - y0) / h, -1, 2)
    out[:, k + 2] = np.clip((r[:, _XHI] - x0) / w, -1, 2)
    out[:, k + 3] = np.clip((r[:, _YHI] - y0) / h, -1, 2)
    out[:, k + 4] = (base[:, 5] + base[:, 6]) / 2
    out[:, k + 5] = np.clip(r[:, _TERMINALS] - r[:, _PINS], 0, None) / np.maximum(1, r[:, _TERMINALS])
    xs = np.asarray(grid["xs"], dtype=np.int64).reshape(-1)
    ys = np.asarray(grid["ys"], dtype=np.int64).reshape(-1)
    if xs.size and ys.size:
        ids = r[:, _NET].astype(np.int32)
        obst = obstacle_grid(grid, ids[mask], ids[~mask]).any(axis=0)  # (ny, nx)
        integral = np.zeros((len(ys) + 1, len(xs) + 1), dtype=np.int64)
        integral[1:, 1:] = obst.astype(np.int64).cumsum(0).cumsum(1)
        ax, bx = _box_cells(xs, r[:, _XLO], r[:, _XHI])
        ay, by = _box_cells(ys, r[:, _YLO], r[:, _YHI])
        count = integral[by, bx] - integral[ay, bx] - integral[by, ax] + integral[ay, ax]
        area = (bx - ax) * (by - ay)
        out[:, k + 6] = np.where(area > 0, count / np.maximum(1, area), 0.0)
        # Terminal nodes of every candidate (2D), counted inside each net's box.
        access = np.asarray(grid["access_net"])
        zi, yi, xi = np.nonzero(access >= 0)
        owner = access[zi, yi, xi]
        cand = np.isin(owner, ids)
        tx, ty, towner = xs[xi[cand]], ys[yi[cand]], owner[cand]
        if tx.size:
            inside = ((tx[None, :] >= r[:, _XLO, None]) & (tx[None, :] <= r[:, _XHI, None])
                      & (ty[None, :] >= r[:, _YLO, None]) & (ty[None, :] <= r[:, _YHI, None])
                      & (towner[None, :] != ids[:, None]))
            out[:, k + 7] = inside.sum(axis=1) / tx.size
    out[:, k + 8] = np.log2(1.0 + n) / 6.0
    return out


def region_set_features(region: Any) -> np.ndarray:
    """:func:`set_features` of an engine Region in its current state."""
    from xroute.policies.rl.observation import unrouted_mask

    return set_features(region.grid(), region.candidates, unrouted_mask(region), tuple(region.box))
