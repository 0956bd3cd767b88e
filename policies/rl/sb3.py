"""MaskablePPO (sb3-contrib) on the net-ordering envs, with a features extractor over the shipped encoders.

Needs ``pip install 'xroute[sb3]'`` (sb3-contrib, which brings stable-baselines3 and torch). The
envs are passed in (this module is layer 3 and does not import :mod:`xroute.envs`);
``examples/maskable_ppo.py`` is the example that trains on a static region.

:class:`NetOrderExtractor` is the piece to reuse with any xroute env. It turns the Dict observation
(:mod:`xroute.envs.core`) into features with the encoders of :class:`~xroute.policies.rl.models.NetOrderModel`:
the obstacle grid and each of the M rows' net grids go through the 3D residual encoders, the scorer
MLP gives one score per row, and the features are ``concat(scores [M], obstacle vector [64])``.
SB3's action head (a linear layer) maps them to the M logits; MaskablePPO masks the rows that
``env.action_masks()`` marks illegal. Every row is encoded, so the cost of a batch grows with M: keep
``max_candidates`` small (the default of the envs, 64, makes each observation 22 MB).
:class:`SetOrderExtractor` does the same for the envs' compact observation (``observation="compact"``:
the set scorer's features per row, no grids) with the set scorer's network; there M can stay 64.

Batch norm stays in eval mode (its running statistics fixed at their initial values, so each batch
norm is a learned per-channel affine map): SB3 switches the policy between training and eval mode
between rollouts and updates, and with batch statistics the two would score differently.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import torch
from gymnasium import spaces
from stable_baselines3.common.torch_layers import BaseFeaturesExtractor
from torch import nn

from xroute.policies.rl.models import EMBED, NetOrderModel


class NetOrderExtractor(BaseFeaturesExtractor):
    """Dict observation -> ``concat(row scores [M], obstacle vector [64])`` (see the module docstring)."""

    def __init__(self, observation_space: spaces.Dict, width: int = 8) -> None:
        m = int(observation_space["action_mask"].n)
        super().__init__(observation_space, features_dim=m + EMBED)
        self.model = NetOrderModel(int(observation_space["net_features"].shape[1]), critic=False, width=width)
        self.train(False)

    def train(self, mode: bool = True) -> "NetOrderExtractor":
        super().train(mode)
        for module in self.modules():
            if isinstance(module, nn.modules.batchnorm._BatchNorm):
                module.eval()
        return self

    def forward(self, observations: dict[str, torch.Tensor]) -> torch.Tensor:
        obstacle = self.model.encode_obstacle(observations["obstacle"])
        nets = observations["nets"]
        b, m = nets.shape[:2]
        scores = self.model.score_rows(obstacle.repeat_interleave(m, 0), nets.flatten(0, 1),
                                       observations["net_features"].flatten(0, 1)).view(b, m)
        return torch.cat([scores, obstacle], 1)


class SetOrderExtractor(BaseFeaturesExtractor):
    """The compact observation (``observation="compact"``: set features [M, F] and the mask) ->
    ``concat(row scores [M], pooled embedding [width])`` with the set scorer's network
    (:class:`~xroute.policies.rl.set_scorer.SetScorer`: an embedding, self-attention over the
    unmasked rows, a score per row and its heuristic prior); the pooled embedding is the mean over
    the unmasked rows, so the critic sees every net. Masked rows score 0 here (MaskablePPO masks
    their logits)."""

    def __init__(self, observation_space: spaces.Dict, width: int = 64) -> None:
        from xroute.policies.rl.set_scorer import SetScorer

        m, f = observation_space["set_features"].shape
        super().__init__(observation_space, features_dim=int(m) + width)
        self.scorer = SetScorer(int(f), width=width)

    def forward(self, observations: dict[str, torch.Tensor]) -> torch.Tensor:
        features, mask = observations["set_features"], observations["action_mask"] > 0.5
        x = self.scorer.encode(features, mask)
        scores = self.scorer.score(x, features)
        weight = mask.float()
        pooled = (x * weight[..., None]).sum(1) / weight.sum(1, keepdim=True).clamp(min=1.0)
        return torch.cat([torch.where(mask, scores, torch.zeros_like(scores)), pooled], 1)


class PerViolation(gym.RewardWrapper):
    """An xroute net-ordering env (or a wrapper of one) with its reward divided by ``scale``, by default
    one violation's weight (500): the reward becomes the drop of the region's cost in violations.
    PPO's value loss grows with the square of the rewards; at the envs' own scale it swamps the
    policy's loss in the encoders the two share. ``action_masks()`` is passed through for MaskablePPO."""

    def __init__(self, env: gym.Env, scale: float | None = None) -> None:
        super().__init__(env)
        self.scale = float(scale if scale is not None else env.unwrapped.weights.drv_weight)

    def reward(self, reward: Any) -> float:
        return float(reward) / self.scale

    def action_masks(self) -> np.ndarray:
        return self.env.unwrapped.action_masks()


