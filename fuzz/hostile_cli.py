"""Hostile-use harness: special files, odd policies, numbers, deep JSON, names, kills.

    python fuzz/hostile_cli.py [--cases N] [--seed S] [--timeout 60] [--keep DIR] [--json FILE]

Each case runs `python -m xroute ...` as its own process in a fresh temporary folder (inputs in
``in/``, the command run from ``work/`` with every output under ``work/out``), drawn from seven
categories:

* ``special-input``: a FIFO, folder, socket or a link to /dev/null or /dev/zero where a config,
  policy, LEF/DEF/guide, routed DEF, metrics JSON, batch file or baseline is read;
* ``special-output``: one where report, global-route, batch --write-baseline, route or check
  writes a file (or its output folder), or /dev/null as the output;
* ``policy``: policy files (net order and schedule) that raise GeneratorExit, BaseException
  subclasses, SystemExit, exceptions whose ``__str__`` fails, or that call os.chdir or start a
  thread that never ends, at import or per call, with a relative ``--out``; also in a ``batch``
  of two jobs in two worker processes;
* ``yaml-number``: NaN, infinities and YAML 1.1 base-60 numbers in every numeric setting of
  route and batch files;
* ``deep-json``: metrics JSON (report, plot), baselines and job records nested up to 300,000 deep
  or holding the wrong types;
* ``names``: bytes that are not UTF-8 in output and input names; an ascii terminal;
* ``kill``: route, check or batch (a job's renames, or, its job resumed from a first batch, the
  summary set's) killed just before a random rename (XROUTE_TEST_KILL_AT), then run again: the
  set must be consistent (hashes agree, summary.json's too) and no leftover remain.

and the six categories of ``hostile_failures.py`` (what a failure tells the user: failing
policies of every form, ``--json`` with printing policies, ``~`` in configs, a full disk, DEFs
without preferred tracks, odd DEF values that must be warned).

Verdicts: crash (a signal other than the kill asked for), traceback, hang, escape (a file written
outside ``work/out``), replaced (a special file no longer special), not-one-line (a failing exit
without exactly one ``error:`` line; ``warning:`` lines aside), accepted (a non-finite or base-60
number that loaded, or an invalid input that did not fail), and inconsistent (after a kill and a
rerun: leftovers, or a manifest whose hashes disagree); those of ``hostile_failures.py`` besides.
Exit status 1 if any was seen.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import signal
import socket
import stat
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from mutate_cli import DEMO, REPO, run_process, snapshot  # noqa: E402 - the sibling harness's helpers
import hostile_failures  # noqa: E402 - the categories of what a failure tells the user

KINDS = ("fifo", "dir", "socket", "devnull", "devzero")
DEMO_ARGS = ["--lef", str(DEMO / "demo.lef"), "--def", str(DEMO / "demo.def")]
BATCH = "testcases: [demo]\nsettings:\n  - {name: one, iteration_count: 1}\n"


@dataclass
class Case:
    category: str
    label: str
    argv: list[str]  # {in}, {out}, {root} replaced
    files: dict[str, bytes] = field(default_factory=dict)  # in/<name>
    specials: dict[str, str] = field(default_factory=dict)  # path under the case root -> kind
    env: dict[str, str] = field(default_factory=dict)
    prefill: dict[str, bytes] = field(default_factory=dict)  # files under the case root before the run
    kill: bool = False  # a kill case: SIGKILL expected, then a rerun and the consistency check
    setup: list[list[str]] = field(default_factory=list)  # commands run first (no kill), e.g. a batch to resume
    must_refuse: bool = False  # the input is invalid: exit 2 expected
    extra: dict = field(default_factory=dict)  # what hostile_failures.judge checks (and how to set the case up)


def make(category: str, label: str, argv: list[str], files: dict[str, str | bytes], must_refuse: bool = False,
         extra: dict | None = None) -> Case:
    """A case of hostile_failures.py's categories (files as text or bytes)."""
    data = {k: v.encode() if isinstance(v, str) else v for k, v in files.items()}
    return Case(category, label, argv, data, must_refuse=must_refuse, extra=extra or {})


