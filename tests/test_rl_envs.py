"""Gymnasium environments of net ordering (xroute.envs, the envs/ folder): check_env, seeded determinism,
rewards against the paper's cost, and the evaluation env against ``xroute route``."""

from __future__ import annotations

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium", reason="the rl extra (gymnasium) is not installed")

from conftest import nets_of, pick, require_testcase  # noqa: E402

# The contract's net_features space is unbounded on purpose; gymnasium warns about it.
pytestmark = pytest.mark.filterwarnings("ignore:.*infinity")


def _rollout(env, seed: int, steps: int) -> list[tuple]:
    """(observation digest, reward, terminated) per step, actions drawn from the mask with ``seed``."""
    rng = np.random.default_rng(seed)
    obs, _ = env.reset(seed=seed)
    out = []
    for _ in range(steps):
        a = int(rng.choice(np.flatnonzero(env.action_masks())))
        obs, reward, terminated, _, _ = env.step(a)
        digest = tuple(float(obs[k].sum()) for k in ("obstacle", "nets", "net_features")) + (
            tuple(obs["action_mask"].tolist()),)
        out.append((digest, reward, terminated))
        if terminated:
            obs, _ = env.reset()
    return out


def test_envs_are_registered_on_import() -> None:
    import xroute.envs  # noqa: F401  (registers the environments)

    for env_id in ("xroute/NetOrdering-v0", "xroute/NetOrderingEval-v0", "xroute/StaticRegion-v0"):
        assert env_id in gym.registry


SAMPLE = pick("ispd18_sample")  # or its generated stand-in (10 nets in one region) without the contest data


def test_training_env_passes_check_env_and_walks_regions() -> None:
    from gymnasium.utils.env_checker import check_env

    import xroute.envs  # noqa: F401  (registers the environments)

    require_testcase(SAMPLE)
    env = gym.make("xroute/NetOrdering-v0", testcase_name=SAMPLE, region_size=2, max_candidates=8)
    check_env(env.unwrapped, skip_render_check=True)
    obs, info = env.reset(seed=3)
    assert env.observation_space.contains(obs)
    first = info["region_location"]
    mask = env.unwrapped.action_masks()
    assert mask.dtype == bool and mask.tolist() == obs["action_mask"].astype(bool).tolist()
    assert mask.sum() == info["candidates"]
    # Route the whole region: the episode ends when every candidate is routed.
    for k in range(info["candidates"]):
        obs, reward, terminated, truncated, step_info = env.step(int(np.flatnonzero(env.unwrapped.action_masks())[0]))
        assert terminated == (k == info["candidates"] - 1) and not truncated
    assert not obs["action_mask"].any()
    _, info2 = env.reset()
    assert info2["region_location"] != first


def test_training_env_same_seed_same_episode() -> None:
    from xroute.envs.ordering_training import ordering_training_env

    require_testcase(SAMPLE)
    a = _rollout(ordering_training_env(SAMPLE, region_size=2, max_candidates=8), 5, 25)
    b = _rollout(ordering_training_env(SAMPLE, region_size=2, max_candidates=8), 5, 25)
    assert a == b
    assert any(term for _, _, term in a)


def test_reward_is_the_drop_of_the_paper_cost() -> None:
    from xroute.envs.core import CostWeights
    from xroute.envs.ordering_training import ordering_training_env

    require_testcase(SAMPLE)
    weights = CostWeights(wirelength_weight=1.0, via_weight=2.0, drv_weight=100.0)
    env = ordering_training_env(SAMPLE, region_size=100, max_candidates=16, weights=weights)
    _, info = env.reset(seed=0)
    cost0 = info["cost"]
    total = 0.0
    done = False
    while not done:
        _, reward, done, _, step = env.step(int(np.flatnonzero(env.action_masks())[0]))
        total += reward
    m = step["metrics"]
    expected = m["wirelength_dbu"] / 2000 * 1.0 + m["vias"] * 2.0 + m["violations"] * 100.0
    assert step["cost"] == pytest.approx(expected)
    assert total == pytest.approx(cost0 - expected)
    assert m["nets_routed"] == info["candidates"] == nets_of(SAMPLE)


def test_an_invalid_action_routes_the_first_legal_row() -> None:
    from xroute.envs.ordering_training import ordering_training_env

    require_testcase(SAMPLE)
    env = ordering_training_env(SAMPLE, region_size=100, max_candidates=16)
    env.reset(seed=0)
    _, _, _, _, info = env.step(15)  # row 15 is past the 11 candidates (10 for the stand-in)
    assert nets_of(SAMPLE) < 15
    assert info["invalid_action"] and info["candidate"] == 0
    _, _, _, _, info = env.step(0)  # row 0 is routed now
    assert info["invalid_action"] and info["candidate"] == 1


def test_evaluation_env_routes_the_testcase_like_xroute_route(tmp_path) -> None:
    from gymnasium.utils.env_checker import check_env

    from xroute.net_order import heuristic_order
    from xroute.envs.ordering_evaluation import ordering_evaluation_env
    from xroute import load_design
    from xroute.router import route_design

    require_testcase(SAMPLE)
    env = ordering_evaluation_env(SAMPLE, region_size=2, iteration_count=3, max_candidates=8,
                                  out_dir=str(tmp_path))
    check_env(env, skip_render_check=True)
    env.reset(seed=0)
    steps, done = 0, False
    while not done:
        # The heuristic's choice: the first unrouted candidate in heuristic order.
        stepper = env._stepper
        order = heuristic_order(stepper.rows)
        pending = [int(c) for c in order if not stepper.region.is_routed(int(c))]
        row = int(np.flatnonzero(stepper.slots == pending[0])[0])
        _, _, done, _, info = env.step(row)
        steps += 1
    env.close()
    result = info["result"]
    reference = route_design(load_design(SAMPLE), region_size=2, iterations=3)
    assert steps == sum(r.net_routes for r in reference.iterations)
    assert result.final.wirelength_dbu == reference.final.wirelength_dbu
    assert result.final.vias == reference.final.vias
    assert result.violations == reference.violations
    outputs = info["outputs"]
    assert outputs.def_path.is_file() and outputs.metrics_path.is_file() and outputs.drc_report_path.is_file()


def test_region_loop_replays_a_region_from_the_same_state_and_location_pins_it() -> None:
    from xroute.envs.ordering_training import ordering_training_env

    require_testcase(SAMPLE)

    def finish(env) -> None:
        done = False
        while not done:
            _, _, done, _, _ = env.step(int(np.flatnonzero(env.action_masks())[-1]))

    env = ordering_training_env(SAMPLE, region_size=2, region_loop=2, max_candidates=8)
    obs1, info1 = env.reset(seed=0)
    finish(env)
    obs2, info2 = env.reset()
    assert (info2["region_location"], info2["replay"]) == (info1["region_location"], 2)
    assert all(np.array_equal(obs1[k], obs2[k]) for k in obs1)
    finish(env)
    _, info3 = env.reset()
    assert info3["region_location"] != info1["region_location"] and info3["replay"] == 1

    pinned = ordering_training_env(SAMPLE, region_size=2, region_location=info3["region_location"],
                                   max_candidates=8)
    first, _ = pinned.reset(seed=1)
    for _ in range(3):
        finish(pinned)
        again, info = pinned.reset()
        assert info["region_location"] == info3["region_location"]
        assert np.array_equal(again["obstacle"], first["obstacle"])
    assert pinned.passes_done == 3 and pinned.finished
