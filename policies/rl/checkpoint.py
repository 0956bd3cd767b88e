"""Training checkpoints: one ``.pt`` file holding the model state and what rebuilds it.

A checkpoint is a dict saved with ``torch.save``::

    {"format": "xroute-checkpoint", "version": 1,
     "algorithm": "ppo" | "dqn",
     "net_features": [names of the per-net scalar features, in column order],
     "model": {"num_net_features": S, "critic": bool, "width": int},
     "config": {the training settings, as in configs/train-<algorithm>.yaml},
     "episode": episodes done, "steps": env steps done,
     "state_dict": the NetOrderModel's parameters and buffers}

Loading checks all of it and raises :class:`CheckpointError` (one line, exit 2 in the CLI) for a
file that is missing, not a torch file or not an xroute checkpoint.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import torch

from xroute.atomic_files import atomic_write_from
from xroute.policies.rl.models import NetOrderModel
from xroute.errors import XrouteError

FORMAT = "xroute-checkpoint"
VERSION = 1
ALGORITHMS: tuple[str, ...] = ("ppo", "dqn")


class CheckpointError(XrouteError):
    """A checkpoint file that cannot be read as an xroute training checkpoint."""


@dataclass
class Checkpoint:
    """What a checkpoint file holds (see the module docstring)."""

    algorithm: str
    net_features: list[str]
    model: NetOrderModel
    config: dict[str, Any] = field(default_factory=dict)
    episode: int = 0
    steps: int = 0


def save_checkpoint(path: str | Path, ckpt: Checkpoint) -> Path:
    """Writes ``ckpt`` to ``path`` atomically (temporary file + rename); returns the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    m = ckpt.model
    data = {
        "format": FORMAT,
        "version": VERSION,
        "algorithm": ckpt.algorithm,
        "net_features": list(ckpt.net_features),
        "model": {"num_net_features": m.num_net_features, "critic": m.critic is not None, "width": m.width},
        "config": dict(ckpt.config),
        "episode": int(ckpt.episode),
        "steps": int(ckpt.steps),
        "state_dict": {k: v.detach().cpu() for k, v in m.state_dict().items()},
    }
    atomic_write_from(p, lambda f: torch.save(data, f))
    return p


def load_checkpoint(path: str | Path) -> Checkpoint:
    """The checkpoint in ``path`` with its model rebuilt (on CPU, in eval mode)."""
    p = Path(path)
    if not p.is_file():
        raise CheckpointError(f"{p}: checkpoint file not found")
    try:
        data = torch.load(p, map_location="cpu", weights_only=True)
    except Exception as exc:  # noqa: BLE001 - any unreadable file is the user's error
        raise CheckpointError(f"{p}: not a torch checkpoint ({type(exc).__name__})") from exc
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise CheckpointError(f"{p}: not an xroute training checkpoint (written by `xroute train`)")
    if data.get("version") != VERSION:
        raise CheckpointError(f"{p}: checkpoint version {data.get('version')} is not supported (expected {VERSION})")
    algorithm = data.get("algorithm")
    if algorithm not in ALGORITHMS:
        raise CheckpointError(f"{p}: unknown algorithm {algorithm!r} (expected one of {', '.join(ALGORITHMS)})")
    try:
        spec = data["model"]
        model = NetOrderModel(int(spec["num_net_features"]), critic=bool(spec["critic"]), width=int(spec["width"]))
        model.load_state_dict(data["state_dict"])
        names = [str(n) for n in data["net_features"]]
    except (KeyError, TypeError, ValueError, RuntimeError) as exc:
        raise CheckpointError(f"{p}: damaged checkpoint: {type(exc).__name__}: {exc}") from exc
    if len(names) != model.num_net_features:
        raise CheckpointError(f"{p}: {len(names)} feature names for a model of {model.num_net_features} features")
    model.eval()
    return Checkpoint(algorithm, names, model, dict(data.get("config") or {}),
                      int(data.get("episode", 0)), int(data.get("steps", 0)))
