"""``xroute/ScheduleIteration-v0``: the iteration schedule as a decision. One episode routes a design.

``reset()`` loads ``testcase_name`` afresh and starts the router's flow (as ``xroute route``) in a
background thread with a schedule policy (:mod:`xroute.schedule`) that hands every decision to this
env: before each iteration the agent picks one entry of ``menu`` - a change to the rule's plan for
that iteration (the rule itself, another region size, repair rounds, other weights, the victims
search in that iteration, or stopping the run) - and the iteration runs with it. The episode ends when the flow ends (the iteration limit,
zero violations, or a stop).

Spaces:

* action: ``Discrete(len(menu))``; ``info["action_mask"]`` masks ``stop`` before the first
  iteration (it routes every net) and any entry whose region size the design cannot take; a masked
  action runs the rule's plan instead, with ``info["masked_action"]`` true;
* observation: ``Box(float32, (8 + number of violation types,), 0..1e9)``: the share of the iteration
  limit done, log1p of the last iteration's violations and of each type's, the last iteration's
  violation ratio to the one before (1 before two iterations), its region size / 10, its wire
  and via totals relative to the first iteration's, the net routes it made per net, and whether
  its violations fell.

Reward after each iteration: the drop of the paper's cost (0.5 per µm + 4 per via + 500 per
violation; from 0 before the first iteration) divided by 1,000, minus ``work_weight`` times the
iteration's net routes per net of the design, times 1 + the iteration's search budget (a
deterministic stand-in for its time: a searched region routes its nets once more per trial at
most); an episode's
return is so minus the final cost / 1,000 minus the weighted work. Stopping earns 0 and ends the
episode. The flow is deterministic, so same actions, same episode; ``reset(seed=)`` only
seeds ``self.np_random`` (the env draws nothing from it).
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import gymnasium as gym
import numpy as np

from xroute.envs.engine_bridge import EngineBridge

# Each entry: (name, change to the rule's plan). A size without an offset takes the rule's offsets for
# that size (0, C/3, 2C/3 by iteration), as --region-size does.
DEFAULT_MENU: tuple[tuple[str, dict[str, Any]], ...] = (
    ("rule", {}),
    ("size 5", {"region_size": 5}),
    ("size 7", {"region_size": 7}),
    ("repair 1", {"repair_rounds": 1}),
    ("double weights", {"marker_penalty": 6000, "history_penalty": 2000}),
    ("victims 4", {"search_budget": 4}),
    ("stop", {"stop": True}),
)


OBS_HIGH = 1e9  # no observation entry comes near it (log counts, ratios, shares)


class _AgentSchedule:
    """The router's schedule policy during an episode: asks the env for each iteration's plan."""

    name = "rl-agent"

    def __init__(self, bridge: EngineBridge) -> None:
        self.bridge = bridge

    def plan(self, history: Sequence[Any], rule: Any) -> Any:
        return self.bridge.ask((list(history), rule))


class ScheduleIterationEnv(gym.Env):
    """The agent chooses each iteration's plan of a whole routing run (see the module docstring)."""

    metadata = {"render_modes": []}

    def __init__(self, testcase_name: str = "ispd19_sample4", region_size: int = 10, iteration_count: int | None = None,
                 *, menu: Sequence[tuple[str, dict[str, Any]]] = DEFAULT_MENU, work_weight: float = 1.0,
                 threads: int = 1, render_mode: str | None = None) -> None:
        from xroute.config import CostSection
        from xroute.router import DEFAULT_ITERATIONS, VIOLATION_TYPES, router_settings

        iteration_count = DEFAULT_ITERATIONS if iteration_count is None else iteration_count
        self._settings = router_settings(region_size=region_size, iterations=iteration_count, threads=threads)
        if not menu or not all(isinstance(change, dict) for _, change in menu):
            raise ValueError("menu: a non-empty sequence of (name, plan change) pairs")
        self.testcase_name = testcase_name
        self.region_size = region_size
        self.iteration_count = iteration_count
        self.threads = threads
        self.menu = tuple((str(name), dict(change)) for name, change in menu)
        self.work_weight = float(work_weight)
        self.cost = CostSection()
        self.types = tuple(VIOLATION_TYPES)
        self.render_mode = render_mode
        self.action_space = gym.spaces.Discrete(len(self.menu))
        self.observation_space = gym.spaces.Box(0.0, OBS_HIGH, shape=(8 + len(self.types),), dtype=np.float32)
        self.design: Any = None
        self._bridge = EngineBridge("xroute-schedule-env")
        self._history: list[Any] = []
        self._rule: Any = None

    # -- the routing thread -------------------------------------------------
    def _start(self) -> None:
        from xroute.pipeline import prepare_design
        from xroute.router import route_design

        self.design = prepare_design(self.testcase_name)
        design, policy = self.design, _AgentSchedule(self._bridge)
        self._bridge.start(lambda: route_design(design, settings=self._settings, schedule_policy=policy))

    def _stop(self) -> None:
        """Aborts an unfinished episode and waits for the routing thread to end."""
        self._bridge.stop()

    def _next_event(self) -> Any:
        """Waits for the router's next question (returns None) or its end (returns the RouteResult)."""
        asked, payload = self._bridge.next_event()
        if asked:
            self._history, self._rule = payload
            return None
        self._history = list(payload.iterations)
        return payload

    # -- observation, mask, reward --------------------------------------------
    def _cost(self, report: Any) -> float:
        return self.cost.cost(report.wirelength_um, report.vias, report.violations)

    def _observation(self) -> np.ndarray:
        obs = np.zeros(self.observation_space.shape, dtype=np.float32)
        obs[0] = len(self._history) / self.iteration_count
        if not self._history:
            return obs
        last, first = self._history[-1], self._history[0]
        obs[1] = math.log1p(last.violations)
        before = self._history[-2].violations if len(self._history) > 1 else last.violations
        obs[2] = last.violations / before if before else 1.0
        obs[3] = last.region_size / 10.0
        obs[4] = last.wirelength_dbu / first.wirelength_dbu if first.wirelength_dbu else 1.0
        obs[5] = last.vias / first.vias if first.vias else 1.0
        obs[6] = last.net_routes / self._nets
        obs[7] = float(len(self._history) > 1 and last.violations < self._history[-2].violations)
        for i, name in enumerate(self.types):
            obs[8 + i] = math.log1p(last.violations_by_type.get(name, 0))
        return obs

    def _mask(self) -> np.ndarray:
        from xroute.defaults import MAX_REGION_SIZE

        mask = np.ones(len(self.menu), dtype=bool)
        for i, (_, change) in enumerate(self.menu):
            if change.get("stop") and not self._history:
                mask[i] = False
            if not 1 <= int(change.get("region_size", 1)) <= MAX_REGION_SIZE:
                mask[i] = False
        return mask

    @staticmethod
    def _work(report: Any) -> float:
        """The iteration's net routes, times 1 + its search budget: each searched region routes its nets
        once more per trial at most (the deterministic stand-in for the search's time)."""
        budget = report.plan.search_budget if report.plan is not None else 0
        return float(report.net_routes * (1 + budget))

    def _info(self, **extra: Any) -> dict[str, Any]:
        # The reports' figures without their wall times, so that same actions give the same info.
        timed = ("seconds", "stage_seconds")  # wall times differ from run to run
        history = [{k: v for k, v in r.to_dict().items() if k not in timed} for r in self._history]
        return {"action_mask": self._mask(), "iteration": len(self._history), "history": history,
                "menu": [name for name, _ in self.menu], **extra}

    def _plan(self, action: int) -> dict[str, Any]:
        """The menu entry's change to the rule's plan (xroute.schedule.plan_from makes it the plan)."""
        change = dict(self.menu[action][1])
        if "region_size" in change and "offset" not in change:
            size = int(change["region_size"])
            change["offset"] = ((len(self._history) % 3) * size) // 3
        return change

    # -- gymnasium API --------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        self._stop()
        self._start()
        self._nets = max(1, self.design.counts()["nets"])
        final = self._next_event()
        return self._observation(), self._info(**({"result": final} if final is not None else {}))

    def step(self, action: int):
        if not self._bridge.running:
            raise RuntimeError("step() after the episode ended: call reset()")
        action = int(action)
        if not 0 <= action < len(self.menu):
            raise ValueError(f"action {action} is not in the menu (0..{len(self.menu) - 1})")
        masked = not self._mask()[action]
        if masked:  # any action of the space is taken (as Gymnasium's checker expects): the rule's plan runs
            action = 0
        done_before = len(self._history)
        before = self._cost(self._history[-1]) if self._history else 0.0
        self._bridge.answer(self._plan(action))
        final = self._next_event()
        reward = 0.0
        if len(self._history) > done_before:  # the iteration ran (a stop ends the run without it)
            report = self._history[done_before]
            reward = (before - self._cost(report)) / 1000.0 - self.work_weight * self._work(report) / self._nets
        terminated = final is not None
        info = self._info(**({"result": final} if final is not None else {}), masked_action=masked)
        return self._observation(), float(reward), terminated, False, info

    def close(self) -> None:
        self._stop()


def schedule_iteration_env(testcase_name: str = "ispd19_sample4", region_size: int = 10,
                           iteration_count: int | None = None,
                           **kwargs: Any) -> ScheduleIterationEnv:
    """The iteration-schedule env (see :class:`ScheduleIterationEnv`)."""
    return ScheduleIterationEnv(testcase_name, region_size, iteration_count, **kwargs)
