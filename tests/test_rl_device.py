"""The torch device of the trainers (policies/rl/device.py) and ``xroute train --device``."""

from __future__ import annotations

import pytest

torch = pytest.importorskip("torch")

NO_CUDA = not torch.cuda.is_available()


def test_pick_device_follows_what_torch_sees(monkeypatch) -> None:
    from xroute.policies.rl.device import pick_device

    monkeypatch.setattr(torch.cuda, "is_available", lambda: False)
    assert pick_device("auto") == torch.device("cpu")
    assert pick_device("cpu") == torch.device("cpu")
    with pytest.raises(ValueError, match="no CUDA device"):
        pick_device("cuda")
    with pytest.raises(ValueError, match="unknown device 'tpu'"):
        pick_device("tpu")
    monkeypatch.setattr(torch.cuda, "is_available", lambda: True)
    assert pick_device("auto") == torch.device("cuda")
    assert pick_device("cuda") == torch.device("cuda")
    assert pick_device("cpu") == torch.device("cpu")


@pytest.mark.skipif(not NO_CUDA, reason="checks the error on a machine without CUDA")
@pytest.mark.parametrize("algorithm", ["ppo", "imitate", "finetune"])
def test_train_on_cuda_without_cuda_is_one_line_and_no_output(algorithm: str, imitation_sample: str, tmp_path) -> None:
    from typer.testing import CliRunner

    from xroute.cli.app import app

    out = tmp_path / "run"
    res = CliRunner().invoke(app, ["train", algorithm, "--testcase", imitation_sample, "--episodes", "1",
                                   "--device", "cuda", "--out", str(out)])
    assert res.exit_code == 2, res.output
    assert "device cuda asked for but torch sees no CUDA device" in res.output
    assert "Traceback" not in res.output and not out.exists()
    res = CliRunner().invoke(app, ["train", algorithm, "--testcase", imitation_sample, "--episodes", "1",
                                   "--device", "tpu", "--out", str(out)])
    assert res.exit_code == 2 and "use auto, cpu or cuda" in res.output and not out.exists()


@pytest.mark.skipif(NO_CUDA, reason="needs a CUDA device")
def test_imitation_and_finetuning_run_on_cuda_and_return_a_cpu_model(imitation_sample: str) -> None:
    from xroute.policies.rl import teacher
    from xroute.policies.rl.finetune import FinetuneConfig, finetune
    from xroute.policies.rl.imitation import ImitationConfig, model_order, train

    regions = teacher.collect([imitation_sample], workers=1, region_size=2, orders=4, max_regions=12)
    model, log = train(regions, ImitationConfig(steps=20, device="cuda", log_every=10))
    assert next(model.parameters()).device.type == "cpu" and len(log) == 2
    order = model_order(model, regions[0].features)
    assert sorted(order.tolist()) == list(range(len(regions[0].features)))
    tuned, log = finetune([imitation_sample], FinetuneConfig(iterations=1, regions=2, samples=2, region_size=2,
                                                             device="cuda"), model=model, workers=1)
    assert next(tuned.parameters()).device.type == "cpu" and [row["iteration"] for row in log] == [0, 1]
