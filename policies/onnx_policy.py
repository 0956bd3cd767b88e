"""``OnnxPolicy(path)``: a net-order policy whose scores come from an ONNX model (onnxruntime).

The model scores every candidate net of a region in one call, on the region's state when it
opens (:func:`xroute.policies.rl.observation.observe`); nets are routed by descending score, ties in the
heuristic order. Signature (written by ``xroute export``, checked on load)::

    inputs   obstacle      float32 [1, 3, 64, 64]
             nets          float32 [N, 7, 3, 64, 64]    N: dynamic ("candidates")
             net_features  float32 [N, S]               S = len(NET_FEATURES)
             mask          bool    [N]
    output   scores        float32 [N]                  masked rows -1e9; higher = routed earlier
    metadata xroute_model = net-order, xroute_algorithm = ppo | dqn,
             xroute_net_features = ",".join(NET_FEATURES)

A second kind, the set scorer (:mod:`xroute.policies.rl.set_scorer`), is recognised by its inputs::

    inputs   set_features  float32 [N, F]               F = len(SET_FEATURES)
             mask          bool    [N]
    output   scores        float32 [N]
    metadata xroute_model = net-order, xroute_algorithm = set,
             xroute_set_features = ",".join(SET_FEATURES)

its features (:func:`xroute.policies.rl.set_features.set_features`, a few numbers per net)
computed from the region's grid when it opens. A model with other inputs, outputs, shapes or
metadata is refused with a :class:`PolicyError` naming the file and both signatures. onnxruntime is imported when a model is loaded (the ``rl``
extra), never when this module is. A model that fails while it runs (e.g. asks for more memory
than there is) is a :class:`PolicyError` naming the file, with onnxruntime's message on the same
line; onnxruntime's own log lines are silenced (:func:`quiet_session_options`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Sequence

import numpy as np

from xroute.net_order import PolicyError, heuristic_order
from xroute.policies.rl.observation import ALIGNED_SHAPE, NET_CHANNELS, NET_FEATURES, observe_arrays, unrouted_mask
from xroute.policies.rl.set_features import SET_FEATURES, set_features

ALGORITHMS: tuple[str, ...] = ("ppo", "dqn")

# name -> (onnxruntime type, shape with None for the candidate axis)
INPUTS: dict[str, tuple[str, tuple[int | None, ...]]] = {
    "obstacle": ("tensor(float)", (1,) + ALIGNED_SHAPE),
    "nets": ("tensor(float)", (None, NET_CHANNELS) + ALIGNED_SHAPE),
    "net_features": ("tensor(float)", (None, len(NET_FEATURES))),
    "mask": ("tensor(bool)", (None,)),
}
OUTPUTS: dict[str, tuple[str, tuple[int | None, ...]]] = {"scores": ("tensor(float)", (None,))}
SET_INPUTS: dict[str, tuple[str, tuple[int | None, ...]]] = {
    "set_features": ("tensor(float)", (None, len(SET_FEATURES))),
    "mask": ("tensor(bool)", (None,)),
}


ORT_LOG_FATAL = 4  # onnxruntime's log severities: 0 verbose ... 3 error, 4 fatal


def quiet_session_options(onnxruntime: Any) -> Any:
    """Session options of one thread each that keep onnxruntime's log lines off stderr: a failure
    comes back as an exception, which the caller reports as one line naming the model."""
    options = onnxruntime.SessionOptions()
    options.intra_op_num_threads = 1
    options.inter_op_num_threads = 1
    options.log_severity_level = ORT_LOG_FATAL
    return options


def run_model(session: Any, source: Any, outputs: list[str], feeds: dict[str, Any]) -> list[Any]:
    """``session.run(outputs, feeds)`` with onnxruntime's logging silenced; a failure is a
    :class:`PolicyError` naming the model file ``source``."""
    import onnxruntime

    run_options = onnxruntime.RunOptions()
    run_options.log_severity_level = ORT_LOG_FATAL
    try:
        return session.run(outputs, feeds, run_options)
    except Exception as exc:  # noqa: BLE001 - onnxruntime's exception classes are not a public API
        text = " ".join(str(exc).split()) or type(exc).__name__
        raise PolicyError(f"{source}: the model failed while it ran: {text}") from None


def _dims(shape: tuple[int | None, ...]) -> str:
    return "[" + ",".join("N" if d is None else str(d) for d in shape) + "]"


EXPECTED_SIGNATURE = (
    "inputs " + ", ".join(f"{n} {t[7:-1].replace('float', 'float32')}{_dims(s)}" for n, (t, s) in INPUTS.items())
    + "; output " + ", ".join(f"{n} float32{_dims(s)}" for n, (_, s) in OUTPUTS.items())
    + "; metadata xroute_model=net-order, xroute_algorithm=ppo|dqn, xroute_net_features="
    + ",".join(NET_FEATURES)
    + "; or (set scorer) inputs set_features float32[N," + str(len(SET_FEATURES)) + "], mask bool[N]; output scores "
    "float32[N]; metadata xroute_model=net-order, xroute_algorithm=set, xroute_set_features=" + ",".join(SET_FEATURES)
)
"""The model signatures an ONNX net-order policy may have, as printed in errors."""


def _check_args(kind: str, got: Sequence[Any], expected: dict[str, tuple[str, tuple[int | None, ...]]]) -> str | None:
    """What is wrong with the model's inputs or outputs, or None."""
    names = [a.name for a in got]
    if sorted(names) != sorted(expected):
        return f"its {kind} are {', '.join(names) or 'none'}"
    for arg in got:
        typ, shape = expected[arg.name]
        if arg.type != typ:
            return f"{kind[:-1]} '{arg.name}' is {arg.type}"
        dims = tuple(arg.shape or ())
        if len(dims) != len(shape):
            return f"{kind[:-1]} '{arg.name}' has shape {list(dims)}"
        for d, e in zip(dims, shape):
            if e is None and isinstance(d, int):  # a fixed candidate axis: must be dynamic
                return f"{kind[:-1]} '{arg.name}' has a fixed candidate axis {d} (must be dynamic)"
            if e is not None and isinstance(d, int) and d != e:
                return f"{kind[:-1]} '{arg.name}' has shape {list(dims)}"
    return None