def make_special(path: Path, kind: str, held: list[socket.socket]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "dir":
        path.mkdir()
    elif kind == "socket":
        s = socket.socket(socket.AF_UNIX)
        s.bind(str(path))
        held.append(s)
    else:
        os.symlink("/dev/null" if kind == "devnull" else "/dev/zero", path)


def still_special(path: Path, kind: str) -> bool:
    try:
        mode = os.lstat(path).st_mode
    except OSError:
        return False
    return {"fifo": stat.S_ISFIFO, "dir": stat.S_ISDIR, "socket": stat.S_ISSOCK,
            "devnull": stat.S_ISLNK, "devzero": stat.S_ISLNK}[kind](mode)


# ----------------------------------------------------------------------------- the categories
def special_input(rng: random.Random, routed: dict[str, bytes]) -> Case:
    kind = rng.choice(KINDS)
    where = rng.choice(["config", "policy", "schedule", "lef", "def", "guide", "check-def", "metrics", "batch",
                        "baseline", "groute-def"])
    files: dict[str, bytes] = {}
    argv = {
        "config": ["route", "--config", "{in}/s.yaml", "--out", "{out}"],
        "policy": ["route", "--policy", "{in}/s.py", "--out", "{out}"],
        "schedule": ["route", "--schedule-policy", "{in}/s.py", "--out", "{out}"],
        "lef": ["info", "--lef", "{in}/s.lef", "--def", str(DEMO / "demo.def")],
        "def": ["info", "--lef", str(DEMO / "demo.lef"), "--def", "{in}/s.def"],
        "guide": ["info", *DEMO_ARGS, "--guide", "{in}/s.guide"],
        "check-def": ["check", "demo", "--def", "{in}/s.def", "--out", "{out}"],
        "metrics": ["report", "{in}/run", "--out", "{out}/r.html"],
        "batch": ["batch", "{in}/s.yaml", "--out", "{out}"],
        "baseline": ["batch", "{in}/b.yaml", "--out", "{out}"],
        "groute-def": ["global-route", "{in}/s.def", str(DEMO / "demo.lef"), "--out", "{out}/g.guide"],
    }[where]
    name = {"config": "s.yaml", "policy": "s.py", "schedule": "s.py", "lef": "s.lef", "batch": "s.yaml",
            "metrics": "run/demo.metrics.json", "baseline": "base.json"}.get(where, "s.def" if "def" in where else
                                                                            "s.guide")
    if where == "metrics":
        files.update({f"run/{n}": d for n, d in routed.items() if not n.endswith(".json")})
    if where == "baseline":
        files["b.yaml"] = (BATCH + "gates:\n  baseline: base.json\n").encode()
    return Case("special-input", f"{where} {kind}", argv, files, {f"in/{name}": kind}, must_refuse=True)


def special_output(rng: random.Random, routed: dict[str, bytes]) -> Case:
    kind = rng.choice(("fifo", "dir", "socket"))
    where = rng.choice(["report", "groute", "baseline", "route-file", "check-file", "route-folder", "devnull"])
    files = {f"run/{n}": d for n, d in routed.items()}
    if where == "report":
        return Case("special-output", f"report {kind}", ["report", "{in}/run", "--out", "{out}/s.html"], files,
                    {"work/out/s.html": kind}, must_refuse=True)
    if where == "groute":
        return Case("special-output", f"global-route {kind}", ["global-route", "demo", "--out", "{out}/s.guide"],
                    specials={"work/out/s.guide": kind}, must_refuse=True)
    if where == "baseline":
        files = {"b.yaml": BATCH.encode()}
        return Case("special-output", f"write-baseline {kind}",
                    ["batch", "{in}/b.yaml", "--out", "{out}/batch", "--write-baseline", "{out}/base.json"], files,
                    {"work/out/base.json": kind}, must_refuse=True)
    if where == "route-file":
        name = rng.choice(["demo.routed.def", "demo.metrics.json", "demo.drc.rpt"])
        return Case("special-output", f"route {name} {kind}", ["route", "--out", "{out}", "--quiet"],
                    specials={f"work/out/{name}": kind}, must_refuse=True)
    if where == "check-file":
        name = rng.choice(["demo.check.json", "demo.drc.rpt", "demo.lyrdb"])
        return Case("special-output", f"check {name} {kind}",
                    ["check", "demo", "--def", "{in}/run/demo.routed.def", "--out", "{out}", "--quiet"], files,
                    {f"work/out/{name}": kind}, must_refuse=True)
    if where == "route-folder":
        kind = rng.choice(("fifo", "socket", "devnull"))
        return Case("special-output", f"route folder {kind}", ["route", "--out", "{out}/o", "--quiet"],
                    specials={"work/out/o": kind}, must_refuse=True)
    cmd = rng.choice([["report", "{in}/run", "--out", "/dev/null"], ["global-route", "demo", "--out", "/dev/null"]])
    return Case("special-output", f"{cmd[0]} /dev/null", cmd, files, must_refuse=True)


RAISES = ["raise GeneratorExit('g')", "raise Boom('b')", "raise SystemExit({code})", "raise Bad()", "raise BadBase()",
          "raise NotText()", "raise ValueError('x\\n' * 500)", "raise StopIteration", "raise RecursionError('deep')"]
PRELUDE = ("import os, sys, threading, time\nclass Boom(BaseException): pass\n"
           "class Bad(Exception):\n    def __str__(self): raise RuntimeError('no')\n"
           "class BadBase(BaseException):\n    def __str__(self): raise BadBase()\n"
           "class NotText(Exception):\n    def __str__(self): return 5\n")
ACTIONS = ["os.chdir({elsewhere!r})", "os.chdir('/')",
           "threading.Thread(target=time.sleep, args=(3600,), daemon=False).start()",
           "threading.Thread(target=lambda: [os.chdir({elsewhere!r}) for _ in iter(int, 1)], daemon=True).start()"]


def policy_case(rng: random.Random, root_hint: str = "{root}/elsewhere") -> Case:
    where = rng.choice(["import", "order", "plan"])
    body = rng.choice(RAISES + ACTIONS).format(code=rng.choice(["0", "1", "None", "'text'", "300"]),
                                               elsewhere=root_hint)
    if where == "import":
        text = PRELUDE + body + "\ndef order(region, features):\n    return list(range(len(features)))\n"
    elif where == "order":
        text = PRELUDE + f"def order(region, features):\n    {body}\n    return list(range(len(features)))\n"
    else:
        text = PRELUDE + f"def plan(history, rule):\n    {body}\n    return None\n"
    if where != "plan" and rng.random() < 0.3:  # in a batch: the policy also runs in the pool's workers
        batch = "testcases: [demo]\npolicies: [{root}/in/p.py, heuristic]\nsettings:\n  - {name: one, iteration_count: 1}\n"
        return Case("policy", f"batch {where}: {body[:44]}", ["batch", "{in}/b.yaml", "--out", "out", "--quiet",
                                                             "--jobs", "2"], {"p.py": text.encode(), "b.yaml": batch.encode()})
    flag = "--schedule-policy" if where == "plan" else "--policy"
    return Case("policy", f"{where}: {body[:50]}", ["route", flag, "{in}/p.py", "--out", "out", "--quiet",
                                                    "--iterations", "2"], {"p.py": text.encode()})


YAML_KEYS = [("policy", "call_timeout"), ("policy", "seed"), ("cost", "via_weight"), ("cost", "wirelength_weight"),
             ("cost", "drv_weight"), ("region", "region_size"), ("router", "iteration_count"),
             ("router", "thread_count"), ("router", "repair_rounds"), ("policy", "search_budget")]
BAD_NUMBERS = [".nan", ".NaN", ".inf", "-.inf", ".Inf", "1:30", "-2:05:00", "1:30.5", "!!int 1:30", "!!float .nan",
               "!!float 1:30"]
ODD_NUMBERS = ["0x10", "1_0", "017", "1e400", "99999999999999999999999", "-0.0", "0o17", "2147483648"]


def yaml_number(rng: random.Random) -> Case:
    section, key = rng.choice(YAML_KEYS)
    bad = rng.random() < 0.75
    value = rng.choice(BAD_NUMBERS if bad else ODD_NUMBERS)
    if rng.random() < 0.3:  # in a batch file (base config values and gates)
        gate = rng.random() < 0.5
        text = BATCH + (f"gates:\n  max_wirelength_increase_pct: {value}\n" if gate else
                        f"base:\n  {section}:\n    {key}: {value}\n")
        argv = ["batch", "{in}/c.yaml", "--out", "{out}", "--quiet"]
    else:
        text = f"{section}:\n  {key}: {value}\n"
        argv = ["route", "--config", "{in}/c.yaml", "--out", "{out}", "--quiet", "--iterations", "1"]
    return Case("yaml-number", f"{argv[0]} {key}: {value}", argv, {"c.yaml": text.encode()}, must_refuse=bad)


def deep_json(rng: random.Random, routed: dict[str, bytes]) -> Case:
    depth = rng.choice([1000, 20000, 200000, 300000])
    open_, close = rng.choice([("[", "]"), ('{"a":', "}")])
    deep = (open_ * depth + "1" + close * depth).encode()
    metrics = json.loads(routed["demo.metrics.json"])
    if rng.random() < 0.5:
        data = deep
        label = f"deep {depth}"
    else:
        key = rng.choice(["final", "iterations", "settings", "inputs", "design", "run", "policy"])
        sub = rng.choice([None, 3, "x", [], {}, [1, "a"], float("nan"), 1e308, -1, 10**30])
        if key in ("final", "iterations") and isinstance(metrics.get(key), dict) and rng.random() < 0.5:
            inner = rng.choice(sorted(metrics[key]))
            metrics[key][inner] = sub
            label = f"{key}.{inner} = {sub!r}"
        else:
            metrics[key] = sub
            label = f"{key} = {sub!r}"
        data = json.dumps(metrics).encode()
    files = {f"run/{n}": d for n, d in routed.items()}
    target = rng.choice(["report", "plot", "baseline", "job"])
    if target == "baseline":
        files = {"b.yaml": (BATCH + "gates:\n  baseline: base.json\n").encode(), "base.json": data}
        return Case("deep-json", f"baseline {label}", ["batch", "{in}/b.yaml", "--out", "{out}", "--quiet"], files)
    if target == "job":
        return Case("deep-json", f"job.json {label}", ["batch", "{in}/b.yaml", "--out", "{out}", "--quiet"],
                    {"b.yaml": BATCH.encode()}, prefill={"work/out/jobs/demo__heuristic__one/job.json": data})
    files["run/demo.metrics.json"] = data
    argv = (["report", "{in}/run", "--out", "{out}/r.html"] if target == "report"
            else ["plot", "{in}/run", "--out", "{out}/p.svg"])
    return Case("deep-json", f"{target} {label}", argv, files)


def names(rng: random.Random, routed: dict[str, bytes]) -> Case:
    bad = os.fsdecode(b"n\xff\xfe")
    choice = rng.choice(["out", "config", "lef", "report", "groute", "ascii-info", "ascii-route", "ascii-check",
                         "c-locale"])
    files = {f"run/{n}": d for n, d in routed.items()}
    argv = {
        "out": ["route", "--out", "{out}/" + bad, "--quiet"],
        "config": ["route", "--config", "{in}/" + bad, "--out", "{out}"],
        "lef": ["info", "--lef", "{in}/" + bad, "--def", str(DEMO / "demo.def")],
        "report": ["report", "{in}/run", "--out", "{out}/" + bad],
        "groute": ["global-route", "demo", "--out", "{out}/" + bad],
        "ascii-info": ["info", "demo"],
        "ascii-route": ["route", "--out", "{out}"],
        "ascii-check": ["check", "demo", "--def", "{in}/run/demo.routed.def", "--out", "{out}"],
        "c-locale": ["info", "demo"],
    }[choice]
    env = {"PYTHONIOENCODING": "ascii"} if choice.startswith("ascii") else (
        {"LC_ALL": "C", "LANG": "C", "PYTHONIOENCODING": ""} if choice == "c-locale" else {})
    return Case("names", choice, argv, files, env=env)


def kill_case(rng: random.Random, routed: dict[str, bytes]) -> Case:
    command = rng.choice(["route", "check", "batch", "batch-summary"])
    # batch: the worker's renames (its job); batch-summary: the job resumed from a first batch, so the
    # batch process's own renames are the summary set's (4 staged, the note, 4 into place).
    at = rng.randint(1, {"route": 6, "check": 7, "batch": 9, "batch-summary": 10}[command])
    files = {f"run/{n}": d for n, d in routed.items()}
    batch = ["batch", "{in}/b.yaml", "--out", "{out}", "--quiet", "--jobs", "1"]
    argv = {"route": ["route", "--out", "{out}", "--quiet", "--policy", rng.choice(["random", "heuristic"])],
            "check": ["check", "demo", "--def", "{in}/run/demo.routed.def", "--out", "{out}", "--quiet"],
            "batch": batch + ["--force"], "batch-summary": batch}[command]
    files["b.yaml"] = BATCH.encode()
    return Case("kill", f"{command} at rename {at}", argv, files, env={"XROUTE_TEST_KILL_AT": str(at)}, kill=True,
                setup=[batch] if command == "batch-summary" else [])


CATEGORIES = {"special-input": (special_input, 3), "special-output": (special_output, 3),
              "policy": (lambda rng, routed: policy_case(rng), 3), "yaml-number": (lambda rng, routed: yaml_number(rng), 3),
              "deep-json": (deep_json, 2), "names": (names, 2), "kill": (kill_case, 2)}
CATEGORIES.update({name: ((lambda f: lambda rng, routed: f(rng, routed, make))(maker), weight)
                   for name, (maker, weight) in hostile_failures.categories().items()})


# ----------------------------------------------------------------------------- running and judging
def leftovers(out: Path) -> list[str]:
    return sorted(str(p.relative_to(out)) for p in out.rglob(".*")) if out.is_dir() else []


def sha256(path: Path) -> str:
    import hashlib

    return hashlib.sha256(path.read_bytes()).hexdigest()


def inconsistent_sets(out: Path) -> list[str]:
    """Manifests under ``out`` whose recorded hashes disagree with the files beside them."""
    bad = []
    for manifest, roles in ((".metrics.json", {"def": ".routed.def", "drc_report": ".drc.rpt"}),
                            (".check.json", {"drc_report": ".drc.rpt", "lyrdb": ".lyrdb"})):
        for m in out.rglob("*" + manifest):
            run = json.loads(m.read_text()).get("run") or {}
            stem = m.name[: -len(manifest)]
            for role, suffix in roles.items():
                f = m.with_name(stem + suffix)
                if f.is_file() and run.get("sha256", {}).get(role) != sha256(f):
                    bad.append(str(f.relative_to(out)))
    for m in out.rglob("summary.json"):  # a batch's summary set
        run = json.loads(m.read_text()).get("run") or {}
        for role, name in (("csv", "summary.csv"), ("md", "summary.md"), ("junit", "junit.xml")):
            f = m.with_name(name)
            if not f.is_file() or run.get("sha256", {}).get(role) != sha256(f):
                bad.append(str(f.relative_to(out)))
    return bad


def execute(argv: list[str], work: Path, env: dict[str, str], timeout: float) -> tuple[int | None, str, str]:
    full = {**os.environ, "CI": "true", "PYTHONPATH": str(REPO), "COLUMNS": "200", **env}
    full = {k: v for k, v in full.items() if v != ""}
    return run_process([sys.executable, "-m", "xroute", *argv], work, full, timeout)


def run_case(case: Case, timeout: float) -> tuple[list[str], str, Path]:
    root = Path(tempfile.mkdtemp(prefix="xroute-hostile-"))
    inp, work, out = root / "in", root / "work", root / "work" / "out"
    for d in (inp, work, out, root / "elsewhere", root / "home"):
        d.mkdir(parents=True, exist_ok=True)
    for name, data in case.files.items():
        dest = root / name if name.startswith("home/") else inp / name
        dest.parent.mkdir(parents=True, exist_ok=True)
        dest.write_bytes(data.replace(b"{root}", str(root).encode()))
    disk = case.extra.get("tmpfs_kb")
    if disk and not hostile_failures.mount_tmpfs(out, disk):
        shutil.rmtree(root, ignore_errors=True)
        return ["skipped"], "mount -t tmpfs failed (not root?)", root
    for name, data in case.prefill.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_bytes(data)
    held: list[socket.socket] = []
    for name, kind in case.specials.items():
        make_special(root / name, kind, held)
    def fill(args: list[str]) -> list[str]:
        return [a.replace("{in}", str(inp)).replace("{out}", str(out)).replace("{root}", str(root)) for a in args]

    argv = fill(case.argv)
    env = {**case.env, "HOME": str(root / "home")} if case.extra.get("home") else case.env
    for setup in case.setup:
        execute(fill(setup), work, {}, timeout)
    before_set = None
    if disk:  # the run once with room: the old set; then the disk filled
        execute(argv, work, env, timeout)
        before_set = hostile_failures.set_hashes(out)
        hostile_failures.fill(out, case.extra["free_kb"])
    before = snapshot(root, (out, inp, root / "home"))
    rc, so, se = execute(argv, work, env, timeout)
    verdict: list[str] = []
    text = so + se
    if rc is None:
        verdict.append("hang")
    elif (rc < 0 or rc >= 128) and not (case.kill and rc == -signal.SIGKILL):
        verdict.append("crash")
    if "Traceback (most recent call last)" in text:
        verdict.append("traceback")
    after = snapshot(root, (out, inp, root / "home"))
    escaped = sorted(set(after) - set(before)) + sorted(k for k in before if k in after and after[k] != before[k])
    if escaped:
        verdict.append("escape")
        se += "\n[harness] written outside the output folder: " + ", ".join(escaped)
    if any(not still_special(root / n, k) for n, k in case.specials.items()):
        verdict.append("replaced")
    if rc not in (0, 1, None) and not case.kill and not verdict:
        lines = [line for line in se.strip().splitlines() if not line.startswith("warning: ")]
        if case.category == "json-print":  # what the policy printed is on stderr too: the last line
            lines = lines[-1:]
        if not (len(lines) == 1 and lines[0].startswith("error: ")):
            verdict.append("not-one-line")
    if case.must_refuse and rc in (0, 1):
        verdict.append("accepted")
    verdict += hostile_failures.judge(case.extra, lambda a: fill([a])[0], rc, so, se, root, work, before_set, out)
    if disk:
        (out / "filler").unlink(missing_ok=True)
        hostile_failures.unmount(out)
    if case.category in ("policy", "policy-failure") and rc in (0, 1) and not (out / "demo.routed.def").is_file() \
            and not any(out.glob("jobs/*/demo.routed.def")):
        verdict.append("escape")  # a run that went well must have written into work/out
    if case.kill and not verdict:
        env = {k: v for k, v in case.env.items() if k != "XROUTE_TEST_KILL_AT"}
        rc2, so2, se2 = execute(argv, work, env, timeout)
        se += f"\n[harness] rerun rc={rc2}: {se2.strip()[-400:]}"
        if rc2 not in (0, 1) or leftovers(out) or inconsistent_sets(out):
            verdict.append("inconsistent")
            se += f"\n[harness] leftovers {leftovers(out)}, mismatched {inconsistent_sets(out)}"
    for s in held:
        s.close()
    return verdict, f"rc={rc}\n--- stdout\n{so[-2000:]}\n--- stderr\n{se[-4000:]}", root


def routed_demo() -> dict[str, bytes]:
    """The demo routed once: the routed DEF, DRC report and metrics JSON that cases start from."""
    folder = Path(tempfile.mkdtemp(prefix="xroute-hostile-demo-"))
    rc, _, se = execute(["route", "--out", str(folder), "--quiet"], folder, {}, 300)
    if rc != 0:
        raise SystemExit(f"routing the demo failed: {se}")
    files = {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}
    shutil.rmtree(folder, ignore_errors=True)
    return files


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds before a case counts as a hang")
    ap.add_argument("--keep", type=Path, default=REPO / "build" / "hostile_cli", help="folder for failing cases")
    ap.add_argument("--only", choices=sorted(CATEGORIES), help="one category only")
    ap.add_argument("--json", type=Path, help="also write the counts as JSON here")
    ap.add_argument("--seconds", type=float, default=0, help="stop starting cases after this long (0: no limit)")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    routed = routed_demo()
    names_, weights = zip(*((n, w) for n, (_, w) in CATEGORIES.items() if args.only in (None, n)))
    verdicts = ("crash", "traceback", "hang", "escape", "replaced", "not-one-line", "accepted", "inconsistent",
                "no-file", "not-json", "fatal", "lib-log", "silent", "tilde", "disk")
    counts = {n: dict.fromkeys(("cases", *verdicts), 0) for n in names_}
    if args.keep.exists():
        shutil.rmtree(args.keep)
    started, failures, ran = time.perf_counter(), 0, 0
    exits: dict[str, dict[str, int]] = {}
    for i in range(args.cases):
        if args.seconds and time.perf_counter() - started > args.seconds:
            break
        ran += 1
        category = rng.choices(names_, weights)[0]
        case = CATEGORIES[category][0](rng, routed)
        verdict, log, root = run_case(case, args.timeout)
        if verdict == ["skipped"]:
            print(f"[{i}] skipped: {category}: {log}", flush=True)
            continue
        counts[category]["cases"] += 1
        status = log.split("\n", 1)[0]  # "rc=N": the exit statuses per category (in --json's counts)
        exits.setdefault(category, {})[status] = exits.setdefault(category, {}).get(status, 0) + 1
        for v in verdict:
            counts[category][v] += 1
        if verdict:
            failures += 1
            print(f"[{i}] {'/'.join(verdict)}: {category}: {case.label}", flush=True)
            dest = args.keep / f"{i:05d}-{category}"
            dest.mkdir(parents=True, exist_ok=True)
            (dest / "case.txt").write_text(f"{case.label}\n{case.argv}\n{case.env}\n{log}\n", errors="replace")
        shutil.rmtree(root, ignore_errors=True)
    took = time.perf_counter() - started
    print(f"\n{ran} cases in {took:.0f} s (seed {args.seed})")
    print(f"{'category':15s} " + " ".join(f"{h[:8]:>8s}" for h in ("cases", *verdicts)))
    for n, c in counts.items():
        print(f"{n:15s} " + " ".join(f"{c[h]:>8d}" for h in ("cases", *verdicts)))
    if args.json:
        args.json.write_text(json.dumps({"seed": args.seed, "seconds": round(took, 1), "counts": counts,
                                         "exit_statuses": exits}, indent=2) + "\n")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
