"""Side by side: xroute and the other detailed routers on the same testcases, in one run.

    python bench/versus.py [TESTCASE ...] [--threads 2] [--markdown]

For each testcase (default: ispd18_test1 and ispd19_test1, contest guides), one fresh process per
router routes the testcase's LEF, DEF and guide with `--threads` threads, one after the other, and
its wall time and peak RSS come from the kernel (wait4). Every routed DEF is then judged by the same
`xroute check`: violations, opens, wirelength, vias and contest score.

The other routers run when they are installed:
- TritonRoute through OpenROAD: `openroad` on PATH or $XROUTE_OPENROAD (read_lef, read_def,
  read_guides, set_thread_count, detailed_route, write_def);
- the standalone TritonRoute binary: $XROUTE_TRITONROUTE (a parameter file with lef, def, guide,
  output and threads lines);
- Dr. CU: `ispd19dr` or `ispd18dr` on PATH or $XROUTE_DRCU
  (`-lef L -def D -guide G -output O -threads T`).
A router that is not installed gets a row of the figures recorded for it (measured
side by side on the same kind of 2-core machine, 2 threads, 2026-11; marked "recorded") instead,
and the ratio is taken against those.

Then the speed floors, each on a route with 0 violations and 0 opens: xroute's wall on
ispd19_test1 at most 0.5x TritonRoute's, and on ispd18_test1 at most Dr. CU's. Prints a table
(markdown with --markdown) and one line per floor; exit status 0 whether or not a floor holds.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from quality import HEADER, check, fmt, row, run_with_rss

DEFAULT = ["ispd18_test1", "ispd19_test1"]

# The recorded side-by-side table (2 threads on the 2-core machine, each routed DEF judged by
# `xroute check`): wall s, peak RSS MB, WL um, vias, violations, contest score.
RECORDED = {
    ("ispd18_test1", "TritonRoute"): (52.5, 599, 86_456, 35_455, 0, 304_962),
    ("ispd18_test1", "Dr. CU 2.0"): (17.9, 260, 86_717, 32_394, 1, 290_260),
    ("ispd19_test1", "TritonRoute"): (203.9, 625, 63_127, 37_074, 0, 433_163),
    ("ispd19_test1", "Dr. CU 2.0"): (274.6, 612, 64_195, 36_866, 135, 420_747),
}

# (testcase, other router, largest ratio of xroute's wall to its wall)
FLOORS = [("ispd19_test1", "TritonRoute", 0.5), ("ispd18_test1", "Dr. CU 2.0", 1.0)]


def installed(env: str, *names: str) -> str | None:
    if os.environ.get(env):
        return os.environ[env]
    return next((p for n in names if (p := shutil.which(n))), None)


def openroad_cmd(exe: str, tc, threads: int, out: Path) -> list[str]:
    script = out.with_suffix(".tcl")
    script.write_text(f"read_lef {tc.lef}\nread_def {tc.def_}\nread_guides {tc.guide}\n"
                      f"set_thread_count {threads}\ndetailed_route\nwrite_def {out}\nexit\n")
    return [exe, "-exit", str(script)]


def tritonroute_cmd(exe: str, tc, threads: int, out: Path) -> list[str]:
    params = out.with_suffix(".param")
    params.write_text(f"lef:{tc.lef}\ndef:{tc.def_}\nguide:{tc.guide}\noutput:{out}\nthreads:{threads}\n")
    return [exe, str(params)]


def drcu_cmd(exe: str, tc, threads: int, out: Path) -> list[str]:
    return [exe, "-lef", str(tc.lef), "-def", str(tc.def_), "-guide", str(tc.guide), "-output", str(out),
            "-threads", str(threads)]


def others() -> list[tuple[str, str | None, object]]:
    """(router, executable or None, command maker) per other router: OpenROAD's TritonRoute first."""
    tr = installed("XROUTE_OPENROAD", "openroad")
    make = openroad_cmd
    if tr is None and (tr := installed("XROUTE_TRITONROUTE")):
        make = tritonroute_cmd
    return [("TritonRoute", tr, make), ("Dr. CU 2.0", installed("XROUTE_DRCU", "ispd19dr", "ispd18dr"), drcu_cmd)]


