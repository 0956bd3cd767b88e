"""``xroute report``: a self-contained HTML page comparing routing runs (no network needed to view it)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from xroute.cli.options import ConfigOption


def report(
    run_dirs: Annotated[list[Path], typer.Argument(help="Output folders of route, evaluate, batch or train (searched "
                                                        "for *.metrics.json and metrics.jsonl), or those files.",
                                                   show_default=False)],
    out: Annotated[Path, typer.Option("--out", help="HTML file to write.")] = Path("report.html"),
    title: Annotated[str, typer.Option("--title", help="Page title.")] = "xroute report",
    config: ConfigOption = None,
) -> None:
    """Write a self-contained HTML report comparing routing runs.

    One page (inline CSS and SVG, nothing fetched) with the summary table of the runs
    (WL, vias, DRVs by type, opens, runtime, the paper's cost with the weights of --config) and, per
    design, trend charts of WL / vias / DRVs over the iterations, one line per run. A training run's
    metrics.jsonl (xroute train) gets the training dashboard: reward, cost and violations per episode.

    Example: xroute report out/evaluate/ispd18_test1 runs/ci-smoke --out report.html
    Example: xroute report runs/train-ppo-ispd18_test1 --out training.html
    """
    from xroute.config import load_config
    from xroute.atomic_files import atomic_write_text
    from xroute.cli.report_html import find_all_runs, render

    cfg = load_config(config)
    runs, training = find_all_runs(run_dirs)
    if out.parent != Path(""):
        out.parent.mkdir(parents=True, exist_ok=True)
    atomic_write_text(out, render(runs, cfg.cost, title, training, out.parent))
    extra = f", {len(training)} training run(s)" if training else ""
    typer.echo(f"report: {len(runs)} run(s){extra} -> {out}")
