"""Users' tools of the net-ordering envs: in-context training episodes, ``info["action_mask"]``,
``render()``, ``generate_static_region`` and held-out regions at the router's size, on generated
designs (no contest data needed)."""

from __future__ import annotations

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium", reason="the rl extra (gymnasium) is not installed")

from conftest import require_testcase  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore:.*infinity")

DESIGN = "standin_sample4"  # generated: several regions at region size 2
SIZE = 2


def _first_legal(mask: np.ndarray) -> int:
    return int(np.flatnonzero(mask)[0])


def test_in_context_training_env_check_env_render_and_mask() -> None:
    from gymnasium.utils.env_checker import check_env

    import xroute.envs  # noqa: F401  (registers the environments)

    require_testcase(DESIGN)
    env = gym.make("xroute/NetOrdering-v0", testcase_name=DESIGN, region_size=SIZE, in_context=True,
                   max_candidates=16, render_mode="rgb_array").unwrapped
    check_env(env)  # the render check included
    obs, info = env.reset(seed=0)
    assert info["in_context"] and info["region_size"] == SIZE
    assert info["action_mask"].dtype == bool
    assert np.array_equal(info["action_mask"], obs["action_mask"].astype(bool))
    assert np.array_equal(info["action_mask"], env.action_masks())
    picture = env.render()
    g = env.region.grid()
    ny, nx = g["flags"].shape[1:]
    assert picture.dtype == np.uint8 and picture.shape == (ny * 4, nx * 4, 3)
    done = False
    while not done:
        obs, _, done, _, step_info = env.step(_first_legal(env.action_masks()))
        assert np.array_equal(step_info["action_mask"], obs["action_mask"].astype(bool))
    assert not step_info["action_mask"].any()
    after = env.render()
    assert after.shape == picture.shape and not np.array_equal(after, picture)  # the routed paths are drawn


def test_in_context_episodes_are_the_first_pass_regions() -> None:
    """The env's episodes are the first pass's regions in its order, each in context: routing one in the
    heuristic order costs what the first pass routed there."""
    from xroute import load_design
    from xroute.config import CostSection
    from xroute.envs.ordering_training import ordering_training_env
    from xroute.net_order import heuristic_order
    from xroute.session import first_pass, open_session

    require_testcase(DESIGN)
    design = load_design(DESIGN)
    fp = first_pass(open_session(design), SIZE)
    env = ordering_training_env(DESIGN, region_size=SIZE, in_context=True, max_candidates=64)
    _, info = env.reset(seed=0)
    assert {c for _, _, c, _ in fp.regions} == {0, 1, 2, 3}
    for i, (location, box, _, _) in enumerate(fp.regions):  # every colour
        if i:
            _, info = env.reset()
        assert tuple(info["region_location"]) == tuple(location) and tuple(info["box"]) == tuple(box)
        stepper = env._stepper
        for c in heuristic_order(stepper.rows):
            row = int(np.flatnonzero(stepper.slots == c)[0])
            _, _, done, _, step = env.step(row)
        assert done
        reference = fp.open_region(i)
        reference.route_rest("heuristic")
        expected = CostSection().region_cost(reference.metrics(), design.dbu_per_micron)
        assert step["cost"] == pytest.approx(expected)


def test_region_filter_holds_out_regions_by_their_column_and_row() -> None:
    from xroute.envs.ordering_training import ordering_training_env
    from xroute.policies.rl.region_filter import RegionFilter, held_out

    assert held_out((1, 1), 3) and not held_out((1, 2), 3)  # 1x1 regions: the GCell itself
    assert held_out((5, 5), 3, region_size=5) and held_out((9, 9), 3, region_size=5)
    assert not held_out((1, 1), 3, region_size=5) and not held_out((10, 5), 3, region_size=5)
    assert not held_out((5, 5), 0, region_size=5)

    require_testcase(DESIGN)
    env = RegionFilter(ordering_training_env(DESIGN, region_size=SIZE, in_context=True, max_candidates=64),
                       hold_out_every=3)
    seen = set()
    _, info = env.reset(seed=0)
    for _ in range(12):
        seen.add(tuple(info["region_location"]))
        assert not held_out(tuple(info["region_location"]), 3, SIZE)
        _, info = env.reset()
    assert env.skipped > 0 and len(seen) > 4


