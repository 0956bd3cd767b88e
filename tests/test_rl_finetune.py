"""Policy-gradient fine-tuning of the set scorer (policies/rl/finetune.py) on a generated design (no contest data)."""

from __future__ import annotations

import numpy as np
import pytest

# Slow set: trains the set scorer (imitation, PPO fine-tuning), Ray workers.
pytestmark = pytest.mark.slow

torch = pytest.importorskip("torch")

SIZE = 2  # regions of the imitation_sample fixture (conftest): 64 of 2x2 GCells


def test_step_log_probs_add_up_to_the_plackett_luce_log_probability() -> None:
    from xroute.policies.rl.finetune import step_log_probs
    from xroute.policies.rl.imitation import order_log_probs

    scores = torch.tensor([[0.5, -1.0, 2.0, 0.0, 7.0]])
    mask = torch.tensor([[True, True, True, True, False]])
    order = torch.tensor([[2, 0, 3, 1, 4]])
    steps = step_log_probs(scores, order, mask)
    assert torch.isclose(steps.sum(), order_log_probs(scores, mask, order[:, None])[0, 0])
    # First step: net 2 among 2, 0, 3, 1 (the padding row 4 is not a choice); the last real step is sure.
    first = 2.0 - torch.logsumexp(torch.tensor([2.0, 0.5, 0.0, -1.0]), 0)
    assert torch.isclose(steps[0, 0], first) and steps[0, 3] == 0 and steps[0, 4] == 0


def test_sampled_orders_are_permutations_and_follow_the_scores() -> None:
    from xroute.policies.rl.finetune import sample_orders

    scores = np.array([0.0, 3.0, 1.0, 2.0])
    cold = sample_orders(scores, 1e-3, 5, np.random.default_rng(0))
    assert all(o.tolist() == [1, 3, 2, 0] for o in cold)
    hot = sample_orders(scores, 100.0, 200, np.random.default_rng(0))
    assert all(sorted(o.tolist()) == [0, 1, 2, 3] for o in hot)
    assert len({tuple(o) for o in hot}) > 12  # near-uniform: most of the 24 orders appear
    again = sample_orders(scores, 100.0, 200, np.random.default_rng(0))
    assert all((a == b).all() for a, b in zip(hot, again))


def test_a_ppo_step_moves_the_greedy_order_towards_a_cheaper_sample() -> None:
    """One sample with a positive advantage (it beat the greedy order) and one with a negative one: after a few
    clipped updates the first is more likely and the second less, each by at most the clip range per update."""
    from xroute.policies.rl.finetune import _batch, _Sample, ppo_loss, step_log_probs
    from xroute.policies.rl.set_features import SET_FEATURES
    from xroute.policies.rl.set_scorer import SetScorer

    torch.manual_seed(0)
    model = SetScorer(width=16, heads=2, layers=1, prior=4.0)
    n = 6
    feats = np.random.default_rng(1).random((n, len(SET_FEATURES))).astype(np.float32)
    feats[:, SET_FEATURES.index("heuristic_rank")] = np.arange(n) / (n - 1)
    temperature = 0.5

    every = torch.ones(1, n, dtype=torch.bool)

    def logp(order: np.ndarray) -> float:
        with torch.no_grad():
            s = model(torch.from_numpy(feats)[None], every) / temperature
            return float(step_log_probs(s, torch.from_numpy(order[None]).long(), every).sum())

    good, bad = np.array([5, 4, 3, 2, 1, 0]), np.array([1, 0, 2, 3, 4, 5])
    with torch.no_grad():
        s = model(torch.from_numpy(feats)[None], every) / temperature
    old = [step_log_probs(s, torch.from_numpy(o[None]).long(), every)[0].numpy() for o in (good, bad)]
    before = logp(good), logp(bad)
    batch = _batch([_Sample(0, good, 1.0, old[0]), _Sample(0, bad, -1.0, old[1])], [feats])
    opt = torch.optim.Adam(model.parameters(), lr=1e-2)
    for _ in range(5):
        loss = ppo_loss(model, batch, temperature, 0.2)
        opt.zero_grad()
        loss.backward()
        opt.step()
    after = logp(good), logp(bad)
    assert after[0] > before[0] and after[1] < before[1], (before, after)


