"""PPO and DQN training loops, ``xroute train`` and ``xroute export`` (the ``train`` extra).

The loops run on a tiny fake env with the contract's spaces (tests/fake_region_env.py); one test
runs ``xroute train`` on the real training env over ispd18_sample regions.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

torch = pytest.importorskip("torch", reason="the train extra (torch) is not installed")
pytest.importorskip("gymnasium", reason="the train extra (gymnasium) is not installed")
ort = pytest.importorskip("onnxruntime", reason="the train extra (onnxruntime) is not installed")

from fake_region_env import FakeRegionEnv  # noqa: E402
from xroute.policies.rl.batch import collate, compact  # noqa: E402
from xroute.policies.rl.checkpoint import load_checkpoint  # noqa: E402
from xroute.policies.rl.export import INPUT_NAMES, export_checkpoint  # noqa: E402
from xroute.policies.rl.train import train  # noqa: E402
from xroute.policies.rl.train_config import config_from_dict  # noqa: E402
from xroute.cli.app import app  # noqa: E402

# Slow set: trains PPO and DQN.
pytestmark = pytest.mark.slow

SMALL = {"ppo": {"update_every": 12, "epochs": 2, "checkpoint_every": 2},
         "dqn": {"learning_starts": 8, "target_update": 5, "checkpoint_every": 2}}


def run(algorithm: str, out: Path, seed: int = 4, episodes: int = 5):
    cfg = config_from_dict(algorithm, SMALL[algorithm])
    return train(algorithm, FakeRegionEnv, episodes, cfg, out, seed=seed)


def without_time(rows: list[dict]) -> list[dict]:
    return [{k: v for k, v in r.items() if k != "seconds"} for r in rows]


def test_compact_keeps_legal_rows_and_shares_the_net_grids_within_an_episode() -> None:
    env = FakeRegionEnv()
    obs, _ = env.reset(seed=2)
    first = compact(obs)
    n = int(obs["action_mask"].sum())
    assert first.nets.shape[0] == n and first.nets.dtype == np.float16
    assert np.array_equal(first.nets.astype(np.float32), obs["nets"][:n])
    obs, *_ = env.step(0)
    second = compact(obs, first)
    assert second.nets is first.nets and second.mask.tolist() == [False] + [True] * (n - 1)
    batch = collate([first, second])
    assert batch.mask.shape == (2, n) and batch.nets.shape[0] == 2 * n - 1
    assert batch.row_state.tolist() == [0] * n + [1] * (n - 1)


@pytest.mark.parametrize("algorithm", ["ppo", "dqn"])
def test_training_writes_log_and_checkpoints_and_is_seeded(tmp_path: Path, algorithm: str) -> None:
    result = run(algorithm, tmp_path / "a")
    names = sorted(p.name for p in (tmp_path / "a").glob("*.pt"))
    assert names == sorted([f"{algorithm}-ep00002.pt", f"{algorithm}-ep00004.pt", f"{algorithm}-final.pt"])
    rows = [json.loads(line) for line in (tmp_path / "a" / "metrics.jsonl").read_text().splitlines()]
    assert [r["episode"] for r in rows] == [1, 2, 3, 4, 5]
    for r in rows:
        assert {"steps", "total_steps", "reward", "cost", "wirelength_dbu", "vias", "drvs", "seconds"} <= set(r)
        assert r["reward"] == pytest.approx(-r["cost"])
        assert r["wirelength_dbu"] == 100 * r["steps"]
    assert rows[-1]["total_steps"] == sum(r["steps"] for r in rows)
    # learning happened: the update's losses are logged
    assert ("policy_loss" if algorithm == "ppo" else "td_loss") in rows[-1]
    ckpt = load_checkpoint(result.final_checkpoint)
    assert ckpt.algorithm == algorithm and ckpt.episode == 5 and ckpt.steps == rows[-1]["total_steps"]
    assert ckpt.config["batch_size"] == 8 and (ckpt.model.critic is not None) == (algorithm == "ppo")
    again = run(algorithm, tmp_path / "b")
    assert without_time(again.episodes) == without_time(result.episodes)
    other = run(algorithm, tmp_path / "c", seed=5)
    assert without_time(other.episodes) != without_time(result.episodes)


@pytest.mark.slow
@pytest.mark.parametrize("algorithm", ["ppo", "dqn"])
def test_training_on_one_region_lowers_its_cost(tmp_path: Path, algorithm: str) -> None:
    """One fake region of 5 nets replayed: routing nets by decreasing feature 0 is cheapest; the
    trained policy's greedy order must close most of the gap between random orders and the best."""
    extra = {"update_every": 20, "epochs": 4} if algorithm == "ppo" else {"learning_starts": 16, "target_update": 20}
    cfg = config_from_dict(algorithm, {"checkpoint_every": 1000, "reward_scale": 0.1, **extra})
    result = train(algorithm, lambda: FakeRegionEnv(5, fixed_seed=3), 50, cfg, tmp_path, seed=1)
    model = load_checkpoint(result.final_checkpoint).model
    env = FakeRegionEnv(5, fixed_seed=3)
    obs, _ = env.reset()
    f0 = env.features[: env.n, 0]
    best = float(env.n)

    def order_cost(order: np.ndarray) -> float:
        return best + 10 * sum(float(f0[order[i:]].max() - f0[order[i]]) for i in range(env.n))

    rng = np.random.default_rng(0)
    random_mean = float(np.mean([order_cost(rng.permutation(env.n)) for _ in range(200)]))
    done, cost = False, 0.0
    while not done:
        b = collate([compact(obs)])
        with torch.no_grad():
            scores, _ = model.score_flat(b.obstacle, b.nets, b.net_features, b.row_state, b.row_slot, b.mask)
        obs, reward, done, _, info = env.step(int(scores[0].argmax()))
        cost = info["cost"]
    assert env.n == 5 and best < random_mean - 5
    assert cost <= best + 0.25 * (random_mean - best)


