"""The outputs of a routing run, checked on what was written.

:func:`write_route_outputs` writes ``<design>.routed.def``, reads it back with the same LEF and
checks the written file (opens, wirelength, vias, design rules), then writes
``<design>.drc.rpt`` and ``<design>.metrics.json``. Every file is written atomically (a
temporary file in the same folder, then ``os.replace``): an interrupted run leaves no partial
file. The figures in the metrics therefore describe the written DEF, not the router's belief.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from xroute.atomic_files import atomic_write_text, owner_gone, pid_alive
from xroute.output_set import clean_leftovers, publish, run_record, staging

if TYPE_CHECKING:
    from xroute.design import Design
    from xroute.router import RouteResult

METRICS_FORMAT = 1  # version of the metrics JSON layout
MAX_OPENS_LISTED = 100  # open nets listed by name in the metrics JSON (all are counted)


def peak_rss_mb() -> float:
    """Peak resident set size of this process so far, in MB (2^20 bytes)."""
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak / 2**20 if sys.platform == "darwin" else peak / 2**10  # bytes on macOS, KiB on Linux


def clean_stale_temporaries(folder: Path) -> list[Path]:
    """Removes what a killed run left in ``folder``: staging folders and interrupted publishes
    (:func:`xroute.output_set.clean_leftovers`), temporary files ``.NAME.PID.XXXX.tmp`` of
    :func:`xroute.atomic_files.atomic_write_text` whose run has ended (their lock is free, whatever
    the process id: :func:`xroute.atomic_files.owner_gone`) and ``NAME.tmp.PID`` of the engine's
    DEF writer whose process is gone; returns the removed paths."""
    removed: list[Path] = []
    if not folder.is_dir():
        return removed
    removed += clean_leftovers(folder)  # staging folders and incomplete output sets (xroute.output_set)
    for p in folder.iterdir():
        parts = p.name.split(".")
        stale = False
        if p.name.startswith(".") and p.name.endswith(".tmp") and len(parts) >= 5 and parts[-3].isdigit():
            stale = owner_gone(p, int(parts[-3]))  # .NAME.PID.HEX.tmp
        elif len(parts) >= 3 and parts[-2] == "tmp" and parts[-1].isdigit():
            stale = int(parts[-1]) != os.getpid() and not pid_alive(int(parts[-1]))  # NAME.tmp.PID
        if stale and p.is_file() and not p.is_symlink():
            try:
                p.unlink()
                removed.append(p)
            except OSError:
                pass
    return removed


@dataclass(frozen=True)
class FinalFigures:
    """The checked figures of a written DEF (the metrics JSON's ``final``, typed)."""

    wirelength_um: float
    vias: int
    violations: int
    violations_by_type: dict[str, int]  # marker type -> count
    nets: int
    nets_routed: int
    open_nets: int
    iterations_run: int
    route_seconds: float  # the router's wall time
    runtime_seconds: float  # the whole run's (loading and output checks included)
    peak_rss_mb: float

    @classmethod
    def from_metrics(cls, final: dict[str, Any]) -> FinalFigures:
        return cls(**{f: final[f] for f in cls.__dataclass_fields__})


@dataclass(frozen=True)
class RouteOutputs:
    """Where the outputs went and the checked figures of the written DEF."""

    def_path: Path
    metrics_path: Path
    drc_report_path: Path
    metrics: dict[str, Any]  # the content of the metrics JSON

    @property
    def final(self) -> dict[str, Any]:
        return self.metrics["final"]

    @property
    def figures(self) -> FinalFigures:
        """The final figures, typed."""
        return FinalFigures.from_metrics(self.final)

    @property
    def open_nets(self) -> int:
        return int(self.final["open_nets"])


def _version() -> str:
    from xroute import __version__

    return __version__


def output_paths(out_dir: Path, design_name: str) -> tuple[Path, Path, Path]:
    """(routed DEF, metrics JSON, DRC report) paths for a design in ``out_dir``: the stem is the
    design name made safe (:func:`xroute.safe_paths.safe_stem`), each path checked to lie in ``out_dir``."""
    from xroute.safe_paths import output_file

    return (
        output_file(out_dir, design_name, ".routed.def"),
        output_file(out_dir, design_name, ".metrics.json"),
        output_file(out_dir, design_name, ".drc.rpt"),
    )


def write_route_outputs(
    design: Design,
    result: RouteResult,
    out_dir: str | os.PathLike[str],
    *,
    started: float | None = None,
) -> RouteOutputs:
    """Writes the routed DEF, re-reads and checks it, and writes the DRC report and metrics JSON.

    ``started`` is the ``time.perf_counter()`` of the start of the whole run (loading included),
    for the runtime figure; by default the routing time is used.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    def_path, metrics_path, drc_path = output_paths(out, design.name)
    # Everything is written and checked in a fresh staging folder, then published as one set.
    with staging(out) as stage:
        return _write_staged(design, result, out, stage, started, (def_path, metrics_path, drc_path))


def _write_staged(design: Design, result: RouteResult, out: Path, stage: Path, started: float | None,
                  final: tuple[Path, Path, Path]) -> RouteOutputs:
    from xroute.design import load_design

    def_path, metrics_path, drc_path = final
    staged_def, staged_metrics, staged_drc = (stage / p.name for p in final)
    design.write_def(staged_def)

    written = load_design(lef=design.lef_paths, def_=staged_def)  # check the file, not the memory
    conn = written.engine.check_connectivity()
    measured = written.engine.metrics()
    drc_report = written.engine.write_drc_report(str(staged_drc), threads=result.settings.threads)
    drc = {str(k): int(v) for k, v in drc_report.items()}

    counts = design.counts()
    runtime = time.perf_counter() - started if started is not None else result.seconds
    opens = conn["opens"]
    metrics: dict[str, Any] = {
        "format": METRICS_FORMAT,
        "xroute_version": _version(),
        "written_utc": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "design": design.name,
        "testcase": design.testcase,
        "inputs": {"lef": design.lef_paths, "def": design.def_path, "guide": design.guide_path},
        "guide": design.guide_source,
        "global_route": gr.to_dict() if (gr := design.global_route_stats) is not None else None,
        "outputs": {"def": str(def_path), "metrics": str(metrics_path), "drc_report": str(drc_path)},
        "settings": {
            "region_size": result.region_size,  # 0 (auto) resolved
            "iterations": result.settings.iterations,
            "threads": result.settings.threads,
            "seed": result.seed,
            "repair_rounds": result.settings.repair_rounds,
            "schedule": [list(step) for step in result.settings.schedule] if result.settings.schedule else None,
            "policy": result.policy,
            "schedule_policy": result.schedule_policy,
            "sole_landing_penalty": result.sole_landing_penalty,  # -1 (automatic) resolved
        },
        "policy": result.policy,
        "iterations": [r.to_dict() for r in result.iterations],
        "final": {
            "wirelength_dbu": int(measured["wirelength_dbu"]),
            "wirelength_um": float(measured["wirelength_um"]),
            "vias": int(measured["vias"]),
            "violations": sum(drc.values()),
            "violations_by_type": drc,
            "nets": int(counts["nets"]),
            "nets_checked": int(conn["nets_checked"]),
            "nets_routed": int(measured["nets_routed"]),
            "open_nets": int(conn["open_nets"]),
            "opens": [
                {"net": o["net"], "pin_groups": len(o["groups"]), "floating_pieces": int(o["floating_pieces"])}
                for o in opens[:MAX_OPENS_LISTED]
            ],
            "unrouted_nets": int(conn["unrouted_nets"]),
            "single_pin_nets": int(conn["single_pin_nets"]),
            "floating_pieces": int(conn["floating_pieces"]),
            "iterations_run": len(result.iterations),
            "route_seconds": result.seconds,
            "policy_seconds": result.policy_seconds,  # in a Python policy's order(); null for built-ins
            "policy_calls": result.policy_calls,
            "runtime_seconds": runtime,
            "peak_rss_mb": round(peak_rss_mb(), 1),
            "wirelength_by_layer": {str(k): int(v) for k, v in measured["wirelength_by_layer"].items()},
            "vias_by_cut_layer": {str(k): int(v) for k, v in measured["vias_by_cut_layer"].items()},
        },
    }
    # The metrics JSON is the run's manifest (published last): its DEF and DRC report, by hash.
    metrics["run"] = run_record({"def": staged_def, "drc_report": staged_drc})
    atomic_write_text(staged_metrics, json.dumps(metrics, indent=2) + "\n")
    publish(out, stage, [(staged_def, def_path), (staged_drc, drc_path), (staged_metrics, metrics_path)])
    return RouteOutputs(def_path=def_path, metrics_path=metrics_path, drc_report_path=drc_path, metrics=metrics)