def recorded_row(name: str, router: str) -> dict | None:
    fig = RECORDED.get((name, router))
    if fig is None:
        return None
    wall, rss, wl, vias, viol, score = fig
    return {"testcase": name, "router": f"{router} (recorded)", "wall_s": wall, "rss_mb": rss, "wl_um": wl,
            "vias": vias, "violations": viol, "by_type": {}, "opens": 0, "off_track_vias": 0,
            "out_of_guide_um": None, "score": score}


def shown(r: dict) -> list[str]:
    """fmt's cells, with "—" for the opens and off-track vias a recorded row does not have."""
    cells = fmt(r)
    if r["router"].endswith("(recorded)"):
        cells[5] = cells[6] = "—"
    return cells


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("testcases", nargs="*", default=DEFAULT)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--markdown", action="store_true")
    args = ap.parse_args()
    xroute = shutil.which("xroute") or sys.exit("xroute is not installed (pip install .)")
    from xroute.errors import TestcaseNotFound
    from xroute.testcases import find_testcase

    rows: dict[tuple[str, str], dict] = {}
    with tempfile.TemporaryDirectory(prefix="versus_") as tmp:
        for name in args.testcases:
            try:
                tc = find_testcase(name)
            except TestcaseNotFound:
                print(f"# {name}: not on the search path, skipped", file=sys.stderr)
                continue
            if tc.guide is None:
                print(f"# {name}: no route guide, skipped (the other routers need one)", file=sys.stderr)
                continue
            out = Path(tmp) / f"{name}-xroute"
            proc, wall, rss = run_with_rss([xroute, "route", name, "--threads", str(args.threads), "--out", str(out)])
            if proc.returncode not in (0, 1):
                raise SystemExit(f"xroute route {name} failed: {proc.stderr.strip()}")
            doc = check(xroute, name, next(out.glob("*.routed.def")), out / "check")
            rows[(name, "xroute")] = row(name, "xroute", doc, wall, rss)
            print(" | ".join(shown(rows[(name, "xroute")])), file=sys.stderr)
            for router, exe, make in others():
                if exe is None:
                    r = recorded_row(name, router)
                    print(f"# {router}: not installed; recorded figures used", file=sys.stderr)
                else:
                    routed = Path(tmp) / f"{name}-{router.split()[0]}.def"
                    proc, wall, rss = run_with_rss(make(exe, tc, args.threads, routed))
                    if proc.returncode != 0 or not routed.exists():
                        print(f"# {router} on {name} failed (exit {proc.returncode}): "
                              f"{(proc.stderr or proc.stdout).strip()[-300:]}", file=sys.stderr)
                        continue
                    r = row(name, router, check(xroute, name, routed, Path(tmp) / f"{routed.stem}-check"), wall, rss)
                if r is not None:
                    rows[(name, router)] = r
                    print(" | ".join(shown(r)), file=sys.stderr)

    if args.markdown:
        print("| " + " | ".join(HEADER) + " |")
        print("|" + "---|" * len(HEADER))
    for r in rows.values():
        cells = shown(r)
        print(("| " + " | ".join(cells) + " |") if args.markdown else "  ".join(cells))
    if any(r["router"].endswith("(recorded)") for r in rows.values()):
        print("(recorded: figures measured side by side in 2026-11; opens and off-track vias were not recorded)")
    for name, router, most in FLOORS:
        ours = rows.get((name, "xroute"))
        theirs = rows.get((name, router))
        if ours is None or theirs is None:
            continue
        ratio = ours["wall_s"] / theirs["wall_s"]
        clean = ours["violations"] == 0 and ours["opens"] == 0
        verdict = "holds" if ratio <= most and clean else "not met"
        print(f"{name}: xroute {ours['wall_s']:.1f} s / {theirs['router']} {theirs['wall_s']:.1f} s = {ratio:.2f}x "
              f"(floor <= {most}x, with 0 violations and 0 opens: {verdict})")


if __name__ == "__main__":
    main()
