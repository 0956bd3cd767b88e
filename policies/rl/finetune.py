"""Policy-gradient fine-tuning of the set scorer on the first pass's training regions, in context.

The deployed scorer routes one order per region: its greedy order (candidates by descending
score). Here the scorer is also a stochastic policy over whole orders, the Plackett-Luce model of
``scores / temperature``; a sample is drawn as ``argsort(-(scores / temperature + Gumbel noise))``.
Each iteration takes ``regions`` training regions (:func:`~xroute.policies.rl.teacher.training_indices`,
less the validation ones, ``index % val_every == 0``), routes in context the greedy order and
``samples`` sampled orders of each, and scores them with the region's first-pass cost
(:func:`~xroute.policies.rl.teacher.route_order`). A sample's advantage is
``(cost(greedy) - cost(sample)) / cost_scale``: the greedy order is the baseline (self-critical), so
the update moves the greedy order towards samples that beat it, the policy the router runs.
The update is PPO's clipped objective per placement step (choosing the net at position t among those
left, the same factors as :func:`~xroute.policies.rl.imitation.order_log_probs`), ``epochs`` passes
over the iteration's samples. Every ``eval_every`` iterations the greedy order is routed on the
validation regions; the checkpoint kept is the one with the lowest validation cost (the held-out
regions (:func:`~xroute.policies.rl.region_filter.held_out`) are never routed here).

Routing runs in ``workers`` processes, or Ray actors on a cluster (:mod:`~xroute.policies.rl.ray_pool`),
each with its own first pass of every testcase (the state the regions open in); a region's routing
depends only on the order, so results do not depend on the worker count or the backend. The
model (72,578 parameters) scores and trains on ``device``: CUDA when torch sees one (``auto``), else
the CPU; the routing stays on the CPU.

``xroute train finetune --testcase A,B --init CKPT.pt``: starts from an imitation checkpoint, or
from an untrained scorer (whose greedy order is the heuristic's).
"""

from __future__ import annotations

import time
from concurrent.futures import Executor, ProcessPoolExecutor
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
import torch

from xroute.policies.rl.device import pick_device
from xroute.policies.rl.imitation import model_order, model_scores, scores_order
from xroute.policies.rl.set_features import SET_FEATURES
from xroute.policies.rl.set_scorer import SetScorer

RANK = SET_FEATURES.index("heuristic_rank")


@dataclass
class FinetuneConfig:
    iterations: int = 40
    regions: int = 16  # training regions per iteration
    samples: int = 4  # sampled orders per region (besides the greedy one)
    temperature: float = 0.1  # sampling: Plackett-Luce over scores / temperature
    epochs: int = 4  # PPO passes over an iteration's samples
    clip: float = 0.2
    lr: float = 3e-4
    cost_scale: float = 500.0  # one violation
    val_every: int = 5
    eval_every: int = 5
    hold_out_every: int = 3
    min_candidates: int = 2
    region_size: int = 0  # 0: the router's
    seed: int = 1
    device: str = "auto"  # torch device of the scorer: auto (cuda if present, else cpu), cpu or cuda


# --- routing (worker processes) -----------------------------------------------------------------

_PASSES: dict[str, tuple[Any, int]] = {}


def _init_worker(testcases: list[str], region_size: int) -> None:
    from xroute.policies.rl.teacher import load_first_pass

    torch.set_num_threads(1)
    for name in testcases:
        _PASSES[name] = load_first_pass(name, region_size)


def _regions_job(job: tuple[str, int, int, int]) -> list[tuple[str, int, np.ndarray]]:
    """(testcase, hold_out_every, min_candidates, region_size) -> (testcase, index, features) of every
    region that is not held out (training and validation)."""
    from xroute.policies.rl.set_features import region_set_features
    from xroute.policies.rl.teacher import training_regions

    name, hold_out_every, min_candidates, size = job
    fp, _dbu = _PASSES[name]
    return [(name, index, region_set_features(region))
            for index, region in training_regions(fp, size, hold_out_every, min_candidates)]


def _route_job(job: tuple[str, int, list[np.ndarray]]) -> list[float]:
    from xroute.policies.rl.teacher import route_order

    name, index, orders = job
    fp, dbu = _PASSES[name]
    return [route_order(fp, index, o, dbu) for o in orders]


class _Local(Executor):
    """An executor that runs in this process (``workers`` = 1)."""

    def map(self, fn: Callable, *iterables: Any, timeout: Any = None, chunksize: int = 1) -> Any:  # noqa: ARG002
        return [fn(*args) for args in zip(*iterables)]

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:  # noqa: ARG002
        _PASSES.clear()  # the first passes this process routed for the run


