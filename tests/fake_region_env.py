"""A tiny Gymnasium env with the net-ordering spaces of the RL contract (no engine, no data).

Each episode is a "region" of 2..max_candidates nets with random grids and features; routing
net i costs ``1 + 10 * (max of feature 0 over the unrouted nets - feature0(i))`` (so routing the
nets by decreasing feature 0 is best, at cost 1 per net), reported like the real envs: reward = cost(s) - cost(s'), ``info["cost"]`` and
``info["metrics"]``. Seeded through ``reset(seed=)``.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from xroute.policies.rl.observation import ALIGNED_SHAPE, NET_CHANNELS, NET_FEATURES


class FakeRegionEnv(gym.Env):
    metadata = {"render_modes": []}

    def __init__(self, max_candidates: int = 6, fixed_seed: int | None = None) -> None:
        m = max_candidates
        self.fixed_seed = fixed_seed  # every reset draws this same region (like the envs' region_loop)
        self.m = m
        self.observation_space = spaces.Dict({
            "obstacle": spaces.Box(0.0, 1.0, ALIGNED_SHAPE, np.float32),
            "nets": spaces.Box(0.0, 1.0, (m, NET_CHANNELS) + ALIGNED_SHAPE, np.float32),
            "net_features": spaces.Box(-np.inf, np.inf, (m, len(NET_FEATURES)), np.float32),
            "action_mask": spaces.MultiBinary(m),
        })
        self.action_space = spaces.Discrete(m)

    def _obs(self) -> dict:
        obstacle = self.base.copy()
        obstacle[0, : 4 * self.routed_count, :8] = 1.0
        return {"obstacle": obstacle, "nets": self.nets, "net_features": self.features,
                "action_mask": self.mask.astype(np.int8)}

    def reset(self, *, seed=None, options=None):
        super().reset(seed=self.fixed_seed if self.fixed_seed is not None else seed)
        r = self.np_random
        self.n = int(r.integers(2, self.m + 1))
        self.base = (r.random(ALIGNED_SHAPE) < 0.2).astype(np.float32)
        self.nets = np.zeros((self.m, NET_CHANNELS) + ALIGNED_SHAPE, np.float32)
        self.nets[: self.n] = (r.random((self.n, NET_CHANNELS) + ALIGNED_SHAPE) < 0.02)
        self.features = np.zeros((self.m, len(NET_FEATURES)), np.float32)
        self.features[: self.n] = r.random((self.n, len(NET_FEATURES)))
        self.mask = np.zeros(self.m, bool)
        self.mask[: self.n] = True
        self.routed_count = 0
        self.cost = 0.0
        return self._obs(), {}

    def action_masks(self) -> np.ndarray:
        return self.mask.copy()

    def step(self, action):
        a = int(action)
        if not self.mask[a]:
            a = int(np.flatnonzero(self.mask)[0])
        best = float(self.features[self.mask, 0].max())
        step_cost = 1.0 + 10.0 * (best - float(self.features[a, 0]))
        self.mask[a] = False
        self.routed_count += 1
        self.cost += step_cost
        done = not self.mask.any()
        info = {"cost": self.cost, "metrics": {"wirelength_dbu": 100 * self.routed_count, "vias": self.routed_count,
                                               "violations": 0}}
        return self._obs(), -step_cost, done, False, info
