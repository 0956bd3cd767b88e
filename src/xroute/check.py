"""Judging a routed design, ours or another router's: ``check_design(design)``.

Everything the engine's ``check_routing`` measures (opens, design-rule markers, wirelength, vias,
wrong-way and off-track wire, off-track vias, out-of-guide wire and vias; definitions in
``engine_cpp/verify/README.md``), the ISPD-2018/2019 contest score before violations computed
from them, and the markers as a KLayout marker database (``.lyrdb``) to browse over the layout.

Contest score (the contest evaluator's weights; lengths in pitches of the second routing layer,
"M2"): 0.5 per pitch of wire, 2 per via, 1 per pitch of out-of-guide wire, 1 per out-of-guide
via, 0.5 per pitch of off-track wire, 1 per off-track via, 1 per pitch of wrong-way wire. The
violations' own terms (weighted by the evaluator's rule check) are not in it.
"""

from __future__ import annotations

import os
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any
from xml.sax.saxutils import escape

from xroute.atomic_files import atomic_write_text

if TYPE_CHECKING:
    from xroute.design import Design

# (figure, weight): the contest score's terms; lengths in M2 pitches.
SCORE_WEIGHTS: dict[str, float] = {
    "wirelength": 0.5,
    "vias": 2.0,
    "out_of_guide_wirelength": 1.0,
    "out_of_guide_vias": 1.0,
    "off_track_wirelength": 0.5,
    "off_track_vias": 1.0,
    "wrong_way_wirelength": 1.0,
}
MAX_OPENS_LISTED = 100


@dataclass(frozen=True)
class CheckResult:
    """What :func:`check_design` found. Lengths in µm unless named ``_pitches``."""

    design: str
    nets_checked: int  # nets with two or more pins
    opens: int  # open nets
    open_nets: list[dict[str, Any]]  # the first MAX_OPENS_LISTED: net, pin_groups
    violations: int
    violations_by_type: dict[str, int]
    markers: list[dict[str, Any]]  # type, layer, box (DBU), nets (ids; -1 = obstruction)
    wirelength_um: float
    vias: int
    wrong_way_wirelength_um: float
    off_track_wirelength_um: float
    off_track_vias: int
    out_of_guide_wirelength_um: float | None  # None without a guide
    out_of_guide_vias: int | None
    m2_pitch_dbu: int
    dbu_per_micron: int
    score_terms: dict[str, float] = field(default_factory=dict)  # weighted, per SCORE_WEIGHTS key
    score: float | None = None  # contest score before violations; None without a guide
    # The rules the LEF states that this check does not judge (Design.unjudged_rules): a count of
    # 0 violations claims nothing about them.
    not_checked: list[dict[str, Any]] = field(default_factory=list)

    def to_dict(self, with_markers: bool = False) -> dict[str, Any]:
        d = asdict(self)
        if not with_markers:
            d.pop("markers")
        return d


def contest_terms(raw: dict[str, Any], pitch_dbu: int) -> dict[str, float]:
    """The contest score's weighted terms from ``check_routing``'s figures (DBU lengths)."""
    if pitch_dbu <= 0:
        return {}

    def pitches(key: str) -> float:
        return float(raw[key]) / pitch_dbu

    figures = {
        "wirelength": pitches("wirelength_dbu"),
        "vias": float(raw["vias"]),
        "out_of_guide_wirelength": pitches("out_of_guide_wirelength_dbu"),
        "out_of_guide_vias": float(raw["out_of_guide_vias"]),
        "off_track_wirelength": pitches("off_track_wirelength_dbu"),
        "off_track_vias": float(raw["off_track_vias"]),
        "wrong_way_wirelength": pitches("wrong_way_wirelength_dbu"),
    }
    return {k: SCORE_WEIGHTS[k] * v for k, v in figures.items()}


def check_design(design: Design, report_path: str | os.PathLike[str] | None = None, threads: int = 1) -> CheckResult:
    """Checks the routing ``design`` holds (a routed DEF, read with its LEF and, for the guide
    figures, its guide file); with ``report_path``, the markers are also written there as a text
    DRC report (atomically, from the same check). ``threads`` layers are checked at once (the
    result does not depend on it)."""
    raw = design.engine.check_routing(report_path=os.fspath(report_path) if report_path is not None else "",
                                      threads=threads)
    by_type: dict[str, int] = {}
    for m in raw["markers"]:
        by_type[m["type"]] = by_type.get(m["type"], 0) + 1
    conn = raw["connectivity"]
    opens = conn["opens"]
    pitch = int(raw["scorer_pitch_dbu"])
    terms = contest_terms(raw, pitch) if raw["has_guides"] else {}
    return CheckResult(
        design=design.name,
        nets_checked=int(conn.get("nets_checked", 0)),
        opens=int(raw["opens"]),
        open_nets=[{"net": o["net"], "pin_groups": len(o["groups"])} for o in opens[:MAX_OPENS_LISTED]],
        violations=len(raw["markers"]),
        violations_by_type=dict(sorted(by_type.items())),
        markers=list(raw["markers"]),
        wirelength_um=float(raw["wirelength_um"]),
        vias=int(raw["vias"]),
        wrong_way_wirelength_um=float(raw["wrong_way_wirelength_um"]),
        off_track_wirelength_um=float(raw["off_track_wirelength_um"]),
        off_track_vias=int(raw["off_track_vias"]),
        out_of_guide_wirelength_um=raw["out_of_guide_wirelength_um"],
        out_of_guide_vias=raw["out_of_guide_vias"],
        m2_pitch_dbu=pitch,
        dbu_per_micron=design.dbu_per_micron,
        score_terms=terms,
        score=sum(terms.values()) if terms else None,
        not_checked=design.unjudged_rules(),
    )


