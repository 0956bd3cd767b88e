"""Models that fail, seen from outside (``python -m xroute route`` as its own process: onnxruntime
logs from C++, on file descriptor 2): one error line naming the model file, with onnxruntime's
message on it and none of its own log lines; a file that is no net-router model is refused the same
way. The models are drawn here: valid signatures whose graphs ask for 4 TiB when they run.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import pick


def route(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "xroute", "route", "--out", str(tmp_path / "o"), *args],
                          capture_output=True, text=True, timeout=300, env={**os.environ, "CI": "true"}, cwd=tmp_path)


def only_error(proc: subprocess.CompletedProcess) -> str:
    """The one stderr line of a run that failed with status 2 (no onnxruntime log line beside it)."""
    assert proc.returncode == 2, (proc.returncode, proc.stdout, proc.stderr)
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    return lines[0]

TB4 = 2**40  # float32 elements: a 4 TiB buffer


def _onnx():  # noqa: ANN202 - the onnx module, or the test is skipped
    pytest.importorskip("onnxruntime", reason="onnxruntime (rl extra) is not installed")
    return pytest.importorskip("onnx", reason="onnx (test extra) is not installed")


def _save(path: Path, nodes: list, inputs: list, outputs: list, inits: list, meta: dict[str, str]) -> Path:
    onnx = _onnx()
    helper = onnx.helper
    model = helper.make_model(helper.make_graph(nodes, "g", inputs, outputs, inits),
                              opset_imports=[helper.make_opsetid("", 18)])
    model.ir_version = 8
    helper.set_model_props(model, meta)
    onnx.save(model, path)
    return path


def _huge(out: str) -> list:
    """Nodes that ask onnxruntime for :data:`TB4` floats and sum them into ``out``."""
    helper, TensorProto = _onnx().helper, _onnx().TensorProto
    value = helper.make_tensor("v", TensorProto.FLOAT, [1], [1.0])
    return [helper.make_node("ConstantOfShape", ["huge_shape"], ["huge"], value=value),
            helper.make_node("ReduceSum", ["huge"], [out], keepdims=0)]


def huge_set_scorer(path: Path) -> Path:
    """A set-scorer net-order model (valid signature) whose graph allocates 4 TiB when it runs."""
    from xroute.policies.rl.set_features import SET_FEATURES

    helper, TensorProto = _onnx().helper, _onnx().TensorProto
    f = len(SET_FEATURES)
    nodes = _huge("big") + [helper.make_node("ReduceSum", ["set_features", "ax"], ["s"], keepdims=0),
                            helper.make_node("Add", ["s", "big"], ["scores"])]
    inits = [helper.make_tensor("huge_shape", TensorProto.INT64, [1], [TB4]),
             helper.make_tensor("ax", TensorProto.INT64, [1], [1])]
    inputs = [helper.make_tensor_value_info("set_features", TensorProto.FLOAT, ["n", f]),
              helper.make_tensor_value_info("mask", TensorProto.BOOL, ["n"])]
    return _save(path, nodes, inputs, [helper.make_tensor_value_info("scores", TensorProto.FLOAT, ["n"])], inits,
                 {"xroute_model": "net-order", "xroute_algorithm": "set", "xroute_set_features": ",".join(SET_FEATURES)})


def huge_net_router(path: Path) -> Path:
    """A net-router model (state [B, 12] -> q [B, 6]) whose graph allocates 4 TiB when it runs."""
    helper, TensorProto = _onnx().helper, _onnx().TensorProto
    nodes = _huge("big") + [helper.make_node("MatMul", ["state", "w"], ["q0"]), helper.make_node("Add", ["q0", "big"], ["q"])]
    inits = [helper.make_tensor("huge_shape", TensorProto.INT64, [1], [TB4]),
             helper.make_tensor("w", TensorProto.FLOAT, [12, 6], [0.0] * 72)]
    return _save(path, nodes, [helper.make_tensor_value_info("state", TensorProto.FLOAT, ["b", 12])],
                 [helper.make_tensor_value_info("q", TensorProto.FLOAT, ["b", 6])], inits, {"xroute_model": "net-router"})


@pytest.mark.parametrize("flag", ["--policy", "--net-router"])
def test_a_model_that_fails_while_it_runs_is_one_line_naming_it(tmp_path: Path, flag: str) -> None:
    make = huge_set_scorer if flag == "--policy" else huge_net_router
    model = make(tmp_path / "huge.onnx")
    line = only_error(route(tmp_path, pick("ispd18_sample"), flag, str(model), "--quiet", "--iterations", "1"))
    assert line.startswith(f"error: {model}: the model failed while it ran: ") and "allocate" in line, line


def test_a_file_that_is_no_net_router_model_is_one_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.onnx"
    bad.write_bytes(b"not a model")
    assert only_error(route(tmp_path, "--net-router", str(bad), "--quiet")).startswith(
        f"error: {bad}: not a readable ONNX model (")
    other = huge_set_scorer(tmp_path / "order.onnx")
    assert only_error(route(tmp_path, "--net-router", str(other), "--quiet")) == (
        f"error: {other}: not a net-router model (xroute_model = 'net-order')")
