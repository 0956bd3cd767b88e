"""Hostile cases of what a failure tells the user, for ``hostile_cli.py`` (its categories and verdicts).

* ``policy-failure``: policies of every form failing: a ``.py`` net-order policy (``os._exit``,
  streams closed, a fork that comes back, a raise, a bad return; on 1 or 2 threads), a ``.py``
  schedule policy, an ONNX model that fails while it runs or is no model, a ``.json`` schedule model
  that is not one, a ``--net-router`` model that fails or is no net router;
* ``json-print``: ``route --json`` and ``batch --json`` with policies that print (``print``, C-level
  writes to descriptor 1, at import, per call, from a thread);
* ``home-path``: ``~`` in a route config's and a batch file's output folder and input files;
* ``full-disk``: ``route``, ``check`` or ``batch`` on a small tmpfs (``mount -t tmpfs``, as root),
  run once with room, then again with the disk filled to a random few kB;
* ``no-tracks``: the demo DEF without the TRACKS of a routing layer's preferred direction (or
  without any of its TRACKS), through ``info``, ``route`` and ``check``;
* ``read-warnings``: the demo DEF (plain or routed) with one odd value: a bad MASK, an unknown
  STYLE, a DEF rectangle written upper right first, a keyword in lower case, a NETS count that
  differs, through ``info`` and ``check``.

Verdicts added to ``hostile_cli.py``'s: no-file (a failing exit whose error line does not name the
file it is about), not-json (``--json`` stdout that does not parse), fatal ("Fatal Python error"),
lib-log (onnxruntime's own log lines), silent (an expected warning missing), tilde (a folder named
``~``, or outputs not under the home folder), disk (after a full disk: the old set not whole, or
the new one inconsistent).
"""

from __future__ import annotations

import json
import os
import random
import re
import subprocess
from pathlib import Path
from typing import Any, Callable

REPO = Path(__file__).resolve().parent.parent
DEMO = REPO / "testcases" / "data" / "demo"
DEMO_ARGS = ["--lef", str(DEMO / "demo.lef"), "--def", "{in}/d.def"]
BATCH = "testcases: [demo]\nsettings:\n  - {name: one, iteration_count: 1}\n"
ORDER = "import os, sys, threading, time\ndef order(region, features):\n    {body}\n    return list(range(len(features)))\n"
PLAN = "import os, sys\ndef plan(history, rule):\n    {body}\n"

# (body of order(), whether the run must fail)
ORDER_BODIES = [
    ("os._exit(0)", True), ("os._exit(1)", True), ("os._exit(3)", True), ("import posix; posix._exit(0)", True),
    ("from os import _exit; _exit(0)", True), ("os.close(1); os.close(2)", False),
    ("sys.stdout.close(); sys.stderr.close()", False), ("os.fork()", False),
    ("pid = os.fork()\n    if pid == 0: os._exit(0)\n    os.waitpid(pid, 0)", False),
    ("raise RuntimeError('policy bug')", True), ("return [0] * len(features)", True), ("return 'x'", True),
    ("threading.Thread(target=os._exit, args=(0,)).start(); time.sleep(5)", True),
    ("sys.exit(0)", True), ("raise KeyError(\"k\\nmulti\\nline\")", True),
]
PLAN_BODIES = [("os._exit(0)", True), ("return 42", True), ("return {'region_size': 10**9}", True),
               ("return {'bogus': 1}", True), ("return {'stop': True}", True), ("raise ValueError('plan bug')", True),
               ("return None", False), ("print('planning'); return None", False)]
JSON_MODELS = [('{"format": "xroute-schedule-switch", "version": 1, "parameters": {"late_size": 0, "switch_ratio": 1}}', True),
               ('{"format": "xroute-schedule-switch", "version": 2, "parameters": null}', True),
               ('{"format": "other"}', True), ('{"format": "xroute-schedule-switch", "version": 1, "parameters": '
                                               '{"late_size": 3, "switch_ratio": NaN}}', True),
               ("[1, 2", True), ('{"format": "xroute-schedule-switch", "version": 1, "parameters": null}', False),
               ('{"format": "xroute-schedule-switch", "version": 1, "parameters": {"late_size": 2, "switch_ratio": 1.0,'
                ' "patience": 1, "late_budget": 2}}', False)]
