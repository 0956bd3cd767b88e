"""The self-contained HTML report of routing runs (``xroute report``): inline CSS and SVG only.

A run is a ``*.metrics.json`` written by route, evaluate or batch; :func:`find_runs` collects
them under the given folders. The page says when and by which xroute it was made and what
the paper cost and the contest score are; it has a summary table (settings, WL, vias, DRVs by
type, opens, runtime, the paper cost, relative links to each run's routed DEF, metrics JSON and
DRC report, when and by which xroute the run was written) and, per design, the charts and tables
of :mod:`xroute.cli.report_trends`. Training runs (a ``metrics.jsonl`` of ``xroute
train``) found there too get the training dashboard (:mod:`xroute.cli.report_training`).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from datetime import datetime, timezone
from html import escape
from pathlib import Path
from typing import Any
from urllib.parse import quote

from xroute.config import CostSection
from xroute.errors import InputError, safe_text
from xroute.cli.report_training import TRAINING_LOG, TrainingRun, find_training_logs, read_training_log, render_training
from xroute.cli.report_trends import design_section
from xroute.glossary import COST_NAME, cost_line, score_line

MAX_DEPTH = 4  # folder levels searched below each RUN_DIR


@dataclass(frozen=True)
class Run:
    name: str  # shown in tables and legends
    path: Path  # the metrics JSON
    metrics: dict[str, Any]


def find_all_runs(folders: list[Path]) -> tuple[list[Run], list[TrainingRun]]:
    """The routing runs (every metrics JSON) and training runs (every ``metrics.jsonl``) in or below
    ``folders`` (or the files themselves), each in path order."""
    files: list[Path] = []
    logs: list[Path] = []
    for folder in folders:
        if folder.is_file():
            (logs if folder.name.endswith(".jsonl") else files).append(folder)
            continue
        if not folder.is_dir():
            raise InputError("run folder not found", str(folder), 0)
        found = sorted(p for p in folder.rglob("*.metrics.json")
                       if len(p.relative_to(folder).parts) <= MAX_DEPTH + 1 and not any(
                           part.startswith(".") for part in p.relative_to(folder).parts))
        found_logs = find_training_logs(folder, MAX_DEPTH)
        if not found and not found_logs:
            raise InputError(f"no *.metrics.json (route, evaluate or batch output) or {TRAINING_LOG} (xroute train) "
                             "found", str(folder), 0)
        files += found
        logs += found_logs
    return _read_runs(files), [read_training_log(p) for p in logs]


def find_runs(folders: list[Path]) -> list[Run]:
    """Every metrics JSON in or below ``folders`` (or the files themselves), in path order."""
    return find_all_runs(folders)[0]


_SHAPE_ERRORS = (KeyError, TypeError, ValueError, AttributeError, IndexError, OverflowError, ZeroDivisionError)


def _read_runs(files: list[Path]) -> list[Run]:
    """The runs of ``files``, each checked by rendering it alone: a metrics JSON that is not one
    (wrong types, missing fields, deep nesting) is an InputError naming that file."""
    from xroute.json_files import read_json

    runs = []
    for f in files:
        metrics = read_json(f, "metrics JSON")
        run = Run(name=_run_name(f), path=f, metrics=metrics)
        try:
            if not isinstance(metrics, dict):
                raise TypeError(f"a JSON {type(metrics).__name__}, not an object")
            metrics["final"], metrics["iterations"]  # noqa: B018 - the fields the report needs
            render([run], CostSection(), "check", [], f.parent)
        except _SHAPE_ERRORS as exc:
            raise InputError(f"not a metrics JSON written by xroute ({type(exc).__name__}: {safe_text(exc)})",
                             str(f), 0) from None
        except RecursionError:
            raise InputError("not a metrics JSON written by xroute (nested too deeply)", str(f), 0) from None
        runs.append(run)
    return runs


def set_warnings(runs: list[Run]) -> list[str]:
    """One line per run whose routed DEF or DRC report beside its metrics JSON is not the file the
    metrics describe (their SHA-256 in the metrics' ``"run"``: a run killed while publishing, or
    files copied in from another run)."""
    from xroute.output_set import set_mismatches

    lines = []
    for r in runs:
        stem = r.path.name[: -len(".metrics.json")] if r.path.name.endswith(".metrics.json") else r.path.stem
        files = {"def": r.path.with_name(f"{stem}.routed.def"), "drc_report": r.path.with_name(f"{stem}.drc.rpt")}
        bad = set_mismatches(r.metrics, files)
        if bad:
            names = " and ".join(p.name for p in bad)
            lines.append(f"{r.path}: {names} {'is not the file' if len(bad) == 1 else 'are not the files'} these "
                         "metrics describe (another run's, or changed since): figures and files may disagree")
    return lines


def _run_name(path: Path) -> str:
    folder = path.parent.name
    return folder if folder else path.stem


CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:24px;color:#222;background:#fff}
h1{font-size:22px;margin:0 0 4px} h2{font-size:18px;margin:28px 0 8px} .sub{color:#666;margin:0 0 16px}
table{border-collapse:collapse;font-size:13px;margin:8px 0} th,td{border:1px solid #d0d0d0;padding:4px 8px}
th{background:#f0f3f7;text-align:left} td.n{text-align:right;font-variant-numeric:tabular-nums}
caption{text-align:left;font-size:12px;color:#555;padding:2px 0}
tr:nth-child(even) td{background:#fafbfc} .charts{display:flex;flex-wrap:wrap;gap:12px}
.chart-title{font-size:13px;font-weight:600} .tick{font-size:10px;fill:#555} .axis{font-size:11px;fill:#333}
.legend{font-size:11px;fill:#222} .range{font-size:10px;fill:#666} .bad{color:#b00020;font-weight:600}
.glossary{font-size:12px;color:#444;margin:2px 0}
"""
FILES = (("def", ".routed.def", "DEF"), ("metrics", ".metrics.json", "metrics"), ("drc_report", ".drc.rpt", "DRC"))


