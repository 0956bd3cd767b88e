"""Read a corpus of public LEF/DEF pairs with `xroute info` and judge each outcome.

Usage:
    python bench/lefdef_corpus.py [MANIFEST] [--root DIR] [--timeout S] [--jobs N]
                                  [--only ID,ID] [--project P] [--json OUT]

MANIFEST defaults to $XROUTE_LEFDEF_CORPUS/manifest.tsv (else /work/corpus/manifest.tsv); file
paths in it are relative to --root, which defaults to the manifest's folder.

Manifest format: tab-separated, one pair per line, `#` starts a comment line, and a header line
whose first field is `id`. Columns:

    id       unique name of the pair (letters, digits, `-_.`)
    project  where the files come from (openroad, klayout, si2, caravel, orfs, ...)
    repo     the public repository (owner/name) the files were taken from
    commit   the repository commit the files were taken at
    def      the DEF file, relative to the corpus root (may end in .gz)
    lefs     the LEF files it needs, `;`-separated, in reading order: technology LEF first
    expect   `read`, or `refuse: <why the file is truly invalid LEF/DEF>`
    source   optional: the paths in the repository and the test script that pairs them

Each pair runs `python -m xroute info --json --lef L1 --lef L2 ... --def D` in its own process
with a time limit and gets one outcome:

    read            exit 0 and JSON on stdout
    refused-valid   exit 2 and a one-line error, but the pair is expected to be read (a failure)
    refused-invalid exit 2 on a pair expected to be refused (as it should)
    traceback       a Python traceback on stderr (a failure)
    crash           killed by a signal or any other exit status (a failure)
    hang            still running at the time limit (a failure)

For a read pair the figures of `info --json` (`counts`) are checked against an independent count
made by a small text scanner here: DEF entries (`- ` statements) of COMPONENTS, NETS,
SPECIALNETS, PINS and VIAS, DEF ROW statements, and the distinct names of the LEF's top-level
LAYER, VIA and MACRO definitions. A difference is a `mismatch` (a failure). A pair expected to be
refused but read is listed as a note, not a failure.

Prints a table per project and every failure with its error line; exits 1 if there is any
failure (so it serves as a check), 0 otherwise.
"""

from __future__ import annotations

import argparse
import collections
import concurrent.futures
import dataclasses
import gzip
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

OUTCOMES = ("read", "refused-valid", "refused-invalid", "traceback", "crash", "hang")
FAILURES = ("refused-valid", "traceback", "crash", "hang")
TOKEN = re.compile(r'"[^"]*"|#[^\n]*|[^\s;]+|;')

LEF_NAMED_BLOCKS = {"LAYER", "VIA", "VIARULE", "SITE", "MACRO", "NONDEFAULTRULE", "ARRAY"}
LEF_UNNAMED_BLOCKS = {"UNITS", "PROPERTYDEFINITIONS", "SPACING", "NOISETABLE",
                      "CORRECTIONTABLE", "IRDROP", "DIELECTRIC"}
DEF_SECTIONS = {"COMPONENTS": "components", "NETS": "nets", "SPECIALNETS": "special_nets",
                "PINS": "io_pins", "VIAS": "def_vias"}


@dataclasses.dataclass
class Pair:
    """One manifest line."""

    id: str
    project: str
    repo: str
    commit: str
    def_path: str
    lefs: list[str]
    expect: str
    source: str = ""

    @property
    def valid(self) -> bool:
        return self.expect.strip() == "read"


@dataclasses.dataclass
class Result:
    """What happened to one pair."""

    pair: Pair
    outcome: str
    error: str = ""
    mismatches: list[str] = dataclasses.field(default_factory=list)
    seconds: float = 0.0