PRINTS = ["print('p' * 50)", "os.write(1, b'raw\\n')", "sys.stdout.write('w'); sys.stdout.flush()",
          "print('x', flush=True); os.write(1, b'{\\n')", "import ctypes; ctypes.CDLL(None).puts(b'libc')"]


def _models() -> dict[str, bytes]:
    """ONNX models built once (empty when onnx is not installed): a set scorer and a net router
    asking for 4 TiB when they run."""
    try:
        import onnx
        from onnx import TensorProto, helper
    except ImportError:
        return {}
    from xroute.policies.rl.set_features import SET_FEATURES

    def save(nodes: list, inputs: list, outputs: list, inits: list, meta: dict[str, str]) -> bytes:
        model = helper.make_model(helper.make_graph(nodes, "g", inputs, outputs, inits),
                                  opset_imports=[helper.make_opsetid("", 18)])
        model.ir_version = 8
        helper.set_model_props(model, meta)
        return model.SerializeToString()

    huge = [helper.make_node("ConstantOfShape", ["shape"], ["h"],
                             value=helper.make_tensor("v", TensorProto.FLOAT, [1], [1.0])),
            helper.make_node("ReduceSum", ["h"], ["big"], keepdims=0)]
    shape = helper.make_tensor("shape", TensorProto.INT64, [1], [2**40])
    f = len(SET_FEATURES)
    order = save(huge + [helper.make_node("ReduceSum", ["set_features", "ax"], ["s"], keepdims=0),
                         helper.make_node("Add", ["s", "big"], ["scores"])],
                 [helper.make_tensor_value_info("set_features", TensorProto.FLOAT, ["n", f]),
                  helper.make_tensor_value_info("mask", TensorProto.BOOL, ["n"])],
                 [helper.make_tensor_value_info("scores", TensorProto.FLOAT, ["n"])],
                 [shape, helper.make_tensor("ax", TensorProto.INT64, [1], [1])],
                 {"xroute_model": "net-order", "xroute_algorithm": "set", "xroute_set_features": ",".join(SET_FEATURES)})
    router = save(huge + [helper.make_node("MatMul", ["state", "w"], ["q0"]), helper.make_node("Add", ["q0", "big"], ["q"])],
                  [helper.make_tensor_value_info("state", TensorProto.FLOAT, ["b", 12])],
                  [helper.make_tensor_value_info("q", TensorProto.FLOAT, ["b", 6])],
                  [shape, helper.make_tensor("w", TensorProto.FLOAT, [12, 6], [0.0] * 72)], {"xroute_model": "net-router"})
    return {"order": order, "router": router}


MODELS: dict[str, bytes] = {}


def policy_failure(rng: random.Random, make: Callable[..., Any]) -> Any:
    if not MODELS:
        MODELS.update(_models() or {"none": b""})
    form = rng.choice(["py-order", "py-order", "py-plan", "onnx", "json", "net-router"])
    route = ["route", "--out", "{out}", "--quiet", "--iterations", "2"]
    if form == "py-order":
        body, fails = rng.choice(ORDER_BODIES)
        threads = rng.choice(["1", "2"])
        args = route + ["--policy", "{in}/p.py", "--threads", threads] + (["--region-size", "2"] if threads == "2" else [])
        return make("policy-failure", f"order: {body[:40]} threads {threads}", args, {"p.py": ORDER.format(body=body)},
                    must_refuse=fails, extra={"error_names": "{in}/p.py"})
    if form == "py-plan":
        body, fails = rng.choice(PLAN_BODIES)
        return make("policy-failure", f"plan: {body[:40]}", route + ["--schedule-policy", "{in}/p.py"],
                    {"p.py": PLAN.format(body=body)}, must_refuse=fails, extra={"error_names": "{in}/p.py"})
    if form == "json":
        text, fails = rng.choice(JSON_MODELS)
        return make("policy-failure", f"json model: {text[:40]}", route + ["--schedule-policy", "{in}/m.json"],
                    {"m.json": text}, must_refuse=fails, extra={"error_names": "{in}/m.json"})
    kind = rng.choice(["huge", "garbage", "other"])
    model = {"huge": MODELS.get("order" if form == "onnx" else "router", b""), "garbage": b"\x08\x01junk",
             "other": MODELS.get("router" if form == "onnx" else "order", b"")}[kind]
    flag = "--policy" if form == "onnx" else "--net-router"
    return make("policy-failure", f"{form} {kind}", route + [flag, "{in}/m.onnx"], {"m.onnx": model},
                must_refuse=True, extra={"error_names": "{in}/m.onnx"})


