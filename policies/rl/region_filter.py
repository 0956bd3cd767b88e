"""A wrapper of the training env that skips some regions: held-out ones, and ones with no choice.

``hold_out_every = K`` (> 0) holds out the regions whose column and row (x, y) in the partition
(the lower-left GCell divided by the region size: the GCell itself for 1x1 regions) have
``x % K == K // 2`` and ``y % K == K // 2`` (a regular 1-in-K² sample across the die, kept for
evaluation). With regions of the flow's first pass (colour ``(x % 2) + 2 (y % 2)``), an even K
holds out regions of one colour only; an odd K (3, the in-context benchmark's) mixes all four; ``min_candidates`` skips regions with fewer candidate nets (a region of one net
has no order to learn). A skipped region is left to the env, which routes it with the heuristic
and commits it before opening the next, so later regions still see it as routed neighbours.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym

MAX_SKIPS = 100_000


def held_out(location: tuple[int, int], hold_out_every: int, region_size: int = 1) -> bool:
    """Whether the region with this lower-left GCell (regions of ``region_size`` GCells, the
    partition starting at GCell 0) is held out (see the module docstring)."""
    if hold_out_every <= 0:
        return False
    k = hold_out_every
    c = max(1, int(region_size))
    return (location[0] // c) % k == k // 2 and (location[1] // c) % k == k // 2


class RegionFilter(gym.Wrapper):
    """Resets until the env's region is neither held out nor smaller than ``min_candidates``."""

    def __init__(self, env: gym.Env, hold_out_every: int = 0, min_candidates: int = 1) -> None:
        super().__init__(env)
        self.hold_out_every = int(hold_out_every)
        self.min_candidates = int(min_candidates)
        self.skipped = 0

    def _skip(self, info: dict[str, Any]) -> bool:
        location = info.get("region_location")
        size = int(info.get("region_size", 1))
        if location is not None and held_out(tuple(location), self.hold_out_every, size):
            return True
        return int(info.get("candidates", self.min_candidates)) < self.min_candidates

    def reset(self, **kwargs: Any):
        obs, info = self.env.reset(**kwargs)
        for _ in range(MAX_SKIPS):
            if not self._skip(info):
                return obs, info
            self.skipped += 1
            obs, info = self.env.reset()
        raise RuntimeError("every region is held out or too small to train on")

    def action_masks(self):
        return self.env.unwrapped.action_masks()