def _pool(testcases: list[str], region_size: int, workers: int, backend: str = "local",
          ray_address: str | None = None) -> Executor:
    if backend == "ray":
        from xroute.policies.rl.ray_pool import RayPool

        return RayPool(testcases, region_size, workers, ray_address)
    if backend != "local":
        raise ValueError(f"unknown backend {backend!r}: use local or ray")
    if workers <= 1:
        _init_worker(testcases, region_size)
        return _Local()
    import multiprocessing

    return ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn"),
                               initializer=_init_worker, initargs=(testcases, region_size))


# --- the policy ---------------------------------------------------------------------------------

def sample_orders(scores: np.ndarray, temperature: float, count: int, rng: np.random.Generator) -> list[np.ndarray]:
    """``count`` orders drawn from the Plackett-Luce model of ``scores / temperature`` (Gumbel-max)."""
    s = np.asarray(scores, dtype=np.float64) / max(temperature, 1e-9)
    return [np.argsort(-(s + rng.gumbel(size=len(s))), kind="stable").astype(np.int32) for _ in range(count)]


def step_log_probs(scores: torch.Tensor, orders: torch.Tensor, valid: torch.Tensor) -> torch.Tensor:
    """[B, N]: log-probability of choosing ``orders[b, t]`` among ``orders[b, t:]`` (the valid ones), under
    Plackett-Luce of ``scores`` [B, N]; 0 at padding positions (``valid`` [B, N], padding at the end)."""
    s = torch.where(valid, torch.gather(scores, 1, orders), torch.full_like(scores, -1e4))
    suffix = torch.logcumsumexp(s.flip(-1), dim=-1).flip(-1)
    return torch.where(valid, s - suffix, torch.zeros_like(s))


@dataclass
class _Sample:
    region: int  # into the training list
    order: np.ndarray
    advantage: float
    old_logp: np.ndarray  # per step


def _batch(samples: list[_Sample], features: list[np.ndarray]) -> tuple[torch.Tensor, ...]:
    b = len(samples)
    n = max(len(features[s.region]) for s in samples)
    f = np.zeros((b, n, len(SET_FEATURES)), dtype=np.float32)
    mask = np.zeros((b, n), dtype=bool)
    orders = np.tile(np.arange(n), (b, 1))
    old = np.zeros((b, n), dtype=np.float32)
    for j, s in enumerate(samples):
        m = len(features[s.region])
        f[j, :m] = features[s.region]
        mask[j, :m] = True
        orders[j, :m] = s.order
        old[j, :m] = s.old_logp
    adv = np.array([s.advantage for s in samples], dtype=np.float32)
    return (torch.from_numpy(f), torch.from_numpy(mask), torch.from_numpy(orders), torch.from_numpy(old),
            torch.from_numpy(adv))


def ppo_loss(model: SetScorer, batch: tuple[torch.Tensor, ...], temperature: float, clip: float) -> torch.Tensor:
    """PPO's clipped surrogate per placement step, averaged over the valid steps of the batch."""
    feats, mask, orders, old, adv = batch
    logp = step_log_probs(model(feats, mask) / temperature, orders, mask)
    ratio = torch.exp(logp - old)
    a = adv[:, None]
    surrogate = torch.minimum(ratio * a, torch.clamp(ratio, 1 - clip, 1 + clip) * a)
    return -(surrogate * mask).sum() / mask.sum().clamp(min=1)


# --- training -----------------------------------------------------------------------------------

