"""DQN over net orders: the candidate scores are Q-values; epsilon-greedy over legal candidates.

Acting: with probability ``epsilon_greedy`` the legal candidate of highest Q (model in eval mode),
otherwise a uniformly random legal one (numpy generator seeded by the caller). Learning: a replay
buffer of ``buffer_size`` transitions (oldest dropped); once it holds ``learning_starts``, every
``train_every`` env steps one gradient step on ``batch_size`` sampled transitions with the Huber
loss between Q(s, a) and r + gamma x max over legal a' of Q_target(s', a') (0 after the last net
of a region); the target network is a copy of the model refreshed every ``target_update``
gradient steps. The model runs in eval mode throughout (as exported); its batch-norm statistics
are re-estimated on :data:`BATCH_NORM_SAMPLE` buffered states just before each target copy
(:func:`~xroute.policies.rl.batch.refresh_batch_norm`), and once when learning starts.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np
import torch

from xroute.policies.rl.batch import StoredObs, chosen_rows, collate, refresh_batch_norm
from xroute.policies.rl.models import NetOrderModel
from xroute.policies.rl.train_config import DQNConfig


BATCH_NORM_SAMPLE = 64
"""Buffered states the batch-norm statistics are re-estimated on."""


@dataclass
class Transition:
    state: StoredObs
    action: int
    reward: float  # scaled
    next_state: StoredObs | None  # None when the region is done


class DQNTrainer:
    """Acts epsilon-greedily, records transitions, learns from replay."""

    algorithm = "dqn"

    def __init__(self, cfg: DQNConfig, num_net_features: int, device: torch.device, seed: int) -> None:
        self.cfg = cfg
        self.device = device
        self.model = NetOrderModel(num_net_features, critic=False, width=cfg.width).to(device)
        self.target = copy.deepcopy(self.model).eval()
        self.optimizer = torch.optim.Adam(self.model.parameters(), lr=cfg.lr)
        self.rng = np.random.default_rng(seed)
        self.buffer: list[Transition] = []
        self.next_slot = 0
        self.env_steps = 0
        self.gradient_steps = 0
        self.last_losses: dict[str, float] = {}

    @torch.no_grad()
    def q_values(self, state: StoredObs) -> torch.Tensor:
        """Q-values [K] of one state (masked rows -1e9), model in eval mode."""
        self.model.eval()
        b = collate([state], self.device)
        return self.model.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)[0][0]

    def act(self, state: StoredObs) -> int:
        legal = np.flatnonzero(state.mask)
        if self.rng.random() < self.cfg.epsilon_greedy:
            return int(torch.argmax(self.q_values(state)))
        return int(self.rng.choice(legal))

    def record(self, state: StoredObs, action: int, reward: float, done: bool, next_state: StoredObs | None) -> None:
        t = Transition(state, action, reward * self.cfg.reward_scale, None if done else next_state)
        if len(self.buffer) < self.cfg.buffer_size:
            self.buffer.append(t)
        else:
            self.buffer[self.next_slot] = t
        self.next_slot = (self.next_slot + 1) % self.cfg.buffer_size
        self.env_steps += 1
        if len(self.buffer) >= self.cfg.learning_starts and self.env_steps % self.cfg.train_every == 0:
            self.learn()

    def learn(self) -> None:
        """One gradient step on a sampled batch."""
        cfg = self.cfg
        if self.gradient_steps == 0:
            refresh_batch_norm(self.model, [t.state for t in self.buffer[:BATCH_NORM_SAMPLE]], self.device)
            self.target.load_state_dict(self.model.state_dict())
        idx = self.rng.choice(len(self.buffer), size=cfg.batch_size, replace=False)
        batch = [self.buffer[i] for i in idx]
        nexts = [t.next_state for t in batch if t.next_state is not None]
        target_max = torch.zeros(len(batch), device=self.device)
        if nexts:
            with torch.no_grad():
                b = collate(nexts, self.device)
                q_next, _ = self.target.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)
                live = torch.tensor([t.next_state is not None for t in batch], device=self.device)
                target_max[live] = q_next.max(dim=1).values
        rewards = torch.tensor([t.reward for t in batch], dtype=torch.float32, device=self.device)
        y = rewards + cfg.gamma * target_max
        b = chosen_rows([t.state for t in batch], [t.action for t in batch], self.device)
        obs_vec = self.model.encode_obstacle(b.obstacle)
        q = self.model.score_rows(obs_vec[b.row_state], b.nets, b.net_features)
        loss = torch.nn.functional.smooth_l1_loss(q, y)
        if not torch.isfinite(loss):
            raise FloatingPointError("training diverged (non-finite loss); lower the learning rate")
        self.optimizer.zero_grad()
        loss.backward()
        torch.nn.utils.clip_grad_norm_(self.model.parameters(), cfg.grad_clip)
        self.optimizer.step()
        self.gradient_steps += 1
        if self.gradient_steps % cfg.target_update == 0:
            sample = self.rng.choice(len(self.buffer), size=min(len(self.buffer), BATCH_NORM_SAMPLE), replace=False)
            refresh_batch_norm(self.model, [self.buffer[i].state for i in sample], self.device)
            self.target.load_state_dict(self.model.state_dict())
        self.last_losses = {"td_loss": loss.item()}
