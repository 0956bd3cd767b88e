"""Observations kept for training (compact) and turned back into model inputs (torch tensors).

An env observation holds M = ``max_candidates`` net grids of 7 x 3 x 64 x 64 floats (7 MB at
M = 64), most of them padding. :func:`compact` keeps only the first K rows (up to the last
candidate that was ever unmasked in the episode), as float16 (exact for the 0/1 grids), and
shares one ``nets`` array between the steps of an episode while it does not change (the net
grids of a region are fixed; only the obstacle, the features and the mask move).

:func:`collate` gathers only the unmasked rows of a batch of states: the model encodes those and
nothing else (a routed or padding row costs no convolution).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import torch


@dataclass
class StoredObs:
    """One state as kept in a rollout or replay buffer."""

    obstacle: np.ndarray  # float16[3, 64, 64]
    nets: np.ndarray  # float16[K, 7, 3, 64, 64], shared between steps of an episode
    net_features: np.ndarray  # float32[K, S]
    mask: np.ndarray  # bool[K]: True = legal action (unrouted candidate)


def compact(obs: dict[str, Any], previous: StoredObs | None = None) -> StoredObs:
    """``obs`` (the env's dict) as a :class:`StoredObs`; reuses ``previous.nets`` when unchanged."""
    mask = np.asarray(obs["action_mask"]).astype(bool)
    rows = np.flatnonzero(mask)
    k = int(rows[-1]) + 1 if len(rows) else 0
    if previous is not None and len(previous.mask) >= k:
        k = len(previous.mask)
    nets = np.asarray(obs["nets"])[:k]
    if previous is not None and previous.nets.shape == nets.shape and np.array_equal(previous.nets, nets):
        shared = previous.nets
    else:
        shared = nets.astype(np.float16)
    return StoredObs(
        obstacle=np.asarray(obs["obstacle"]).astype(np.float16),
        nets=shared,
        net_features=np.asarray(obs["net_features"], dtype=np.float32)[:k].copy(),
        mask=mask[:k].copy(),
    )


@dataclass
class Batch:
    """Model inputs of B states, only their legal rows: see :meth:`NetOrderModel.score_flat`."""

    obstacle: torch.Tensor  # float32[B, 3, 64, 64]
    nets: torch.Tensor  # float32[R, 7, 3, 64, 64]: the legal rows of all B states
    net_features: torch.Tensor  # float32[R, S]
    row_state: torch.Tensor  # int64[R]: which state (0..B-1) a row belongs to
    row_slot: torch.Tensor  # int64[R]: its row index in that state
    mask: torch.Tensor  # bool[B, K]: K = the longest state's rows


def collate(states: list[StoredObs], device: torch.device | str = "cpu") -> Batch:
    """A :class:`Batch` of ``states`` (their legal rows only) on ``device``."""
    k = max((len(s.mask) for s in states), default=0)
    mask = np.zeros((len(states), k), dtype=bool)
    nets, feats, row_state, row_slot = [], [], [], []
    for b, s in enumerate(states):
        mask[b, : len(s.mask)] = s.mask
        rows = np.flatnonzero(s.mask)
        nets.append(s.nets[rows])
        feats.append(s.net_features[rows])
        row_state.append(np.full(len(rows), b, dtype=np.int64))
        row_slot.append(rows.astype(np.int64))
    s0 = states[0]
    obstacle = np.stack([s.obstacle for s in states]).astype(np.float32)
    net_arr = np.concatenate(nets).astype(np.float32) if nets else np.zeros((0, *s0.nets.shape[1:]), np.float32)

    def t(a: np.ndarray) -> torch.Tensor:
        return torch.from_numpy(a).to(device)

    return Batch(t(obstacle), t(net_arr), t(np.concatenate(feats).astype(np.float32)),
                 t(np.concatenate(row_state)), t(np.concatenate(row_slot)), t(mask))


def chosen_rows(states: list[StoredObs], actions: list[int], device: torch.device | str = "cpu") -> Batch:
    """A :class:`Batch` holding, for each state, only the row of its action (DQN's Q(s, a))."""
    one = [StoredObs(s.obstacle, s.nets, s.net_features, np.arange(len(s.mask)) == a) for s, a in zip(states, actions)]
    return collate(one, device)


@torch.no_grad()
def refresh_batch_norm(model: torch.nn.Module, states: list[StoredObs], device: torch.device | str = "cpu",
                       chunk: int = 16) -> None:
    """Re-estimates every BatchNorm3d's running statistics on ``states`` (a no-grad pass in train
    mode, equal-weight average over chunks of ``chunk`` states); leaves the model in eval mode.

    The trainers run the model in eval mode throughout (acting, and the gradient steps too), so
    that a transition's probabilities are the same when acted and when learned from and the same
    as in the exported model; this pass is how the statistics follow the data.
    """
    norms = [m for m in model.modules() if isinstance(m, torch.nn.BatchNorm3d)]
    momenta = [m.momentum for m in norms]
    for m in norms:
        m.reset_running_stats()
        m.momentum = None  # cumulative average over the chunks
    model.train()
    for start in range(0, len(states), chunk):
        b = collate(states[start : start + chunk], device)
        model.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)  # type: ignore[operator]
    for m, momentum in zip(norms, momenta):
        m.momentum = momentum
    model.eval()
