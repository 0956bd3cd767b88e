"""The training loop shared by PPO and DQN: episodes on a Gymnasium env, metrics log, checkpoints.

:func:`train` runs ``episodes`` episodes (one region each in the net-ordering envs) and writes
into ``out_dir``:

* ``metrics.jsonl``: one JSON object per episode: ``episode`` (1-based), ``steps`` (nets routed),
  ``total_steps``, ``reward`` (sum of the env's rewards, unscaled), ``cost`` (the region's cost
  at the end: 0.5 WL(um) + 4 vias + 500 DRVs), ``wirelength_dbu``, ``vias``, ``drvs``,
  ``seconds`` (wall time of the episode, updates included) and the last losses; the file is whole at
  every moment (:class:`xroute.atomic_files.AtomicLog`: rewritten at most once a second, and at the end);
* ``<algorithm>-epNNNNN.pt`` every ``checkpoint_every`` episodes and ``<algorithm>-final.pt``
  at the end (see :mod:`xroute.policies.rl.checkpoint`).

Determinism: ``torch.manual_seed(seed)``, the DQN generator seeded with ``seed`` and the env's
first ``reset(seed=seed)``; later resets continue the env's own generator. Same seed, same log
(apart from ``seconds``) on the same machine and torch build.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import torch

from xroute.atomic_files import AtomicLog
from xroute.policies.rl.batch import compact
from xroute.policies.rl.checkpoint import Checkpoint, save_checkpoint
from xroute.policies.rl.device import pick_device
from xroute.policies.rl.dqn import DQNTrainer
from xroute.policies.rl.observation import NET_FEATURES
from xroute.policies.rl.ppo import PPOTrainer
from xroute.policies.rl.train_config import CommonConfig, DQNConfig, PPOConfig, config_dict


@dataclass
class TrainResult:
    """What a training run produced."""

    out_dir: Path
    final_checkpoint: Path
    checkpoints: list[Path] = field(default_factory=list)
    episodes: list[dict[str, Any]] = field(default_factory=list)
    seconds: float = 0.0


def make_trainer(algorithm: str, cfg: CommonConfig, num_net_features: int, seed: int) -> PPOTrainer | DQNTrainer:
    """The trainer of ``algorithm`` with a freshly initialised model (seeded)."""
    torch.manual_seed(seed)
    device = pick_device(cfg.device)
    if algorithm == "ppo":
        assert isinstance(cfg, PPOConfig)
        return PPOTrainer(cfg, num_net_features, device)
    assert isinstance(cfg, DQNConfig)
    return DQNTrainer(cfg, num_net_features, device, seed)


def _episode_metrics(info: dict[str, Any]) -> dict[str, Any]:
    m = info.get("metrics") or {}
    return {
        "cost": float(info["cost"]) if "cost" in info else None,
        "wirelength_dbu": int(m.get("wirelength_dbu", 0)),
        "vias": int(m.get("vias", 0)),
        "drvs": int(m.get("violations", 0)),
    }


def train(
    algorithm: str,
    make_env: Callable[[], Any],
    episodes: int,
    cfg: CommonConfig,
    out_dir: str | Path,
    seed: int = 1,
    on_episode: Callable[[dict[str, Any]], None] | None = None,
) -> TrainResult:
    """Trains ``algorithm`` ("ppo" or "dqn") for ``episodes`` episodes of ``make_env()``."""
    torch.set_num_threads(cfg.threads)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    env = make_env()
    num_features = int(env.observation_space["net_features"].shape[1])
    names = list(NET_FEATURES) if num_features == len(NET_FEATURES) else [f"f{i}" for i in range(num_features)]
    trainer = make_trainer(algorithm, cfg, num_features, seed)
    result = TrainResult(out, out / f"{algorithm}-final.pt")
    log_path = out / "metrics.jsonl"
    start = time.perf_counter()
    total_steps = 0

    def checkpoint(path: Path, episode: int) -> None:
        save_checkpoint(path, Checkpoint(algorithm, names, trainer.model, config_dict(cfg), episode, total_steps))
        trainer.model.eval()

    with AtomicLog(log_path) as log:  # whole at every moment, at most a second behind
        for episode in range(1, episodes + 1):
            t0 = time.perf_counter()
            obs, info = env.reset(seed=seed) if episode == 1 else env.reset()
            state = compact(obs)
            steps, reward_sum, done = 0, 0.0, not state.mask.any()
            while not done:
                action = trainer.act(state)
                obs, reward, terminated, truncated, info = env.step(action)
                done = bool(terminated or truncated)
                next_state = compact(obs, state)
                trainer.record(state, action, float(reward), done, next_state)
                state = next_state
                steps += 1
                reward_sum += float(reward)
            total_steps += steps
            row = {"episode": episode, "steps": steps, "total_steps": total_steps, "reward": reward_sum,
                   **_episode_metrics(info), "seconds": round(time.perf_counter() - t0, 4), **trainer.last_losses}
            log.write_line(json.dumps(row))
            result.episodes.append(row)
            if on_episode is not None:
                on_episode(row)
            if episode % cfg.checkpoint_every == 0 and episode < episodes:
                path = out / f"{algorithm}-ep{episode:05d}.pt"
                checkpoint(path, episode)
                result.checkpoints.append(path)
    checkpoint(result.final_checkpoint, episodes)
    result.checkpoints.append(result.final_checkpoint)
    result.seconds = time.perf_counter() - start
    env.close()
    return result
