"""``xroute/NetOrderingEval-v0``: net ordering, evaluation mode. One episode routes a whole testcase.

``reset()`` loads ``testcase_name`` afresh and starts the router's own flow (as ``xroute route``:
regions of ``region_size`` GCells, up to ``iteration_count`` iterations, rip-up and reroute of the
nets in design-rule markers, early stop at zero violations) in a background thread, with a policy
that lends every region to this env (``needs_region = True``, see :mod:`xroute.net_order`). Each
step routes one net of the region being routed (``action`` = its row, see
:mod:`xroute.envs.core` for the spaces and the reward); when the region's last net is routed
the router commits it and moves on, and the next observation is the next region's. The episode
terminates when the router is done; the final ``info`` holds ``result`` (the
:class:`~xroute.router.RouteResult`) and, with ``out_dir``, ``outputs``: the routed DEF,
metrics JSON and DRC report written by :func:`xroute.outputs.write_route_outputs`, exactly as
``xroute route`` writes them.

The flow is deterministic (one routing thread), so same actions, same episode; ``reset(seed=)``
only seeds ``self.np_random`` (the env draws nothing from it).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from xroute.envs.core import (
    DEFAULT_MAX_CANDIDATES,
    CostWeights,
    RegionEnv,
    RegionStepper,
    RewardFn,
    empty_observation,
)
from xroute.envs.engine_bridge import EngineBridge


class _LendingPolicy:
    """The router's policy during an episode: hands each region to the env and waits until the env
    has routed all of its nets."""

    name = "rl-agent"
    needs_region = True

    def __init__(self, bridge: EngineBridge) -> None:
        self.bridge = bridge

    def order(self, region: dict[str, Any], features: np.ndarray) -> list[int]:
        info = {k: v for k, v in region.items() if k != "engine_region"}
        self.bridge.ask((region["engine_region"], info))
        return list(range(len(features)))  # every net is routed already; nothing is left to order


class NetOrderingEvaluationEnv(RegionEnv):
    """The whole routing flow of a testcase with the agent ordering every region (see the module
    docstring). observation_space / action_space as in :mod:`xroute.envs.core`."""

    def __init__(
        self,
        testcase_name: str = "ispd18_test1",
        region_size: int = 5,
        iteration_count: int = 10,
        *,
        max_candidates: int = DEFAULT_MAX_CANDIDATES,
        weights: CostWeights = CostWeights(),
        reward_fn: RewardFn | None = None,
        out_dir: str | None = None,
        render_mode: str | None = None,
        observation: str = "grid",
    ) -> None:
        from xroute.router import router_settings

        self._settings = router_settings(region_size=region_size, iterations=iteration_count, threads=1)  # checked
        self._init_spaces(max_candidates, observation, render_mode, weights, reward_fn)
        self.testcase_name = testcase_name
        self.region_size = region_size
        self.iteration_count = iteration_count
        self.out_dir = out_dir
        self.design: Any = None
        self._bridge = EngineBridge("xroute-eval-env")
        self._stepper: RegionStepper | None = None
        self._region_info: dict[str, Any] = {}
        self.regions_done = 0

    # -- the routing thread -------------------------------------------------
    def _start(self) -> None:
        from xroute.pipeline import prepare_design
        from xroute.router import route_design

        self.design = prepare_design(self.testcase_name)
        design, policy = self.design, _LendingPolicy(self._bridge)
        self._bridge.start(lambda: route_design(design, settings=self._settings, policy=policy))
        self.regions_done = 0

    def _stop(self) -> None:
        """Aborts an unfinished episode and waits for the routing thread to end."""
        self._bridge.stop()
        self._stepper = None

    def _next_event(self) -> dict[str, Any]:
        """Waits for the router's next region (returns {}) or its end (returns the final info)."""
        asked, payload = self._bridge.next_event()
        if asked:
            region, self._region_info = payload
            self._stepper = RegionStepper(region, self.design.dbu_per_micron, self.max_candidates, self.weights,
                                          self.reward_fn, self.observation)
            return {}
        self._stepper = None
        out: dict[str, Any] = {"result": payload}
        if self.out_dir is not None:
            from xroute.outputs import write_route_outputs

            out["outputs"] = write_route_outputs(self.design, payload, self.out_dir)
        return out

    # -- gymnasium API --------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        self._stop()
        self._start()
        final = self._next_event()
        if self._stepper is None:  # nothing to route at all
            return empty_observation(self.max_candidates, self.observation), self._with_mask(final)
        observation = self._stepper.observation()
        return observation, self._with_mask(self._info())

    def _info(self) -> dict[str, Any]:
        s = self._stepper
        return {"iteration": self._region_info.get("iteration"), "region": self._region_info.get("region"),
                "box": self._region_info.get("box"), "candidates": len(s.rows), "regions_done": self.regions_done,
                "cost": s.cost, "metrics": s.metrics}

    def step(self, action: int):
        observation, reward, region_done, info = self._step_region(action)
        if not region_done:
            return observation, reward, False, False, info
        self.regions_done += 1
        info["regions_done"] = self.regions_done
        self._bridge.answer(None)
        final = self._next_event()
        if self._stepper is None:
            info.update(final)
            return empty_observation(self.max_candidates, self.observation), reward, True, False, self._with_mask(info)
        info.update(self._info())
        observation = self._stepper.observation()
        return observation, reward, False, False, self._with_mask(info)

    def close(self) -> None:
        self._stop()


def ordering_evaluation_env(testcase_name: str = "ispd18_test1", region_size: int = 5, iteration_count: int = 10,
                            **kwargs: Any) -> NetOrderingEvaluationEnv:
    """The paper's evaluation-mode env (see :class:`NetOrderingEvaluationEnv`)."""
    return NetOrderingEvaluationEnv(testcase_name, region_size, iteration_count, **kwargs)
