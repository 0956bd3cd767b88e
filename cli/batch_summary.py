"""What a batch leaves for people and CI: gates, summary.{json,csv,md}, junit.xml, baseline files.

The four summary files are one set (:func:`write_summary`): summary.json, written last, records
the SHA-256 of the other three, so a set mixed from two batches can be told
(:func:`xroute.output_set.set_mismatches`).

Gates (``gates:`` in the batch YAML) are checked on each job's final figures (those of the
written DEF). ``max_wirelength_increase_pct`` / ``max_vias_increase_pct`` compare with a baseline
file (JSON written by ``xroute batch --write-baseline``): the entry of the same job id, else the
entry of the same testcase. Each failed gate gives one message naming the job and the gate.
"""

from __future__ import annotations

import csv
import io
import json
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from xroute.cli.batch_config import Gates
from xroute.config_schema import ConfigError
from xroute.errors import InputError
from xroute.atomic_files import atomic_write_text
from xroute.glossary import COST_NAME

SUMMARY_FORMAT = 1
BASELINE_FORMAT = 1
CSV_COLUMNS = ("id", "testcase", "policy", "settings", "status", "resumed", "wirelength_um", "vias", "violations",
               "open_nets", "route_seconds", "cost", "gates", "message")


def load_baseline(path: str | None) -> dict[str, Any] | None:
    if path is None:
        return None
    from xroute.json_files import read_json

    try:
        data = read_json(path, "baseline file")
    except InputError as exc:
        raise ConfigError(exc.message, exc.path, 0) from None
    if not isinstance(data, dict) or data.get("format") != BASELINE_FORMAT:
        raise ConfigError(f"not a baseline file (format {BASELINE_FORMAT} written by `xroute batch --write-baseline`)",
                          path, 0)
    return data


def baseline_entry(baseline: dict[str, Any], row: dict[str, Any]) -> dict[str, Any] | None:
    return baseline.get("jobs", {}).get(row["id"]) or baseline.get("testcases", {}).get(row["testcase"])


def _increase_pct(value: float, base: float) -> float:
    return 100.0 * (value - base) / base if base > 0 else (0.0 if value <= base else float("inf"))


def check_gates(row: dict[str, Any], gates: Gates, baseline: dict[str, Any] | None) -> list[str]:
    """The failed gates of one finished job, as messages naming the job."""
    if row["status"] != "done":
        return []
    out: list[str] = []
    job = row["id"]
    if gates.max_violations is not None and row["violations"] > gates.max_violations:
        out.append(f"job {job}: violations {row['violations']} > max_violations {gates.max_violations}")
    if gates.max_opens is not None and row["open_nets"] > gates.max_opens:
        out.append(f"job {job}: open nets {row['open_nets']} > max_opens {gates.max_opens}")
    for key, limit, gate in (("wirelength_um", gates.max_wirelength_increase_pct, "max_wirelength_increase_pct"),
                             ("vias", gates.max_vias_increase_pct, "max_vias_increase_pct")):
        if limit is None:
            continue
        entry = baseline_entry(baseline or {}, row)
        if entry is None or key not in entry:
            out.append(f"job {job}: {gate}: no baseline entry for this job or testcase in {gates.baseline}")
            continue
        pct = _increase_pct(float(row[key]), float(entry[key]))
        if pct > limit:
            out.append(f"job {job}: {key} {row[key]:,} is {pct:+.2f}% over the baseline {entry[key]:,} "
                       f"> {gate} {limit}")
    return out


def job_row(record: dict[str, Any], resumed: bool) -> dict[str, Any]:
    """A flat summary row from a job record."""
    row: dict[str, Any] = {
        "id": record["id"], "testcase": record["testcase"], "policy": record["policy"],
        "settings": record["settings_name"], "status": record["status"], "resumed": resumed,
        "message": record.get("message", ""), "run_dir": record.get("run_dir", ""),
    }
    if record["status"] == "done":
        f = record["summary"]["final"]
        row.update(wirelength_um=f["wirelength_um"], vias=f["vias"], violations=f["violations"],
                   violations_by_type=f["violations_by_type"], open_nets=f["open_nets"],
                   route_seconds=f["route_seconds"], runtime_seconds=f["runtime_seconds"], cost=f["cost"],
                   policy_seconds=f["policy_seconds"], iterations=record["summary"]["iterations"])
    return row


SUMMARY_FILES = (("csv", "summary.csv"), ("md", "summary.md"), ("junit", "junit.xml"), ("json", "summary.json"))


def summary_paths(out_root: Path) -> dict[str, Path]:
    """The summary files of a batch in ``out_root``, by role, in publishing order (the manifest last)."""
    return {role: out_root / name for role, name in SUMMARY_FILES}