def _net_label(design: Design, net: int) -> str:
    if net < 0:
        return "obstruction"
    names = design.net_names
    return names[net] if net < len(names) else f"fixed shape #{net}"


def lyrdb_text(result: CheckResult, design: Design) -> str:
    """The markers as a KLayout report database (XML): one category per marker type, one item per
    marker with its box (µm) and a text naming the layer and nets."""
    dbu = float(result.dbu_per_micron or 1)
    cell = escape(result.design)
    out = ['<?xml version="1.0" encoding="utf-8"?>', "<report-database>",
           f" <description>xroute check: {result.violations} markers</description>",
           " <original-file/>", " <generator>xroute check</generator>", f" <top-cell>{cell}</top-cell>",
           " <tags/>", " <categories>"]
    for kind in result.violations_by_type:
        out += ["  <category>", f"   <name>{escape(kind)}</name>", f"   <description>{escape(kind)}</description>",
                "   <categories/>", "  </category>"]
    out += [" </categories>", " <cells>", "  <cell>", f"   <name>{cell}</name>", "   <variant/>",
            "   <references/>", "  </cell>", " </cells>", " <items>"]
    for m in result.markers:
        xlo, ylo, xhi, yhi = (v / dbu for v in m["box"])
        ids = [int(n) for n in m["nets"]]
        if m["type"] == "MinArea":  # one conductor: its second id is -1 for "none", not an obstruction
            ids = ids[:1]
        nets = ", ".join(_net_label(design, n) for n in ids)
        text = escape(f"{m['layer']}: {nets}").replace("'", "&apos;")
        out += ["  <item>", "   <tags/>", f"   <category>{escape(m['type'])}</category>", f"   <cell>{cell}</cell>",
                "   <visited>false</visited>", "   <multiplicity>1</multiplicity>", "   <image/>", "   <values>",
                f"    <value>box: ({xlo:.6g},{ylo:.6g};{xhi:.6g},{yhi:.6g})</value>",
                f"    <value>text: '{text}'</value>", "   </values>", "  </item>"]
    out += [" </items>", "</report-database>", ""]
    return "\n".join(out)


def check_paths(out_dir: str | os.PathLike[str], stem: str) -> dict[str, Path]:
    """Where :func:`check_to_outputs` writes in ``out_dir``: the check JSON, the text DRC report and
    the marker database."""
    out = Path(out_dir)
    return {"json": out / f"{stem}.check.json", "report": out / f"{stem}.drc.rpt", "lyrdb": out / f"{stem}.lyrdb"}


def check_to_outputs(design: Design, out_dir: str | os.PathLike[str], stem: str) -> tuple[CheckResult, dict[str, Path]]:
    """Checks ``design`` and publishes :func:`check_paths` as one set, like a route's outputs
    (:mod:`xroute.output_set`): the three files are written in a staging folder, then renamed into
    place, the check JSON last; it is the set's manifest (``"run"``: the SHA-256 of the DRC
    report and the marker database). Leftovers of a killed run in ``out_dir`` are cleaned first;
    a folder, FIFO or device at an output path is refused before the check runs."""
    import json

    from xroute.output_set import publish, run_record, staging
    from xroute.outputs import clean_stale_temporaries
    from xroute.regular_files import check_output, make_output_folder

    out = make_output_folder(out_dir)
    paths = check_paths(out, stem)
    for path in paths.values():
        check_output(path)
    clean_stale_temporaries(out)
    with staging(out) as stage:
        staged = {role: stage / path.name for role, path in paths.items()}
        result = check_design(design, report_path=staged["report"])
        atomic_write_text(staged["lyrdb"], lyrdb_text(result, design))
        doc = result.to_dict(with_markers=True)
        doc["run"] = run_record({"drc_report": staged["report"], "lyrdb": staged["lyrdb"]})
        atomic_write_text(staged["json"], json.dumps(doc, indent=2) + "\n")
        publish(out, stage, [(staged[r], paths[r]) for r in ("report", "lyrdb", "json")])
    return result, paths
