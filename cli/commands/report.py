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

    One page (inline CSS and SVG, nothing fetched): when and by which xroute it was made, what the
    paper cost (weights of --config) and the contest score are, the table of the runs (settings,
    WL, vias, DRVs by type, opens, runtime, paper cost, relative links to each run's routed DEF,
    metrics JSON and DRC report) and, per design, WL / vias / time per iteration, violations on a
    log axis with their exact counts, and violations by type per run; every series in its own
    colour, dash and marker, identical runs both visible. Runs of one iteration get a table. A
    training run's metrics.jsonl (xroute train) gets the training dashboard: reward, cost and
    violations per episode.

    Example: xroute report out/evaluate/ispd18_test1 runs/ci-smoke --out report.html
    Example: xroute report runs/train-ppo-ispd18_test1 --out training.html
    """
    from xroute.config import load_config
    from xroute.atomic_files import atomic_write_text
    from xroute.cli.report_html import find_all_runs, render, set_warnings

    from xroute.regular_files import check_output

    check_output(out, "report file")  # a folder, FIFO or device there: refused before any work
    cfg = load_config(config)
    runs, training = find_all_runs(run_dirs)
    for line in set_warnings(runs):  # a mixed set (a run killed while publishing): said, then reported
        typer.echo(f"warning: {line}", err=True)
    if out.parent != Path(""):
        out.parent.mkdir(parents=True, exist_ok=True)
    replaced = out.is_file()
    atomic_write_text(out, render(runs, cfg.cost, title, training, out.parent))
    extra = f", {len(training)} training run(s)" if training else ""
    typer.echo(f"report: {len(runs)} run(s){extra} -> {out}" + (" (replaced the file that was there)" if replaced else ""))
