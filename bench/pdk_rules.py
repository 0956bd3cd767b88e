"""Per PDK, every design rule its LEFs state on metal and cut layers, and whether xroute models it.

    python bench/pdk_rules.py [--manifest bench/real_designs.tsv] [--root DIR] [--git-dir GIT]
                              [--contest NAME,NAME] [--json FILE]

The PDKs are those of the real-designs manifest (``real_designs.tsv``, files fetched as
``bench/real_designs.py`` fetches them: ``--root``, ``--git-dir``); each is read once, with the LEFs
and DEF of its first design there. ``--contest`` adds contest testcases by name (their technology
LEFs). For each rule a row: the layers that state it and its status:

* ``checked``: the checker judges it and the router keeps it (SPACING and its PARALLELRUNLENGTH
  table, END OF LINE spacing, corner spacing, cut spacing, MINAREA);
* ``router only``: read and used by the router, judged by no marker (MINWIDTH);
* ``not modelled``: read and set aside (``xroute check``'s not-checked list; ``xroute route`` warns
  of each).

Then a count per PDK. Nothing is routed.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from real_designs import add_source_args, ensure_files, read_manifest  # noqa: E402


def stated_rules(design) -> list[dict]:
    """The rules ``design``'s LEFs state on metal and cut layers: ``{"rule", "layers", "status"}``
    in the order of the layers, the modelled ones first."""
    found: dict[tuple[str, str], list[str]] = {}

    def note(rule: str, status: str, layer: str) -> None:
        layers = found.setdefault((rule, status), [])
        if layer not in layers:
            layers.append(layer)

    for layer in design.layers:
        if layer.type not in ("ROUTING", "CUT"):
            continue
        r = layer.rules
        if layer.type == "ROUTING":
            if r["spacing_rules"] or layer.min_spacing > 0:
                note("SPACING", "checked", layer.name)
            if r["spacing_table"]["prls"]:
                note("SPACINGTABLE PARALLELRUNLENGTH", "checked", layer.name)
            if r["eol_rules"]:
                note("SPACING ENDOFLINE", "checked", layer.name)
            if r["corner_spacing_rules"]:
                note("CORNERSPACING", "checked", layer.name)
            if layer.min_area > 0:
                note("MINAREA", "checked", layer.name)
        elif r["cut_spacing_rules"]:
            note("SPACING (cut)", "checked", layer.name)
    from xroute.design import ROUTER_ONLY_RULES

    for entry in design.unjudged_rules():
        status = "router only" if entry["rule"] in ROUTER_ONLY_RULES else "not modelled"
        for name in entry["layers"]:
            note(entry["rule"], status, name)
    return [{"rule": rule, "status": status, "layers": layers} for (rule, status), layers in found.items()]


def counts(rules: list[dict]) -> dict[str, int]:
    out = {"checked": 0, "router only": 0, "not modelled": 0}
    for r in rules:
        out[r["status"]] += 1
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_source_args(ap)
    ap.add_argument("--contest", default="", help="comma-separated testcase names (their technologies)")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args(argv)

    from xroute.design import load_design

    sources: list[tuple[str, object]] = []
    seen: set[str] = set()
    for row in read_manifest(args.manifest):
        if row["pdk"] in seen:
            continue
        why = ensure_files(row, args.root, args.git_dir)
        if why is not None:
            print(f"{row['pdk']}: skipped: {why}", flush=True)
            continue
        seen.add(row["pdk"])
        lefs = [args.root / p for p in row["lefs"].split(";")]
        sources.append((row["pdk"], lambda lefs=lefs, d=args.root / row["def"]: load_design(lef=lefs, def_=d)))
    for name in (s for s in args.contest.split(",") if s):
        sources.append((name, lambda name=name: load_design(name, use_guide=False)))

    report = []
    for pdk, load in sources:
        rules = stated_rules(load())
        report.append({"pdk": pdk, "counts": counts(rules), "rules": rules})
        c = counts(rules)
        print(f"\n## {pdk}: {len(rules)} rules stated: {c['checked']} checked, {c['router only']} router only, "
              f"{c['not modelled']} not modelled\n")
        print("| rule | status | layers |\n|---|---|---|")
        for r in rules:
            print(f"| {r['rule']} | {r['status']} | {', '.join(r['layers'])} |")
    if args.json is not None:
        args.json.write_text(json.dumps(report, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
