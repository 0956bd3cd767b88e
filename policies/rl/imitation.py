"""Imitation training of the set scorer on teacher orders (:mod:`xroute.policies.rl.teacher`).

Loss per region: a cost-weighted Plackett-Luce likelihood of the orders the teacher routed,
``-sum_k w_k log P(order_k | scores) / N`` with ``w = softmax(-(cost - min cost) / temperature)``
over the region's K + 1 orders (the heuristic's and K random ones): mostly the cheapest order, the
others by how close they came. ``log P`` of an order is ``sum_t s[o_t] - logsumexp(s[o_t..o_N])``,
the per-step cross-entropy of choosing each next net among those left. Regions where every order
cost the same teach nothing about order and are left out. Each region is also seen mirrored in x,
in y and in both (the box columns of :data:`SET_FEATURES` reflected; the other columns do not
change), as routing has no preferred side.

``train(regions, ...)`` returns the model and a log; ``xroute train imitate`` routes (or loads) the
teacher data, trains and writes a checkpoint and an ONNX model.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import torch

from xroute.policies.rl.device import pick_device
from xroute.policies.rl.set_features import SET_FEATURES
from xroute.policies.rl.set_scorer import SetScorer
from xroute.policies.rl.teacher import TeacherRegion

_BOX = [SET_FEATURES.index(c) for c in ("box_xlo", "box_ylo", "box_xhi", "box_yhi")]


@dataclass
class ImitationConfig:
    width: int = 64
    heads: int = 4
    layers: int = 2
    prior: float = 4.0
    steps: int = 600
    batch: int = 16
    lr: float = 1e-3
    weight_decay: float = 1e-4
    temperature: float = 200.0  # cost units (one violation = 500)
    mirror: bool = True
    loss: str = "pl"  # "pl": imitate the cheap orders; "contrast": rank the region's orders by cost; "both"
    seed: int = 1
    device: str = "auto"  # torch device: auto (cuda if present, else cpu), cpu or cuda
    log_every: int = 50
    extra: dict[str, Any] = field(default_factory=dict)


def mirrored(features: np.ndarray, flip_x: bool, flip_y: bool) -> np.ndarray:
    """The features of the region reflected in x and/or y (box columns only)."""
    f = features.copy()
    xlo, ylo, xhi, yhi = _BOX
    if flip_x:
        f[:, xlo], f[:, xhi] = 1.0 - features[:, xhi], 1.0 - features[:, xlo]
    if flip_y:
        f[:, ylo], f[:, yhi] = 1.0 - features[:, yhi], 1.0 - features[:, ylo]
    return f


def order_weights(costs: np.ndarray, temperature: float) -> np.ndarray:
    c = np.asarray(costs, dtype=np.float64)
    z = -(c - c.min()) / max(temperature, 1e-9)
    w = np.exp(z - z.max())
    return np.maximum(w / w.sum(), 1e-12)


def informative(regions: list[TeacherRegion]) -> list[TeacherRegion]:
    """The regions where the orders' costs differ."""
    return [r for r in regions if np.ptp(r.costs) > 1e-6]


def batch_tensors(regions: list[TeacherRegion], temperature: float,
                  flips: list[tuple[bool, bool]] | None = None) -> tuple[torch.Tensor, ...]:
    """Padded features [B, N, F], mask [B, N], orders [B, K1, N] (padding rows at the end), weights [B, K1]."""
    b = len(regions)
    n = max(len(r.features) for r in regions)
    k1 = max(len(r.costs) for r in regions)
    feats = np.zeros((b, n, regions[0].features.shape[1]), dtype=np.float32)
    mask = np.zeros((b, n), dtype=bool)
    orders = np.tile(np.arange(n), (b, k1, 1))
    weights = np.zeros((b, k1), dtype=np.float32)
    for j, r in enumerate(regions):
        m = len(r.features)
        fx, fy = flips[j] if flips else (False, False)
        feats[j, :m] = mirrored(r.features, fx, fy)
        mask[j, :m] = True
        kk = len(r.costs)
        orders[j, :kk, :m] = r.orders
        weights[j, :kk] = order_weights(r.costs, temperature)
    return torch.from_numpy(feats), torch.from_numpy(mask), torch.from_numpy(orders), torch.from_numpy(weights)


def order_log_probs(scores: torch.Tensor, mask: torch.Tensor, orders: torch.Tensor) -> torch.Tensor:
    """[B, K1]: log P(order_k) under the Plackett-Luce model of ``scores`` (padding rows left out)."""
    b, k1, n = orders.shape
    s = torch.where(mask, scores, torch.full_like(scores, -1e4))
    s_ord = torch.gather(s[:, None, :].expand(b, k1, n), 2, orders)
    valid = torch.gather(mask[:, None, :].expand(b, k1, n), 2, orders)
    suffix = torch.logcumsumexp(s_ord.flip(-1), dim=-1).flip(-1)
    return torch.where(valid, s_ord - suffix, torch.zeros_like(s_ord)).sum(-1)