def json_print(rng: random.Random, make: Callable[..., Any]) -> Any:
    what = rng.choice(PRINTS)
    where = rng.choice(["import", "order", "plan", "thread"])
    if where == "import":
        text = "import os, sys\n" + what + "\n" + ORDER.format(body="pass")
    elif where == "order":
        text = ORDER.format(body=what)
    elif where == "plan":
        text = PLAN.format(body=what + "\n    return None")
    else:
        text = ("import os, sys, threading, time\ndef _loop():\n    for _ in range(200):\n        " + what +
                "\n        time.sleep(0.005)\nthreading.Thread(target=_loop, daemon=True).start()\n"
                + ORDER.format(body="pass").split("\n", 1)[1])
    if rng.random() < 0.2 and where != "plan":
        batch = "testcases: [demo]\npolicies: [{root}/in/p.py]\nsettings:\n  - {name: one, iteration_count: 1}\n"
        return make("json-print", f"batch {where}: {what[:30]}", ["batch", "{in}/b.yaml", "--out", "{out}", "--json"],
                    {"p.py": text, "b.yaml": batch}, extra={"json": True})
    flag = "--schedule-policy" if where == "plan" else "--policy"
    return make("json-print", f"route {where}: {what[:30]}", ["route", "--out", "{out}", "--json", "--iterations", "1",
                                                              flag, "{in}/p.py"], {"p.py": text}, extra={"json": True})


def home_path(rng: random.Random, make: Callable[..., Any]) -> Any:
    sub = rng.choice(["x", "a/b", "runs/one", "sp ace"])
    choice = rng.choice(["batch-out", "route-out", "route-policy", "batch-config"])
    files = {"home/p.py": ORDER.format(body="pass"), "home/base.yaml": "router:\n  iteration_count: 1\n"}
    if choice == "batch-out":
        files["b.yaml"] = BATCH + f"out_dir: ~/{sub}\n"
        return make("home-path", choice, ["batch", "{in}/b.yaml", "--quiet"], files,
                    extra={"home": True, "home_out": sub + "/summary.json"})
    if choice == "batch-config":
        files["b.yaml"] = BATCH + f"config: ~/base.yaml\nout_dir: ~/{sub}\n"
        return make("home-path", choice, ["batch", "{in}/b.yaml", "--quiet"], files,
                    extra={"home": True, "home_out": sub + "/summary.json"})
    policy = "  policy: ~/p.py\n" if choice == "route-policy" else ""
    files["c.yaml"] = f"output:\n  out_dir: ~/{sub}\nrouter:\n  iteration_count: 1\n" + ("policy:\n" + policy if policy else "")
    return make("home-path", choice, ["route", "--config", "{in}/c.yaml", "--quiet"], files,
                extra={"home": True, "home_out": sub + "/demo.routed.def"})