def read_manifest(path: Path) -> list[Pair]:
    """Parse a manifest (see the module docstring)."""
    pairs = []
    for lineno, line in enumerate(path.read_text().splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        cols = line.split("\t")
        if cols[0] == "id":
            continue
        if len(cols) < 7:
            raise ValueError(f"{path}:{lineno}: expected 7 tab-separated columns, got {len(cols)}")
        lefs = [p for p in cols[5].split(";") if p]
        pairs.append(Pair(cols[0], cols[1], cols[2], cols[3], cols[4], lefs, cols[6],
                          cols[7] if len(cols) > 7 else ""))
    return pairs


def read_text(path: Path) -> str:
    """A file's text, gunzipped when its bytes start with the gzip magic."""
    data = path.read_bytes()
    if data[:2] == b"\x1f\x8b":
        data = gzip.decompress(data)
    return data.decode("latin-1")


def tokens(text: str) -> list[str]:
    """Whitespace tokens, `;` on its own, quoted strings whole, comments dropped."""
    return [t for t in TOKEN.findall(text) if not t.startswith("#")]


def _skip_statement(toks: list[str], i: int) -> int:
    while i < len(toks) and toks[i] != ";":
        i += 1
    return i + 1


def _skip_block(toks: list[str], i: int, name: str, upper: bool) -> int:
    """Index after `END name` (name compared upper-case when upper)."""
    while i < len(toks) - 1:
        if toks[i].upper() == "END":
            nxt = toks[i + 1].upper() if upper else toks[i + 1]
            if nxt == name:
                return i + 2
        i += 1
    return len(toks)


def _skip_macro(toks: list[str], i: int, name: str) -> int:
    """Index after `END name` of a MACRO, stepping over its PIN blocks (a pin may share the
    macro's name, or a later END's name)."""
    start = i
    while i < len(toks) - 1:
        tok = toks[i].upper()
        at_statement = i == start or toks[i - 1] == ";" or (i >= 2 and toks[i - 2].upper() == "END")
        if at_statement and tok == "PIN":
            i = _skip_block(toks, i + 2, toks[i + 1], upper=False)
            continue
        if tok == "END" and toks[i + 1] == name:
            return i + 2
        i += 1
    return len(toks)


def count_lef(text: str, names: dict[str, set[str]] | None = None) -> dict[str, set[str]]:
    """Distinct names of top-level LAYER, VIA and MACRO definitions, added into `names`."""
    names = names if names is not None else {"LAYER": set(), "VIA": set(), "MACRO": set()}
    toks = tokens(text)
    i = 0
    while i < len(toks):
        kw = toks[i].upper()
        if kw == "END" and i + 1 < len(toks) and toks[i + 1].upper() == "LIBRARY":
            break
        if kw in LEF_NAMED_BLOCKS and i + 1 < len(toks):
            name = toks[i + 1]
            if kw in names:
                names[kw].add(name)
            if kw == "MACRO":
                i = _skip_macro(toks, i + 2, name)
            else:
                i = _skip_block(toks, i + 2, name, upper=False)
        elif kw in LEF_UNNAMED_BLOCKS:
            i = _skip_block(toks, i + 1, kw, upper=True)
        elif kw == "BEGINEXT":
            while i < len(toks) and toks[i].upper() != "ENDEXT":
                i += 1
            i += 1
        else:
            i = _skip_statement(toks, i)
    return names


def count_def(text: str) -> dict[str, int]:
    """Entries of the DEF sections that `info` counts, and ROW statements."""
    counts = {key: 0 for key in DEF_SECTIONS.values()}
    counts["rows"] = 0
    toks = tokens(text)
    i = 0
    while i < len(toks):
        kw = toks[i].upper()
        if kw == "END" and i + 1 < len(toks) and toks[i + 1].upper() == "DESIGN":
            break
        if kw == "END":  # the end of a section this scanner does not count
            i += 2
            continue
        if kw == "PROPERTYDEFINITIONS":  # its `ROW name TYPE ;` lines define properties, not rows
            while i < len(toks) and not (toks[i].upper() == "END" and i + 1 < len(toks)
                                         and toks[i + 1].upper() == "PROPERTYDEFINITIONS"):
                i += 1
            i += 2
            continue
        if kw == "ROW":
            counts["rows"] += 1
        if kw in DEF_SECTIONS:
            i = _skip_statement(toks, i)
            start = True
            while i < len(toks):
                tok = toks[i]
                if tok.upper() == "END" and i + 1 < len(toks) and toks[i + 1].upper() == kw:
                    break
                if start and tok == "-":
                    counts[DEF_SECTIONS[kw]] += 1
                start = tok == ";"
                i += 1
            i += 2
        else:
            i = _skip_statement(toks, i)
    return counts


def independent_counts(root: Path, pair: Pair) -> dict[str, int]:
    """The scanner's figures for one pair, keyed like `info --json`'s `counts`."""
    names: dict[str, set[str]] = {"LAYER": set(), "VIA": set(), "MACRO": set()}
    for lef in pair.lefs:
        count_lef(read_text(root / lef), names)
    counts = count_def(read_text(root / pair.def_path))
    counts.update(layers=len(names["LAYER"]), lef_vias=len(names["VIA"]),
                  macros=len(names["MACRO"]))
    return counts


def compare(expected: dict[str, int], reported: dict[str, int]) -> list[str]:
    """`field: info N, scanner M` for each figure that differs."""
    return [f"{key}: info {reported.get(key)}, scanner {value}"
            for key, value in sorted(expected.items()) if reported.get(key) != value]


def run_pair(root: Path, pair: Pair, timeout: float) -> Result:
    """Run `xroute info --json` on one pair and classify what happened."""
    cmd = [sys.executable, "-m", "xroute", "info", "--json"]
    for lef in pair.lefs:
        cmd += ["--lef", str(root / lef)]
    cmd += ["--def", str(root / pair.def_path)]
    start = time.monotonic()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                              errors="replace")
    except subprocess.TimeoutExpired:
        return Result(pair, "hang", f"no answer in {timeout:g} s", seconds=timeout)
    seconds = time.monotonic() - start
    err_lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    last = err_lines[-1].strip() if err_lines else ""
    if "Traceback (most recent call last)" in proc.stderr:
        return Result(pair, "traceback", last, seconds=seconds)
    if proc.returncode == 2:
        outcome = "refused-invalid" if not pair.valid else "refused-valid"
        return Result(pair, outcome, " | ".join(ln.strip() for ln in err_lines[:3]),
                      seconds=seconds)
    if proc.returncode != 0:
        why = f"signal {-proc.returncode}" if proc.returncode < 0 else f"exit {proc.returncode}"
        return Result(pair, "crash", f"{why}: {last}", seconds=seconds)
    result = Result(pair, "read", seconds=seconds)
    try:
        reported = json.loads(proc.stdout)["counts"]
    except (ValueError, KeyError) as exc:
        result.mismatches = [f"no JSON counts on stdout ({exc})"]
        return result
    result.mismatches = compare(independent_counts(root, pair), reported)
    return result


