"""Torch models of the net-order policy (the XRoute paper's architecture, sized for CPU).

Imported only by the training, checkpoint and export modules (``pip install 'xroute[train]'``);
nothing that routes with a shipped ONNX model imports torch.

Layout (shapes as in ``xroute.policies.rl.observation``: the aligned grid is (z, y, x) = (3, 64, 64))::

    obstacle [B, 3, 64, 64]  --GridEncoder(1 channel)-->  obstacle vector [B, 64]
    nets  [K, 7, 3, 64, 64]  --GridEncoder(7 channels)--> net vector      [K, 64]
    scorer MLP(64 + 64 + S -> 128 -> 64 -> 1, ELU) on concat(obstacle, net, net features) -> score
    critic MLP(64 -> 64 -> 64 -> 1, tanh) on the obstacle vector -> state value (PPO only)

GridEncoder (the paper's 3D residual encoder; the strides are ours, chosen so that scoring a
region's candidate nets costs a few milliseconds on one CPU thread):

* stem: Conv3d k=(1,8,8) stride (1,8,8) -> width 8 on (3, 8, 8), BatchNorm3d, ReLU (each output
  sees its whole 8x8 patch of one layer, so no cell of the 0/1 grid is skipped; a max-pool first
  was measured slower than this strided convolution, which reads the big input only once);
* residual block at width 8 on (3, 8, 8): two Conv3d 3x3x3 (padding 1) + BatchNorm3d, skip;
* down: Conv3d k=(1,2,2) stride (1,2,2) -> width 16 on (3, 4, 4), BatchNorm3d, ReLU;
* residual block at width 16 on (3, 4, 4);
* final Conv3d with a (3, 4, 4) kernel -> 64 channels on one cell = the 64-d vector.

The z axis (3 layers) is never strided: the 3x3x3 convolutions see layer neighbours.

Masked candidates (``mask`` False) score -1e9 (:data:`MASKED_SCORE`): higher score = route earlier,
so they are never chosen and sort last.
"""

from __future__ import annotations

import torch
from torch import nn

from xroute.policies.rl.observation import ALIGNED_SHAPE, NET_CHANNELS

EMBED = 64
"""Length of the obstacle and net vectors."""

MASKED_SCORE = -1e9
"""Score of a masked (already routed or padding) candidate."""


class ResBlock3d(nn.Module):
    """Two 3x3x3 convolutions with batch norm and an identity skip connection."""

    def __init__(self, width: int) -> None:
        super().__init__()
        self.conv1 = nn.Conv3d(width, width, 3, padding=1, bias=False)
        self.bn1 = nn.BatchNorm3d(width)
        self.conv2 = nn.Conv3d(width, width, 3, padding=1, bias=False)
        self.bn2 = nn.BatchNorm3d(width)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        y = torch.relu(self.bn1(self.conv1(x)))
        y = self.bn2(self.conv2(y))
        return torch.relu(x + y)