def full_disk(rng: random.Random, make: Callable[..., Any], routed: dict[str, bytes]) -> Any:
    command = rng.choice(["route", "route", "check", "batch"])
    free = rng.choice([0, 4, 8, 16, 64, 120, 148, 152, 156, 160, 200, rng.randint(0, 400)])
    args = {"route": ["route", "--out", "{out}", "--quiet", "--iterations", "1"],
            "check": ["check", "demo", "--def", "{in}/r.def", "--out", "{out}", "--quiet"],
            "batch": ["batch", "{in}/b.yaml", "--out", "{out}", "--quiet", "--force"]}[command]
    files = {"r.def": routed["demo.routed.def"], "b.yaml": BATCH.encode()}
    return make("full-disk", f"{command} with {free} kB free", args, files,
                extra={"tmpfs_kb": 2048, "free_kb": free, "error_names": "{out}", "same_set": command != "batch"})


def _without_tracks(rng: random.Random, text: str) -> tuple[str, str]:
    layer = rng.choice(["Metal1", "Metal2", "Metal3", "Metal4", "Metal5", "Metal6"])
    lines = [m for m in re.finditer(rf"^TRACKS ([XY]) .* LAYER {layer} ;\n", text, re.M)]
    horizontal = layer in ("Metal1", "Metal3", "Metal5")
    pref = [m for m in lines if (m.group(1) == "Y") == horizontal]
    drop = pref if rng.random() < 0.7 else lines
    for m in sorted(drop, key=lambda m: m.start(), reverse=True):
        text = text[:m.start()] + text[m.end():]
    return layer + (" preferred" if drop is pref else " all"), text


def no_tracks(rng: random.Random, make: Callable[..., Any], routed: dict[str, bytes]) -> Any:
    command = rng.choice(["info", "route", "check"])
    base = routed["demo.routed.def"].decode() if command == "check" else (DEMO / "demo.def").read_text()
    label, text = _without_tracks(rng, base)
    args = {"info": ["info", *DEMO_ARGS], "route": ["route", *DEMO_ARGS, "--out", "{out}", "--quiet"],
            "check": ["check", "--lef", str(DEMO / "demo.lef"), "--def", "{in}/d.def", "--out", "{out}", "--quiet"]}
    return make("no-tracks", f"{command} {label}", args[command], {"d.def": text},
                must_refuse=command == "route", extra={"error_names": "{in}/d.def", "warning": "{in}/d.def:"})


def _odd_value(rng: random.Random, text: str) -> tuple[str, str]:
    kind = rng.choice(["via mask", "wire mask", "style", "rect", "lower", "nets count", "pin rect"])
    if kind == "via mask":
        return kind, re.sub(r"(\( \d+ \d+ \)) (VIA\d+)", rf"\1 MASK {rng.choice([1000, 4096, -1, 99999])} \2", text, 1)
    if kind == "wire mask":
        return kind, re.sub(r"(  \+ ROUTED Metal\d )", rf"\1MASK {rng.choice([0, -3])} ", text, 1)
    if kind == "style":
        return kind, re.sub(r"(  \+ ROUTED Metal\d )", rf"\1STYLE {rng.randint(0, 9)} ", text, 1)
    if kind == "rect":
        return kind, re.sub(r"RECT \( 0 0 (\d+) (\d+) \)", r"RECT ( \1 \2 0 0 )", text, 1)
    if kind == "pin rect":
        return kind, re.sub(r"\+ LAYER (Metal\d) \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)",
                            r"+ LAYER \1 ( \4 \5 ) ( \2 \3 )", text, 1)
    if kind == "lower":
        word = rng.choice(["NETS", "COMPONENTS", "PINS", "ROUTED", "NEW", "PLACED", "DIEAREA", "TRACKS"])
        return f"lower {word}", re.sub(rf"\b{word}\b", word.lower(), text, 1)
    return kind, re.sub(r"^NETS (\d+) ;", lambda m: f"NETS {rng.choice([0, int(m.group(1)) + 1, 99999])} ;", text,
                        count=1, flags=re.M)


