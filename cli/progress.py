"""Progress of routing runs on the terminal: a Rich progress bar, plain log lines, or nothing.

:func:`output_mode` picks the mode once per command: ``json`` and ``quiet`` when asked for;
otherwise Rich progress on a terminal, and one plain line per event when stdout is not a
terminal or the environment says ``CI=true`` (CI logs keep no carriage returns).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import typer
from rich.markup import escape

from xroute.cli.console import counted
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

if TYPE_CHECKING:
    from rich.console import Console

    from xroute.router import RouteProgress

MODES = ("rich", "lines", "quiet", "json")


def in_ci() -> bool:
    """True when the environment says this runs in CI (``CI=true``/``1``, as CI services set)."""
    return os.environ.get("CI", "").strip().lower() in ("1", "true", "yes")


def output_mode(console: Console, *, as_json: bool = False, quiet: bool = False, configured: str = "auto") -> str:
    """One of rich, lines, quiet, json: flags first, then the config's ``output.mode``, then auto."""
    if as_json:
        return "json"
    if quiet:
        return "quiet"
    if configured != "auto":
        return configured
    return "rich" if console.is_terminal and not in_ci() else "lines"


def display_mode(mode: str) -> str:
    """The progress display for an output mode: rich, lines, or off."""
    return mode if mode in ("rich", "lines") else "off"


def by_type(counts: dict[str, int]) -> str:
    parts = [f"{k} {v}" for k, v in counts.items() if v]
    return ", ".join(parts) if parts else "none"


def iteration_line(progress: RouteProgress) -> str:
    """One plain line for a finished iteration."""
    r = progress.report
    return (
        f"iteration {r.iteration}: region size {r.region_size}, {counted(r.regions, 'region')}, "
        f"{counted(r.net_routes, 'net route')}, "
        f"WL {r.wirelength_um:,.1f} um, {counted(r.vias, 'via')}, {counted(r.violations, 'violation')} "
        f"({by_type(r.violations_by_type)}), {r.seconds:.2f} s"
    )


class ProgressDisplay:
    """Shows routing progress: a Rich progress bar on a terminal, plain lines otherwise, or nothing."""

    def __init__(self, console: Console, mode: str, iterations: int, label: str = "") -> None:
        self.console = console
        self.iterations = iterations
        self.mode = display_mode(mode)  # "rich", "lines" or "off"
        self.label = f"{label}: " if label else ""  # prefix of every line (e.g. the run's name)
        self.last_violations: int | None = None
        self.progress: Progress | None = None
        self.task: Any = None

    def __enter__(self) -> ProgressDisplay:
        if self.mode == "rich":
            self.progress = Progress(
                SpinnerColumn(),
                TextColumn("[bold]{task.description}"),
                BarColumn(),
                TextColumn("regions {task.completed:.0f}/{task.total:.0f}"),
                TextColumn("{task.fields[status]}"),
                TimeElapsedColumn(),
                console=self.console,
            )
            self.progress.__enter__()
            self.task = self.progress.add_task(f"{self.label}iteration 0 (limit {self.iterations})", total=1, status="")
        return self

    def __exit__(self, *exc: Any) -> None:
        if self.progress is not None:
            self.progress.__exit__(*exc)

    def __call__(self, event: RouteProgress) -> None:
        r = event.report
        if event.iteration_done:
            self.last_violations = r.violations
            if self.mode == "lines":
                typer.echo(self.label + iteration_line(event))
            elif self.progress is not None:
                self.progress.console.print(escape(self.label + iteration_line(event)))
        if self.progress is not None:
            viol = "-" if self.last_violations is None else f"{self.last_violations}"
            wl = f"WL {r.wirelength_um:,.0f} um" if event.iteration_done else ""
            self.progress.update(
                self.task,
                description=f"{self.label}iteration {r.iteration} (limit {event.iterations})",
                completed=event.regions_done,
                total=max(event.regions_total, 1),
                status=f"violations {viol}  {wl}".rstrip(),
            )