def test_static_region_env_render_and_generate_static_region(tmp_path) -> None:
    from gymnasium.utils.env_checker import check_env

    import xroute.envs as envs

    require_testcase(DESIGN)
    folder = envs.generate_static_region(DESIGN, (2, 2), 2, str(tmp_path / "r"))
    assert (tmp_path / "r" / "region.yaml").is_file() and folder == str((tmp_path / "r").resolve())
    env = envs.static_region_env(folder, max_candidates=16, render_mode="rgb_array")
    check_env(env)
    obs, info = env.reset(seed=0)
    assert np.array_equal(info["action_mask"], obs["action_mask"].astype(bool)) and info["action_mask"].any()
    picture = env.render()
    assert picture.dtype == np.uint8 and picture.ndim == 3 and picture.shape[2] == 3
    assert envs.static_region_env(folder).render() is None  # no render mode, no picture
    with pytest.raises(ValueError, match="render_mode"):
        envs.static_region_env(folder, render_mode="human")


def test_evaluation_env_gives_the_mask_in_info_and_renders() -> None:
    from xroute.envs.ordering_evaluation import ordering_evaluation_env

    require_testcase(DESIGN)
    env = ordering_evaluation_env(DESIGN, region_size=4, iteration_count=1, max_candidates=64,
                                  render_mode="rgb_array")
    obs, info = env.reset(seed=0)
    assert np.array_equal(info["action_mask"], obs["action_mask"].astype(bool))
    assert env.render().dtype == np.uint8
    for _ in range(5):
        obs, _, done, _, info = env.step(_first_legal(env.action_masks()))
        assert np.array_equal(info["action_mask"], obs["action_mask"].astype(bool))
        if done:
            break
    env.close()


def test_render_grid_draws_each_kind_of_node() -> None:
    from xroute.envs.render import LAYER_COLOURS, render_grid

    shape = (2, 3, 4)  # z, y, x
    grid = {k: np.zeros(shape, np.int32) for k in ("flags", "fixed_owner", "wire_use")}
    grid["routed_net"] = np.full(shape, -1, np.int32)
    grid["flags"][:] = 1  # all on track
    grid["fixed_owner"][0, 0, 0] = -2  # blocked at (x0, y0)
    grid["routed_net"][1, 1, 2] = 7  # a path on the second layer at (x2, y1)
    grid["flags"][0, 2, 3] |= 2  # an access point at (x3, y2)
    img = render_grid(grid, scale=2)
    assert img.shape == (6, 8, 3) and img.dtype == np.uint8

    def at(x: int, y: int) -> tuple[int, ...]:
        return tuple(img[(3 - 1 - y) * 2, x * 2])  # row 0 of the picture is the top

    assert at(0, 0) == (110, 110, 110)
    assert at(2, 1) == tuple(LAYER_COLOURS[1])
    assert at(3, 2) == (0, 0, 0)
    assert at(1, 0) == (225, 225, 225)


def test_compact_observation_of_every_ordering_env() -> None:
    """observation="compact": check_env passes; each row is the set scorer's features of its candidate as
    the region is at that step (routed nets change the obstacle column); the observation is far under
    1 MB at M = 64; the mask is the grid observation's; an unknown kind is a one-line ValueError."""
    from gymnasium.utils.env_checker import check_env

    from xroute.envs import ordering_evaluation_env, ordering_training_env
    from xroute.policies.rl.set_features import SET_FEATURES, region_set_features

    require_testcase(DESIGN)
    env = ordering_training_env(DESIGN, region_size=SIZE, in_context=True, max_candidates=64, observation="compact")
    check_env(env)
    assert set(env.observation_space.spaces) == {"set_features", "action_mask"}
    obs, info = env.reset(seed=0)
    assert obs["set_features"].shape == (64, len(SET_FEATURES)) and sum(v.nbytes for v in obs.values()) < 2**20
    grid_env = ordering_training_env(DESIGN, region_size=SIZE, in_context=True, max_candidates=64)
    grid_obs, _ = grid_env.reset(seed=0)
    assert np.array_equal(grid_obs["action_mask"], obs["action_mask"])
    steps = 0
    while True:
        stepper = env._stepper
        k = len(stepper.slots)
        np.testing.assert_array_equal(obs["set_features"][:k], region_set_features(stepper.region)[stepper.slots])
        assert not obs["set_features"][k:].any()
        if stepper.done:
            break
        obs, _, done, _, info = env.step(_first_legal(obs["action_mask"]))
        assert np.array_equal(info["action_mask"], obs["action_mask"].astype(bool))
        steps += 1
    assert steps >= 2
    evaluation = ordering_evaluation_env(DESIGN, region_size=4, iteration_count=1, max_candidates=16,
                                         observation="compact")
    obs, info = evaluation.reset(seed=0)
    assert evaluation.observation_space.contains(obs) and np.array_equal(info["action_mask"], obs["action_mask"].astype(bool))
    evaluation.close()
    for make in (lambda: ordering_training_env(DESIGN, region_size=SIZE, observation="grids"),
                 lambda: ordering_evaluation_env(DESIGN, observation="")):
        with pytest.raises(ValueError, match="observation must be one of"):
            make()