def make_maskable_ppo(env: Any, seed: int = 1, n_steps: int = 64, batch_size: int = 32, **kwargs: Any) -> Any:
    """A MaskablePPO on ``env`` (an xroute net-ordering env, best wrapped in :class:`PerViolation`) with
    :class:`NetOrderExtractor` (grid observations) or :class:`SetOrderExtractor` (compact), sized for a
    CPU: ``n_steps`` steps per rollout (the rollout buffer holds that many observations). Learning
    rate 1e-3 and gamma 1 unless ``kwargs`` (MaskablePPO's) say otherwise. With the set extractor its
    row scores start as the heuristic prior alone (the scorer's head at zero, as in imitation)."""
    from sb3_contrib import MaskablePPO
    from stable_baselines3.common.logger import Logger

    compact = "set_features" in env.observation_space.spaces
    policy_kwargs = {"features_extractor_class": SetOrderExtractor if compact else NetOrderExtractor,
                     "net_arch": {"pi": [], "vf": [64]}}
    policy_kwargs.update(kwargs.pop("policy_kwargs", {}))
    settings = {"learning_rate": 1e-3, "gamma": 1.0, **kwargs}  # gamma 1: a region's cost is the sum of its rewards
    model = MaskablePPO("MultiInputPolicy", env, n_steps=n_steps, batch_size=batch_size, seed=seed,
                        policy_kwargs=policy_kwargs, device="cpu", **settings)
    # A logger of its own: SB3's default one makes a folder SB3-<date> in the system's temporary
    # folder at every learn(), outside any folder the caller named.
    model.set_logger(Logger(folder=None, output_formats=[]))
    if compact:  # SB3's orthogonal initialisation redrew the set scorer's head, which starts at zero
        with torch.no_grad():
            for extractor in (model.policy.pi_features_extractor, model.policy.vf_features_extractor):
                extractor.scorer.head.weight.zero_()
                extractor.scorer.head.bias.zero_()
    return model


def greedy_cost(model: Any, env: Any) -> float:
    """The region's cost after one episode in ``model``'s most likely legal action at every step. ``env``
    must not be the one ``model`` trains on (an episode here would end the one its rollout is in)."""
    obs, info = env.reset(seed=0)
    done = False
    while not done:
        action, _ = model.predict(obs, deterministic=True, action_masks=env.action_masks())
        obs, _, done, _, info = env.step(int(action))
    return float(info["cost"])


def random_costs(env: Any, episodes: int, seed: int) -> list[float]:
    """The region's cost after ``episodes`` episodes of uniformly random legal actions (seeded)."""
    rng = np.random.default_rng(seed)
    costs = []
    for _ in range(episodes):
        obs, info = env.reset(seed=0)
        done = False
        while not done:
            obs, _, done, _, info = env.step(int(rng.choice(np.flatnonzero(obs["action_mask"]))))
        costs.append(float(info["cost"]))
    return costs
