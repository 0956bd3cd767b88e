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


def test_every_shipped_model_has_a_short_card_and_the_package_ships_no_log() -> None:
    """One card per model (CONTRIBUTING.md): <model>.card.md beside <model>.onnx (a net-order or
    net-router network) or <model>.json (a schedule model), at most 100 lines, with its intended use,
    data, protocol and figures; nothing else in the folder but models and cards (research logs live
    in experiments/). Every schedule model loads as one."""
    from xroute.schedule_model import SwitchSchedule, load_schedule_model

    onnx = sorted(p.stem for p in MODELS.glob("*.onnx"))
    schedules = sorted(p.stem for p in MODELS.glob("*.json"))
    assert onnx == ["dqn", "net_router_dqn", "ppo", "set_imitation"]
    assert schedules == ["schedule_switch", "schedule_switch_no19t3"]
    for name in schedules:
        assert isinstance(load_schedule_model(MODELS / f"{name}.json"), SwitchSchedule), name
    models = onnx + schedules
    for name in models:
        card = MODELS / f"{name}.card.md"
        text = card.read_text()
        assert len(text.splitlines()) <= 100, card
        for heading in ("## Intended use", "## Training data", "## Evaluation protocol", "## Figures"):
            assert heading in text, (card, heading)
        assert "2026-" in text.split("## Figures")[1], f"{card}: figures without a date"
    assert sorted(p.name for p in MODELS.iterdir()) == sorted([f"{m}.onnx" for m in onnx] + [f"{m}.json" for m in schedules]
                                                               + [f"{m}.card.md" for m in models])
