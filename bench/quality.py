"""The quality table: every testcase present routed by xroute and judged by `xroute check`, beside
the reference routes that are present (another router's routed DEFs, judged by the same check).

    python bench/quality.py [TESTCASE ...] [--threads 2] [--iterations N] [--policy P ...] [--markdown]
                            [--json-out FILE] [--note TEXT] [--readme README.md]
    python bench/quality.py --from-json FILE [--markdown] [--readme README.md]

For each testcase found on the search path (default: the demo and the seven contest testcases),
one fresh process per `--policy` (default: heuristic) runs `xroute route TESTCASE --threads T
--policy P --json` (the pipeline: built-in global routing when there is no guide); its wall time
and peak RSS come from the kernel (wait4). Then `xroute check` reads the routed DEF back with the
testcase's LEF and guide: opens, violations by type, wirelength, vias, off-track vias,
out-of-guide wire and the contest score before violations. Reference routes: `../shared/reference_routes/<name>.<router>.def.gz`, unpacked to a
temporary file and checked the same way (their wall time and memory are not ours to measure;
the reference folder's README has the figures its router reported).

Prints a table (markdown with --markdown) and one line per xroute row on the quality floors (0
violations and 0 opens, peak RSS, and the wirelength, vias and score floors of ispd18_test1,
ispd19_test1 and ispd19_test3): on standard output after the markdown table, on standard error
with the JSON. Exit status 0 whether or not a floor holds.

`--json-out FILE` also writes the results with how they were measured: the date, the machine
(cores, CPU model and memory from /proc), the load average before and after, the commit, the
settings and `--note` (say there whether other jobs were running). `--from-json FILE` reads such a
file instead of routing, and `--markdown` renders it: a line saying when, where and how it was
measured, the table and the floor lines. `--readme FILE` writes that rendering into FILE between
its two status-table markers (README.md's status table is made this way, never by hand):

    python bench/quality.py --threads 2 --json-out bench/results/quality.json --readme README.md
"""

from __future__ import annotations

import argparse
import gzip
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent
REFERENCES = REPO_ROOT.parent / "shared" / "reference_routes"
DEFAULT = ["demo", "ispd18_sample", "ispd18_sample2", "ispd18_sample3", "ispd19_sample4", "ispd18_test1",
           "ispd19_test1", "ispd19_test3"]


def run_with_rss(cmd: list[str]) -> tuple[subprocess.CompletedProcess, float, float]:
    """(the finished process, wall seconds, peak RSS MB) of ``cmd`` (xroute.route_process)."""
    from xroute.route_process import run_process

    run = run_process(cmd)
    return subprocess.CompletedProcess(cmd, run.returncode, run.stdout, run.stderr), run.wall_s, run.peak_rss_mb


def check(xroute: str, testcase: str, def_path: Path, out: Path) -> dict:
    proc = subprocess.run([xroute, "check", testcase, "--def", str(def_path), "--out", str(out), "--json"],
                          capture_output=True, text=True)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"xroute check {testcase} failed: {proc.stderr.strip()}")
    return json.loads(proc.stdout)


def row(name: str, router: str, doc: dict, wall: float | None, rss: float | None) -> dict:
    return {"testcase": name, "router": router, "wall_s": wall, "rss_mb": rss, "wl_um": doc["wirelength_um"],
            "vias": doc["vias"], "violations": doc["violations"], "by_type": doc["violations_by_type"],
            "opens": doc["opens"], "off_track_vias": doc["off_track_vias"],
            "out_of_guide_um": doc["out_of_guide_wirelength_um"], "score": doc["score"]}


def fmt(r: dict) -> list[str]:
    by = ", ".join(f"{k} {v:,}" for k, v in r["by_type"].items() if v)
    viol = f"{r['violations']:,}" + (f" ({by})" if by else "")
    wall = f"{r['wall_s']:.1f} s" if r["wall_s"] is not None else "—"
    rss = f"{r['rss_mb']:.0f} MB" if r["rss_mb"] is not None else "—"
    score = f"{r['score']:,.0f}" if r["score"] is not None else "—"
    oog = f"{r['out_of_guide_um']:,.0f}" if r["out_of_guide_um"] is not None else "—"
    return [r["testcase"], r["router"], f"{r['wl_um']:,.1f}", f"{r['vias']:,}", viol, str(r["opens"]),
            f"{r['off_track_vias']:,}", oog, score, wall, rss]