def read_warnings(rng: random.Random, make: Callable[..., Any], routed: dict[str, bytes]) -> Any:
    command = rng.choice(["info", "check"])
    kind, text = _odd_value(rng, routed["demo.routed.def"].decode())
    args = {"info": ["info", *DEMO_ARGS],
            "check": ["check", "--lef", str(DEMO / "demo.lef"), "--def", "{in}/d.def", "--out", "{out}", "--quiet"]}
    return make("read-warnings", f"{command} {kind}", args[command], {"d.def": text},
                extra={"warning": "{in}/d.def:", "error_names": "{in}/d.def"})


# ----------------------------------------------------------------------------- disks and judging
def mount_tmpfs(out: Path, size_kb: int) -> bool:
    out.mkdir(parents=True, exist_ok=True)
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size_kb}k", "tmpfs", str(out)], capture_output=True)
    return done.returncode == 0


def unmount(out: Path) -> None:
    subprocess.run(["umount", "-l", str(out)], capture_output=True)


def fill(out: Path, free_kb: int) -> None:
    """Writes a filler file into ``out`` leaving about ``free_kb`` kB free on its file system."""
    st = os.statvfs(out)
    room = st.f_bavail * st.f_frsize - free_kb * 1024
    with open(out / "filler", "wb") as f:
        while room > 0:
            chunk = min(room, 1 << 20)
            try:
                f.write(b"\0" * chunk)
                f.flush()
            except OSError:
                break
            room -= chunk


def set_hashes(out: Path) -> dict[str, str]:
    import hashlib

    return {str(p.relative_to(out)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(out.rglob("*")) if p.is_file() and p.name != "filler"}


def judge(extra: dict[str, Any], fill_in: Callable[[str], str], rc: int | None, so: str, se: str, root: Path,
          work: Path, before_set: dict[str, str] | None, out: Path) -> list[str]:
    """The verdicts of the module doc for one case (``fill_in`` replaces {in}/{out}/{root})."""
    verdict: list[str] = []
    text = so + se
    if "Fatal Python error" in text:
        verdict.append("fatal")
    if re.search(r"\[[EWIV]:onnxruntime", text):
        verdict.append("lib-log")
    errors = [line for line in se.splitlines() if line.startswith("error: ")]
    if rc not in (0, 1, None) and extra.get("error_names"):
        if not errors or fill_in(extra["error_names"]) not in errors[-1]:
            verdict.append("no-file")
    named = errors + [line for line in se.splitlines() if line.startswith("job failed: ")]
    if any(".xroute-stage." in line or ".tmp-" in line for line in named) and "no-file" not in verdict:
        verdict.append("no-file")  # a temporary file or folder, gone by the time the message is read
    if extra.get("json") and rc in (0, 1):
        try:
            json.loads(so)
        except ValueError:
            verdict.append("not-json")
    if extra.get("warning") and rc in (0, 1):
        wanted = fill_in(extra["warning"])
        if not any(line.startswith("warning: " + wanted) or ("warning: " + wanted) in line for line in text.splitlines()):
            verdict.append("silent")
    if extra.get("home"):
        if any(p.name == "~" for p in work.rglob("*")) or rc != 0 or not (root / "home" / extra["home_out"]).is_file():
            verdict.append("tilde")
    if before_set is not None and rc is not None:
        after = set_hashes(out)
        from hostile_cli import inconsistent_sets, leftovers

        changed = extra.get("same_set") and rc not in (0, 1) and after != before_set
        if changed or leftovers(out) or inconsistent_sets(out):
            verdict.append("disk")
    return verdict


def categories() -> dict[str, tuple[Callable[..., Any], int]]:
    """The categories above: name -> (maker(rng, routed demo files, make), weight)."""
    return {"policy-failure": (lambda rng, routed, make: policy_failure(rng, make), 3),
            "json-print": (lambda rng, routed, make: json_print(rng, make), 2),
            "home-path": (lambda rng, routed, make: home_path(rng, make), 1),
            "full-disk": (lambda rng, routed, make: full_disk(rng, make, routed), 2),
            "no-tracks": (lambda rng, routed, make: no_tracks(rng, make, routed), 1),
            "read-warnings": (lambda rng, routed, make: read_warnings(rng, make, routed), 2)}

