"""Two more CLI mutators (hostile use), judged as ``mutate_cli.py`` judges its cases.

    python fuzz/mutate_hostile.py check    [--cases N] [--seconds T] [--seed S] [--timeout 60] [--keep DIR]
    python fuzz/mutate_hostile.py extremes [--cases N] [--seed S] [--route-share 0.5] ...

* ``check``: the demo routed once (``xroute route``), then its NETS section mutated and given to
  ``xroute check``: a routing line repeated up to 200,000 times, up to 50,000 overlapping copies
  of a wire (often the longest) shifted across it or along it, numbers of the routing replaced by values at the ends of int32 or of the engine's range
  (2^28 - 1), patches and vias at those values, lines dropped, duplicated or swapped.
* ``extremes``: the demo's or the tiny design's LEF, DEF or guide with one to three numbers set to
  such values (for the LEF also in microns, so that they reach them once converted), or a
  component placed near +-(2^28 - 1) in any orientation, its macro given an OBS reaching beyond
  its SIZE; given to ``xroute info`` or ``xroute route``.

Each case runs in a fresh folder as its own process; a crash (signal), a traceback, a hang, a
write outside ``--out``, or a failing exit without exactly one ``error:`` line is counted. Prints
the counts and the slowest case; exit status 1 on a crash, traceback, hang or escape.
"""

from __future__ import annotations

import argparse
import importlib.util
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

_spec = importlib.util.spec_from_file_location("xroute_mutate_cli", Path(__file__).with_name("mutate_cli.py"))
assert _spec is not None and _spec.loader is not None
base = importlib.util.module_from_spec(_spec)
sys.modules["xroute_mutate_cli"] = base
_spec.loader.exec_module(base)

LIMIT = 2**28 - 1
# DBU values at the ends of int32 and of the engine's range, and a few between.
EXTREME_DBU = [2**31 - 1, -(2**31), 2**31, -(2**31) - 1, 2**32, LIMIT, -LIMIT, LIMIT + 1, -LIMIT - 1, 2**30,
               -(2**30), 2**29, 10**9, -(10**9), 2147483000, -2147483000, 0]
NUM = re.compile(rb"(?<![A-Za-z_0-9.])-?\d+(?:\.\d+)?")


def extreme(rng: random.Random, microns: bool) -> bytes:
    v = rng.choice(EXTREME_DBU)
    if microns and rng.random() < 0.7:  # the demo's LEF is at 2,000 DBU per micron, the tiny one at 1,000
        return f"{v / rng.choice([2000, 1000]):.4f}".encode()
    return str(v).encode()


def set_numbers(rng: random.Random, text: bytes, k: int, microns: bool, lo: int = 0, hi: int | None = None) -> bytes:
    """``k`` numbers of ``text[lo:hi]`` replaced by extreme values."""
    hi = len(text) if hi is None else hi
    spans = [m.span() for m in NUM.finditer(text, lo, hi)]
    for a, b in sorted(rng.sample(spans, min(k, len(spans))), reverse=True):
        text = text[:a] + extreme(rng, microns) + text[b:]
    return text


def routed_demo(python: str) -> bytes:
    with tempfile.TemporaryDirectory(prefix="xroute-hostile-") as tmp:
        subprocess.run([python, "-m", "xroute", "route", "--out", tmp, "--quiet"], check=True,
                       env={**base.os.environ, "PYTHONPATH": str(base.REPO)}, stdout=subprocess.DEVNULL)
        return (Path(tmp) / "demo.routed.def").read_bytes()


def wire_length(m: re.Match) -> int:
    pts = re.findall(rb"\( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", m.group(0))
    return abs(int(pts[0][2]) - int(pts[0][0])) + abs(int(pts[0][3]) - int(pts[0][1])) if pts else 0


