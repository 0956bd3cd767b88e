"""What a learning policy sees of a routing region (numpy only; no engine, no torch at import).

Layout (the XRoute paper's, aligned to a standard grid of ``ALIGNED_SHAPE`` = (z, y, x) = (3, 64, 64)):

* ``obstacle`` float32[3, 64, 64]: 1 where a node of the region grid is taken: a blockage (a fixed
  shape no net may touch), a node where a wire would violate already-routed metal (routing
  committed before this region, or nets routed in this region so far), a node on the path of a
  net routed in this region, a fixed shape owned by a net that is not an unrouted candidate
  (pins of routed or non-candidate nets), and the terminals of candidates already routed.
* ``nets`` float32[N, 7, 3, 64, 64], one block per candidate net (the region's candidate rows,
  in the engine's order): channel 0 = the node is a terminal of this net (a pin access point or a
  boundary terminal where its routing outside the region ends); channels 1..6 = for the
  directions +x, -x, +y, -y, +z, -z, the node is a pin access point of this net and its
  neighbour in that direction is an access point of the same pin.
* ``net_features`` float32[N, S], columns :data:`NET_FEATURES` (counts as log2(1 + n) / 6, so 63
  gives 1; lengths as a share of the region box).
* ``mask`` bool[N]: True while the candidate is unrouted (a legal action).
* ``net_ids`` int32[N]: the design's net id of each candidate.

Alignment (:func:`align`): stride s = ceil(D / T) per axis (D the region grid's size, T the
target), each output cell the maximum over its s-window (a 1 anywhere inside survives), zero
padding up to T at the high end. :func:`observe` computes exactly ``align`` of the full-size
channels, but scatters the few terminal nodes straight into the aligned grid instead of
building N x 7 full-size grids.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from xroute.net_order import FEATURE_COLUMNS

ALIGNED_SHAPE: tuple[int, int, int] = (3, 64, 64)
"""The standard grid (z, y, x) every region is aligned to."""

NET_CHANNELS = 7
"""Channels per candidate net: terminal, then same-pin neighbour along +x, -x, +y, -y, +z, -z."""

NET_FEATURES: tuple[str, ...] = (
    "pins",  # pins of the net inside the region, log2(1 + n) / 6
    "terminals",  # all terminals in the region (pins + boundary crossings), log2(1 + n) / 6
    "access_points",  # terminal nodes in the region grid, log2(1 + n) / 6
    "boundary_terminals",  # terminals - pins (where routing outside the region must be met), log2(1 + n) / 6
    "net_pins",  # pins of the whole net, log2(1 + n) / 6
    "bbox_width",  # terminal bounding box width / region box width
    "bbox_height",  # terminal bounding box height / region box height
    "overlap",  # share of the other candidates whose terminal bounding boxes intersect this one's
    "overlap_unrouted",  # the same counting only unrouted other candidates
    "heuristic_rank",  # position in the built-in heuristic order / max(1, N - 1) (0 = routed first)
)
"""Names of the per-net scalar features (columns of ``net_features``)."""

# Grid flag bits (engine_cpp/grid/region_grid.hpp NodeFlag).
_ACCESS = 2
_OWNER_MIXED = -2
# Columns of the engine's candidate rows, by name (xroute.net_order.FEATURE_COLUMNS; later columns are
# not read here, and rows from before they were added, 9 columns wide, still work).
_NET, _PINS, _TERMINALS, _APS, _XLO, _YLO, _XHI, _YHI, _NET_PINS = (
    FEATURE_COLUMNS.index(c) for c in ("net", "pins", "terminals", "access_points", "bbox_xlo", "bbox_ylo", "bbox_xhi",
                                      "bbox_yhi", "net_pins"))


def _rows(rows: Any, dtype: type) -> np.ndarray:
    """Candidate rows as a 2-D array (an empty or flat input as rows of FEATURE_COLUMNS)."""
    r = np.asarray(rows, dtype=dtype)
    return r if r.ndim == 2 else r.reshape(-1, len(FEATURE_COLUMNS))


@dataclass
class RegionObservation:
    """One region's observation (see the module docstring for the layout)."""

    obstacle: np.ndarray  # float32[3, 64, 64]
    nets: np.ndarray  # float32[N, 7, 3, 64, 64]
    net_features: np.ndarray  # float32[N, len(NET_FEATURES)]
    mask: np.ndarray  # bool[N]: True = unrouted
    net_ids: np.ndarray  # int32[N]