class OnnxPolicy:
    """Orders a region's nets by an ONNX model's scores (see the module docstring)."""

    builtin = None
    needs_region = True  # the router lends it the region (grid views) in region["engine_region"]

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.name = self.path.name
        self.source = str(self.path)  # named by every failure of the model (xroute.policy_guard)
        if not self.path.is_file():
            raise PolicyError(f"ONNX model not found: {self.path}")
        try:
            import onnxruntime
        except ImportError as exc:
            raise PolicyError(f"{self.path}: ONNX policies need onnxruntime: pip install 'xroute[rl]'") from exc
        options = quiet_session_options(onnxruntime)
        try:
            self.session = onnxruntime.InferenceSession(str(self.path), options, providers=["CPUExecutionProvider"])
        except Exception as exc:  # noqa: BLE001 - any load failure is a bad model file
            first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
            raise PolicyError(f"{self.path}: not a readable ONNX model ({first}); expected {EXPECTED_SIGNATURE}") from exc
        names = {a.name for a in self.session.get_inputs()}
        self.kind = "set" if "set_features" in names else "grid"
        problem = (_check_args("inputs", self.session.get_inputs(), SET_INPUTS if self.kind == "set" else INPUTS)
                   or _check_args("outputs", self.session.get_outputs(), OUTPUTS)
                   or self._check_metadata())
        if problem:
            raise PolicyError(f"{self.path}: not an xroute net-order model: {problem}; expected {EXPECTED_SIGNATURE}")

    def _check_metadata(self) -> str | None:
        meta = self.session.get_modelmeta().custom_metadata_map
        if meta.get("xroute_model") != "net-order":
            return f"metadata xroute_model is {meta.get('xroute_model')!r}"
        self.algorithm = meta.get("xroute_algorithm", "")
        if self.kind == "set":
            if self.algorithm != "set":
                return f"metadata xroute_algorithm is {self.algorithm!r} (a set scorer's is 'set')"
            if meta.get("xroute_set_features") != ",".join(SET_FEATURES):
                return f"metadata xroute_set_features is {meta.get('xroute_set_features')!r}"
            return None
        if self.algorithm not in ALGORITHMS:
            return f"metadata xroute_algorithm is {self.algorithm!r}"
        if meta.get("xroute_net_features") != ",".join(NET_FEATURES):
            return f"metadata xroute_net_features is {meta.get('xroute_net_features')!r}"
        return None

    def scores(self, obstacle: np.ndarray, nets: np.ndarray, net_features: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """float32[N]: the model's scores of N candidates (one call)."""
        out = run_model(self.session, self.path, ["scores"], {
            "obstacle": np.ascontiguousarray(obstacle, dtype=np.float32).reshape((1,) + ALIGNED_SHAPE),
            "nets": np.ascontiguousarray(nets, dtype=np.float32),
            "net_features": np.ascontiguousarray(net_features, dtype=np.float32),
            "mask": np.ascontiguousarray(mask, dtype=bool),
        })[0]
        return np.asarray(out, dtype=np.float32).reshape(-1)

    def set_scores(self, features: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """float32[N]: a set scorer's scores of N candidates (one call)."""
        out = run_model(self.session, self.path, ["scores"], {
            "set_features": np.ascontiguousarray(features, dtype=np.float32),
            "mask": np.ascontiguousarray(mask, dtype=bool),
        })[0]
        return np.asarray(out, dtype=np.float32).reshape(-1)

    def order(self, region: dict[str, Any], features: np.ndarray) -> Sequence[int]:
        """The unrouted candidates (rows of ``features``) by descending score, ties in heuristic order."""
        n = len(features)
        if n == 0:
            return []
        engine_region = region.get("engine_region")
        if engine_region is None:
            raise PolicyError(f"ONNX policy {self.name} needs the region's grid (region['engine_region']); "
                              "route with xroute.router.route_design, which lends it")
        mask = unrouted_mask(engine_region)
        pending = np.flatnonzero(mask)  # the rows of `features`, in order
        if self.kind == "set":
            rows = set_features(engine_region.grid(), engine_region.candidates, mask, tuple(engine_region.box))
            s = self.set_scores(rows[pending], mask[pending])
        else:
            obs = observe_arrays(engine_region.grid(), engine_region.candidates, mask, tuple(engine_region.box),
                                 select=pending)
            s = self.scores(obs.obstacle, obs.nets, obs.net_features, obs.mask)
        if s.shape != (n,):
            raise PolicyError(f"{self.path}: ONNX policy {self.name} returned {s.shape} scores for {n} candidate nets")
        rank = np.empty(n, dtype=np.int64)
        rank[heuristic_order(features)] = np.arange(n)
        return np.lexsort((rank, -s.astype(np.float64)))

    def __repr__(self) -> str:
        return f"OnnxPolicy({str(self.path)!r})"