def print_table(results: list[Result]) -> None:
    """Per-project counts of each outcome and of mismatches, then a total."""
    by_project: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
    for res in results:
        for key in (res.pair.project, "TOTAL"):
            by_project[key][res.outcome] += 1
            by_project[key]["pairs"] += 1
            by_project[key]["mismatch"] += bool(res.mismatches)
    cols = ("pairs",) + OUTCOMES + ("mismatch",)
    print("| project | " + " | ".join(cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    for project in sorted(by_project, key=lambda p: (p == "TOTAL", p)):
        row = by_project[project]
        print(f"| {project} | " + " | ".join(str(row[c]) for c in cols) + " |")


def print_failures(results: list[Result]) -> int:
    """Each failure with its error line; returns how many there were."""
    failures = [r for r in results if r.outcome in FAILURES or r.mismatches]
    if failures:
        print(f"\nFailures ({len(failures)}):")
    for res in failures:
        what = "; ".join(res.mismatches) if res.outcome == "read" else res.error
        print(f"  {res.pair.id} [{res.outcome}{', mismatch' if res.mismatches else ''}] {what}")
    notes = [r for r in results if r.outcome == "read" and not r.pair.valid]
    if notes:
        print(f"\nRead although expected to be refused ({len(notes)}):")
        for res in notes:
            print(f"  {res.pair.id}: {res.pair.expect}")
    return len(failures)


def main(argv: list[str] | None = None) -> int:
    env_root = os.environ.get("XROUTE_LEFDEF_CORPUS", "/work/corpus")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("manifest", nargs="?", type=Path,
                        default=Path(env_root) / "manifest.tsv")
    parser.add_argument("--root", type=Path, help="corpus root (default: the manifest's folder)")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per pair")
    parser.add_argument("--jobs", type=int, default=1, help="pairs run at once")
    parser.add_argument("--only", default="", help="comma-separated pair ids")
    parser.add_argument("--project", default="", help="only this project's pairs")
    parser.add_argument("--json", type=Path, help="write every result here as JSON")
    args = parser.parse_args(argv)
    root = args.root or args.manifest.parent
    pairs = read_manifest(args.manifest)
    if args.only:
        wanted = set(args.only.split(","))
        pairs = [p for p in pairs if p.id in wanted]
    if args.project:
        pairs = [p for p in pairs if p.project == args.project]
    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        results = list(pool.map(lambda p: run_pair(root, p, args.timeout), pairs))
    print_table(results)
    failed = print_failures(results)
    if args.json:
        args.json.write_text(json.dumps(
            [dict(id=r.pair.id, project=r.pair.project, outcome=r.outcome, error=r.error,
                  mismatches=r.mismatches, seconds=round(r.seconds, 3)) for r in results],
            indent=1) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