def _strides(shape: tuple[int, ...]) -> tuple[int, ...]:
    return tuple(max(1, -(-d // t)) for d, t in zip(shape, ALIGNED_SHAPE))


def align(grid: np.ndarray) -> np.ndarray:
    """The last three axes (Z, Y, X) of a 0/1 grid mapped to :data:`ALIGNED_SHAPE` (max over
    windows of stride ceil(D / T), zero padding at the high end); leading axes kept; float32."""
    g = np.asarray(grid)
    if g.ndim < 3:
        raise ValueError(f"align needs at least 3 axes (z, y, x), got shape {g.shape}")
    lead, dims = g.shape[:-3], g.shape[-3:]
    strides = _strides(dims)
    padded = [-(-d // s) * s for d, s in zip(dims, strides)]
    if list(dims) != padded:
        pad = [(0, 0)] * len(lead) + [(0, p - d) for d, p in zip(dims, padded)]
        g = np.pad(g, pad)
    blocks = lead + sum(((p // s, s) for p, s in zip(padded, strides)), ())
    k = len(lead)
    pooled = g.reshape(blocks).max(axis=(k + 1, k + 3, k + 5)) if g.size else np.zeros(
        lead + tuple(p // s for p, s in zip(padded, strides)), dtype=g.dtype)
    out = np.zeros(lead + ALIGNED_SHAPE, dtype=np.float32)
    out[(...,) + tuple(slice(0, n) for n in pooled.shape[-3:])] = pooled
    return out


def _log_count(values: np.ndarray) -> np.ndarray:
    return (np.log2(1.0 + np.maximum(values, 0).astype(np.float64)) / 6.0).astype(np.float32)


def _heuristic_rank(rows: np.ndarray) -> np.ndarray:
    n = len(rows)
    if n == 0:
        return np.zeros(0, dtype=np.float32)
    hpwl = (rows[:, _XHI] - rows[:, _XLO]) + (rows[:, _YHI] - rows[:, _YLO])
    order = np.lexsort((rows[:, _NET], -rows[:, _TERMINALS], hpwl))
    rank = np.empty(n, dtype=np.float64)
    rank[order] = np.arange(n)
    return (rank / max(1, n - 1)).astype(np.float32)


def net_features(rows: np.ndarray, mask: np.ndarray, box: tuple[int, int, int, int]) -> np.ndarray:
    """float32[N, len(NET_FEATURES)] from the engine's candidate rows (int32[N, len(FEATURE_COLUMNS)]), the unrouted
    mask and the region box (DBU)."""
    r = _rows(rows, np.int64)
    n = len(r)
    width = max(1, int(box[2]) - int(box[0]))
    height = max(1, int(box[3]) - int(box[1]))
    w = np.clip(r[:, _XHI] - r[:, _XLO], 0, None)
    h = np.clip(r[:, _YHI] - r[:, _YLO], 0, None)
    # Closed-box intersection between every pair of terminal bounding boxes.
    inter = ((r[:, None, _XLO] <= r[None, :, _XHI]) & (r[None, :, _XLO] <= r[:, None, _XHI])
             & (r[:, None, _YLO] <= r[None, :, _YHI]) & (r[None, :, _YLO] <= r[:, None, _YHI]))
    np.fill_diagonal(inter, False)
    others = max(1, n - 1)
    out = np.zeros((n, len(NET_FEATURES)), dtype=np.float32)
    out[:, 0] = _log_count(r[:, _PINS])
    out[:, 1] = _log_count(r[:, _TERMINALS])
    out[:, 2] = _log_count(r[:, _APS])
    out[:, 3] = _log_count(r[:, _TERMINALS] - r[:, _PINS])
    out[:, 4] = _log_count(r[:, _NET_PINS])
    out[:, 5] = w / width
    out[:, 6] = h / height
    out[:, 7] = inter.sum(axis=1) / others
    out[:, 8] = (inter & np.asarray(mask, dtype=bool)[None, :]).sum(axis=1) / others
    out[:, 9] = _heuristic_rank(r)
    return out


def _same_pin_neighbours(pin: np.ndarray) -> list[np.ndarray]:
    """For +x, -x, +y, -y, +z, -z: bool grids, True where the node is a pin access point and its
    neighbour that way is an access point of the same pin."""
    out = []
    for axis in (2, 1, 0):  # x, y, z in a (z, y, x) grid
        plus = np.zeros(pin.shape, dtype=bool)
        minus = np.zeros(pin.shape, dtype=bool)
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis] = slice(0, -1)
        hi[axis] = slice(1, None)
        same = (pin[tuple(lo)] == pin[tuple(hi)]) & (pin[tuple(lo)] >= 0)
        plus[tuple(lo)] = same
        minus[tuple(hi)] = same
        out += [plus, minus]
    return out


def obstacle_grid(grid: dict[str, np.ndarray], unrouted_nets: np.ndarray, routed_nets: np.ndarray) -> np.ndarray:
    """bool[nz, ny, nx]: the full-size obstacle grid (see the module docstring)."""
    exists = grid["flags"] != 0
    owner = grid["fixed_owner"]
    taken = (owner == _OWNER_MIXED) | (grid["wire_use"] > 0) | (grid["routed_net"] >= 0)
    taken |= (owner >= 0) & ~np.isin(owner, unrouted_nets)
    access_net = grid["access_net"]
    taken |= (access_net >= 0) & np.isin(access_net, routed_nets)
    return taken & exists


def observe_arrays(grid: dict[str, np.ndarray], rows: np.ndarray, mask: np.ndarray,
                   box: tuple[int, int, int, int], select: np.ndarray | None = None,
                   nets_out: np.ndarray | None = None, with_nets: bool = True) -> RegionObservation:
    """The observation from a region's grid views (:meth:`Region.grid`), candidate rows, unrouted
    mask and box: what :func:`observe` does, usable on hand-made arrays in tests. ``select``
    (candidate indices) keeps only those rows, in that order (the obstacle grid and the overlap
    features still count every candidate). ``nets_out``: a zeroed float32 array of at least
    ``(len(rows), 7, 3, 64, 64)`` to fill instead of a new one (the returned ``nets`` is a view of it);
    ``with_nets=False`` skips them (``nets`` is then empty: for a caller that keeps them, as they
    depend only on the terminals)."""
    rows = _rows(rows, np.int32)
    mask = np.asarray(mask, dtype=bool)
    all_ids = rows[:, _NET].astype(np.int32)
    obstacle = align(obstacle_grid(grid, all_ids[mask], all_ids[~mask]))
    features = net_features(rows, mask, box)
    if select is not None:
        select = np.asarray(select, dtype=np.int64)
        rows, mask, features = rows[select], mask[select], features[select]
    n = len(rows)
    net_ids = rows[:, _NET].astype(np.int32)

    nets = np.zeros((n, NET_CHANNELS) + ALIGNED_SHAPE, dtype=np.float32) if nets_out is None else nets_out[:n]
    access_net = grid["access_net"]
    dims = access_net.shape
    if not with_nets:
        nets = np.zeros((0, NET_CHANNELS) + ALIGNED_SHAPE, dtype=np.float32)
    elif n and access_net.size:
        # Candidate index of each net id (-1 for nets that are not candidates).
        top = int(max(int(net_ids.max()), int(access_net.max()))) + 1
        cand_of = np.full(top + 1, -1, dtype=np.int64)
        cand_of[net_ids] = np.arange(n)
        term = np.flatnonzero(access_net.reshape(-1) >= 0)
        cand = cand_of[access_net.reshape(-1)[term]]
        keep = cand >= 0
        term, cand = term[keep], cand[keep]
        z, y, x = np.unravel_index(term, dims)
        sz, sy, sx = _strides(dims)
        az, ay, ax = z // sz, y // sy, x // sx
        nets[cand, 0, az, ay, ax] = 1.0
        pin = grid["access_pin"]
        is_pin_ap = ((grid["flags"] & _ACCESS) != 0).reshape(-1)[term]
        for ch, same in enumerate(_same_pin_neighbours(pin), start=1):
            hit = same.reshape(-1)[term] & is_pin_ap
            nets[cand[hit], ch, az[hit], ay[hit], ax[hit]] = 1.0
    return RegionObservation(
        obstacle=obstacle,
        nets=nets,
        net_features=features,
        mask=mask.copy(),
        net_ids=net_ids,
    )


def unrouted_mask(region: Any) -> np.ndarray:
    """bool[N]: True for the region's candidates not routed yet."""
    mask = np.zeros(len(region.candidates), dtype=bool)
    mask[np.asarray(region.unrouted(), dtype=np.int64)] = True
    return mask


def observe(region: Any) -> RegionObservation:
    """The observation of an engine Region (``RoutingSession.open_region``) in its current state."""
    return observe_arrays(region.grid(), region.candidates, unrouted_mask(region), tuple(region.box))
