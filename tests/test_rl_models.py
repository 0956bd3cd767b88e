"""Torch net-order models, checkpoints, training configs and ONNX export (the ``train`` extra)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch", reason="the train extra (torch) is not installed")
onnx = pytest.importorskip("onnx", reason="the train extra (onnx) is not installed")
ort = pytest.importorskip("onnxruntime", reason="the train extra (onnxruntime) is not installed")

from xroute.policies.rl.checkpoint import Checkpoint, CheckpointError, load_checkpoint, save_checkpoint  # noqa: E402
from xroute.policies.rl.export import INPUT_NAMES, example_inputs, export_checkpoint  # noqa: E402
from xroute.policies.rl.models import MASKED_SCORE, NetOrderModel, RegionScorer  # noqa: E402
from xroute.policies.rl.observation import NET_FEATURES  # noqa: E402
from xroute.policies.rl.train_config import default_config, load_config  # noqa: E402
from xroute.errors import InputError  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
S = len(NET_FEATURES)


def random_model(critic: bool = True, seed: int = 0) -> NetOrderModel:
    """A model with random weights and random batch-norm statistics (so eval mode is not identity)."""
    torch.manual_seed(seed)
    model = NetOrderModel(S, critic=critic)
    for m in model.modules():
        if isinstance(m, torch.nn.BatchNorm3d):
            m.running_mean.uniform_(-0.5, 0.5)
            m.running_var.uniform_(0.5, 2.0)
    return model.eval()


def test_masked_rows_score_minus_1e9_and_batched_scores_match_the_region_scorer() -> None:
    model = random_model()
    obstacle, nets, features, mask = example_inputs(S, n=5, seed=3)
    with torch.no_grad():
        single = RegionScorer(model)(obstacle, nets, features, mask)
        batched = model(obstacle, nets.unsqueeze(0), features.unsqueeze(0), mask.unsqueeze(0))[0]
    assert single.shape == (5,)
    assert not bool(mask[0]) and float(single[0]) == MASKED_SCORE == float(batched[0])
    legal = mask.nonzero().flatten()
    assert len(legal) >= 1 and (single[legal] > -1e6).all()
    assert torch.allclose(single, batched, atol=1e-5)


def test_critic_values_the_obstacle_and_dqn_has_none() -> None:
    ppo = random_model(critic=True)
    obstacle = example_inputs(S, n=1)[0]
    with torch.no_grad():
        assert ppo.value(ppo.encode_obstacle(obstacle)).shape == (1,)
    dqn = random_model(critic=False)
    with pytest.raises(RuntimeError, match="no critic"):
        dqn.value(torch.zeros(1, 64))


def test_checkpoint_round_trip_keeps_weights_and_metadata(tmp_path: Path) -> None:
    model = random_model()
    path = save_checkpoint(tmp_path / "c.pt", Checkpoint("ppo", list(NET_FEATURES), model, {"gamma": 0.9}, 7, 123))
    back = load_checkpoint(path)
    assert (back.algorithm, back.net_features, back.config, back.episode, back.steps) == (
        "ppo", list(NET_FEATURES), {"gamma": 0.9}, 7, 123)
    for k, v in model.state_dict().items():
        assert torch.equal(v, back.model.state_dict()[k]), k


def test_bad_checkpoints_are_one_line_errors(tmp_path: Path) -> None:
    with pytest.raises(CheckpointError, match="not found"):
        load_checkpoint(tmp_path / "missing.pt")
    text = tmp_path / "text.pt"
    text.write_text("hello")
    with pytest.raises(CheckpointError, match="not a torch checkpoint"):
        load_checkpoint(text)
    foreign = tmp_path / "foreign.pt"
    torch.save({"weights": torch.zeros(2)}, foreign)
    with pytest.raises(CheckpointError, match="not an xroute training checkpoint"):
        load_checkpoint(foreign)


@pytest.mark.parametrize("algorithm", ["ppo", "dqn"])
def test_export_matches_torch_within_1e_4_for_1_and_5_candidates(tmp_path: Path, algorithm: str) -> None:
    model = random_model(critic=algorithm == "ppo", seed=5)
    ckpt = save_checkpoint(tmp_path / "c.pt", Checkpoint(algorithm, list(NET_FEATURES), model, {}, 2, 10))
    path = export_checkpoint(ckpt, tmp_path / "m.onnx")
    proto = onnx.load(str(path))
    meta = {p.key: p.value for p in proto.metadata_props}
    assert meta["xroute_model"] == "net-order"
    assert meta["xroute_algorithm"] == algorithm
    assert meta["xroute_net_features"] == ",".join(NET_FEATURES)
    session = ort.InferenceSession(str(path), providers=["CPUExecutionProvider"])
    inputs = {i.name: (i.shape, i.type) for i in session.get_inputs()}
    assert list(inputs) == list(INPUT_NAMES)
    assert inputs["obstacle"] == ([1, 3, 64, 64], "tensor(float)")
    assert inputs["nets"] == (["candidates", 7, 3, 64, 64], "tensor(float)")
    assert inputs["net_features"] == (["candidates", S], "tensor(float)")
    assert inputs["mask"] == (["candidates"], "tensor(bool)")
    assert [o.name for o in session.get_outputs()] == ["scores"]
    scorer = RegionScorer(model).eval()
    for n in (1, 5):
        tensors = example_inputs(S, n=n, seed=10 + n)
        if n == 1:
            tensors[3][0] = True
        with torch.no_grad():
            expected = scorer(*tensors).numpy()
        got = session.run(None, dict(zip(INPUT_NAMES, (t.numpy() for t in tensors))))[0]
        assert got.shape == (n,) and got.dtype == np.float32
        assert np.abs(got - expected).max() <= 1e-4
        assert (got[~tensors[3].numpy()] == MASKED_SCORE).all()


def test_config_files_list_exactly_the_defaults() -> None:
    for algorithm in ("ppo", "dqn"):
        path = REPO / "configs" / f"train-{algorithm}.yaml"
        assert load_config(algorithm, path) == default_config(algorithm)
    ppo = default_config("ppo")
    assert (ppo.lr_actor, ppo.lr_critic, ppo.clip, ppo.epochs, ppo.batch_size, ppo.gamma, ppo.update_every) == (
        3e-4, 1e-3, 0.2, 10, 8, 0.99, 100)
    dqn = default_config("dqn")
    assert (dqn.lr, dqn.buffer_size, dqn.epsilon_greedy, dqn.target_update) == (2e-3, 1000, 0.9, 300)


def test_bad_config_values_name_the_file_and_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("gamma: 0.9\nepochs: 3\nlearning_rate: 1\n")
    with pytest.raises(InputError, match="unknown ppo setting 'learning_rate'") as err:
        load_config("ppo", bad)
    assert err.value.line == 3
    bad.write_text("clip: fast\n")
    with pytest.raises(InputError, match="'clip' must be float") as err:
        load_config("ppo", bad)
    assert err.value.line == 1
    bad.write_text("lr: 0.01\nbuffer_size: 0\n")
    with pytest.raises(InputError, match="buffer_size must be > 0") as err:
        load_config("dqn", bad)
    assert err.value.line == 2
    bad.write_text("lr: [1\n")
    with pytest.raises(InputError, match="invalid YAML"):  # the same reader and message as the route configs
        load_config("dqn", bad)
    bad.write_text("lr: [1, 2]\n")
    with pytest.raises(InputError, match="'lr' must be a single value") as err:
        load_config("dqn", bad)
    assert err.value.line == 1
