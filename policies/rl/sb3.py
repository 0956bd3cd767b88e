"""MaskablePPO (sb3-contrib) on the net-ordering envs, with a features extractor over the shipped encoders.

    python -m xroute.policies.rl.sb3 REGION_DIR [--steps 512] [--max-candidates 8] [--seed 1]

REGION_DIR is a static region (``xroute make-region`` or :func:`xroute.envs.generate_static_region`);
the script trains MaskablePPO on it and prints the cost of the region routed in the policy's
greedy order before and after training, against the mean of random legal orders. Needs
``pip install 'xroute[sb3]'`` (sb3-contrib, which brings stable-baselines3 and torch).

:class:`NetOrderExtractor` is the piece to reuse with any xroute env. It turns the Dict observation
(:mod:`xroute.envs.core`) into features with the encoders of :class:`~xroute.policies.rl.models.NetOrderModel`:
the obstacle grid and each of the M rows' net grids go through the 3D residual encoders, the scorer
MLP gives one score per row, and the features are ``concat(scores [M], obstacle vector [64])``.
SB3's action head (a linear layer) maps them to the M logits; MaskablePPO masks the rows that
``env.action_masks()`` marks illegal. Every row is encoded, so the cost of a batch grows with M: keep
``max_candidates`` small (the default of the envs, 64, makes each observation 22 MB).

Batch norm stays in eval mode (its running statistics fixed at their initial values, so each batch
norm is a learned per-channel affine map): SB3 switches the policy between training and eval mode
between rollouts and updates, and with batch statistics the two would score differently.
"""

from __future__ import annotations

import argparse
from typing import Any, Callable

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
        self.rows = m
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


def violations_reward(env: Any) -> Callable[[dict[str, Any], dict[str, Any]], float]:
    """A ``reward_fn`` for ``env`` (an xroute env): its reward, the drop of the region's cost, in units
    of one violation's weight (500). PPO's value loss grows with the square of the rewards; at the
    envs' scale it swamps the policy's loss in the encoders the two share."""
    weights, dbu = env.weights, env.design.dbu_per_micron

    def reward(before: dict[str, Any], after: dict[str, Any]) -> float:
        return (weights.region_cost(before, dbu) - weights.region_cost(after, dbu)) / weights.drv_weight

    return reward


def make_maskable_ppo(env: Any, seed: int = 1, n_steps: int = 64, batch_size: int = 32, **kwargs: Any) -> Any:
    """A MaskablePPO on ``env`` (an xroute net-ordering env, best with :func:`violations_reward`) with
    :class:`NetOrderExtractor`, sized for CPU: ``n_steps`` steps per rollout (the rollout buffer holds
    that many observations). Learning rate 1e-3 and gamma 1 unless ``kwargs`` (MaskablePPO's) say
    otherwise."""
    from sb3_contrib import MaskablePPO

    policy_kwargs = {"features_extractor_class": NetOrderExtractor, "net_arch": {"pi": [], "vf": [64]}}
    policy_kwargs.update(kwargs.pop("policy_kwargs", {}))
    settings = {"learning_rate": 1e-3, "gamma": 1.0, **kwargs}  # gamma 1: a region's cost is the sum of its rewards
    return MaskablePPO("MultiInputPolicy", env, n_steps=n_steps, batch_size=batch_size, seed=seed,
                       policy_kwargs=policy_kwargs, device="cpu", **settings)


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


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("region_dir")
    ap.add_argument("--steps", type=int, default=512, help="environment steps (nets routed) to train for")
    ap.add_argument("--max-candidates", type=int, default=8)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args(argv)
    from xroute.envs import static_region_env

    torch.set_num_threads(1)
    env = static_region_env(a.region_dir, max_candidates=a.max_candidates)
    env.reward_fn = violations_reward(env)
    judge = static_region_env(a.region_dir, max_candidates=a.max_candidates)
    model = make_maskable_ppo(env, seed=a.seed)
    before = greedy_cost(model, judge)
    model.learn(total_timesteps=a.steps)
    after = greedy_cost(model, judge)
    rand = random_costs(judge, 20, a.seed)
    print(f"greedy order: cost {before:,.1f} before training, {after:,.1f} after {a.steps} steps; "
          f"random orders: mean {np.mean(rand):,.1f}, best {min(rand):,.1f} of {len(rand)}")


if __name__ == "__main__":
    main()
