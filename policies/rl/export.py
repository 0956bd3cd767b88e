"""Checkpoint -> ONNX net-order model (the contract read by ``OnnxPolicy``).

Signature of the written model (N is the dynamic axis ``candidates``)::

    inputs   obstacle      float32 [1, 3, 64, 64]
             nets          float32 [N, 7, 3, 64, 64]
             net_features  float32 [N, S]
             mask          bool    [N]
    output   scores        float32 [N]   (masked rows -1e9; higher = route earlier)
    metadata xroute_model = "net-order", xroute_algorithm = "ppo" | "dqn",
             xroute_net_features = the S feature names joined with commas

The graph is the model in eval mode (batch norm uses its running statistics), traced by torch's
TorchScript-based exporter (no onnxscript needed) at opset :data:`OPSET`.
"""

from __future__ import annotations

import io
import warnings
from pathlib import Path

import onnx
import torch

from xroute.atomic_files import atomic_write_bytes
from xroute.policies.rl.checkpoint import Checkpoint, load_checkpoint
from xroute.policies.rl.models import ALIGNED_SHAPE, NET_CHANNELS, RegionScorer

OPSET = 17
INPUT_NAMES: tuple[str, ...] = ("obstacle", "nets", "net_features", "mask")
OUTPUT_NAME = "scores"
CANDIDATE_AXIS = "candidates"


def example_inputs(num_net_features: int, n: int = 2, seed: int = 0) -> tuple[torch.Tensor, ...]:
    """Random inputs of the contract's shapes with ``n`` candidates (0/1 grids, mask with a False row)."""
    g = torch.Generator().manual_seed(seed)
    obstacle = (torch.rand((1, *ALIGNED_SHAPE), generator=g) < 0.3).float()
    nets = (torch.rand((n, NET_CHANNELS, *ALIGNED_SHAPE), generator=g) < 0.05).float()
    features = torch.rand((n, num_net_features), generator=g)
    mask = torch.rand((n,), generator=g) < 0.7
    if n > 1:
        mask[0] = False
        mask[1] = True
    return obstacle, nets, features, mask


def to_onnx(ckpt: Checkpoint) -> onnx.ModelProto:
    """The ONNX model of a checkpoint, with the contract's metadata."""
    model = ckpt.model.cpu().eval()
    scorer = RegionScorer(model).eval()
    buf = io.BytesIO()
    # The TorchScript exporter: it needs no onnxscript and handles this static graph; torch marks
    # it deprecated, which is no news to a user running `xroute export`.
    with torch.no_grad(), warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        torch.onnx.export(
            scorer,
            example_inputs(model.num_net_features),
            buf,
            dynamo=False,
            input_names=list(INPUT_NAMES),
            output_names=[OUTPUT_NAME],
            dynamic_axes={"nets": {0: CANDIDATE_AXIS}, "net_features": {0: CANDIDATE_AXIS},
                          "mask": {0: CANDIDATE_AXIS}, OUTPUT_NAME: {0: CANDIDATE_AXIS}},
            opset_version=OPSET,
            do_constant_folding=True,
        )
    proto = onnx.load_from_string(buf.getvalue())
    meta = {
        "xroute_model": "net-order",
        "xroute_algorithm": ckpt.algorithm,
        "xroute_net_features": ",".join(ckpt.net_features),
        "xroute_episodes": str(ckpt.episode),
        "xroute_steps": str(ckpt.steps),
    }
    del proto.metadata_props[:]
    for key, value in meta.items():
        entry = proto.metadata_props.add()
        entry.key, entry.value = key, value
    proto.producer_name = "xroute export"
    onnx.checker.check_model(proto)
    return proto


def export_checkpoint(checkpoint: str | Path, out: str | Path) -> Path:
    """Writes the ONNX model of ``checkpoint`` to ``out`` (atomically); returns ``out``."""
    proto = to_onnx(load_checkpoint(checkpoint))
    p = Path(out)
    p.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_bytes(p, proto.SerializeToString())
    return p
