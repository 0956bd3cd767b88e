"""``xroute report``: a self-contained HTML page comparing routing runs (no network needed to view it)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.options import ConfigOption


def report(
    run_dirs: Annotated[list[Path], typer.Argument(help="Output folders of route, evaluate or batch (searched for "
                                                        "*.metrics.json), or metrics files.", show_default=False)],
    out: Annotated[Path, typer.Option("--out", help="HTML file to write.")] = Path("report.html"),
    title: Annotated[str, typer.Option("--title", help="Page title.")] = "xroute report",
    config: ConfigOption = None,
) -> None:
    """Write a self-contained HTML report comparing routing runs.

    One page (inline CSS and SVG, nothing fetched) with the summary table of the runs
    (WL, vias, DRVs by type, opens, runtime, the paper's cost with the weights of --config) and, per
    design, trend charts of WL / vias / DRVs over the iterations, one line per run.

    Example: xroute report out/evaluate/ispd18_test1 runs/ci-smoke --out report.html
    """
    from xroute.config import load_config
    from xroute.outputs import atomic_write_text
    from xroute.cli.report_html import find_runs, render

    cfg = load_config(config)
    runs = find_runs(run_dirs)
    if out.parent != Path(""):
        out.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out, render(runs, cfg.cost, title))
    typer.echo(f"report: {len(runs)} run(s) -> {out}")