def _links(r: Run, out_dir: Path) -> str:
    """Relative links from the report's folder to the run's routed DEF, metrics JSON and DRC report."""
    stem = r.path.name[: -len(".metrics.json")] if r.path.name.endswith(".metrics.json") else r.path.stem
    links = []
    for _, suffix, text in FILES:
        f = r.path.parent / f"{stem}{suffix}"
        if f.is_file():
            rel = Path(os.path.relpath(f.resolve(), out_dir.resolve())).as_posix()
            links.append(f'<a href="{escape(quote(rel))}">{text}</a>')
    return " ".join(links)


def _settings(r: Run) -> str:
    s = r.metrics.get("settings", {})
    names = {"region_size": "region", "iterations": "iterations", "threads": "threads", "seed": "seed",
             "repair_rounds": "repair"}
    parts = [f"{name}&nbsp;{escape(str(s[k]))}" for k, name in names.items() if s.get(k) is not None]
    return ", ".join(parts)


def _written(r: Run) -> str:
    stamp = r.metrics.get("written_utc")
    if not stamp:  # older metrics: the file's time
        stamp = datetime.fromtimestamp(r.path.stat().st_mtime, timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return f"{stamp}; xroute {r.metrics.get('xroute_version', 'not recorded')}"


def _runs_table(runs: list[Run], cost: CostSection, out_dir: Path) -> str:
    types = [t for t in _types(runs) if any(r.metrics["final"]["violations_by_type"].get(t) for r in runs)]
    head = ["run", "design", "policy", "settings", "iterations", "WL (µm)", "vias", "DRVs", *types, "opens",
            "runtime (s)", COST_NAME, "files", "written"]
    rows = []
    for r in runs:
        f = r.metrics["final"]
        c = cost.cost(f["wirelength_um"], f["vias"], f["violations"])
        cells = [
            f"<td>{escape(r.name)}</td>", f"<td>{escape(str(r.metrics.get('design', '')))}</td>",
            f"<td>{escape(str(r.metrics.get('policy', '')))}</td>", f"<td>{_settings(r)}</td>",
            f'<td class="n">{f.get("iterations_run", len(r.metrics["iterations"]))}</td>',
            f'<td class="n">{f["wirelength_um"]:,.1f}</td>', f'<td class="n">{f["vias"]:,}</td>',
            f'<td class="n">{f["violations"]:,}</td>',
            *[f'<td class="n">{f["violations_by_type"].get(t, 0):,}</td>' for t in types],
            f'<td class="n{" bad" if f.get("open_nets") else ""}">{f.get("open_nets", 0)}</td>',
            f'<td class="n">{f.get("runtime_seconds", f.get("route_seconds", 0.0)):.2f}</td>',
            f'<td class="n">{c:,.1f}</td>', f"<td>{_links(r, out_dir)}</td>", f"<td>{escape(_written(r))}</td>",
        ]
        rows.append(f'<tr class="run">{"".join(cells)}</tr>')
    return ("<table id=\"runs\"><thead><tr>" + "".join(f"<th>{escape(h)}</th>" for h in head)
            + "</tr></thead><tbody>\n" + "\n".join(rows) + "\n</tbody></table>")


def render(runs: list[Run], cost: CostSection, title: str = "xroute report",
           training: list[TrainingRun] | None = None, out_dir: Path | None = None) -> str:
    """The whole HTML page (the runs table and charts when there are routing runs, the training
    dashboard when there are training runs). ``out_dir``: the report's folder, for relative links."""
    from xroute import __version__

    out_dir = out_dir if out_dir is not None else Path(".")
    sections = []
    for design in sorted({str(r.metrics.get("design", "")) for r in runs}):
        sections.append(design_section(design, [r for r in runs if str(r.metrics.get("design", "")) == design]))
    training = training or []
    made = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    sub = f"{len(runs)} run(s); final figures of the written DEF; made {made} by xroute {__version__}"
    if training:
        sub = f"{len(training)} training run(s)" + (f"; {sub}" if runs else f"; episode figures from metrics.jsonl; "
                                                    f"made {made} by xroute {__version__}")
    glossary = (f'<p class="glossary">{escape(cost_line(cost))}</p>\n<p class="glossary">{escape(score_line())}</p>\n'
                if runs else "")
    body = (f"<h2>Runs</h2>\n{_runs_table(runs, cost, out_dir)}\n" + "\n".join(sections) + "\n"
            if runs or not training else "")
    if training:
        body += render_training(training) + "\n"
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{escape(title)}</title><style>{CSS}</style></head><body>\n"
            f"<h1>{escape(title)}</h1><p class=\"sub\">{escape(sub)}</p>\n{glossary}" + body + "</body></html>\n")


def _types(runs: list[Run]) -> list[str]:
    seen: list[str] = []
    for r in runs:
        for t in r.metrics["final"]["violations_by_type"]:
            if t not in seen:
                seen.append(t)
    return seen
