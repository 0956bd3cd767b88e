"""The shipped net-order models (policies/models/*.onnx) load as ONNX policies and order regions."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import pick, require_testcase

SAMPLE = pick("ispd18_sample")  # or its generated stand-in without the contest data

pytest.importorskip("onnxruntime", reason="the rl extra (onnxruntime) is not installed")

MODELS = Path(__file__).resolve().parent.parent / "policies" / "models"


@pytest.mark.parametrize("algorithm,name", [("ppo", "ppo"), ("dqn", "dqn"), ("set", "set_imitation")])
def test_shipped_model_has_the_contract_signature_and_orders_a_sample_region(algorithm: str, name: str) -> None:
    from xroute.policies.onnx_policy import OnnxPolicy
    from xroute.policies.registry import get_policy
    from xroute import _engine, load_design

    path = MODELS / f"{name}.onnx"
    assert path.is_file() and path.stat().st_size < 2_000_000
    policy = get_policy(str(path))
    assert isinstance(policy, OnnxPolicy) and policy.algorithm == algorithm
    require_testcase(SAMPLE)
    design = load_design(SAMPLE)
    region = _engine.RoutingSession(design.engine).open_region(tuple(int(v) for v in design.die_area))
    rows = region.candidates
    order = policy.order({"iteration": 0, "region": 0, "box": region.box, "engine_region": region}, rows)
    assert sorted(int(i) for i in order) == list(range(len(rows)))
    again = policy.order({"iteration": 0, "region": 0, "box": region.box, "engine_region": region}, rows)
    assert np.array_equal(np.asarray(order), np.asarray(again))
    for i in order:
        assert region.route_net(int(i))["routed"]
    assert region.metrics()["unreached"] == 0