HEADER = ["testcase", "router", "WL µm", "vias", "violations", "opens", "off-track vias", "out-of-guide µm",
          "score", "wall", "peak RSS"]


# The quality floors: testcase -> (row field, largest value allowed). Every xroute row also needs 0
# violations, 0 opens and a peak RSS of MAX_RSS_MB at most.
FLOORS: dict[str, list[tuple[str, float]]] = {
    "ispd18_test1": [("score", 290_260), ("vias", 34_000)],
    "ispd19_test1": [("wl_um", 64_000), ("vias", 38_000)],
    "ispd19_test3": [("wl_um", 84_000)],
}
MAX_RSS_MB = 300
FLOOR_NAMES = {"violations": "violations", "opens": "opens", "rss_mb": "peak RSS MB", "score": "score",
               "vias": "vias", "wl_um": "WL µm"}


def floor_lines(rows: list[dict]) -> list[str]:
    """One line per xroute row (not the --policy rows, not the references): each floor, its value and
    whether it holds."""
    lines = []
    for r in rows:
        if r["router"] != "xroute":
            continue
        floors = [("violations", 0), ("opens", 0)] + FLOORS.get(r["testcase"], [])
        if r["rss_mb"] is not None:
            floors.append(("rss_mb", MAX_RSS_MB))
        parts = []
        for field, most in floors:
            value = r[field]
            if value is None:  # no score without a guide file
                parts.append(f"{FLOOR_NAMES[field]} unknown (floor {most:,})")
                continue
            shown = f"{value:,.1f}" if isinstance(value, float) and field != "score" else f"{value:,.0f}"
            parts.append(f"{FLOOR_NAMES[field]} {shown} <= {most:,}: {'holds' if value <= most else 'NOT MET'}")
        lines.append(f"{r['testcase']}: " + "; ".join(parts))
    return lines


def measure(names: list[str], policies: list[str], threads: int, iterations: int | None) -> list[dict]:
    """Route and check every testcase present, then check its reference routes: the table's rows."""
    xroute = shutil.which("xroute") or sys.exit("xroute is not installed (pip install .)")
    from xroute.errors import TestcaseNotFound
    from xroute.testcases import find_testcase

    rows = []
    with tempfile.TemporaryDirectory(prefix="quality_") as tmp:
        for name in names:
            try:
                find_testcase(name)
            except TestcaseNotFound:
                print(f"# {name}: not on the search path, skipped", file=sys.stderr)
                continue
            for k, policy in enumerate(policies):
                out = Path(tmp) / f"{name}-{k}"
                cmd = [xroute, "route", name, "--threads", str(threads), "--policy", policy, "--out", str(out),
                       "--json"]
                if iterations:
                    cmd += ["--iterations", str(iterations)]
                proc, wall, rss = run_with_rss(cmd)
                if proc.returncode not in (0, 1):
                    raise SystemExit(f"xroute route {name} --policy {policy} failed: {proc.stderr.strip()}")
                design = json.loads(proc.stdout)["design"]
                router = "xroute" if policy == "heuristic" else f"xroute --policy {policy}"
                doc = check(xroute, name, out / f"{design}.routed.def", out / "check")
                rows.append(row(name, router, doc, wall, rss))
                print(" | ".join(fmt(rows[-1])), file=sys.stderr)
            for ref in sorted(REFERENCES.glob(f"{name}.*.def.gz")):
                router = ref.name[len(name) + 1: -len(".def.gz")]
                plain = Path(tmp) / f"{name}.{router}.def"
                plain.write_bytes(gzip.decompress(ref.read_bytes()))
                rows.append(row(name, router, check(xroute, name, plain, Path(tmp) / f"{router}-check"), None, None))
                print(" | ".join(fmt(rows[-1])), file=sys.stderr)
    return rows


def _proc_field(path: str, key: str) -> str | None:
    """The value of the first ``key: value`` line of a /proc file, or None."""
    try:
        for line in Path(path).read_text().splitlines():
            name, _, value = line.partition(":")
            if name.strip() == key:
                return value.strip()
    except OSError:
        pass
    return None


def machine() -> dict:
    """The machine the figures were measured on: cores, CPU model, memory."""
    mem_kb = _proc_field("/proc/meminfo", "MemTotal")
    return {"cores": os.cpu_count(), "cpu": _proc_field("/proc/cpuinfo", "model name") or "unknown",
            "memory_gb": round(int(mem_kb.split()[0]) / 2**20) if mem_kb else None}


