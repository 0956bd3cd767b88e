"""Training settings of PPO and DQN: typed dataclasses, read from YAML once and validated.

The defaults are the XRoute paper's hyperparameters where it gives them (marked "paper");
``configs/train-ppo.yaml`` and ``configs/train-dqn.yaml`` list every key with its unit and default
(a test keeps them equal to these dataclasses). Numpy/yaml only: no torch here.

A YAML file may set any subset of the keys; an unknown key, a value of the wrong type or out of
range raises :class:`~xroute.errors.InputError` with the file and line.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import Any

import yaml

from xroute.config_schema import compose_file, scalar_value
from xroute.errors import InputError


@dataclass
class CommonConfig:
    """Settings both algorithms share."""

    gamma: float = 0.99  # discount per step (net routed); paper
    batch_size: int = 8  # transitions per gradient step; paper (PPO)
    reward_scale: float = 0.01  # rewards (cost units: 0.5/um WL, 4/via, 500/DRV) are multiplied by this
    max_candidates: int = 64  # candidate rows of the env's observation (M)
    checkpoint_every: int = 10  # episodes between checkpoints (one more at the end)
    width: int = 8  # channels of the encoder's first residual block (the second has twice)
    device: str = "auto"  # torch device: auto (cuda if present, else cpu), cpu or cuda
    threads: int = 1  # torch CPU threads
    grad_clip: float = 10.0  # max L2 norm of the gradient per step


@dataclass
class PPOConfig(CommonConfig):
    """PPO with a masked categorical policy over the candidate scores."""

    lr_actor: float = 3e-4  # Adam learning rate of encoders + scorer; paper
    lr_critic: float = 1e-3  # Adam learning rate of the critic MLP; paper
    clip: float = 0.2  # PPO ratio clip; paper
    epochs: int = 10  # passes over each rollout; paper
    update_every: int = 100  # env steps between updates (the rollout length); paper
    gae_lambda: float = 0.95  # GAE lambda (1 = Monte-Carlo returns)
    entropy_coef: float = 0.01  # weight of the entropy bonus
    value_coef: float = 0.5  # weight of the critic's squared error


@dataclass
class DQNConfig(CommonConfig):
    """DQN whose Q-values are the candidate scores, epsilon-greedy over legal candidates."""

    lr: float = 2e-3  # Adam learning rate; paper
    buffer_size: int = 1000  # replay buffer capacity in transitions; paper
    epsilon_greedy: float = 0.9  # probability of the greedy action (else a random legal one); paper
    target_update: int = 300  # gradient steps between target-network copies; paper
    learning_starts: int = 50  # transitions in the buffer before the first gradient step
    train_every: int = 1  # env steps between gradient steps


CONFIG_CLASSES: dict[str, type[CommonConfig]] = {"ppo": PPOConfig, "dqn": DQNConfig}


def default_config(algorithm: str) -> CommonConfig:
    """The default settings of ``algorithm`` ("ppo" or "dqn")."""
    return CONFIG_CLASSES[algorithm]()


def _check(cfg: CommonConfig) -> str | None:
    """A message for the first setting out of range, or None."""
    positive = ["batch_size", "max_candidates", "checkpoint_every", "width", "threads", "grad_clip", "reward_scale"]
    if isinstance(cfg, PPOConfig):
        positive += ["lr_actor", "lr_critic", "clip", "epochs", "update_every"]
    if isinstance(cfg, DQNConfig):
        positive += ["lr", "buffer_size", "target_update", "train_every"]
    for name in positive:
        if getattr(cfg, name) <= 0:
            return f"{name} must be > 0, got {getattr(cfg, name)}"
    if not 0.0 <= cfg.gamma <= 1.0:
        return f"gamma must be in [0, 1], got {cfg.gamma}"
    if cfg.device not in ("auto", "cpu", "cuda"):
        return f"device must be auto, cpu or cuda, got {cfg.device!r}"
    if isinstance(cfg, PPOConfig) and not 0.0 <= cfg.gae_lambda <= 1.0:
        return f"gae_lambda must be in [0, 1], got {cfg.gae_lambda}"
    if isinstance(cfg, DQNConfig) and not 0.0 <= cfg.epsilon_greedy <= 1.0:
        return f"epsilon_greedy must be in [0, 1], got {cfg.epsilon_greedy}"
    if isinstance(cfg, DQNConfig) and cfg.learning_starts < cfg.batch_size:
        return f"learning_starts ({cfg.learning_starts}) must be >= batch_size ({cfg.batch_size})"
    return None


def config_from_dict(algorithm: str, values: dict[str, Any], path: str = "",
                     lines: dict[str, int] | None = None) -> CommonConfig:
    """Settings of ``algorithm`` with ``values`` over the defaults (checked; errors name ``path``:line)."""
    lines = lines or {}
    cls = CONFIG_CLASSES[algorithm]
    types = {f.name: f.type for f in fields(cls)}
    kwargs: dict[str, Any] = {}
    for key, value in values.items():
        line = lines.get(key, 0)
        if key not in types:
            raise InputError(f"unknown {algorithm} setting '{key}' (known: {', '.join(types)})", path, line)
        want = types[key]
        if want == "float" and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        ok = {"int": isinstance(value, int) and not isinstance(value, bool),
              "float": isinstance(value, float), "str": isinstance(value, str)}[want]
        if not ok:
            raise InputError(f"setting '{key}' must be {want}, got {value!r}", path, line)
        if want == "float" and not math.isfinite(value):
            raise InputError(f"setting '{key}' must be a finite number, got {value!r}", path, line)
        kwargs[key] = value
    cfg = cls(**kwargs)
    problem = _check(cfg)
    if problem:
        key = problem.split()[0]
        raise InputError(problem, path, lines.get(key, 0))
    return cfg


def load_config(algorithm: str, path: str | Path | None) -> CommonConfig:
    """Settings of ``algorithm`` from a YAML file (a mapping of keys; absent keys keep defaults), or
    the defaults when ``path`` is None."""
    if path is None:
        return default_config(algorithm)
    p = Path(path)
    if not p.is_file():
        raise InputError("config file not found", str(p))
    node = compose_file(p)  # the one YAML reader of configs (xroute.config_schema): file:line errors
    if node is None:
        return default_config(algorithm)
    if not isinstance(node, yaml.MappingNode):
        raise InputError("a training config must be a mapping of settings", str(p), node.start_mark.line + 1)
    values: dict[str, Any] = {}
    lines: dict[str, int] = {}
    for key_node, value_node in node.value:
        key = str(key_node.value)
        lines[key] = key_node.start_mark.line + 1
        if not isinstance(value_node, yaml.ScalarNode):
            raise InputError(f"setting '{key}' must be a single value", str(p), lines[key])
        values[key] = scalar_value(value_node)
    return config_from_dict(algorithm, values, str(p), lines)


def config_dict(cfg: CommonConfig) -> dict[str, Any]:
    """The settings as a plain dict (stored in checkpoints)."""
    return asdict(cfg)
