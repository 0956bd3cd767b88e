"""PPO over net orders: a masked categorical policy on the candidate scores, a critic on the obstacle.

The model always runs in eval mode (batch norm on its running statistics, as the exported model
does). Every ``update_every`` env steps: the batch-norm statistics are re-estimated on the
rollout's states (:func:`~xroute.policies.rl.batch.refresh_batch_norm`), the rollout's log-probs and
values are recomputed with them (so each update starts at ratio 1), and the rollout is replayed
``epochs`` times in shuffled minibatches of ``batch_size`` transitions: clipped surrogate loss +
``value_coef`` x squared error of the critic against GAE(``gamma``, ``gae_lambda``) returns -
``entropy_coef`` x entropy. Two Adam parameter groups: encoders + scorer at ``lr_actor``,
critic MLP at ``lr_critic`` (the critic's error also trains the obstacle encoder, at the
actor's rate). Advantages are normalised per rollout. Randomness: torch's generator, seeded by
the caller (``torch.manual_seed``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from xroute.policies.rl.batch import StoredObs, collate, refresh_batch_norm
from xroute.policies.rl.models import NetOrderModel
from xroute.policies.rl.train_config import PPOConfig


@dataclass
class Step:
    state: StoredObs
    action: int
    log_prob: float
    value: float
    reward: float  # scaled
    done: bool


class PPOTrainer:
    """Acts, records transitions and updates the model every ``update_every`` steps."""

    algorithm = "ppo"

    def __init__(self, cfg: PPOConfig, num_net_features: int, device: torch.device) -> None:
        self.cfg = cfg
        self.device = device
        self.model = NetOrderModel(num_net_features, critic=True, width=cfg.width).to(device)
        assert self.model.critic is not None
        critic_ids = {id(p) for p in self.model.critic.parameters()}
        actor = [p for p in self.model.parameters() if id(p) not in critic_ids]
        self.optimizer = torch.optim.Adam([
            {"params": actor, "lr": cfg.lr_actor},
            {"params": list(self.model.critic.parameters()), "lr": cfg.lr_critic},
        ])
        self.rollout: list[Step] = []
        self.updates = 0
        self.last_losses: dict[str, float] = {}

    @torch.no_grad()
    def _evaluate(self, state: StoredObs) -> tuple[torch.Tensor, float]:
        self.model.eval()
        b = collate([state], self.device)
        scores, obs_vec = self.model.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)
        return scores[0], float(self.model.value(obs_vec)[0])

    def act(self, state: StoredObs) -> int:
        """Samples an action of the masked categorical policy (and remembers its log-prob, value)."""
        scores, value = self._evaluate(state)
        dist = torch.distributions.Categorical(logits=scores)
        action = int(dist.sample())
        self._pending = (action, float(dist.log_prob(torch.tensor(action, device=scores.device))), value)
        return action

    def record(self, state: StoredObs, action: int, reward: float, done: bool, next_state: StoredObs | None) -> None:
        """Stores the transition; updates when the rollout is full (``next_state`` bootstraps it)."""
        a, log_prob, value = self._pending
        assert a == action, "record() must follow act() for the same state"
        self.rollout.append(Step(state, action, log_prob, value, reward * self.cfg.reward_scale, done))
        if len(self.rollout) >= self.cfg.update_every:
            self.update(None if done else next_state)

    def _advantages(self, last_value: float) -> tuple[np.ndarray, np.ndarray]:
        n = len(self.rollout)
        adv = np.zeros(n, dtype=np.float64)
        gae = 0.0
        for t in reversed(range(n)):
            s = self.rollout[t]
            next_value = last_value if t == n - 1 else self.rollout[t + 1].value
            nonterminal = 0.0 if s.done else 1.0
            delta = s.reward + self.cfg.gamma * next_value * nonterminal - s.value
            gae = delta + self.cfg.gamma * self.cfg.gae_lambda * nonterminal * gae
            adv[t] = gae
        returns = adv + np.array([s.value for s in self.rollout])
        return adv, returns

    def update(self, next_state: StoredObs | None) -> None:
        """PPO epochs over the rollout (``next_state``: the state after its last step, None when
        that step ended an episode), then clears it."""
        cfg = self.cfg
        refresh_batch_norm(self.model, [s.state for s in self.rollout], self.device)
        with torch.no_grad():
            for start in range(0, len(self.rollout), 16):
                steps = self.rollout[start : start + 16]
                b = collate([s.state for s in steps], self.device)
                scores, obs_vec = self.model.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)
                log_prob = torch.distributions.Categorical(logits=scores).log_prob(
                    torch.tensor([s.action for s in steps], device=self.device))
                for s, lp, v in zip(steps, log_prob.tolist(), self.model.value(obs_vec).tolist()):
                    s.log_prob, s.value = lp, v
        last_value = 0.0 if next_state is None else self._evaluate(next_state)[1]
        adv, returns = self._advantages(last_value)
        adv = (adv - adv.mean()) / (adv.std() + 1e-8)
        n = len(self.rollout)
        totals = {"policy_loss": 0.0, "value_loss": 0.0, "entropy": 0.0}
        count = 0
        for _ in range(cfg.epochs):
            perm = torch.randperm(n).tolist()
            for start in range(0, n, cfg.batch_size):
                idx = perm[start : start + cfg.batch_size]
                steps = [self.rollout[i] for i in idx]
                b = collate([s.state for s in steps], self.device)
                scores, obs_vec = self.model.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)
                dist = torch.distributions.Categorical(logits=scores)
                actions = torch.tensor([s.action for s in steps], device=self.device)
                log_prob = dist.log_prob(actions)
                old = torch.tensor([s.log_prob for s in steps], device=self.device)
                a = torch.tensor(adv[idx], dtype=torch.float32, device=self.device)
                ratio = torch.exp(log_prob - old)
                policy_loss = -torch.min(ratio * a, torch.clamp(ratio, 1 - cfg.clip, 1 + cfg.clip) * a).mean()
                ret = torch.tensor(returns[idx], dtype=torch.float32, device=self.device)
                value_loss = ((self.model.value(obs_vec) - ret) ** 2).mean()
                entropy = dist.entropy().mean()
                loss = policy_loss + cfg.value_coef * value_loss - cfg.entropy_coef * entropy
                if not torch.isfinite(loss):
                    raise FloatingPointError("training diverged (non-finite loss); lower the learning rates")
                self.optimizer.zero_grad()
                loss.backward()
                torch.nn.utils.clip_grad_norm_(self.model.parameters(), cfg.grad_clip)
                self.optimizer.step()
                totals["policy_loss"] += policy_loss.item()
                totals["value_loss"] += value_loss.item()
                totals["entropy"] += entropy.item()
                count += 1
        self.rollout.clear()
        self.updates += 1
        self.last_losses = {k: v / max(1, count) for k, v in totals.items()}