def commit() -> str:
    """The checkout's commit (short hash), with ``-dirty`` when tracked files differ from it."""
    def git(*a: str) -> subprocess.CompletedProcess:
        return subprocess.run(["git", "-C", str(REPO_ROOT), *a], capture_output=True, text=True)
    head = git("rev-parse", "--short=10", "HEAD")
    if head.returncode != 0:
        return "unknown"
    dirty = git("diff", "--quiet", "HEAD", "--").returncode != 0
    return head.stdout.strip() + ("-dirty" if dirty else "")


def caption(results: dict) -> str:
    """The line above the table: when, where and how it was measured."""
    m, s = results["machine"], results["settings"]
    loads = results["load_average"]
    memory = f", {m['memory_gb']} GB" if m.get("memory_gb") else ""
    iterations = f"up to {s['iterations']} iterations" if s["iterations"] else "the default iterations"
    note = f" {results['note']}" if results.get("note") else ""
    return (f"Measured {results['date']} at commit `{results['commit']}` on a machine of {m['cores']} cores "
            f"({m['cpu']}{memory}; load average {loads[0]:.2f} before, {loads[1]:.2f} after): "
            f"{s['threads']} threads, {iterations}, the defaults otherwise.{note}")


def render_markdown(results: dict) -> str:
    """The caption, the table and the floor lines of a results document, as Markdown."""
    lines = [caption(results), "", "| " + " | ".join(HEADER) + " |", "|" + "---|" * len(HEADER)]
    lines += ["| " + " | ".join(fmt(r)) + " |" for r in results["rows"]]
    lines += [""] + [f"- {line}" for line in floor_lines(results["rows"])]
    return "\n".join(lines) + "\n"


MARK_BEGIN = ("<!-- status table: generated by `python bench/quality.py --from-json bench/results/quality.json "
              "--markdown`; do not edit by hand -->")
MARK_END = "<!-- end of the generated status table -->"


def generated_block(text: str) -> str | None:
    """What lies between the two markers of a document (None without both)."""
    begin, end = text.find(MARK_BEGIN), text.find(MARK_END)
    if begin < 0 or end < begin:
        return None
    return text[begin + len(MARK_BEGIN) + 1:end]


def write_readme(path: Path, results: dict) -> None:
    """Replace the text between the markers of ``path`` with the rendering of ``results``."""
    text = path.read_text()
    old = generated_block(text)
    if old is None:
        raise SystemExit(f"{path}: no status-table markers ({MARK_BEGIN} ... {MARK_END})")
    begin = text.index(MARK_BEGIN) + len(MARK_BEGIN) + 1
    path.write_text(text[:begin] + render_markdown(results) + text[begin + len(old):])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("testcases", nargs="*", default=DEFAULT)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--iterations", type=int, default=None)
    ap.add_argument("--policy", action="append",
                    help="net-order policy of a row (repeatable; default heuristic); rows other than the heuristic's "
                         "are named 'xroute --policy P'")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--json-out", type=Path, help="also write the results and how they were measured to this file")
    ap.add_argument("--note", default="", help="a sentence on the conditions, kept in --json-out's file")
    ap.add_argument("--from-json", type=Path, help="render this results file instead of routing")
    ap.add_argument("--readme", type=Path, help="write the rendering between this file's status-table markers")
    args = ap.parse_args()
    if args.from_json:
        results = json.loads(args.from_json.read_text())
    else:
        policies = args.policy or ["heuristic"]
        start_load = os.getloadavg()[0]
        rows = measure(args.testcases, policies, args.threads, args.iterations)
        results = {"date": time.strftime("%Y-%m-%d", time.gmtime()), "machine": machine(), "commit": commit(),
                   "load_average": [round(start_load, 2), round(os.getloadavg()[0], 2)],
                   "settings": {"threads": args.threads, "iterations": args.iterations, "policies": policies},
                   "note": args.note, "rows": rows}
        if args.json_out:
            args.json_out.parent.mkdir(parents=True, exist_ok=True)
            tmp = args.json_out.with_name(args.json_out.name + ".tmp")
            tmp.write_text(json.dumps(results, indent=1, ensure_ascii=False) + "\n")
            tmp.replace(args.json_out)
    if args.readme:
        write_readme(args.readme, results)
    if args.markdown:
        print(render_markdown(results), end="")
    else:
        print(json.dumps(results["rows"], indent=2))
        for line in floor_lines(results["rows"]):
            print(line, file=sys.stderr)


if __name__ == "__main__":
    main()
