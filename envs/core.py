"""What every net-ordering environment shares: spaces, the cost and reward, and one region stepped
net by net (:class:`RegionStepper`).

Spaces (M = ``max_candidates``, S = ``len(NET_FEATURES)``; see :mod:`xroute.policies.rl.observation`)::

    observation = Dict(obstacle:     Box(0, 1, (3, 64, 64), float32),
                       nets:         Box(0, 1, (M, 7, 3, 64, 64), float32),
                       net_features: Box(-inf, inf, (M, S), float32),
                       action_mask:  MultiBinary(M))
    action      = Discrete(M)   # the row of the next net to route

With ``observation="compact"`` (every env takes it; the default is ``"grid"``, the paper's), the
grids are left out and each row carries the set scorer's features instead
(:data:`~xroute.policies.rl.set_features.SET_FEATURES`, F of them, computed from the region as it
is at that step)::

    observation = Dict(set_features: Box(-inf, inf, (M, F), float32),
                       action_mask:  MultiBinary(M))

about 5 KB at M = 64 against 22 MB for the grids.

Rows: when the region has N <= M candidates, row i is candidate i (rows of routed candidates and
rows past N are masked out; rows past N are zero). When N > M, the rows are the M unrouted
candidates first in the heuristic order, chosen again at every step. An action on a masked row
routes the first unmasked row instead (``info["invalid_action"] = True``).

Reward of a step: ``cost(s) - cost(s')`` with ``cost = wirelength_um * 0.5 + vias * 4 +
violations * 500`` (:class:`CostWeights`) over the region's new routing and its design-rule
markers (``Region.metrics()``: violations inside the region box, the new routing against
everything around it; a full check of the box after every step). ``reward_fn(before, after)`` on
the two metrics dicts replaces it; ``info`` carries ``metrics`` and ``cost`` for wrappers.
"""

from __future__ import annotations

from typing import Any, Callable

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from xroute.config import CostSection
from xroute.net_order import heuristic_order
from xroute.policies.rl.observation import ALIGNED_SHAPE, NET_CHANNELS, NET_FEATURES, observe_arrays, unrouted_mask
from xroute.policies.rl.set_features import SET_FEATURES, region_set_features

DEFAULT_MAX_CANDIDATES = 64
OBSERVATIONS = ("grid", "compact")
"""The observation kinds (see the module docstring); ``grid`` is the default."""

RewardFn = Callable[[dict[str, Any], dict[str, Any]], float]


CostWeights = CostSection
"""The paper's cost weights (:class:`xroute.config.CostSection`, their one definition)."""


def check_observation(value: str) -> str:
    if value not in OBSERVATIONS:
        raise ValueError(f"observation must be one of {list(OBSERVATIONS)}, got {value!r}")
    return value


def observation_space(max_candidates: int, observation: str = "grid") -> spaces.Dict:
    """The Dict observation space of every xroute env (see the module docstring)."""
    m = int(max_candidates)
    if check_observation(observation) == "compact":
        return spaces.Dict({
            "set_features": spaces.Box(-np.inf, np.inf, (m, len(SET_FEATURES)), np.float32),
            "action_mask": spaces.MultiBinary(m),
        })
    return spaces.Dict({
        "obstacle": spaces.Box(0.0, 1.0, ALIGNED_SHAPE, np.float32),
        "nets": spaces.Box(0.0, 1.0, (m, NET_CHANNELS) + ALIGNED_SHAPE, np.float32),
        "net_features": spaces.Box(-np.inf, np.inf, (m, len(NET_FEATURES)), np.float32),
        "action_mask": spaces.MultiBinary(m),
    })


def empty_observation(max_candidates: int, observation: str = "grid") -> dict[str, np.ndarray]:
    """An all-zero observation (every row masked): what an env shows once there is nothing left."""
    m = int(max_candidates)
    if check_observation(observation) == "compact":
        return {"set_features": np.zeros((m, len(SET_FEATURES)), np.float32), "action_mask": np.zeros(m, np.int8)}
    return {
        "obstacle": np.zeros(ALIGNED_SHAPE, np.float32),
        "nets": np.zeros((m, NET_CHANNELS) + ALIGNED_SHAPE, np.float32),
        "net_features": np.zeros((m, len(NET_FEATURES)), np.float32),
        "action_mask": np.zeros(m, np.int8),
    }


def check_max_candidates(value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"max_candidates must be a positive integer, got {value!r}")
    return int(value)


