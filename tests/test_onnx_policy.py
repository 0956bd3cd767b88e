"""OnnxPolicy: loading and checking net-order models, and ordering regions by their scores.

The models are tiny graphs built with onnx.helper (no torch): ``scores = net_features[:, k] * w``
(plus the other inputs times zero, so every input is used), masked rows -1e9.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

onnx = pytest.importorskip("onnx", reason="onnx (test extra) is not installed")
pytest.importorskip("onnxruntime", reason="onnxruntime (rl extra) is not installed")

from onnx import TensorProto, helper  # noqa: E402

from conftest import pick, require_testcase  # noqa: E402

SAMPLE = pick("ispd18_sample")  # or its generated stand-in without the contest data
from xroute.net_order import PolicyError  # noqa: E402
from xroute.policies.rl.observation import NET_FEATURES  # noqa: E402

FEATURES = ",".join(NET_FEATURES)


def make_model(path: Path, *, column: str = "heuristic_rank", weight: float = -1.0,
               meta: dict[str, str] | None = None, rename: str | None = None, fixed_n: int | None = None,
               feature_count: int | None = None) -> Path:
    n = fixed_n if fixed_n is not None else "candidates"
    s = feature_count or len(NET_FEATURES)
    inputs = [
        helper.make_tensor_value_info("obstacle", TensorProto.FLOAT, [1, 3, 64, 64]),
        helper.make_tensor_value_info("nets", TensorProto.FLOAT, [n, 7, 3, 64, 64]),
        helper.make_tensor_value_info(rename or "net_features", TensorProto.FLOAT, [n, s]),
        helper.make_tensor_value_info("mask", TensorProto.BOOL, [n]),
    ]
    col = NET_FEATURES.index(column)
    nodes = [
        helper.make_node("Gather", [rename or "net_features", "col"], ["picked"], axis=1),
        helper.make_node("Mul", ["picked", "w"], ["raw"]),
        helper.make_node("ReduceSum", ["nets", "axes_net"], ["net_sum"], keepdims=0),
        helper.make_node("ReduceSum", ["obstacle"], ["obs_sum"], keepdims=0),
        helper.make_node("Add", ["net_sum", "obs_sum"], ["grid_sum"]),
        helper.make_node("Mul", ["grid_sum", "zero"], ["grid_zero"]),
        helper.make_node("Add", ["raw", "grid_zero"], ["score"]),
        helper.make_node("Where", ["mask", "score", "neg"], ["scores"]),
    ]
    inits = [
        helper.make_tensor("col", TensorProto.INT64, [], [col]),
        helper.make_tensor("w", TensorProto.FLOAT, [], [weight]),
        helper.make_tensor("zero", TensorProto.FLOAT, [], [0.0]),
        helper.make_tensor("neg", TensorProto.FLOAT, [], [-1e9]),
        helper.make_tensor("axes_net", TensorProto.INT64, [4], [1, 2, 3, 4]),
    ]
    graph = helper.make_graph(nodes, "net_order", inputs,
                              [helper.make_tensor_value_info("scores", TensorProto.FLOAT, [n])], inits)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 18)])
    model.ir_version = 8
    props = {"xroute_model": "net-order", "xroute_algorithm": "ppo", "xroute_net_features": FEATURES}
    props.update(meta or {})
    helper.set_model_props(model, props)
    onnx.save(model, path)
    return path


def test_registry_loads_an_onnx_model(tmp_path: Path) -> None:
    from xroute.policies import get_policy
    from xroute.policies.onnx_policy import OnnxPolicy

    p = get_policy(str(make_model(tmp_path / "m.onnx")), 1)
    assert isinstance(p, OnnxPolicy) and p.name == "m.onnx" and p.algorithm == "ppo" and p.needs_region
    feats = np.zeros((3, len(NET_FEATURES)), np.float32)
    feats[:, NET_FEATURES.index("heuristic_rank")] = [0.5, 0.0, 1.0]
    nets = np.zeros((3, 7, 3, 64, 64), np.float32)
    scores = p.scores(np.zeros((3, 64, 64), np.float32), nets, feats, np.array([True, True, False]))
    assert scores.tolist() == [-0.5, 0.0, -1e9]


@pytest.mark.parametrize(
    ("kwargs", "problem"),
    [
        ({"rename": "features"}, "its inputs are obstacle, nets, features, mask"),
        ({"fixed_n": 5}, "fixed candidate axis 5"),
        ({"feature_count": 3}, "input 'net_features' has shape"),
        ({"meta": {"xroute_model": "placer"}}, "metadata xroute_model is 'placer'"),
        ({"meta": {"xroute_algorithm": "a2c"}}, "metadata xroute_algorithm is 'a2c'"),
        ({"meta": {"xroute_net_features": "pins"}}, "metadata xroute_net_features is 'pins'"),
    ],
)
def test_a_model_with_the_wrong_signature_is_refused(tmp_path: Path, kwargs: dict, problem: str) -> None:
    from xroute.policies.onnx_policy import EXPECTED_SIGNATURE, OnnxPolicy

    path = make_model(tmp_path / "bad.onnx", **kwargs)
    with pytest.raises(PolicyError) as err:
        OnnxPolicy(path)
    msg = str(err.value)
    assert str(path) in msg and problem in msg and msg.endswith("expected " + EXPECTED_SIGNATURE)
    assert "nets float32[N,7,3,64,64]" in EXPECTED_SIGNATURE and "mask bool[N]" in EXPECTED_SIGNATURE


def test_missing_and_unreadable_model_files(tmp_path: Path) -> None:
    from xroute.policies.onnx_policy import OnnxPolicy

    with pytest.raises(PolicyError, match="ONNX model not found"):
        OnnxPolicy(tmp_path / "nothing.onnx")
    (tmp_path / "junk.onnx").write_bytes(b"\0garbage")
    with pytest.raises(PolicyError, match=r"junk.onnx: not a readable ONNX model .*expected inputs obstacle"):
        OnnxPolicy(tmp_path / "junk.onnx")


def test_a_model_scoring_minus_the_heuristic_rank_routes_like_the_heuristic(tmp_path: Path) -> None:
    from xroute.policies.onnx_policy import OnnxPolicy
    from xroute import load_design
    from xroute.router import route_design

    require_testcase(SAMPLE)
    policy = OnnxPolicy(make_model(tmp_path / "h.onnx"))
    calls = []
    scores = policy.scores

    def counting(*args):
        calls.append(len(args[2]))
        return scores(*args)

    policy.scores = counting
    onnx_result = route_design(load_design(SAMPLE), region_size=2, iterations=2, policy=policy)
    heuristic = route_design(load_design(SAMPLE), region_size=2, iterations=2)
    assert calls and len(calls) == sum(r.regions for r in onnx_result.iterations)  # one model call per region
    assert onnx_result.policy == "h.onnx"
    assert onnx_result.final.wirelength_dbu == heuristic.final.wirelength_dbu
    assert onnx_result.final.vias == heuristic.final.vias

    # The reverse order (+rank) routes differently but completely.
    reverse = OnnxPolicy(make_model(tmp_path / "r.onnx", weight=1.0))
    d = load_design(SAMPLE)
    route_design(d, region_size=100, iterations=1, policy=reverse)
    assert d.engine.check_connectivity()["open_nets"] == 0


def test_order_without_the_region_is_a_policy_error(tmp_path: Path) -> None:
    from xroute.policies.onnx_policy import OnnxPolicy

    policy = OnnxPolicy(make_model(tmp_path / "m.onnx"))
    with pytest.raises(PolicyError, match="needs the region's grid"):
        policy.order({"iteration": 0, "region": 0, "box": (0, 0, 1, 1)}, np.zeros((2, 9), np.int32))