def plackett_luce_loss(scores: torch.Tensor, mask: torch.Tensor, orders: torch.Tensor,
                       weights: torch.Tensor) -> torch.Tensor:
    """Mean over regions of ``-sum_k w_k log P(order_k) / N`` (scores [B, N], orders [B, K1, N])."""
    logp = order_log_probs(scores, mask, orders)
    count = mask.sum(-1).clamp(min=1).float()
    return (-(weights * logp).sum(-1) / count).mean()


def contrast_loss(scores: torch.Tensor, mask: torch.Tensor, orders: torch.Tensor,
                  weights: torch.Tensor) -> torch.Tensor:
    """Cross-entropy between the cost weights and the softmax over the region's orders of their
    log-probabilities: only the differences between orders count (not how sure the model is of any)."""
    logp = order_log_probs(scores, mask, orders)
    tried = weights > 0
    logp = torch.where(tried, logp, torch.full_like(logp, -1e4))
    return -(weights * torch.log_softmax(logp, dim=-1)).sum(-1).mean()


def train(regions: list[TeacherRegion], cfg: ImitationConfig = ImitationConfig(),
          on_log: Any = None, model: SetScorer | None = None) -> tuple[SetScorer, list[dict[str, Any]]]:
    """Trains a :class:`SetScorer` on ``regions`` (their informative part) on ``cfg.device``; returns it (eval
    mode, on the CPU) and the log. ``model``: the scorer to train (None: a new one from ``cfg`` over
    the set features, made after torch is seeded). The regions' feature columns begin with
    :data:`SET_FEATURES`; mirroring changes only the box columns, so further ones pass unchanged."""
    device = pick_device(cfg.device)
    torch.manual_seed(cfg.seed)
    rng = np.random.default_rng(cfg.seed)
    data = informative(regions)
    if not data:
        raise ValueError("no teacher region where the order changed the cost: nothing to imitate")
    if model is None:
        model = SetScorer(len(SET_FEATURES), cfg.width, cfg.heads, cfg.layers, cfg.prior)
    model = model.to(device)
    opt = torch.optim.AdamW(model.parameters(), lr=cfg.lr, weight_decay=cfg.weight_decay)
    sched = torch.optim.lr_scheduler.CosineAnnealingLR(opt, max(1, cfg.steps))
    log: list[dict[str, Any]] = []
    t0 = time.perf_counter()
    running = []
    model.train()
    for step in range(1, cfg.steps + 1):
        pick = rng.choice(len(data), size=min(cfg.batch, len(data)), replace=False)
        flips = [(bool(rng.integers(2)), bool(rng.integers(2))) if cfg.mirror else (False, False) for _ in pick]
        feats, mask, orders, weights = (t.to(device) for t in batch_tensors([data[i] for i in pick],
                                                                              cfg.temperature, flips))
        scores = model(feats, mask)
        loss = torch.zeros((), device=device)
        if cfg.loss in ("pl", "both"):
            loss = loss + plackett_luce_loss(scores, mask, orders, weights)
        if cfg.loss in ("contrast", "both"):
            loss = loss + contrast_loss(scores, mask, orders, weights)
        opt.zero_grad()
        loss.backward()
        torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
        opt.step()
        sched.step()
        running.append(float(loss.detach()))
        if step % cfg.log_every == 0 or step == cfg.steps:
            row = {"step": step, "loss": float(np.mean(running)), "prior": float(model.prior.detach()),
                   "seconds": round(time.perf_counter() - t0, 2)}
            running = []
            log.append(row)
            if on_log:
                on_log(row)
    return model.cpu().eval(), log



def model_scores(model: SetScorer, features: np.ndarray) -> np.ndarray:
    """float64[N]: the model's scores of one region's candidates (features float32[N, F]), on the model's device."""
    device = next(model.parameters()).device
    with torch.no_grad():
        f = torch.from_numpy(np.asarray(features, dtype=np.float32))[None].to(device)
        scores = model(f, torch.ones(f.shape[:2], dtype=torch.bool, device=device))[0]
        return scores.cpu().numpy().astype(np.float64)


def scores_order(features: np.ndarray, scores: np.ndarray) -> np.ndarray:
    """Candidate rows by descending score, ties in heuristic order (as the router's lexsort)."""
    return np.lexsort((features[:, SET_FEATURES.index("heuristic_rank")], -np.asarray(scores)))


def model_order(model: SetScorer, features: np.ndarray) -> np.ndarray:
    """The model's order of one region's candidates (:func:`scores_order` of :func:`model_scores`)."""
    return scores_order(features, model_scores(model, features))
