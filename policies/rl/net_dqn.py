"""The paper's net-routing baseline: a small DQN over the 12-d head state of ``xroute/NetRouting-v0``.

Model (:class:`NetRouterQ`): three fully connected layers 32 / 64 / 32 with ReLU, 6 Q-values (UP,
DOWN, NORTH, SOUTH, EAST, WEST). The raw state (grid indices, distances, edge costs; see
:mod:`xroute.envs.net_routing`) goes through a fixed ``sign(v) * log1p(|v|)`` first (part of the
model and of its ONNX graph), so the same model reads small and large regions. Training (:func:`train_net_router`): plain DQN
with a replay buffer, a target network, epsilon-greedy exploration over the legal moves
(``env.legal_actions()``), Huber loss, optional potential-based shaping toward the target
(``NetDQNConfig.shaping``, training only: the env's reward is the paper's); CPU. Acting (:class:`OnnxNetRouter`): the exported ONNX
model through onnxruntime, the best legal direction.

ONNX signature: input ``state`` float32 [B, 12], output ``q`` float32 [B, 6]; metadata
``xroute_model = "net-router"``.

The env is passed in (this module is layer 3 and does not import :mod:`xroute.envs`).
"""

from __future__ import annotations

import io
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from xroute.atomic_files import atomic_write_bytes

STATE_SIZE = 12
ACTIONS = 6


def _torch() -> Any:
    import torch

    return torch


def build_model() -> Any:
    """The paper's network (see the module docstring), a torch module."""
    torch = _torch()
    nn = torch.nn

    class NetRouterQ(nn.Module):
        def __init__(self) -> None:
            super().__init__()
            self.body = nn.Sequential(nn.Linear(STATE_SIZE, 32), nn.ReLU(), nn.Linear(32, 64), nn.ReLU(),
                                      nn.Linear(64, 32), nn.ReLU(), nn.Linear(32, ACTIONS))

        def forward(self, state: Any) -> Any:
            x = torch.sign(state) * torch.log1p(torch.abs(state))
            return self.body(x)

    return NetRouterQ()


@dataclass
class NetDQNConfig:
    episodes: int = 4000
    gamma: float = 0.9
    lr: float = 1e-3
    batch: int = 64
    buffer: int = 50_000
    target_every: int = 250  # gradient steps
    eps_start: float = 1.0
    eps_end: float = 0.05
    eps_episodes: int = 300  # linear decay over this many episodes
    warmup: int = 500  # transitions before learning starts
    reward_scale: float = 0.1
    max_seconds: float = 240.0
    # Shaping for training only: r + shaping * (dist(s) - dist(s')), dist = |dx| + |dy| + |dz| of the
    # state (0 at the end): +shaping per step toward the target, -shaping away (the potential-based form
    # of Ng et al. with the discount left out, which would add a bias of dist * (1 - gamma)).
    shaping: float = 10.0
    # Training only: the scaled reward clipped to [-reward_clip, reward_clip] (0 = no clip). The end
    # of an episode carries -500 per new violation, which the 12-d state can hardly predict; unclipped
    # it drowns the rest of the signal.
    reward_clip: float = 5.0


@dataclass
class NetDQNResult:
    model: Any
    episodes: int
    transitions: int
    seconds: float
    connected: int  # episodes that connected their net


def greedy(q: np.ndarray, legal: np.ndarray) -> int:
    """The legal direction of highest Q (any direction when none is legal)."""
    q = np.asarray(q, dtype=np.float64).reshape(-1)
    legal = np.asarray(legal, dtype=bool)
    if not legal.any():
        return int(np.argmax(q))
    return int(np.argmax(np.where(legal, q, -np.inf)))