def finetune(testcases: list[str], cfg: FinetuneConfig = FinetuneConfig(), *, model: SetScorer | None = None,
             workers: int = 2, backend: str = "local", ray_address: str | None = None,
             on_log: Callable[[dict[str, Any]], None] | None = None) -> tuple[SetScorer, list[dict[str, Any]]]:
    """Fine-tunes ``model`` (default: an untrained scorer) on ``testcases``, routing in ``workers`` local
    processes or, with ``backend="ray"``, Ray actors (:mod:`~xroute.policies.rl.ray_pool`; ``ray_address``
    None: a local instance); the scorer runs on ``cfg.device``. Returns the checkpoint with the lowest validation
    cost (eval mode, on the CPU) and the log (one row per evaluation)."""
    from xroute.defaults import REGION_SIZE

    size = cfg.region_size or REGION_SIZE
    device = pick_device(cfg.device)
    torch.manual_seed(cfg.seed)
    rng = np.random.default_rng(cfg.seed)
    model = (model if model is not None else SetScorer()).to(device)
    opt = torch.optim.Adam(model.parameters(), lr=cfg.lr)
    t0 = time.perf_counter()
    pool = _pool(testcases, size, workers, backend, ray_address)
    try:
        jobs = [(t, cfg.hold_out_every, cfg.min_candidates, size) for t in testcases]
        found = [(t, i, np.array(f, dtype=np.float32)) for part in pool.map(_regions_job, jobs) for t, i, f in part]
        train = [r for r in found if not (cfg.val_every and r[1] % cfg.val_every == 0)]
        val = [r for r in found if cfg.val_every and r[1] % cfg.val_every == 0]
        if not train:
            raise ValueError(f"no training region with >= {cfg.min_candidates} nets in {', '.join(testcases)}")
        features = [r[2] for r in train]

        def route_val(order_of: Callable[[np.ndarray], np.ndarray]) -> list[float]:
            """The cost of each validation region routed in ``order_of(its features)``."""
            jobs = [(r[0], r[1], [order_of(r[2]).astype(np.int32)]) for r in val]
            return [costs[0] for costs in pool.map(_route_job, jobs)]

        val_base = route_val(lambda f: np.argsort(f[:, RANK], kind="stable"))  # the heuristic's order

        def by_testcase(costs: list[float]) -> dict[str, float]:
            out: dict[str, float] = {}
            for name in testcases:
                got = sum(c for c, r in zip(costs, val) if r[0] == name)
                base = sum(c for c, r in zip(val_base, val) if r[0] == name)
                out[name] = round((got - base) / base, 4) if base else 0.0
            return out

        log: list[dict[str, Any]] = []
        best_cost, best_state = None, None
        sample_gain = 0.0  # since the last evaluation: per region, cost(greedy) - its cheapest order
        greedy_cost = sample_cost = 0.0  # since the last evaluation: greedy orders, mean of the samples
        base_total = float(sum(val_base))
        for it in range(cfg.iterations + 1):
            if val and (it % cfg.eval_every == 0 or it == cfg.iterations):
                costs = route_val(lambda f: model_order(model, f))
                cost = float(sum(costs))
                row = {"iteration": it, "val_cost": round(cost, 1), "val_heuristic": round(base_total, 1),
                       "val_vs_heuristic": round((cost - base_total) / max(base_total, 1e-9), 4),
                       "val_by_testcase": by_testcase(costs),
                       "sample_gain": round(sample_gain, 1),
                       "samples_vs_greedy": round((sample_cost - greedy_cost) / greedy_cost, 4) if greedy_cost else 0.0,
                       "prior": round(float(model.prior.detach()), 3), "seconds": round(time.perf_counter() - t0, 1)}
                sample_gain = greedy_cost = sample_cost = 0.0
                log.append(row)
                if on_log:
                    on_log(row)
                if best_cost is None or cost < best_cost - 1e-9:
                    best_cost = cost
                    best_state = {k: v.detach().clone() for k, v in model.state_dict().items()}
            if it == cfg.iterations:
                break
            picks = rng.choice(len(train), size=min(cfg.regions, len(train)), replace=False)
            jobs, tried = [], []
            for p in picks:
                s = model_scores(model, features[p])
                greedy = scores_order(features[p], s).astype(np.int32)
                orders = [greedy, *sample_orders(s, cfg.temperature, cfg.samples, rng)]
                jobs.append((train[p][0], train[p][1], orders))
                tried.append((p, orders, s))
            samples: list[_Sample] = []
            for (p, orders, s), costs in zip(tried, pool.map(_route_job, jobs)):
                sample_gain += costs[0] - min(costs)
                greedy_cost += costs[0]
                sample_cost += float(np.mean(costs[1:]))
                st = torch.from_numpy(s[None] / cfg.temperature).float()
                for o, c in zip(orders[1:], costs[1:]):
                    lp = step_log_probs(st, torch.from_numpy(o[None]).long(), torch.ones(1, len(o), dtype=torch.bool))
                    samples.append(_Sample(p, o, (costs[0] - c) / cfg.cost_scale, lp[0].numpy()))
            model.train()
            batch = tuple(t.to(device) for t in _batch(samples, features))
            for _ in range(cfg.epochs):
                loss = ppo_loss(model, batch, cfg.temperature, cfg.clip)
                opt.zero_grad()
                loss.backward()
                torch.nn.utils.clip_grad_norm_(model.parameters(), 1.0)
                opt.step()
            model.eval()
    finally:
        pool.shutdown()
    if best_state is not None:
        model.load_state_dict(best_state)
    return model.cpu().eval(), log