def test_cli_export_writes_an_onnx_model_that_runs(tmp_path: Path) -> None:
    result = run("dqn", tmp_path, episodes=2)
    out = tmp_path / "dqn.onnx"
    cli = CliRunner().invoke(app, ["export", str(result.final_checkpoint), "--out", str(out)])
    assert cli.exit_code == 0, cli.output
    assert out.is_file() and "wrote" in cli.output
    session = ort.InferenceSession(str(out), providers=["CPUExecutionProvider"])
    obs, _ = FakeRegionEnv().reset(seed=9)
    n = int(obs["action_mask"].sum())
    scores = session.run(None, {"obstacle": obs["obstacle"][None], "nets": obs["nets"][:n],
                                "net_features": obs["net_features"][:n],
                                "mask": obs["action_mask"][:n].astype(bool)})[0]
    assert scores.shape == (n,) and np.isfinite(scores).all()


def test_cli_errors_are_one_line(tmp_path: Path) -> None:
    runner = CliRunner()
    res = runner.invoke(app, ["export", str(tmp_path / "none.pt"), "--out", str(tmp_path / "m.onnx")])
    assert res.exit_code == 2 and "checkpoint file not found" in res.output
    assert not (tmp_path / "m.onnx").exists()
    res = runner.invoke(app, ["train", "sac", "--testcase", "ispd18_sample", "--episodes", "1"])
    assert res.exit_code == 2 and "unknown algorithm" in res.output
    bad = tmp_path / "bad.yaml"
    bad.write_text("clip: 2\nwhat: 1\n")
    res = runner.invoke(app, ["train", "ppo", "--testcase", "ispd18_sample", "--episodes", "1", "--config", str(bad)])
    assert res.exit_code == 2 and f"{bad}:2:" in res.output
    res = runner.invoke(app, ["train", "ppo", "--testcase", "no_such_case", "--episodes", "1", "--out", str(tmp_path)])
    assert res.exit_code == 2 and "no_such_case" in res.output


def test_cli_train_on_sample_regions_then_export_then_route_with_the_onnx_policy(tmp_path: Path) -> None:
    """The whole chain on real data: `xroute train` (3 regions of ispd18_sample), `xroute export`,
    and the exported model ordering every region of a route through OnnxPolicy."""
    from conftest import pick, require_testcase

    sample = pick("ispd18_sample")  # or its generated stand-in without the contest data
    require_testcase(sample)
    from xroute.policies.onnx_policy import OnnxPolicy
    from xroute import load_design
    from xroute.router import route_design

    runner = CliRunner()
    res = runner.invoke(app, ["train", "dqn", "--testcase", sample, "--episodes", "3", "--region-size", "2",
                              "--out", str(tmp_path / "run"), "--seed", "2", "--json"])
    assert res.exit_code == 0, res.output
    report = json.loads(res.output)
    rows = report["episodes"]
    assert [r["episode"] for r in rows] == [1, 2, 3] and all(r["steps"] >= 1 for r in rows)
    assert report["summary"]["steps"] == sum(r["steps"] for r in rows)
    for r in rows:  # the env's cost: 0.5 per um of wire, 4 per via, 500 per DRV (ispd18_sample: 2000 DBU/um)
        assert r["wirelength_dbu"] > 0 and r["cost"] >= 0.5 * r["wirelength_dbu"] / 2000 + 4 * r["vias"] - 1e-6
    ckpt = tmp_path / "run" / "dqn-final.pt"
    res = runner.invoke(app, ["export", str(ckpt), "--out", str(tmp_path / "m.onnx")])
    assert res.exit_code == 0, res.output
    policy = OnnxPolicy(tmp_path / "m.onnx")
    assert policy.algorithm == "dqn"
    design = load_design(sample)
    result = route_design(design, region_size=2, iterations=1, policy=policy)
    assert result.policy == "m.onnx" and result.iterations[0].regions > 1
    assert design.engine.check_connectivity()["open_nets"] == 0


@pytest.mark.slow
def test_cli_train_in_a_fresh_process(tmp_path: Path) -> None:
    """`xroute train` registers the env IDs itself (through xroute.envs): no earlier import needed."""
    import os
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-m", "xroute", "train", "dqn", "--testcase", "demo", "--episodes", "1",
                           "--region-size", "2", "--out", str(tmp_path / "run"), "--json"],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path, env={**os.environ, "CI": "true"})
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert json.loads(proc.stdout)["episodes"]


def test_cli_train_in_context(tmp_path: Path) -> None:
    """`xroute train --in-context`: episodes are first-pass regions (held-out ones skipped)."""
    from conftest import require_testcase

    require_testcase("standin_sample4")
    runner = CliRunner()
    res = runner.invoke(app, ["train", "ppo", "--testcase", "standin_sample4", "--episodes", "3", "--region-size", "2",
                              "--in-context", "--hold-out-every", "3", "--out", str(tmp_path / "run"), "--json"])
    assert res.exit_code == 0, res.output
    rows = json.loads(res.output)["episodes"]
    assert len(rows) == 3 and all(r["steps"] >= 1 and r["cost"] > 0 for r in rows)
    assert (tmp_path / "run" / "metrics.jsonl").read_text().count("\n") == 3