def train_net_router(envs: list[Any], cfg: NetDQNConfig | None = None, seed: int = 0,
                     log: Any = None) -> NetDQNResult:
    """Trains :func:`build_model` on net-routing envs (round robin, one episode each in turn)."""
    cfg = cfg if cfg is not None else NetDQNConfig()
    torch = _torch()
    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    q = build_model()
    target = build_model()
    target.load_state_dict(q.state_dict())
    opt = torch.optim.Adam(q.parameters(), lr=cfg.lr)
    torch.set_num_threads(1)
    size = 0
    pos = 0
    S = np.zeros((cfg.buffer, STATE_SIZE), np.float32)
    S2 = np.zeros((cfg.buffer, STATE_SIZE), np.float32)
    A = np.zeros(cfg.buffer, np.int64)
    R = np.zeros(cfg.buffer, np.float32)
    D = np.zeros(cfg.buffer, np.float32)
    L2 = np.zeros((cfg.buffer, ACTIONS), bool)
    t0 = time.process_time()
    updates = transitions = connected = 0
    obs_by_env = [env.reset(seed=seed + i)[0] for i, env in enumerate(envs)]
    episode = 0
    while episode < cfg.episodes and time.process_time() - t0 < cfg.max_seconds:
        k = episode % len(envs)
        env = envs[k]
        obs = obs_by_env[k]
        eps = max(cfg.eps_end, cfg.eps_start - (cfg.eps_start - cfg.eps_end) * episode / max(1, cfg.eps_episodes))
        done = False
        info: dict[str, Any] = {}
        while not done:
            legal = env.legal_actions()
            if rng.random() < eps and legal.any():
                a = int(rng.choice(np.flatnonzero(legal)))
            else:
                with torch.no_grad():
                    a = greedy(q(torch.as_tensor(obs[None])).numpy()[0], legal)
            nxt, r, term, trunc, info = env.step(a)
            done = term or trunc
            if cfg.shaping:
                dist = float(np.abs(obs[3:6]).sum())
                dist2 = 0.0 if done else float(np.abs(nxt[3:6]).sum())
                r = r + cfg.shaping * (dist - dist2)
            r_train = r * cfg.reward_scale
            if cfg.reward_clip:
                r_train = float(np.clip(r_train, -cfg.reward_clip, cfg.reward_clip))
            S[pos], A[pos], R[pos], S2[pos], D[pos] = obs, a, r_train, nxt, float(term)
            L2[pos] = env.legal_actions() if not done else False
            pos = (pos + 1) % cfg.buffer
            size = min(size + 1, cfg.buffer)
            obs = nxt
            transitions += 1
            if size >= cfg.warmup:
                idx = rng.integers(0, size, cfg.batch)
                s = torch.from_numpy(S[idx])
                s2 = torch.from_numpy(S2[idx])
                a_t = torch.from_numpy(A[idx])
                r_t = torch.from_numpy(R[idx])
                d_t = torch.from_numpy(D[idx])
                l2_t = torch.from_numpy(L2[idx])
                with torch.no_grad():
                    q2 = target(s2).masked_fill(~l2_t, -1e9).max(1).values
                    q2 = torch.where(l2_t.any(1), q2, torch.zeros_like(q2))
                    y = r_t + cfg.gamma * (1.0 - d_t) * q2
                pred = q(s).gather(1, a_t[:, None])[:, 0]
                loss = torch.nn.functional.smooth_l1_loss(pred, y)
                opt.zero_grad()
                loss.backward()
                opt.step()
                updates += 1
                if updates % cfg.target_every == 0:
                    target.load_state_dict(q.state_dict())
        connected += int(bool(info.get("connected")))
        episode += 1
        if log is not None and episode % 25 == 0:
            log(f"episode {episode}: eps {eps:.2f}, transitions {transitions}, connected {connected}/{episode}")
        obs_by_env[k] = env.reset()[0]
    return NetDQNResult(q.eval(), episode, transitions, time.process_time() - t0, connected)


def export_onnx(model: Any, out: str | Path, meta: dict[str, str] | None = None) -> Path:
    """Writes the model as ONNX (input ``state`` [B, 12], output ``q`` [B, 6]), atomically."""
    torch = _torch()
    import onnx

    buf = io.BytesIO()
    with torch.no_grad(), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        torch.onnx.export(model.cpu().eval(), (torch.zeros(1, STATE_SIZE),), buf, dynamo=False,
                          input_names=["state"], output_names=["q"],
                          dynamic_axes={"state": {0: "batch"}, "q": {0: "batch"}}, opset_version=17)
    proto = onnx.load_from_string(buf.getvalue())
    del proto.metadata_props[:]
    for key, value in {"xroute_model": "net-router", **(meta or {})}.items():
        entry = proto.metadata_props.add()
        entry.key, entry.value = key, str(value)
    onnx.checker.check_model(proto)
    p = Path(out)
    p.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(p, proto.SerializeToString())
    return p


class OnnxNetRouter:
    """An exported net-router model: ``act(state, legal)`` -> direction."""

    def __init__(self, path: str | Path) -> None:
        """Loads the model; a :class:`~xroute.errors.PolicyError` naming the file when it is not a
        readable net-router model (onnxruntime's log lines silenced)."""
        from xroute.errors import PolicyError
        from xroute.policies.onnx_policy import quiet_session_options

        try:
            import onnxruntime as ort
        except ImportError as exc:
            raise PolicyError(f"{path}: net-router models need onnxruntime: pip install 'xroute[rl]'") from exc
        self.path = str(path)
        try:
            self.session = ort.InferenceSession(self.path, quiet_session_options(ort), providers=["CPUExecutionProvider"])
        except Exception as exc:  # noqa: BLE001 - any load failure is a bad model file
            first = " ".join(str(exc).split()) or type(exc).__name__
            raise PolicyError(f"{self.path}: not a readable ONNX model ({first})") from None
        meta = self.session.get_modelmeta().custom_metadata_map
        if meta.get("xroute_model") != "net-router":
            raise PolicyError(f"{self.path}: not a net-router model (xroute_model = {meta.get('xroute_model')!r})")
        names = ([a.name for a in self.session.get_inputs()], [a.name for a in self.session.get_outputs()])
        if names != (["state"], ["q"]):
            raise PolicyError(f"{self.path}: a net-router model has input state float32[B,{STATE_SIZE}] and output "
                              f"q float32[B,{ACTIONS}]; this one has inputs {names[0]} and outputs {names[1]}")

    def q_values(self, state: np.ndarray) -> np.ndarray:
        from xroute.policies.onnx_policy import run_model

        s = np.asarray(state, dtype=np.float32).reshape(-1, STATE_SIZE)
        q = np.asarray(run_model(self.session, self.path, ["q"], {"state": s})[0])
        if q.ndim != 2 or q.shape[1] != ACTIONS:
            from xroute.errors import PolicyError

            raise PolicyError(f"{self.path}: the net-router model returned q of shape {list(q.shape)}, "
                              f"not [B, {ACTIONS}]")
        return q

    def act(self, state: np.ndarray, legal: np.ndarray | None = None) -> int:
        q = self.q_values(state)[0]
        return greedy(q, np.ones(ACTIONS, bool) if legal is None else legal)
