"""MaskablePPO (sb3-contrib) with the features extractors of xroute.policies.rl.sb3 (over the shipped
3D encoders, and over the set scorer) on a static region of a generated design; the example
examples/maskable_ppo.py."""

from __future__ import annotations

import numpy as np
import pytest

torch = pytest.importorskip("torch")
pytest.importorskip("sb3_contrib", reason="the sb3 extra (sb3-contrib) is not installed")

from conftest import load_file, require_testcase  # noqa: E402

# Slow set: trains MaskablePPO.
pytestmark = [pytest.mark.slow, pytest.mark.filterwarnings("ignore:.*infinity")]

DESIGN = "standin_marked"  # generated (conftest)
# A 1x1 region of 7 nets. Measured 2026-11-27: 20 random orders cost 8,090.1 to 9,089.6, 8,416.2 on
# average (three costs; 12 of the 20 at the lowest). Of 11 other 1x1 regions tried, 8 cost the same
# in every order and 3 vary by 4.2 at most (5,11: 2,584.3 to 2,588.5).
LOCATION = (6, 11)
M = 8


@pytest.fixture(scope="module")
def region_dir(tmp_path_factory: pytest.TempPathFactory) -> str:
    import xroute.envs as envs

    require_testcase(DESIGN)
    return envs.generate_static_region(DESIGN, LOCATION, 1, str(tmp_path_factory.mktemp("sb3") / "region"))


def test_extractor_scores_each_row_and_keeps_batch_norm_fixed(region_dir: str) -> None:
    from torch import nn

    from xroute.envs import static_region_env
    from xroute.policies.rl.models import EMBED
    from xroute.policies.rl.sb3 import NetOrderExtractor

    env = static_region_env(region_dir, max_candidates=M)
    obs, info = env.reset(seed=0)
    assert 2 <= info["candidates"] <= M
    torch.manual_seed(0)
    extractor = NetOrderExtractor(env.observation_space)
    extractor.train(True)
    assert not any(m.training for m in extractor.modules() if isinstance(m, nn.modules.batchnorm._BatchNorm))
    batch = {k: torch.as_tensor(np.stack([v, v])).float() for k, v in obs.items()}
    swapped = {k: v.clone() for k, v in batch.items()}
    for k in ("nets", "net_features"):
        swapped[k][1, [0, 1]] = batch[k][1, [1, 0]]
    with torch.no_grad():
        f, g = extractor(batch), extractor(swapped)
    assert f.shape == (2, M + EMBED) and extractor.features_dim == M + EMBED
    other = {k: v.clone() for k, v in batch.items()}
    other["obstacle"][1] = 1.0 - other["obstacle"][1]
    other["nets"][1] = 1.0 - other["nets"][1]
    with torch.no_grad():
        torch.testing.assert_close(extractor(other)[0], f[0])  # batch norm: no statistics of the batch
    torch.testing.assert_close(g[1, [0, 1]], f[1, [1, 0]])  # a row's score goes with the row
    torch.testing.assert_close(g[1, 2:], f[1, 2:])


def test_per_violation_reward_sums_to_the_cost_drop(region_dir: str) -> None:
    from xroute.envs import static_region_env
    from xroute.policies.rl.sb3 import PerViolation

    env = PerViolation(static_region_env(region_dir, max_candidates=M))
    obs, info = env.reset(seed=0)
    start, total, done = info["cost"], 0.0, False
    while not done:
        assert np.array_equal(env.action_masks(), obs["action_mask"].astype(bool))
        obs, r, done, _, info = env.step(int(np.flatnonzero(obs["action_mask"])[-1]))
        total += r
    assert total == pytest.approx((start - info["cost"]) / 500.0)


def test_set_extractor_scores_each_row_and_pools_the_legal_ones(region_dir: str) -> None:
    from xroute.envs import static_region_env
    from xroute.policies.rl.sb3 import SetOrderExtractor

    env = static_region_env(region_dir, max_candidates=M, observation="compact")
    obs, info = env.reset(seed=0)
    torch.manual_seed(0)
    extractor = SetOrderExtractor(env.observation_space, width=16)
    batch = {k: torch.as_tensor(np.stack([v, v])).float() for k, v in obs.items()}
    n = info["candidates"]
    perm = list(range(M))
    perm[0], perm[n - 1] = perm[n - 1], perm[0]
    swapped = {k: v[:, perm] for k, v in batch.items()}
    noise = {k: v.clone() for k, v in batch.items()}
    noise["set_features"][:, n:] = 7.0  # padding rows: masked out of attention, scores and pooling
    with torch.no_grad():
        f, g, h = extractor(batch), extractor(swapped), extractor(noise)
    assert f.shape == (2, M + 16) and extractor.features_dim == M + 16
    torch.testing.assert_close(g[:, :M], f[:, perm])  # scores go with their rows
    torch.testing.assert_close(g[:, M:], f[:, M:])  # the pooled vector does not see the rows' order
    torch.testing.assert_close(h, f)
    assert not f[:, n:M].any()


@pytest.mark.slow
@pytest.mark.parametrize(("observation", "steps"), [("grid", 384), ("compact", 768)])
def test_maskable_ppo_learns_the_region(region_dir: str, observation: str, steps: int) -> None:
    """MaskablePPO with fixed seeds (384 steps are about 55 episodes) ends with a greedy order no
    costlier than the best of 20 random orders, and no costlier than the untrained model's.

    Measured 2026-11-27, greedy cost after 0 / 384 / 768 / 1,152 steps (successive calls of 384),
    seeds 1, 2, 3: grid 8,598 / 8,090 / 8,090 / 8,090 for seeds 1 and 2 (seed 3: 9,090 until 1,152
    steps, then 8,090); compact 8,090 throughout but seed 2's 8,598 after 384 steps. The untrained
    compact model already picks a best order here, so only the grid model has a drop to show."""
    from xroute.envs import static_region_env
    from xroute.policies.rl.sb3 import PerViolation, greedy_cost, make_maskable_ppo, random_costs

    torch.set_num_threads(1)
    env = PerViolation(static_region_env(region_dir, max_candidates=M, observation=observation))
    judge = static_region_env(region_dir, max_candidates=M, observation=observation)
    model = make_maskable_ppo(env, seed=2)
    before = greedy_cost(model, judge)
    model.learn(total_timesteps=steps)
    after = greedy_cost(model, judge)
    random = random_costs(judge, 20, seed=1)
    assert after <= min(random) < np.mean(random)
    assert after <= before
    if observation == "grid":
        assert after < before


def test_the_example_script_trains_and_reports(region_dir: str, capsys: pytest.CaptureFixture[str]) -> None:
    load_file("examples/maskable_ppo.py").main([region_dir, "--steps", "64", "--observation", "compact"])
    out = capsys.readouterr().out
    assert "before training" in out and "after 64 steps" in out and "of 20" in out