@pytest.mark.slow
def test_finetune_starts_at_the_heuristic_and_does_not_depend_on_the_workers(imitation_sample: str) -> None:
    """An untrained scorer's greedy order is the heuristic's, so the first evaluation costs exactly the
    heuristic's on the validation regions; two worker processes, and two Ray actors on a local instance,
    give the same log and the same model as one process."""
    from xroute.policies.rl.finetune import FinetuneConfig, finetune
    from xroute.policies.rl.set_scorer import SetScorer

    torch.set_num_threads(1)
    cfg = FinetuneConfig(iterations=4, regions=6, samples=3, temperature=0.5, epochs=2, lr=3e-3, eval_every=2,
                         region_size=SIZE, seed=3)
    runs = []
    backends = [(1, "local"), (2, "local")]
    try:
        import ray  # noqa: F401

        backends.append((2, "ray"))
    except ImportError:
        pass
    for workers, backend in backends:
        torch.manual_seed(0)
        model, log = finetune([imitation_sample], cfg, model=SetScorer(width=16, heads=2, layers=1), workers=workers,
                              backend=backend)
        runs.append((model, log))
    (m1, log1) = runs[0]
    assert [row["iteration"] for row in log1] == [0, 2, 4]
    assert log1[0]["val_cost"] == log1[0]["val_heuristic"] > 0
    assert log1[0]["sample_gain"] == 0 and sum(row["sample_gain"] for row in log1) > 0  # a sample beat greedy
    assert log1[0]["samples_vs_greedy"] == 0 and log1[1]["samples_vs_greedy"] != 0
    strip = [{k: v for k, v in row.items() if k != "seconds"} for row in log1]
    for (m2, log2), (workers, backend) in zip(runs[1:], backends[1:]):
        assert strip == [{k: v for k, v in row.items() if k != "seconds"} for row in log2], (workers, backend)
        assert all(torch.equal(a, b) for a, b in zip(m1.state_dict().values(), m2.state_dict().values()))


def test_xroute_train_finetune_writes_a_model_the_router_takes(imitation_sample: str, tmp_path) -> None:
    import json

    from typer.testing import CliRunner

    from xroute.cli.app import app
    from xroute.policies.onnx_policy import OnnxPolicy

    pytest.importorskip("onnxruntime")
    runner = CliRunner()
    out = tmp_path / "run"
    res = runner.invoke(app, ["train", "finetune", "--testcase", imitation_sample, "--episodes", "2", "--region-size",
                              str(SIZE), "--workers", "1", "--out", str(out), "--json"])
    assert res.exit_code == 0, res.output
    got = json.loads(res.stdout)
    assert got["summary"]["iterations"] == 2 and [row["iteration"] for row in got["log"]] == [0, 2]
    assert OnnxPolicy(out / "set.onnx").kind == "set"
    # Going on from the checkpoint it wrote; a file that is not a checkpoint is one line, exit 2.
    res = runner.invoke(app, ["train", "finetune", "--testcase", imitation_sample, "--episodes", "1", "--region-size",
                              str(SIZE), "--workers", "1", "--init", str(out / "set-final.pt"), "--out",
                              str(tmp_path / "again"), "--json"])
    assert res.exit_code == 0, res.output
    (tmp_path / "junk.pt").write_bytes(b"junk")
    res = runner.invoke(app, ["train", "finetune", "--testcase", imitation_sample, "--episodes", "1", "--init",
                              str(tmp_path / "junk.pt"), "--out", str(tmp_path / "bad")])
    assert res.exit_code == 2 and "junk.pt: not a set-scorer checkpoint" in res.output
    assert not (tmp_path / "bad").exists()


@pytest.mark.slow
def test_teacher_shards_on_ray_give_the_regions_of_one_process(imitation_sample: str) -> None:
    """The teacher's shards as Ray tasks on a local instance: the same regions, orders and costs as one process."""
    pytest.importorskip("ray")
    from xroute.policies.rl.teacher import collect

    kwargs = {"region_size": SIZE, "hold_out_every": 3, "orders": 2, "seed": 4, "max_regions": 10}
    local = collect([imitation_sample], workers=1, **kwargs)
    on_ray = collect([imitation_sample], workers=2, backend="ray", **kwargs)
    assert len(local) >= 5 and [(r.testcase, r.index) for r in local] == [(r.testcase, r.index) for r in on_ray]
    for a, b in zip(local, on_ray):
        assert np.array_equal(a.features, b.features) and np.array_equal(a.orders, b.orders)
        assert np.array_equal(a.costs, b.costs)
    with pytest.raises(ValueError, match="unknown backend 'slurm'"):
        collect([imitation_sample], workers=1, backend="slurm", **kwargs)