class RegionStepper:
    """One engine Region routed one net per step, with observations, costs and rewards."""

    def __init__(self, region: Any, dbu_per_micron: int, max_candidates: int, weights: CostWeights,
                 reward_fn: RewardFn | None = None, observation: str = "grid") -> None:
        self.region = region
        self.kind = check_observation(observation)
        self.dbu = int(dbu_per_micron)
        self.m = int(max_candidates)
        self.weights = weights
        self.reward_fn = reward_fn
        self.rows = np.asarray(region.candidates, dtype=np.int32)
        self.heuristic = heuristic_order(self.rows)
        self.metrics = region.metrics()
        self.cost = weights.region_cost(self.metrics, self.dbu)
        self.slots = np.zeros(0, dtype=np.int64)
        self.order: list[int] = []  # candidate indices in the order routed
        # The net channels depend only on the terminals, fixed for the region: built once per row set.
        self._nets: np.ndarray | None = None
        self._nets_slots: np.ndarray | None = None

    @property
    def done(self) -> bool:
        return len(self.region.unrouted()) == 0

    def _choose_slots(self, mask: np.ndarray) -> np.ndarray:
        n = len(self.rows)
        if n <= self.m:
            return np.arange(n, dtype=np.int64)
        pending = self.heuristic[mask[self.heuristic]]
        return np.asarray(pending[: self.m], dtype=np.int64)

    def observation(self) -> dict[str, np.ndarray]:
        """The padded observation dict of the region now (and fixes the rows the next action means)."""
        mask = unrouted_mask(self.region)
        self.slots = self._choose_slots(mask)
        out = empty_observation(self.m, self.kind)
        if self.kind == "compact":
            k = len(self.slots)
            out["set_features"][:k] = region_set_features(self.region)[self.slots]
            out["action_mask"][:k] = mask[self.slots]
            return out
        reuse = self._nets is not None and np.array_equal(self._nets_slots, self.slots)
        obs = observe_arrays(self.region.grid(), self.rows, mask, tuple(self.region.box), select=self.slots,
                             nets_out=None if reuse else out["nets"], with_nets=not reuse)
        k = len(self.slots)
        if reuse:
            out["nets"][:k] = self._nets[:k]  # a new array every step (gymnasium's rule), same content
        else:
            self._nets, self._nets_slots = out["nets"], self.slots.copy()
        out["obstacle"] = obs.obstacle
        out["net_features"][:k] = obs.net_features
        out["action_mask"][:k] = obs.mask
        return out

    def action_mask(self) -> np.ndarray:
        """bool[M]: the legal rows of the last observation."""
        out = np.zeros(self.m, dtype=bool)
        if len(self.slots):
            routed = np.array([self.region.is_routed(int(c)) for c in self.slots], dtype=bool)
            out[: len(self.slots)] = ~routed
        return out

    def step(self, action: int) -> tuple[float, dict[str, Any]]:
        """Routes the net of row ``action``; returns the reward and an info dict."""
        legal = self.action_mask()
        if not legal.any():
            raise RuntimeError("this region has no unrouted candidate left; reset the environment")
        a = int(action)
        invalid = not (0 <= a < self.m and legal[a])
        if invalid:
            a = int(np.flatnonzero(legal)[0])
        cand = int(self.slots[a])
        result = self.region.route_net(cand)
        self.order.append(cand)
        before = self.metrics
        self.metrics = self.region.metrics()
        cost = self.weights.region_cost(self.metrics, self.dbu)
        if self.reward_fn is not None:
            reward = float(self.reward_fn(before, self.metrics))
        else:
            reward = self.cost - cost
        self.cost = cost
        info = {"net": int(result["net"]), "candidate": cand, "invalid_action": invalid,
                "metrics": self.metrics, "cost": cost, "unreached": int(result["unreached"])}
        return float(reward), info


RENDER_MODES = ["rgb_array"]


def check_render_mode(render_mode: str | None) -> str | None:
    if render_mode is not None and render_mode not in RENDER_MODES:
        raise ValueError(f"render_mode must be None or one of {RENDER_MODES}, got {render_mode!r}")
    return render_mode


class RegionEnv(gym.Env):
    """What the net-ordering envs share: the current episode's :class:`RegionStepper` (None between
    episodes), its action mask and its engine Region, ``info["action_mask"]`` and ``render()``.
    Subclasses call :meth:`_init_spaces` in ``__init__``, create the stepper in ``reset`` and
    define ``_info()`` (the env's own info keys)."""

    metadata = {"render_modes": RENDER_MODES, "render_fps": 4}
    max_candidates: int
    render_mode: str | None = None
    _stepper: RegionStepper | None = None

    def _init_spaces(self, max_candidates: int, observation: str, render_mode: str | None,
                     weights: CostWeights, reward_fn: RewardFn | None) -> None:
        """Checks and keeps the settings every net-ordering env has, and sets its spaces:
        Dict observations of ``max_candidates`` rows (:func:`observation_space`), Discrete(M) actions."""
        self.render_mode = check_render_mode(render_mode)
        self.observation = check_observation(observation)
        self.max_candidates = check_max_candidates(max_candidates)
        self.weights = weights
        self.reward_fn = reward_fn
        self.observation_space = observation_space(self.max_candidates, self.observation)
        self.action_space = gym.spaces.Discrete(self.max_candidates)

    def _info(self) -> dict[str, Any]:
        raise NotImplementedError

    def _with_mask(self, info: dict[str, Any]) -> dict[str, Any]:
        """``info`` with ``action_mask`` (bool[M]) of the observation just made (call after it)."""
        info["action_mask"] = self.action_masks()
        return info

    def _step_region(self, action: int) -> tuple[dict[str, np.ndarray], float, bool, dict[str, Any]]:
        """Routes the chosen net: (observation, reward, region done, info with the env's keys and the
        next observation's action mask)."""
        if self._stepper is None:
            raise RuntimeError("the episode is over (or never started): call reset()")
        reward, info = self._stepper.step(action)
        info.update(self._info())
        observation = self._stepper.observation()
        return observation, reward, self._stepper.done, self._with_mask(info)

    def render(self) -> np.ndarray | None:
        """With ``render_mode="rgb_array"``: uint8[H, W, 3], the current region seen from above
        (:func:`xroute.envs.render.render_grid`; a blank square between episodes). Otherwise None."""
        if self.render_mode != "rgb_array":
            return None
        from xroute.envs.render import blank_picture, render_region

        return blank_picture() if self._stepper is None else render_region(self._stepper.region)

    def action_masks(self) -> np.ndarray:
        """bool[M]: rows that are legal actions now (sb3-contrib MaskablePPO convention)."""
        if self._stepper is None:
            return np.zeros(self.max_candidates, dtype=bool)
        return self._stepper.action_mask()

    @property
    def region(self) -> Any:
        """The engine Region of the current episode (None between episodes)."""
        return None if self._stepper is None else self._stepper.region
