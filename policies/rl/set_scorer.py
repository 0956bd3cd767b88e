"""The set scorer: one score per candidate net from compact features, the candidates seen together.

``SetScorer``: per-candidate features (:data:`~xroute.policies.rl.set_features.SET_FEATURES`)
-> MLP embedding (width ``width``) -> ``layers`` pre-norm self-attention blocks over the
candidate set (``heads`` heads, padded rows masked out of the keys) each followed by an MLP ->
a linear score per candidate, plus ``prior`` x (-heuristic_rank): a learned multiple of the
built-in order, initialised so that an untrained scorer orders as the heuristic does and
learning moves away from it only where the data says so. The order is by descending score.

Attention is written with plain matmuls so that the exported ONNX graph is small and takes any N.
Exported by :func:`export_onnx` with the signature :mod:`xroute.policies.onnx_policy` detects as
the ``set`` kind: input ``set_features f32[N, F]`` and ``mask bool[N]``, output ``scores f32[N]``.
"""

from __future__ import annotations

from pathlib import Path

import torch
from torch import nn

from xroute.atomic_files import atomic_write_bytes, atomic_write_from
from xroute.policies.rl.set_features import SET_FEATURES

RANK_COLUMN = SET_FEATURES.index("heuristic_rank")
MASKED_SCORE = -1e9


class AttentionBlock(nn.Module):
    def __init__(self, width: int, heads: int) -> None:
        super().__init__()
        self.heads = heads
        self.norm1 = nn.LayerNorm(width)
        self.qkv = nn.Linear(width, 3 * width)
        self.proj = nn.Linear(width, width)
        self.norm2 = nn.LayerNorm(width)
        self.ff = nn.Sequential(nn.Linear(width, 2 * width), nn.ReLU(), nn.Linear(2 * width, width))

    def forward(self, x: torch.Tensor, key_bias: torch.Tensor) -> torch.Tensor:
        """x: [B, N, W]; key_bias: [B, 1, 1, N] (0 for real rows, -1e9 for padding)."""
        b, n, w = x.shape
        h = self.heads
        qkv = self.qkv(self.norm1(x)).reshape(b, n, 3, h, w // h).permute(2, 0, 3, 1, 4)
        q, k, v = qkv[0], qkv[1], qkv[2]
        att = torch.softmax(q @ k.transpose(-1, -2) * (w // h) ** -0.5 + key_bias, dim=-1)
        x = x + self.proj((att @ v).transpose(1, 2).reshape(b, n, w))
        return x + self.ff(self.norm2(x))


class SetScorer(nn.Module):
    """Scores [B, N] of candidate sets [B, N, F] with validity mask [B, N] (see the module docstring)."""

    def __init__(self, features: int = len(SET_FEATURES), width: int = 64, heads: int = 4, layers: int = 2,
                 prior: float = 4.0) -> None:
        super().__init__()
        self.config = {"features": features, "width": width, "heads": heads, "layers": layers, "prior": prior}
        self.embed = nn.Sequential(nn.Linear(features, width), nn.ReLU(), nn.Linear(width, width))
        self.blocks = nn.ModuleList(AttentionBlock(width, heads) for _ in range(layers))
        self.norm = nn.LayerNorm(width)
        self.head = nn.Linear(width, 1)
        nn.init.zeros_(self.head.weight)
        nn.init.zeros_(self.head.bias)
        self.prior = nn.Parameter(torch.tensor(float(prior)))

    def encode(self, features: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
        """Row embeddings [B, N, width]: after attention over the unmasked rows and the final norm."""
        key_bias = torch.where(mask, 0.0, MASKED_SCORE)[:, None, None, :]
        x = self.embed(features)
        for block in self.blocks:
            x = block(x, key_bias)
        return self.norm(x)

    def score(self, embedded: torch.Tensor, features: torch.Tensor) -> torch.Tensor:
        """Raw scores [B, N] of the rows embedded by :meth:`encode` (the heuristic prior included)."""
        return self.head(embedded).squeeze(-1) - self.prior * features[..., RANK_COLUMN]

    def forward(self, features: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
        s = self.score(self.encode(features, mask), features)
        return torch.where(mask, s, torch.full_like(s, MASKED_SCORE))


class _OnnxWrapper(nn.Module):
    """Unbatched signature of the exported graph: [N, F], [N] -> [N]."""

    def __init__(self, model: SetScorer) -> None:
        super().__init__()
        self.model = model

    def forward(self, set_features: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
        return self.model(set_features[None], mask[None])[0]


def save_checkpoint(model: SetScorer, path: str | Path, extra: dict | None = None) -> None:
    """Writes ``model`` (and ``extra``) to ``path`` atomically."""
    state = {"kind": "set", "config": model.config, "state": model.state_dict(), "set_features": list(SET_FEATURES),
             **(extra or {})}
    atomic_write_from(path, lambda f: torch.save(state, f))


def load_checkpoint(path: str | Path) -> SetScorer:
    ck = torch.load(path, map_location="cpu", weights_only=False)
    if ck.get("kind") != "set":
        raise ValueError(f"{path}: not a set-scorer checkpoint")
    if tuple(ck["set_features"]) != SET_FEATURES:
        raise ValueError(f"{path}: trained on other features ({', '.join(ck['set_features'])})")
    model = SetScorer(**ck["config"])
    model.load_state_dict(ck["state"])
    return model.eval()


def export_onnx(model: SetScorer, path: str | Path, metadata: dict[str, str] | None = None) -> Path:
    """Writes ``model`` as an ONNX net-order model of the ``set`` kind (see :mod:`xroute.policies.onnx_policy`)."""
    import io
    import warnings

    import onnx

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    model = model.eval()
    n = 5
    example = (torch.rand(n, len(SET_FEATURES)), torch.ones(n, dtype=torch.bool))
    buf = io.BytesIO()
    with torch.no_grad(), warnings.catch_warnings():  # the TorchScript exporter (no onnxscript needed)
        warnings.simplefilter("ignore", DeprecationWarning)
        torch.onnx.export(_OnnxWrapper(model), example, buf, input_names=["set_features", "mask"],
                          output_names=["scores"], dynamic_axes={"set_features": {0: "candidates"},
                                                                 "mask": {0: "candidates"},
                                                                 "scores": {0: "candidates"}},
                          opset_version=17, dynamo=False, do_constant_folding=True)
    proto = onnx.load_from_string(buf.getvalue())
    del proto.metadata_props[:]
    meta = {"xroute_model": "net-order", "xroute_algorithm": "set", "xroute_set_features": ",".join(SET_FEATURES),
            **(metadata or {})}
    for key, value in meta.items():
        entry = proto.metadata_props.add()
        entry.key, entry.value = key, str(value)
    atomic_write_bytes(path, proto.SerializeToString())
    return path
