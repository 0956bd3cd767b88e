"""``xroute/StaticRegion-v0``: net ordering on one static region written by ``xroute make-region``.

``region_dir`` holds region.lef / region.def / region.guide / region.yaml (see
:mod:`xroute.testcases.regions`). Every episode routes the same region from scratch: the whole die of the
clipped design (the region box plus the components it keeps), with its boundary pins as terminals.
Nothing is committed, so every episode starts from the same state.

Spaces and reward: see :mod:`xroute.envs.core`. ``reset(seed=)`` seeds ``self.np_random``;
the env draws nothing from it (same actions, same episode).
"""

from __future__ import annotations

from typing import Any


from xroute.envs.core import (
    DEFAULT_MAX_CANDIDATES,
    CostWeights,
    RegionEnv,
    RegionStepper,
    RewardFn,
)


class StaticRegionEnv(RegionEnv):
    """One static region, one episode per reset (see the module docstring).

    observation_space: Dict(obstacle (3, 64, 64), nets (M, 7, 3, 64, 64), net_features (M, S),
    action_mask MultiBinary(M)), or with ``observation="compact"`` Dict(set_features (M, F), action_mask);
    action_space: Discrete(M), M = ``max_candidates``.
    """

    def __init__(self, region_dir: str, *, max_candidates: int = DEFAULT_MAX_CANDIDATES,
                 weights: CostWeights = CostWeights(), reward_fn: RewardFn | None = None,
                 render_mode: str | None = None, observation: str = "grid") -> None:
        from xroute.testcases.regions import load_region
        from xroute.session import open_session

        self.region_dir = str(region_dir)
        self._init_spaces(max_candidates, observation, render_mode, weights, reward_fn)
        self.design, self.meta = load_region(self.region_dir)
        self.box = tuple(self.meta["die"])
        self._session = open_session(self.design)
        self._stepper: RegionStepper | None = None

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        region = self._session.open_region(self.box)
        self._stepper = RegionStepper(region, self.design.dbu_per_micron, self.max_candidates, self.weights,
                                      self.reward_fn, self.observation)
        observation = self._stepper.observation()
        return observation, self._with_mask(self._info())

    def _info(self) -> dict[str, Any]:
        s = self._stepper
        return {"box": self.box, "candidates": len(s.rows), "cost": s.cost, "metrics": s.metrics}

    def step(self, action: int):
        observation, reward, done, info = self._step_region(action)
        return observation, reward, done, False, info


def static_region_env(region_dir: str, **kwargs: Any) -> StaticRegionEnv:
    """The paper's static-region env (see :class:`StaticRegionEnv`)."""
    return StaticRegionEnv(region_dir, **kwargs)


def generate_static_region(testcase_name: str, region_location: tuple[int, int] | None = None, region_size: int = 1,
                           out_dir: str | None = None, *, box: tuple[int, int, int, int] | None = None) -> str:
    """The paper's ``generate_static_region``: writes the region of ``testcase_name`` whose lower-left GCell
    is ``region_location`` (``region_size`` GCells a side), or the ``box`` in DBU, as a static region
    folder (:func:`xroute.testcases.regions.make_region`, ``xroute make-region``) into ``out_dir`` (default:
    a new temporary folder) and returns the folder, ready for :func:`static_region_env`."""
    import tempfile
    from pathlib import Path

    from xroute.testcases.regions import make_region

    if out_dir is None:
        out_dir = str(Path(tempfile.mkdtemp(prefix="xroute-region-")) / "region")
    if box is not None:
        summary = make_region(testcase_name, out_dir, box=tuple(int(v) for v in box))
    else:
        location = None if region_location is None else (int(region_location[0]), int(region_location[1]))
        summary = make_region(testcase_name, out_dir, location=location, size=int(region_size))
    return str(summary.out_dir)
