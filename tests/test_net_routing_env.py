"""``xroute/NetRouting-v0`` (envs/net_routing.py): check_env, seeded determinism, A* paths replayed as
actions give the maze's routing, illegal moves, the T_min cut, net_loop, and the shipped ONNX model.
All on the shipped demo design (no contest data)."""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium", reason="the rl extra (gymnasium) is not installed")

pytestmark = pytest.mark.filterwarnings("ignore:.*infinity")

MODEL = Path(__file__).resolve().parent.parent / "policies" / "models" / "net_router_dqn.onnx"


def _env(**kwargs):
    import xroute.envs  # noqa: F401  (registers the environments)

    return gym.make("xroute/NetRouting-v0", **kwargs).unwrapped


def _rollout(env, seed: int, episodes: int) -> list[tuple]:
    rng = np.random.default_rng(seed)
    obs, info = env.reset(seed=seed)
    out = [(obs.tobytes(), info["candidate"])]
    for _ in range(episodes):
        done = False
        while not done:
            legal = env.legal_actions()
            a = int(rng.choice(np.flatnonzero(legal))) if legal.any() and rng.random() < 0.9 else int(rng.integers(6))
            obs, reward, terminated, truncated, info = env.step(a)
            out.append((obs.tobytes(), reward, terminated, truncated))
            done = terminated or truncated
        obs, info = env.reset()
        out.append((obs.tobytes(), info["candidate"]))
    return out


def _actions_for(region, cand: int, path: list[int]) -> list[int]:
    out = []
    for u, v in itertools.pairwise(path):
        nodes, _ = region.moves(cand, u)
        out.append(list(nodes).index(v))
    return out


def test_registered_and_check_env() -> None:
    from gymnasium.utils.env_checker import check_env

    import xroute.envs

    assert "xroute/NetRouting-v0" in gym.registry
    assert xroute.envs.net_routing_env().action_space == gym.spaces.Discrete(6)
    env = _env()
    check_env(env, skip_render_check=True)
    obs, info = env.reset(seed=1)
    assert env.observation_space.contains(obs) and obs.shape == (12,)
    assert info["pins"] >= 2 and info["t_min"] == -info["hpwl"] * info["pins"]


def test_seeded_determinism() -> None:
    a = _rollout(_env(), seed=5, episodes=4)
    b = _rollout(_env(), seed=5, episodes=4)
    assert a == b


def test_astar_path_replayed_gives_the_maze_routing() -> None:
    env = _env()
    obs, info = env.reset(seed=0)
    cand, box = info["candidate"], info["box"]
    maze_region = env._session.open_region(box)  # the same state: a fresh region, nothing routed yet
    maze = maze_region.route_net(cand)
    paths = maze_region.net_paths(cand)
    assert maze["unreached"] == 0 and len(paths) == 1 and info["pins"] == 2  # a two-pin net: one path
    obs, info = env.reset(seed=0, options={"start_node": paths[0][0]})
    assert info["candidate"] == cand
    total = 0.0
    actions = _actions_for(env.region, cand, paths[0])
    for k, a in enumerate(actions):
        assert obs[6 + a] >= 0  # the observation shows the move as legal
        obs, reward, terminated, truncated, info = env.step(a)
        total += reward
        assert terminated == (k == len(actions) - 1) and not truncated
    assert info["connected"] and not info["illegal"] and info["paths"] == paths
    got, want = info["metrics"], maze_region.metrics()
    assert (got["wirelength_dbu"], got["vias"], got["violations"]) == (maze["wirelength_dbu"], maze["vias"],
                                                                       want["violations"])
    cost = env.weights.cost(maze["wirelength_dbu"] / env.dbu, maze["vias"], want["violations"])
    assert total == pytest.approx(info["hpwl"] - cost)


def test_multi_terminal_net_connects() -> None:
    """A net with three or more terminals: a scripted walk toward the target connects every terminal, the
    head jumping back to the tree after each one; one path per terminal reached is committed."""
    env = _env()
    env.reset(seed=0)
    for _ in range(40):
        obs, info = env.reset()
        if info["pins"] >= 3:
            break
    else:
        pytest.skip("no net with three terminals in the first regions of the demo")
    cand = info["candidate"]
    walk = env._net
    done = False
    steps = 0
    while not done and steps < 2000:
        legal = env.legal_actions()
        d = obs[3:6]
        prefs = []
        for axis, (pos, neg) in enumerate(((4, 5), (2, 3), (0, 1))):
            v = d[(0, 1, 2)[axis]]
            if v > 0:
                prefs.append(pos)
            elif v < 0:
                prefs.append(neg)
        choice = next((a for a in prefs if legal[a]), None)
        if choice is None:
            choice = int(np.flatnonzero(legal)[0]) if legal.any() else 0
        obs, _reward, terminated, truncated, info = env.step(choice)
        done = terminated or truncated
        steps += 1
    assert done and info["candidate"] == cand
    assert info["connected"] and all(walk.reached) and len(info["paths"]) == info["pins"] - 1
    assert info["unreached"] == 0  # the engine's count of the committed paths