def mutate_routing(rng: random.Random, routed: bytes) -> tuple[str, bytes]:
    """One hostile change inside the NETS section of a routed DEF."""
    lo, hi = routed.index(b"\nNETS "), routed.index(b"\nEND NETS")
    paths = [m for m in re.finditer(rb"\n    NEW [^\n]*|\n  \+ ROUTED [^\n]*", routed[lo:hi])]
    m = rng.choice(paths) if rng.random() < 0.7 else max(paths, key=wire_length)  # the longest wire: the worst band
    at = lo + m.end()
    line = m.group(0).replace(b"+ ROUTED", b"  NEW")
    r = rng.random()
    if r < 0.25:
        copies = rng.choice([10, 1000, 20000, 50000, 200000])
        return f"repeat x{copies}", routed[:at] + line * copies + routed[at:]
    if r < 0.4:
        pts = re.findall(rb"\( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", line)
        if pts:
            x1, y1, x2, y2 = map(int, pts[0])
            layer = line.split()[1]
            step, n = rng.choice([1, 3, 17]), rng.choice([100, 5000, 50000])
            across = rng.random() < 0.5  # overlapping into a band as wide as n * step, or along the wire
            dx, dy = (step, 0) if (y1 == y2) != across else (0, step)
            extra = b"".join(b"\n    NEW %s ( %d %d ) ( %d %d )" % (layer, x1 + i * dx, y1 + i * dy, x2 + i * dx, y2 + i * dy)
                             for i in range(n))
            return f"shifted {'across' if across else 'along'} x{n}", routed[:at] + extra + routed[at:]
    if r < 0.65:
        return "extreme numbers", set_numbers(rng, routed, rng.randint(1, 3), False, lo, hi)
    if r < 0.8:
        layer = rng.choice([b"Metal1", b"Metal2", b"Metal3"])
        a, b = extreme(rng, False), extreme(rng, False)
        shape = rng.choice([b"RECT ( 0 0 %s %s )" % (a, b), b"VIA12", b"VIA23", b"( %s %s )" % (a, b)])
        extra = b"\n    NEW %s ( %s %s ) %s" % (layer, extreme(rng, False), extreme(rng, False), shape)
        return "extreme shape", routed[:at] + extra + routed[at:]
    section = base.mutate_lines(rng, routed[lo:hi])
    return "lines", routed[:lo] + section + routed[hi:]


def check_case(rng: random.Random, routed: bytes) -> base.Case:
    kind, data = mutate_routing(rng, routed)
    files = {"d.lef": (base.DEMO / "demo.lef").read_bytes(), "r.def": data, "d.guide": (base.DEMO / "demo.guide").read_bytes()}
    args = ["--lef", "{in}/d.lef", "--def", "{in}/r.def", "--out", "{out}", "--quiet"]
    if rng.random() < 0.7:
        args += ["--guide", "{in}/d.guide"]
    return base.Case(kind, "check", files, args)


ORIENTS = [b"N", b"S", b"E", b"W", b"FN", b"FS", b"FE", b"FW"]
COMPONENT = re.compile(rb"- (\S+) (\S+) \+ (PLACED|FIXED) \( (-?\d+) (-?\d+) \) (\w+)")


def macro_near_bound(rng: random.Random, files: dict[str, bytes]) -> str:
    """One component placed near +-(2^28 - 1) in x or y with any orientation, its macro given (most
    times) a pin or OBS rect reaching up to 20 um beyond its SIZE on some side."""
    comps = list(COMPONENT.finditer(files["d.def"]))
    m = rng.choice(comps)
    macro = m.group(2)
    x, y = int(m.group(4)), int(m.group(5))
    far = rng.choice([1, -1]) * (LIMIT - rng.choice([0, 500, 3000, 12000, 40000, 100000]))
    x, y = (far, y) if rng.random() < 0.5 else (x, far)
    orient = rng.choice(ORIENTS)
    line = b"- %s %s + %s ( %d %d ) %s" % (m.group(1), macro, m.group(3), x, y, orient)
    files["d.def"] = files["d.def"][:m.start()] + line + files["d.def"][m.end():]
    label = f"{macro.decode(errors='replace')} at ({x} {y}) {orient.decode()}"
    end = files["d.lef"].find(b"\nEND " + macro + b"\n")
    if end >= 0 and rng.random() < 0.8:
        a, b = rng.uniform(-20, 0), rng.uniform(0, 20)
        rect = rng.choice([b"%.3f 0 0 0.1" % a, b"0 0 %.3f 0.1" % b, b"0 %.3f 0.1 0" % a, b"0 0 0.1 %.3f" % b])
        layer = re.search(rb"LAYER (\S+) ;", files["d.lef"][files["d.lef"].rfind(b"\nMACRO ", 0, end):end])
        if layer:
            obs = b"\n  OBS\n    LAYER %s ;\n      RECT %s ;\n  END" % (layer.group(1), rect)
            files["d.lef"] = files["d.lef"][:end] + obs + files["d.lef"][end:]
            label += f", OBS RECT {rect.decode()}"
    return label


