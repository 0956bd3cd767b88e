"""CLI-level mutation harness: hostile inputs through `xroute info` and `xroute route`.

    python fuzz/mutate_cli.py [--cases N] [--seed S] [--route-share 0.3] [--timeout 60] [--keep DIR]

Starts from the shipped demo design (testcases/data/demo: LEF, DEF, guide), a tiny hand-drawn
design, configs/default.yaml and a few policy files, and makes N mutated cases: numbers replaced
by 0 / negative / huge values, lines dropped, duplicated or swapped, bytes flipped (invalid UTF-8
included), files truncated or emptied, DIEAREA / guide rectangles made degenerate, inverted or
moved out of the die, hostile DESIGN names (``../escaped``, an absolute path), YAML with merge
keys, tags, deep nesting, odd command-line flags, and policies that raise, exit or hang. Each
case runs as its own process (`python -m xroute ...`) in a fresh temporary folder with
``--out`` inside it, and is judged:

* crash: killed by a signal (segfault, SIGFPE, abort, ...);
* traceback: "Traceback (most recent call last)" on stdout or stderr;
* hang: still running after --timeout seconds;
* escape: any file created or changed in the case's folder outside the --out folder and the
  inputs (the hostile names point inside the case's folder, so an escape is seen there);
* not one line: a failing exit whose stderr is not exactly one "error: ..." line (reported, not
  counted as a failure: Typer's usage errors are boxes).

Prints a table of counts and writes the failing cases (inputs and output) under --keep. Exit
status 1 if any crash, traceback, hang or escape was seen.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
DEMO = REPO / "testcases" / "data" / "demo"
CONFIG = REPO / "configs" / "default.yaml"

TINY_LEF = """VERSION 5.8 ;
UNITS DATABASE MICRONS 1000 ; END UNITS
LAYER M1 TYPE ROUTING ; DIRECTION HORIZONTAL ; PITCH 0.2 ; WIDTH 0.1 ; SPACING 0.1 ; END M1
LAYER V1 TYPE CUT ; WIDTH 0.1 ; SPACING 0.1 ; END V1
LAYER M2 TYPE ROUTING ; DIRECTION VERTICAL ; PITCH 0.2 ; WIDTH 0.1 ; SPACING 0.1 ; END M2
VIA V12 DEFAULT LAYER M1 ; RECT -0.05 -0.05 0.05 0.05 ; LAYER V1 ; RECT -0.05 -0.05 0.05 0.05 ;
  LAYER M2 ; RECT -0.05 -0.05 0.05 0.05 ; END V12
SITE core CLASS CORE ; SIZE 0.2 BY 1.0 ; END core
MACRO BUF CLASS CORE ; SIZE 0.6 BY 1.0 ; SITE core ;
  PIN A DIRECTION INPUT ; PORT LAYER M1 ; RECT 0.05 0.35 0.15 0.45 ; END END A
  PIN Y DIRECTION OUTPUT ; PORT LAYER M1 ; RECT 0.45 0.35 0.55 0.45 ; END END Y