class GridEncoder(nn.Module):
    """A (channels, 3, 64, 64) grid -> a 64-d vector (see the module docstring for the strides)."""

    def __init__(self, in_channels: int, width: int = 8) -> None:
        super().__init__()
        self.stem = nn.Sequential(
            nn.Conv3d(in_channels, width, kernel_size=(1, 8, 8), stride=(1, 8, 8), bias=False),
            nn.BatchNorm3d(width),
            nn.ReLU(),
        )
        self.block1 = ResBlock3d(width)
        self.down = nn.Sequential(
            nn.Conv3d(width, 2 * width, kernel_size=(1, 2, 2), stride=(1, 2, 2), bias=False),
            nn.BatchNorm3d(2 * width),
            nn.ReLU(),
        )
        self.block2 = ResBlock3d(2 * width)
        z, y, x = ALIGNED_SHAPE
        self.head = nn.Conv3d(2 * width, EMBED, kernel_size=(z, y // 16, x // 16))

    def forward(self, grid: torch.Tensor) -> torch.Tensor:
        h = self.block1(self.stem(grid))
        h = self.block2(self.down(h))
        return self.head(h).flatten(1)


def mlp(sizes: list[int], activation: type[nn.Module]) -> nn.Sequential:
    """Linear layers of the given sizes with ``activation`` between them (none after the last)."""
    layers: list[nn.Module] = []
    for i in range(len(sizes) - 1):
        layers.append(nn.Linear(sizes[i], sizes[i + 1]))
        if i < len(sizes) - 2:
            layers.append(activation())
    return nn.Sequential(*layers)


class NetOrderModel(nn.Module):
    """Scores every candidate net of a region; with ``critic=True`` also values the state (PPO).

    DQN uses the same model without critic: the scores are its Q-values.
    """

    def __init__(self, num_net_features: int, critic: bool = False, width: int = 8) -> None:
        super().__init__()
        self.num_net_features = int(num_net_features)
        self.width = int(width)
        self.obstacle_encoder = GridEncoder(1, width)
        self.net_encoder = GridEncoder(NET_CHANNELS, width)
        self.scorer = mlp([2 * EMBED + self.num_net_features, 128, 64, 1], nn.ELU)
        self.critic = mlp([EMBED, 64, 64, 1], nn.Tanh) if critic else None

    def encode_obstacle(self, obstacle: torch.Tensor) -> torch.Tensor:
        """obstacle [B, 3, 64, 64] -> [B, 64]."""
        return self.obstacle_encoder(obstacle.unsqueeze(1))

    def score_rows(self, obstacle_vec: torch.Tensor, nets: torch.Tensor, net_features: torch.Tensor) -> torch.Tensor:
        """Raw scores [K] of K nets [K, 7, 3, 64, 64] with their features [K, S], each against its
        state's obstacle vector [K, 64]."""
        net_vec = self.net_encoder(nets)
        return self.scorer(torch.cat([obstacle_vec, net_vec, net_features], dim=1)).squeeze(1)

    def forward(
        self, obstacle: torch.Tensor, nets: torch.Tensor, net_features: torch.Tensor, mask: torch.Tensor
    ) -> torch.Tensor:
        """Scores [B, M] of a batch of states: obstacle [B, 3, 64, 64], nets [B, M, 7, 3, 64, 64],
        net_features [B, M, S], mask bool [B, M]. Only the unmasked rows are encoded; masked rows
        get :data:`MASKED_SCORE`."""
        scores, _ = self.scores_and_obstacle(obstacle, nets, net_features, mask)
        return scores

    def scores_and_obstacle(
        self, obstacle: torch.Tensor, nets: torch.Tensor, net_features: torch.Tensor, mask: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """(scores [B, M], obstacle vectors [B, 64]): :meth:`forward` plus what the critic reads."""
        b_idx, m_idx = torch.nonzero(mask, as_tuple=True)
        return self.score_flat(obstacle, nets[b_idx, m_idx], net_features[b_idx, m_idx], b_idx, m_idx, mask)

    def score_flat(
        self,
        obstacle: torch.Tensor,
        rows: torch.Tensor,
        row_features: torch.Tensor,
        row_state: torch.Tensor,
        row_slot: torch.Tensor,
        mask: torch.Tensor,
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """(scores [B, K], obstacle vectors [B, 64]) from B obstacles [B, 3, 64, 64] and R legal rows
        (nets [R, 7, 3, 64, 64], features [R, S]) placed at (row_state, row_slot) of a [B, K] score
        table; every other entry of the table is :data:`MASKED_SCORE`."""
        obstacle_vec = self.encode_obstacle(obstacle)
        raw = self.score_rows(obstacle_vec[row_state], rows, row_features)
        scores = torch.full(mask.shape, MASKED_SCORE, dtype=raw.dtype, device=raw.device)
        scores = scores.index_put((row_state, row_slot), raw)
        return scores, obstacle_vec

    def value(self, obstacle_vec: torch.Tensor) -> torch.Tensor:
        """State values [B] from obstacle vectors [B, 64] (PPO's critic)."""
        if self.critic is None:
            raise RuntimeError("this model has no critic (DQN)")
        return self.critic(obstacle_vec).squeeze(1)


class RegionScorer(nn.Module):
    """The exported graph (the ONNX contract): one region, all N candidates scored in one call.

    obstacle [1, 3, 64, 64], nets [N, 7, 3, 64, 64], net_features [N, S], mask bool [N] -> scores [N].
    Every row is encoded (no data-dependent gather, so the graph has a plain dynamic N axis) and the
    mask is applied with ``where``.
    """

    def __init__(self, model: NetOrderModel) -> None:
        super().__init__()
        self.model = model

    def forward(
        self, obstacle: torch.Tensor, nets: torch.Tensor, net_features: torch.Tensor, mask: torch.Tensor
    ) -> torch.Tensor:
        obstacle_vec = self.model.encode_obstacle(obstacle)
        rows = obstacle_vec.expand(nets.shape[0], EMBED)
        raw = self.model.score_rows(rows, nets, net_features)
        return torch.where(mask, raw, torch.full_like(raw, MASKED_SCORE))


def parameter_count(module: nn.Module) -> int:
    """Number of trainable parameters."""
    return sum(p.numel() for p in module.parameters() if p.requires_grad)