def extremes_case(rng: random.Random, route_share: float) -> base.Case:
    files, src = base.base_files(rng)
    if rng.random() < 0.25:
        label = macro_near_bound(rng, files)
        command = "route" if rng.random() < route_share else "info"
        args = base.design_args(files, True) + (base.route_args() if command == "route" else [])
        return base.Case(f"macro near the bound: {label}", command, files, args, note=src)
    target = rng.choice(["d.lef", "d.def", "d.def", "d.guide"])
    files[target] = set_numbers(rng, files[target], rng.randint(1, 3), target == "d.lef")
    command = "route" if rng.random() < route_share else "info"
    args = base.design_args(files, True) + (base.route_args() if command == "route" else [])
    return base.Case(f"extremes in {target[2:]}", command, files, args, note=src)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mode", choices=["check", "extremes"])
    ap.add_argument("--cases", type=int, default=100)
    ap.add_argument("--seconds", type=float, default=0, help="stop starting cases after this long (0: no limit)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--route-share", type=float, default=0.5)
    ap.add_argument("--timeout", type=float, default=60.0)
    ap.add_argument("--keep", type=Path, default=base.REPO / "build" / "mutate_hostile")
    ap.add_argument("--python", default=sys.executable)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    routed = routed_demo(args.python) if args.mode == "check" else b""
    counts = dict.fromkeys(["crash", "traceback", "hang", "escape", "not-one-line"], 0)
    codes: dict[str, int] = {}
    slowest = (0.0, "")
    started = time.perf_counter()
    shutil.rmtree(args.keep, ignore_errors=True)
    done = 0
    for i in range(args.cases):
        if args.seconds and time.perf_counter() - started > args.seconds:
            break
        done += 1
        case = check_case(rng, routed) if args.mode == "check" else extremes_case(rng, args.route_share)
        outcome, root = base.run_case(case, args.timeout, args.python)
        codes[str(outcome.rc)] = codes.get(str(outcome.rc), 0) + 1
        slowest = max(slowest, (outcome.seconds, f"{case.command} {case.kind}"))
        for v in outcome.verdict:
            counts[v] += 1
        if outcome.verdict:
            dest = args.keep / f"{i:05d}-{'-'.join(outcome.verdict)}"
            shutil.copytree(root / "in", dest / "in", dirs_exist_ok=True)
            (dest / "case.txt").write_text(f"{case.command} {case.kind} {case.args}\nrc={outcome.rc}\n{outcome.stderr[-4000:]}")
            print(f"[{i}] {'/'.join(outcome.verdict)}: {case.command} {case.kind} rc={outcome.rc} "
                  f"{(outcome.stderr.strip().splitlines() or [''])[-1][:160]}", flush=True)
        shutil.rmtree(root, ignore_errors=True)
    print(f"{args.mode}: {done} cases in {time.perf_counter() - started:.0f} s, seed {args.seed}; "
          f"exit codes {dict(sorted(codes.items()))}; slowest {slowest[0]:.1f} s ({slowest[1]})")
    for k, v in counts.items():
        print(f"  {k:13s} {v}")
    return 1 if any(counts[k] for k in ("crash", "traceback", "hang", "escape")) else 0


if __name__ == "__main__":
    sys.exit(main())