END BUF
END LIBRARY
"""

TINY_DEF = """VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN tiny ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 4000 4000 ) ;
ROW r0 core 0 0 N DO 20 BY 1 STEP 200 0 ;
TRACKS Y 100 DO 20 STEP 200 LAYER M1 ;
TRACKS X 100 DO 20 STEP 200 LAYER M2 ;
GCELLGRID X 0 DO 5 STEP 1000 ;
GCELLGRID Y 0 DO 5 STEP 1000 ;
COMPONENTS 2 ;
- u1 BUF + PLACED ( 400 1000 ) N ;
- u2 BUF + PLACED ( 2800 2000 ) N ;
END COMPONENTS
NETS 1 ;
- n1 ( u1 Y ) ( u2 A ) ;
END NETS
END DESIGN
"""

TINY_GUIDE = """n1
(
0 0 4000 3000 M1
0 0 4000 3000 M2
)
"""

POLICIES = {
    "raises.py": "def order(region, features):\n    raise ZeroDivisionError('policy bug')\n",
    "exits.py": "import sys\ndef order(region, features):\n    sys.exit(0)\n",
    "exits_on_import.py": "import sys\nsys.exit(0)\n",
    "hangs.py": "def order(region, features):\n    while True:\n        pass\n",
    "sleeps.py": "import time\ndef order(region, features):\n    time.sleep(3600)\n",
    "garbage.py": "def order(region, features):\n    return ['a', None]\n",
    "recursion.py": "def order(region, features):\n    return order(region, features)\n",
    "memoryish.py": "def order(region, features):\n    return list(range(len(features)))[::-1]\n",
    "keyboard.py": "def order(region, features):\n    raise MemoryError('out of memory in policy')\n",
    "bad_import.py": "import no_such_module_xyz\n",
    "not_python.py": "\xff\xfe garbage",
}

HUGE = ["0", "-1", "-1000", "2147483648", "-2147483649", "99999999999999999999", "1e30", "nan", "inf", "0.0",
        "-0.001", "x", "", "1e-30", "4294967296"]
HOSTILE_NAMES = ["../escaped", "{root}/abs_escape", "a/../../up", "..", ".", "/", "", "x/y/z", "..\\win",
                 "\u00e9t\u00e9", "a" * 300, ".hidden", "-rf", "~/home_escape", "name;with;semi",
                 "{root}/out/../sibling"]


@dataclass
class Case:
    kind: str  # what was mutated
    command: str  # info or route
    files: dict[str, bytes]  # name -> content, written into the case's in/ folder
    args: list[str]  # command arguments, {in} and {out} and {root} replaced
    note: str = ""


@dataclass
class Outcome:
    case: Case
    rc: int | None
    seconds: float
    stdout: str
    stderr: str
    verdict: list[str] = field(default_factory=list)


# ----------------------------------------------------------------------------- mutators
NUM = re.compile(rb"(?<![A-Za-z_])-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")


def mutate_numbers(rng: random.Random, text: bytes, k: int = 1) -> bytes:
    spans = [m.span() for m in NUM.finditer(text)]
    if not spans:
        return text
    for a, b in sorted(rng.sample(spans, min(k, len(spans))), reverse=True):
        old = text[a:b]
        choice = rng.random()
        if choice < 0.5:
            new = rng.choice(HUGE).encode()
        elif choice < 0.75:
            new = b"-" + old.lstrip(b"-")
        else:
            try:
                new = str(int(float(old) * rng.choice([0, 1000, -1, 100000]))).encode()
            except (ValueError, OverflowError):
                new = b"0"
        text = text[:a] + new + text[b:]
    return text


def mutate_lines(rng: random.Random, text: bytes) -> bytes:
    lines = text.split(b"\n")
    if len(lines) < 2:
        return text
    op = rng.choice(["drop", "dup", "swap", "truncate_line", "shuffle_words"])
    i = rng.randrange(len(lines))
    if op == "drop":
        del lines[i]
    elif op == "dup":
        lines.insert(i, lines[i])
    elif op == "swap":
        j = rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    elif op == "truncate_line":
        lines[i] = lines[i][: rng.randrange(len(lines[i]) + 1)]
    else:
        words = lines[i].split(b" ")
        rng.shuffle(words)
        lines[i] = b" ".join(words)
    return b"\n".join(lines)


def mutate_bytes(rng: random.Random, text: bytes) -> bytes:
    if not text:
        return b"\xff"
    data = bytearray(text)
    for _ in range(rng.randint(1, 4)):
        i = rng.randrange(len(data))
        op = rng.random()
        if op < 0.3:
            data[i] = rng.choice([0xFF, 0xC3, 0x80, 0x00, 0xE2, 0xF0])
        elif op < 0.6:
            data[i:i] = rng.choice([b"\xff\xfe", b"\xc3(", b"\x00", b"\xed\xa0\x80", b'"', b";", b"#", b"(", b")"])
        else:
            data[i] ^= 1 << rng.randrange(8)
    return bytes(data)


def truncate(rng: random.Random, text: bytes) -> bytes:
    return text[: rng.randrange(len(text) + 1)] if text else text


def set_design_name(text: bytes, name: str) -> bytes:
    line = b"DESIGN " + name.encode("utf-8", "surrogateescape") + b" ;"
    return re.sub(rb"(?m)^DESIGN .*;", lambda _m: line, text, count=1)


def set_diearea(text: bytes, box: str) -> bytes:
    line = b"DIEAREA " + box.encode() + b" ;"
    return re.sub(rb"(?m)^DIEAREA .*;", lambda _m: line, text, count=1)


def die_variants(text: bytes) -> list[tuple[str, bytes]]:
    m = re.search(rb"DIEAREA \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", text)
    assert m is not None
    x1, y1, x2, y2 = (int(v) for v in m.groups())
    boxes = {
        "zero width": f"( {x1} {y1} ) ( {x1} {y2} )",
        "zero height": f"( {x1} {y1} ) ( {x2} {y1} )",
        "zero both": f"( {x1} {y1} ) ( {x1} {y1} )",
        "inverted": f"( {x2} {y2} ) ( {x1} {y1} )",
        "inverted x": f"( {x2} {y1} ) ( {x1} {y2} )",
        "inverted y": f"( {x1} {y2} ) ( {x2} {y1} )",
        "one point": f"( {x1} {y1} )",
        "tiny": f"( {x1} {y1} ) ( {x1 + 1} {y1 + 1} )",
        "shifted away": f"( {x2 * 10} {y2 * 10} ) ( {x2 * 11} {y2 * 11} )",
        "huge": "( -2147483648 -2147483648 ) ( 2147483647 2147483647 )",
        "polygon flat": f"( {x1} {y1} ) ( {x2} {y1} ) ( {x1} {y1} )",
        "missing": "",
    }
    out = []
    for name, box in boxes.items():
        t = set_diearea(text, box) if box else re.sub(rb"(?m)^DIEAREA .*;\n", b"", text, count=1)
        out.append((name, t))
    return out


def structural_variants(rng: random.Random, files: dict[str, bytes]) -> str:
    """Grid and technology extremes that parse but stress the router: GCell grids of one line,
    huge or tiny steps, grids outside the die, tracks of one line or outside the die, pitches,
    widths and spacings far too large or small, a database unit of 1."""
    d, lef = files["d.def"].decode(), files["d.lef"].decode()
    m = re.search(r"DIEAREA \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", d)
    w = int(m.group(3)) if m else 10000

    def gcell(rep: str) -> str:
        return re.sub(r"(?m)^GCELLGRID.*\n", "", d).replace("COMPONENTS", rep + "COMPONENTS", 1)

    variants = {
        "gcell one line": lambda: gcell("GCELLGRID X 0 DO 1 STEP 100 ;\nGCELLGRID Y 0 DO 1 STEP 100 ;\n"),
        "gcell huge step": lambda: gcell("GCELLGRID X 0 DO 2 STEP 100000000 ;\nGCELLGRID Y 0 DO 2 STEP 100000000 ;\n"),
        "gcell step 1": lambda: gcell(f"GCELLGRID X 0 DO {w + 1} STEP 1 ;\nGCELLGRID Y 0 DO {w + 1} STEP 1 ;\n"),
        "gcell outside": lambda: gcell("GCELLGRID X 90000000 DO 3 STEP 3000 ;\nGCELLGRID Y 90000000 DO 3 STEP 3000 ;\n"),
        "gcell x only": lambda: gcell("GCELLGRID X 0 DO 5 STEP 3000 ;\n"),
        "no gcell": lambda: gcell(""),
        "no tracks": lambda: re.sub(r"(?m)^TRACKS.*\n", "", d),
        "tracks count 1": lambda: re.sub(r"(TRACKS [XY] -?\d+) DO \d+", r"\1 DO 1", d),
        "tracks outside": lambda: re.sub(r"(TRACKS [XY]) -?\d+", r"\1 90000000", d),
        "tracks step 1": lambda: re.sub(r"(TRACKS [XY] -?\d+) DO \d+ STEP \d+", rf"\1 DO {w} STEP 1", d),
        "no nets": lambda: re.sub(r"(?s)\nNETS \d+ ;.*END NETS", "\nNETS 0 ;\nEND NETS", d),
        "no components": lambda: re.sub(r"(?s)\nCOMPONENTS \d+ ;.*?END COMPONENTS", "\nCOMPONENTS 0 ;\nEND COMPONENTS", d),
    }
    lef_variants = {
        "pitch huge": lambda: re.sub(r"PITCH [\d.]+", "PITCH 900000", lef, count=1),
        "pitch tiny": lambda: re.sub(r"PITCH [\d.]+", "PITCH 0.0005", lef),
        "width huge": lambda: re.sub(r"WIDTH [\d.]+ ;", "WIDTH 900000 ;", lef, count=1),
        "spacing huge": lambda: re.sub(r"SPACING [\d.]+ ;", "SPACING 900000 ;", lef, count=1),
        "area huge": lambda: re.sub(r"AREA [\d.]+ ;", "AREA 1e12 ;", lef, count=1),
        "no vias": lambda: re.sub(r"(?s)\nVIA .*?\nEND \S+", "", lef),
        "dbu 1": lambda: re.sub(r"DATABASE MICRONS \d+", "DATABASE MICRONS 1", lef),
    }
    name = rng.choice(sorted(variants) + sorted(lef_variants))
    if name in variants:
        files["d.def"] = variants[name]().encode()
    else:
        files["d.lef"] = lef_variants[name]().encode()
        if name == "dbu 1":
            files["d.def"] = re.sub(r"MICRONS \d+", "MICRONS 1", d).encode()
    return name


def guide_variants(rng: random.Random, guide: bytes) -> tuple[str, bytes]:
    lines = guide.split(b"\n")
    rect_lines = [i for i, ln in enumerate(lines) if len(ln.split()) == 5]
    if not rect_lines:
        return "none", guide
    i = rng.choice(rect_lines)
    x1, y1, x2, y2, layer = lines[i].split()
    op = rng.choice(["inverted", "zero", "outside", "partly", "unknown layer", "cut layer", "unknown net", "empty"])
    if op == "inverted":
        lines[i] = b" ".join([x2, y2, x1, y1, layer])
    elif op == "zero":
        lines[i] = b" ".join([x1, y1, x1, y2, layer])
    elif op == "outside":
        lines[i] = b" ".join([b"90000000", b"90000000", b"90001000", b"90001000", layer])
    elif op == "partly":
        lines[i] = b" ".join([b"-5000", y1, x2, y2, layer])
    elif op == "unknown layer":
        lines[i] = b" ".join([x1, y1, x2, y2, b"Metal99"])
    elif op == "cut layer":
        lines[i] = b" ".join([x1, y1, x2, y2, b"V1"])
    elif op == "unknown net":
        lines[0] = b"no_such_net"
    else:
        return "guide empty", b""
    return f"guide {op}", b"\n".join(lines)


YAML_SNIPPETS = [
    "base: &b {region_size: 3}\nregion:\n  <<: *b\n",
    "region: !custom {region_size: 3}\n",
    "router: !!python/name:os.system\n",
    "router: !!python/object/apply:os.system ['echo hi']\n",
    "policy: {seed: !!binary aGVsbG8=}\n",
    "a: " + "[" * 5000 + "]" * 5000 + "\n",
    "a: " + "{b: " * 3000 + "1" + "}" * 3000 + "\n",
    "region: {region_size: 2147483648}\n",
    "router: {iteration_count: 99999999999999999999}\n",
    "router: {thread_count: -1}\n",
    "policy: {seed: -1}\n",
    "policy: {call_timeout: nan}\n",
    "region: {region_size: 1e3}\n",
    "region: {region_size: .inf}\n",
    "router: {iteration_schedule: [{region_size: 99999999999999999999, offset: 0}]}\n",
    "router: {iteration_schedule: [{region_size: 5, offset: 7}]}\n",
    "output: {out_dir: 2020-13-45}\n",
    "region: {region_size: 2020-01-01}\n",
    "a: &a [x, x, x, x, x, x, x, x, x]\nb: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\nc: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\n"
    "d: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c]\ne: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d]\n"
    "f: [*e, *e, *e, *e, *e, *e, *e, *e, *e]\n",
    "--- {}\n--- {}\n",
    "\xff\xfe",
    "region: [1, 2\n",
    ": : :\n",
    "? [a, b]\n: c\n",
    "region:\n  region_size: 3\n  region_size: 4\n",
    "policy: {policy: /dev/zero}\n",
    "output: {out_dir: ../escaped_out}\n",
    "output: {mode: 7}\n",
    "testcase: {testcase_name: ../../etc}\n",
]

FLAG_CASES = [
    ["--region-size", "2147483648"], ["--region-size", "-1"], ["--region-size", "0"], ["--region-size", "1e3"],
    ["--region-size", "99999999999999999999"], ["--schedule", "99999999999999999999:0"], ["--schedule", ":"],
    ["--schedule", "5:-1"], ["--schedule", ""], ["--schedule", "1:0," * 2000 + "1:0"], ["--schedule", "0:0"],
    ["--threads", "100000"], ["--threads", "-3"], ["--seed", "-1"], ["--seed", "18446744073709551616"],
    ["--iterations", "0"], ["--iterations", "99999999999999999999"], ["--iterations", "1.5"],
    ["--policy", ""], ["--policy", "/dev/null"], ["--policy", "/"], ["--policy", "x.onnx"], ["--policy", "\x01"],
    ["--config", "/dev/null"], ["--config", "/"], ["--config", "{in}/missing.yaml"],
    ["--out", "/dev/null/x"], ["--out", ""], ["--threads", "2", "--iterations", "1"],
]


def base_files(rng: random.Random) -> tuple[dict[str, bytes], str]:
    """A clean input set: the demo (most cases) or the tiny drawn design."""
    if rng.random() < 0.7:
        return ({"d.lef": (DEMO / "demo.lef").read_bytes(), "d.def": (DEMO / "demo.def").read_bytes(),
                 "d.guide": (DEMO / "demo.guide").read_bytes()}, "demo")
    return {"d.lef": TINY_LEF.encode(), "d.def": TINY_DEF.encode(), "d.guide": TINY_GUIDE.encode()}, "tiny"


def design_args(files: dict[str, bytes], guide: bool) -> list[str]:
    args = ["--lef", "{in}/d.lef", "--def", "{in}/d.def"]
    return args + (["--guide", "{in}/d.guide"] if guide and "d.guide" in files else [])


def route_args(extra: list[str] | None = None) -> list[str]:
    return ["--out", "{out}", "--iterations", "1", "--quiet", *(extra or [])]


def make_case(rng: random.Random, route_share: float) -> Case:
    files, src = base_files(rng)
    command = "route" if rng.random() < route_share else "info"
    guide = rng.random() < 0.8
    r = rng.random()
    if r < 0.22:
        target = rng.choice(["d.lef", "d.def", "d.guide"])
        files[target] = mutate_numbers(rng, files[target], rng.randint(1, 3))
        kind = f"numbers in {target[2:]}"
        guide = guide or target == "d.guide"
    elif r < 0.36:
        target = rng.choice(["d.lef", "d.def", "d.guide"])
        files[target] = mutate_lines(rng, files[target])
        kind = f"lines in {target[2:]}"
        guide = guide or target == "d.guide"
    elif r < 0.48:
        target = rng.choice(["d.lef", "d.def", "d.guide"])
        files[target] = mutate_bytes(rng, files[target])
        kind = f"bytes in {target[2:]}"
        guide = guide or target == "d.guide"
    elif r < 0.53:
        target = rng.choice(["d.lef", "d.def", "d.guide"])
        files[target] = truncate(rng, files[target]) if rng.random() < 0.7 else b""
        kind = f"truncated {target[2:]}"
        guide = guide or target == "d.guide"
    elif r < 0.58:
        name, files["d.def"] = rng.choice(die_variants(files["d.def"]))
        kind = f"DIEAREA {name}"
    elif r < 0.63:
        kind = "structure " + structural_variants(rng, files)
        command = "route" if rng.random() < 0.7 else command
    elif r < 0.71:
        kind, files["d.guide"] = guide_variants(rng, files["d.guide"])
        guide = True
    elif r < 0.79:
        name = rng.choice(HOSTILE_NAMES)
        files["d.def"] = set_design_name(files["d.def"], name)
        kind = f"DESIGN {name[:20]!r}"
        command = "route"
    elif r < 0.87:
        snippet = rng.choice(YAML_SNIPPETS)
        text = CONFIG.read_text() if rng.random() < 0.3 else ""
        files["c.yaml"] = (text + snippet).encode("utf-8", "surrogateescape") if "\xff" not in snippet else b"\xff\xfe"
        if rng.random() < 0.5 and text:
            files["c.yaml"] = mutate_lines(rng, mutate_numbers(rng, CONFIG.read_bytes(), 2))
        return Case("yaml", "route", files, [*design_args(files, True), "--config", "{in}/c.yaml", *route_args()],
                    note=src)
    elif r < 0.93:
        flags = [f for f in rng.choice(FLAG_CASES)]
        args = [*design_args(files, True), "--out", "{out}", "--quiet"]
        if "--iterations" not in flags:
            args += ["--iterations", "1"]
        if "--out" in flags:
            args = [a for a in args if a not in ("--out", "{out}")]
        return Case(f"flags {' '.join(flags)[:40]}", "route", files, args + flags, note=src)
    else:
        name = rng.choice(sorted(POLICIES))
        files[name] = POLICIES[name].encode("utf-8", "surrogateescape")
        files["c.yaml"] = b"policy: {call_timeout: 2}\n"
        return Case(f"policy {name}", "route", files,
                    [*design_args(files, True), "--config", "{in}/c.yaml", "--policy", "{in}/" + name, *route_args()],
                    note=src)
    args = design_args(files, guide)
    if command == "route":
        args += route_args()
    return Case(kind, command, files, args, note=src)


# ----------------------------------------------------------------------------- running
def snapshot(root: Path, skip: tuple[Path, ...]) -> dict[str, tuple[int, int]]:
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        d = Path(dirpath)
        if any(d == s or s in d.parents for s in skip):
            dirnames[:] = []
            continue
        for name in filenames + [n for n in dirnames if (d / n).is_symlink()]:
            p = d / name
            try:
                st = p.lstat()
            except OSError:
                continue
            out[str(p)] = (st.st_size, st.st_mtime_ns)
    return out


def run_process(cmd: list[str], cwd: Path, env: dict[str, str], timeout: float) -> tuple[int | None, str, str]:
    """(exit status, stdout, stderr) of ``cmd`` in a session of its own; the status is None when it ran
    past ``timeout`` (the whole session is killed then: a hang)."""
    proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    try:
        so, se = proc.communicate(timeout=timeout)
        rc: int | None = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        so, se = proc.communicate()
        rc = None
    return rc, so.decode("utf-8", "replace"), se.decode("utf-8", "replace")


def run_case(case: Case, timeout: float, python: str) -> tuple[Outcome, Path]:
    root = Path(tempfile.mkdtemp(prefix="xroute-mutate-"))
    inp, work = root / "in", root / "work"
    inp.mkdir()
    work.mkdir()
    out = work / "out"
    for name, data in case.files.items():
        data = data.replace(b"{root}", str(root).encode())
        (inp / name).write_bytes(data)
    args = [a.replace("{in}", str(inp)).replace("{out}", str(out)).replace("{root}", str(root)) for a in case.args]
    if "--out" in args and args.index("--out") + 1 < len(args):  # an odd --out flag: that is the output folder
        out = work / args[args.index("--out") + 1]
    before = snapshot(root, (out, inp))
    env = {**os.environ, "CI": "true", "PYTHONPATH": str(REPO), "COLUMNS": "200"}
    start = time.perf_counter()
    rc, so, se = run_process([python, "-m", "xroute", case.command, *args], work, env, timeout)
    o = Outcome(case, rc, time.perf_counter() - start, so, se)
    after = snapshot(root, (out, inp))
    escaped = sorted(set(after) - set(before)) + sorted(k for k in before if k in after and after[k] != before[k])
    if rc is None:
        o.verdict.append("hang")
    elif rc < 0 or rc >= 128:
        o.verdict.append("crash")
    if "Traceback (most recent call last)" in o.stdout + o.stderr:
        o.verdict.append("traceback")
    if escaped:
        o.verdict.append("escape")
        o.stderr += "\n[harness] written outside --out: " + ", ".join(escaped)
    if rc not in (0, 1, None) and not o.verdict:
        lines = o.stderr.strip().splitlines()
        if not (len(lines) == 1 and lines[0].startswith("error: ")):
            o.verdict.append("not-one-line")
    return o, root


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--route-share", type=float, default=0.3, help="share of file mutations run through route")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds before a case counts as a hang")
    ap.add_argument("--keep", type=Path, default=REPO / "build" / "mutate_cli", help="folder for failing cases")
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--json", type=Path, help="also write the counts as JSON here")
    args = ap.parse_args()

    rng = random.Random(args.seed)
    counts: dict[str, int] = {"cases": 0, "crash": 0, "traceback": 0, "hang": 0, "escape": 0, "not-one-line": 0}
    by_command: dict[str, int] = {}
    exit_codes: dict[str, int] = {}
    bad: list[Outcome] = []
    started = time.perf_counter()
    if args.keep.exists():
        shutil.rmtree(args.keep)
    for i in range(args.cases):
        case = make_case(rng, args.route_share)
        outcome, root = run_case(case, args.timeout, args.python)
        counts["cases"] += 1
        by_command[case.command] = by_command.get(case.command, 0) + 1
        exit_codes[str(outcome.rc)] = exit_codes.get(str(outcome.rc), 0) + 1
        for v in outcome.verdict:
            counts[v] += 1
        serious = [v for v in outcome.verdict if v != "not-one-line"]
        if outcome.verdict:
            dest = args.keep / f"{i:05d}-{'-'.join(outcome.verdict)}"
            dest.mkdir(parents=True, exist_ok=True)
            shutil.copytree(root / "in", dest / "in", dirs_exist_ok=True)
            (dest / "case.json").write_text(json.dumps(
                {"kind": case.kind, "command": case.command, "args": case.args, "rc": outcome.rc,
                 "verdict": outcome.verdict, "stderr": outcome.stderr[-4000:], "stdout": outcome.stdout[-2000:]},
                indent=2))
        if serious:
            bad.append(outcome)
            print(f"[{i}] {'/'.join(serious)}: {case.command} {case.kind} rc={outcome.rc} "
                  f"{outcome.stderr.strip().splitlines()[-1][:160] if outcome.stderr.strip() else ''}", flush=True)
        shutil.rmtree(root, ignore_errors=True)
    took = time.perf_counter() - started
    print(f"\n{counts['cases']} cases in {took:.0f} s ({', '.join(f'{k}: {v}' for k, v in sorted(by_command.items()))}); "
          f"exit codes {dict(sorted(exit_codes.items()))}")
    for k in ("crash", "traceback", "hang", "escape", "not-one-line"):
        print(f"  {k:13s} {counts[k]}")
    if args.json:
        args.json.write_text(json.dumps({"counts": counts, "by_command": by_command, "exit_codes": exit_codes,
                                         "seconds": round(took, 1), "seed": args.seed}, indent=2) + "\n")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