def test_illegal_move_ends_the_episode() -> None:
    env = _env()
    obs, info = env.reset(seed=0)
    legal = env.legal_actions()
    assert ((obs[6:] >= 0) == legal).all()
    bad = int(np.flatnonzero(~legal)[0])
    obs, reward, terminated, truncated, info = env.step(bad)
    assert terminated and not truncated and info["illegal"] and not info["connected"]
    assert info["moves"] == 0 and reward == pytest.approx(0.0) and info["unreached"] == info["pins"] - 1
    with pytest.raises(RuntimeError):
        env.step(0)
    # the net is kept unrouted, and the next episode routes the next net
    obs, info2 = env.reset()
    assert info2["candidate"] != info["candidate"]


def test_t_min_cuts_an_episode() -> None:
    env = _env(t_min_scale=0.02)
    _, info = env.reset(seed=0)
    assert info["t_min"] == pytest.approx(-0.02 * info["hpwl"] * info["pins"])
    total, done, steps = 0.0, False, 0
    while not done:
        # away from the target: the head wanders until the total reward is below T_min
        a = int(np.flatnonzero(env.legal_actions())[-1])
        _obs, reward, terminated, truncated, info = env.step(a)
        total += reward
        done = terminated or truncated
        steps += 1
    assert truncated and not terminated and info["cut"] and not info["connected"]
    assert info["total_reward"] < info["t_min"]


def test_net_loop_replays_each_net() -> None:
    env = _env(net_loop=2)
    seen = []
    _, info = env.reset(seed=0)
    for _ in range(4):
        seen.append((info["candidate"], info["attempt"]))
        env.step(int(np.flatnonzero(env.legal_actions())[0]))
        _obs, info = env.reset()
    assert seen[0][0] == seen[1][0] and [s[1] for s in seen] == [1, 2, 1, 2] and seen[2][0] != seen[0][0]


def test_shipped_onnx_model_acts() -> None:
    pytest.importorskip("onnxruntime")
    from xroute.policies.rl.net_dqn import OnnxNetRouter

    model = OnnxNetRouter(MODEL)
    env = _env()
    obs, _ = env.reset(seed=0)
    q = model.q_values(obs)
    assert q.shape == (1, 6) and np.isfinite(q).all()
    for _ in range(5):
        a = model.act(obs, env.legal_actions())
        assert 0 <= a < 6 and env.legal_actions()[a]
        obs, _reward, terminated, truncated, _info = env.step(a)
        if terminated or truncated:
            break


def test_net_router_policy_routes_the_demo_with_astar_taking_over() -> None:
    """`xroute route --net-router`'s policy: the model's connected nets committed, A* for the rest, no opens."""
    pytest.importorskip("onnxruntime")
    from xroute import load_design
    from xroute.policies.net_router import NetRouterPolicy
    from xroute.router import route_design

    d = load_design("demo")
    policy = NetRouterPolicy(MODEL, d.dbu_per_micron, max_moves=60)
    route_design(d, iterations=1, policy=policy)
    assert policy.stats["agent_connected"] > 0 and policy.stats["astar_fallback"] > 0
    assert d.engine.check_connectivity()["open_nets"] == 0


def test_route_net_router_option_is_checked(runner, tmp_path) -> None:
    from xroute.cli.app import app

    both = runner.invoke(app, ["route", "demo", "--net-router", str(MODEL), "--policy", "random",
                               "--out", str(tmp_path)])
    assert both.exit_code == 2 and "--net-router" in both.output
    missing = runner.invoke(app, ["route", "demo", "--net-router", str(tmp_path / "none.onnx"), "--out", str(tmp_path)])
    assert missing.exit_code == 2 and "no such model file" in missing.output


def test_steps_setting_moves_several_edges() -> None:
    env1, env3 = _env(), _env(steps=3)
    env1.reset(seed=0)
    env3.reset(seed=0)
    a = int(np.flatnonzero(env1.legal_actions())[0])
    total1 = 0.0
    for _ in range(3):
        if not env1.legal_actions()[a]:
            break
        _, r, term, trunc, info1 = env1.step(a)
        total1 += r
        if term or trunc:
            break
    _, r3, _, _, info3 = env3.step(a)
    assert info3["moves"] == info1["moves"] and info3["head"] == info1["head"]
    assert r3 == pytest.approx(total1)


def test_static_region_folder(tmp_path) -> None:
    """A region written by make-region (here of the demo) is one region whose nets the env walks."""
    from gymnasium.utils.env_checker import check_env

    from xroute.testcases.regions import make_region

    make_region("demo", tmp_path / "r", location=(2, 2), size=2)
    env = _env(region_dir=str(tmp_path / "r"))
    check_env(env, skip_render_check=True)
    _, info = env.reset(seed=0)
    assert info["box"] == tuple(env._walk[0]) and info["pins"] >= 2


def test_full_state_dict_observation() -> None:
    from gymnasium.utils.env_checker import check_env

    env = _env(full_state=True)
    check_env(env, skip_render_check=True)
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    assert obs["net"][0].sum() >= 1 and obs["net"][2].sum() >= 1  # the head, the unreached terminals
    plain, _ = _env().reset(seed=0)
    assert np.array_equal(obs["state"], plain)