def write_summary(out_root: Path, doc: dict[str, Any]) -> dict[str, Path]:
    """Publishes summary.csv, summary.md, junit.xml and summary.json as one set, like a route's
    outputs (:mod:`xroute.output_set`): written in a staging folder, then renamed into place,
    summary.json last; it is the set's manifest (``"run"``: the SHA-256 of the other three). A
    batch killed between the renames leaves the staging folder, which the next batch in the same
    folder finishes (or undoes) before anything else."""
    from xroute.output_set import publish, run_record, staging

    paths = summary_paths(out_root)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(CSV_COLUMNS)
    for r in doc["jobs"]:
        w.writerow([_csv_value(r, c) for c in CSV_COLUMNS])
    texts = {"csv": buf.getvalue(), "md": markdown_table(doc), "junit": junit_xml(doc)}
    with staging(out_root) as stage:
        staged = {role: stage / path.name for role, path in paths.items()}
        for role, text in texts.items():
            atomic_write_text(staged[role], text)
        manifest = {**doc, "run": run_record({role: staged[role] for role in texts})}
        atomic_write_text(staged["json"], json.dumps(manifest, indent=2) + "\n")
        publish(out_root, stage, [(staged[role], path) for role, path in paths.items()])
    return paths


def _csv_value(row: dict[str, Any], col: str) -> Any:
    if col == "gates":
        return "fail" if row.get("gate_failures") else ("pass" if row["status"] == "done" else "")
    value = row.get(col, "")
    return "" if value is None else value


def markdown_table(doc: dict[str, Any]) -> str:
    lines = [f"# xroute batch: {doc['batch']}", "",
             f"{len(doc['jobs'])} jobs, {doc['counts']['failed']} failed, {doc['counts']['errors']} errors, "
             f"{doc['counts']['resumed']} resumed; wall time {doc['wall_seconds']:.1f} s", "",
             f"{COST_NAME}: the XRoute paper's weighted sum of WL (µm), vias and violations, with the batch "
             "config's cost weights (0.5, 4, 500 by default); lower is better", "",
             f"| job | testcase | policy | settings | WL (µm) | vias | DRVs | opens | route (s) | {COST_NAME} | gates |",
             "|---|---|---|---|---:|---:|---:|---:|---:|---:|---|"]
    for r in doc["jobs"]:
        if r["status"] == "done":
            gates = "FAIL: " + "; ".join(r["gate_failures"]) if r["gate_failures"] else "pass"
            lines.append(f"| {r['id']} | {r['testcase']} | {r['policy']} | {r['settings']} | {r['wirelength_um']:,.1f} "
                         f"| {r['vias']:,} | {r['violations']:,} | {r['open_nets']} | {r['route_seconds']:.2f} "
                         f"| {r['cost']:,.1f} | {gates} |")
        else:
            lines.append(f"| {r['id']} | {r['testcase']} | {r['policy']} | {r['settings']} | | | | | | "
                         f"| ERROR: {r['message']} |")
    return "\n".join(lines) + "\n"


def junit_xml(doc: dict[str, Any]) -> str:
    """JUnit XML: one testcase per job; gate failures as <failure>, job errors as <error>."""
    rows = doc["jobs"]
    suite = ET.Element("testsuite", name=f"xroute batch {doc['batch']}", tests=str(len(rows)),
                       failures=str(doc["counts"]["failed"]), errors=str(doc["counts"]["errors"]),
                       skipped="0", time=f"{doc['wall_seconds']:.3f}")
    for r in rows:
        case = ET.SubElement(suite, "testcase", classname=f"xroute.batch.{r['testcase']}", name=r["id"],
                             time=f"{r.get('route_seconds') or 0:.3f}")
        if r["status"] != "done":
            ET.SubElement(case, "error", message=r["message"], type="XrouteError").text = r["message"]
            continue
        if r["gate_failures"]:
            ET.SubElement(case, "failure", message=r["gate_failures"][0], type="gate").text = "\n".join(r["gate_failures"])
        out = ET.SubElement(case, "system-out")
        out.text = (f"WL {r['wirelength_um']:.1f} um, {r['vias']} vias, {r['violations']} violations, "
                    f"{r['open_nets']} opens, {COST_NAME} {r['cost']:.1f}, run dir {r['run_dir']}"
                    + (" (resumed)" if r["resumed"] else ""))
    root = ET.Element("testsuites")
    root.append(suite)
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def baseline_doc(doc: dict[str, Any]) -> dict[str, Any]:
    """A baseline file from a batch summary: per job id and per testcase (its first finished job)."""
    jobs: dict[str, Any] = {}
    testcases: dict[str, Any] = {}
    for r in doc["jobs"]:
        if r["status"] != "done":
            continue
        entry = {"wirelength_um": r["wirelength_um"], "vias": r["vias"], "violations": r["violations"]}
        jobs[r["id"]] = entry
        testcases.setdefault(r["testcase"], {**entry, "job": r["id"]})
    return {"format": BASELINE_FORMAT, "source": doc["batch"], "jobs": jobs, "testcases": testcases}
