"""xroute/ScheduleIteration-v0: each iteration's plan of a whole routing run as the agent's action.

On ispd19_sample4 (or its stand-in) at region size 1, where the flow runs several iterations.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import xroute.envs  # noqa: F401 - registers the IDs
from conftest import pick, require_testcase
from xroute.config import CostSection

SAMPLE4 = pick("ispd19_sample4")
SIZE = 1


@pytest.fixture
def env() -> Any:
    require_testcase(SAMPLE4)
    e = gym.make("xroute/ScheduleIteration-v0", testcase_name=SAMPLE4, region_size=SIZE).unwrapped
    yield e
    e.close()


def episode(env: Any, choose: Any) -> tuple[list[float], dict[str, Any], list[int]]:
    """Runs one episode with ``choose(step, info) -> action``; (rewards, last info, actions)."""
    _, info = env.reset(seed=0)
    rewards, actions = [], []
    while True:
        action = choose(len(actions), info)
        actions.append(action)
        _, reward, terminated, truncated, info = env.step(action)
        rewards.append(reward)
        assert not truncated
        if terminated:
            return rewards, info, actions


def test_check_env_passes(env: Any) -> None:
    from gymnasium.utils.env_checker import check_env

    check_env(env)


@pytest.mark.slow
def test_the_rule_every_iteration_routes_as_the_router_and_the_return_is_the_final_cost(env: Any) -> None:
    """Choosing 'rule' throughout routes the design exactly as route_design does; the rewards add
    up to minus the final cost / 1000 minus the work (net routes per net, times 1 + the search budget)."""
    from xroute.design import load_design
    from xroute.router import route_design

    rewards, info, _ = episode(env, lambda step, info: 0)
    result = info["result"]
    reference = load_design(SAMPLE4)
    expected = route_design(reference, region_size=SIZE)
    assert env.design.def_text() == reference.def_text()
    assert [it.violations for it in result.iterations] == [it.violations for it in expected.iterations]
    assert len(rewards) == len(result.iterations) >= 3
    final = result.iterations[-1]
    nets = env.design.counts()["nets"]
    cost = CostSection().cost(final.wirelength_um, final.vias, final.violations)
    # The rule's own late search (once few markers are left) counts as work too.
    work = sum(it.net_routes * (1 + it.plan.search_budget) for it in result.iterations) / nets
    assert sum(rewards) == pytest.approx(-cost / 1000.0 - work)


def test_stop_is_masked_first_then_ends_the_run_without_the_iteration(env: Any) -> None:
    stop = env.menu.index(("stop", {"stop": True}))
    masks: list[np.ndarray] = []

    def choose(step: int, info: dict[str, Any]) -> int:
        masks.append(info["action_mask"].copy())
        return stop if step == 2 else 0

    rewards, info, _ = episode(env, choose)
    assert not masks[0][stop] and masks[1][stop] and masks[2][stop]
    assert len(info["result"].iterations) == 2 and len(rewards) == 3 and rewards[-1] == 0.0
    with pytest.raises(RuntimeError, match="call reset"):
        env.step(0)


def test_a_size_action_sets_that_iterations_region_size(env: Any) -> None:
    five = [name for name, _ in env.menu].index("size 5")
    _, info, _ = episode(env, lambda step, info: five if step == 1 else 0)
    sizes = [(it.region_size, it.offset) for it in info["result"].iterations]
    assert sizes[0] == (SIZE, 0) and sizes[1] == (5, 1) and all(s == (SIZE, 0) for s in sizes[2:])


def test_a_search_action_runs_the_victims_search_and_costs_its_trials(env: Any) -> None:
    """'victims 4' in the second iteration: that iteration's plan has search budget 4 and its reward
    charges five times its net routes (each searched region routes its nets once more per trial at most)."""
    search = [name for name, _ in env.menu].index("victims 4")
    _, info = env.reset(seed=0)
    env.step(0)
    before = env._cost(env._history[-1])
    _, reward, _, _, info = env.step(search)
    report = info["result"].iterations[1] if "result" in info else env._history[1]
    assert report.plan.search_budget == 4
    expected = (before - env._cost(report)) / 1000.0 - 5 * report.net_routes / env._nets
    assert reward == pytest.approx(expected)


def test_masked_and_unknown_actions_and_a_reset_mid_episode(env: Any) -> None:
    """A masked action (stop before the first iteration) runs the rule's plan and says so; an action
    outside the menu is an error; a reset drops the unfinished run."""
    env.reset(seed=1)
    with pytest.raises(ValueError, match="not in the menu"):
        env.step(len(env.menu))
    _, _, terminated, _, info = env.step(len(env.menu) - 1)  # stop, masked before the first iteration
    assert info["masked_action"] and info["iteration"] == 1 and not terminated
    assert info["history"][0]["plan"]["stop"] is False
    env.step(0)
    obs, info = env.reset(seed=2)  # drops the unfinished run
    assert info["iteration"] == 0 and obs.shape == env.observation_space.shape
    rewards, info, _ = episode(env, lambda step, info: 0)
    assert info["result"].iterations
