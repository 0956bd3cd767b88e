"""``xroute route``: route a design, write the routed DEF, metrics JSON and DRC report, check opens.

Exit status: 0 when the written DEF has no open net, 1 when opens remain (they are listed on
stderr), 2 for user errors (bad files, unknown testcase or policy, invalid settings).
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer
from rich.markup import escape
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn
from rich.table import Table

from xroute_cli.console import (
    DefOption,
    GuideOption,
    LefOption,
    TestcaseArg,
    check_design_args,
    load_design_args,
    print_json,
    stdout_console,
)
from xroute_cli.router import DEFAULT_ITERATIONS, DEFAULT_REGION_SIZE, MAX_ITERATIONS, RouteProgress, RouteSettings

if TYPE_CHECKING:
    from rich.console import Console

    from xroute_cli.groute import GlobalRouteStats
    from xroute_cli.outputs import RouteOutputs

EXIT_OPENS = 1
MAX_OPENS_PRINTED = 20


def _by_type(counts: dict[str, int]) -> str:
    parts = [f"{k} {v}" for k, v in counts.items() if v]
    return ", ".join(parts) if parts else "none"


def iteration_line(progress: RouteProgress) -> str:
    """One plain line for a finished iteration."""
    r = progress.report
    return (
        f"iteration {r.iteration}: {r.regions} regions, {r.net_routes} net routes, "
        f"WL {r.wirelength_um:,.1f} um, {r.vias:,} vias, {r.violations} violations "
        f"({_by_type(r.violations_by_type)}), {r.seconds:.2f} s"
    )


class ProgressDisplay:
    """Shows routing progress: a Rich progress bar on a terminal, plain lines otherwise, or nothing."""

    def __init__(self, console: Console, mode: str, iterations: int) -> None:
        self.console = console
        self.iterations = iterations
        self.mode = mode  # "rich", "lines" or "off"
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
            self.task = self.progress.add_task(f"iteration 0 (limit {self.iterations})", total=1, status="")
        return self

    def __exit__(self, *exc: Any) -> None:
        if self.progress is not None:
            self.progress.__exit__(*exc)

    def __call__(self, event: RouteProgress) -> None:
        r = event.report
        if event.iteration_done:
            self.last_violations = r.violations
            if self.mode == "lines":
                typer.echo(iteration_line(event))
            elif self.progress is not None:
                self.progress.console.print(escape(iteration_line(event)))
        if self.progress is not None:
            viol = "-" if self.last_violations is None else f"{self.last_violations}"
            wl = f"WL {r.wirelength_um:,.0f} um" if event.iteration_done else ""
            self.progress.update(
                self.task,
                description=f"iteration {r.iteration} (limit {event.iterations})",
                completed=event.regions_done,
                total=max(event.regions_total, 1),
                status=f"violations {viol}  {wl}".rstrip(),
            )


def global_route_summary(stats: GlobalRouteStats) -> str:
    """One line of global-routing figures."""
    nx, ny = stats.gcells
    return (f"{nx} x {ny} GCells, {stats.nets} nets, overflow {stats.overflow} "
            f"(after pattern routing {stats.initial_overflow}), {stats.wirelength_gcells:,} GCells of wire, "
            f"{stats.vias:,} vias, {stats.guides:,} guides, {_seconds(stats.seconds)} s")


def _seconds(t: float) -> str:
    return f"{t:.2f}" if t < 10 else f"{t:.1f}"


def final_line(outputs: RouteOutputs, out_dir: Path) -> str:
    f = outputs.final
    status = "routed" if f["open_nets"] == 0 else "OPENS REMAIN"
    return (
        f"{outputs.metrics['design']}: {status}: {f['nets']} nets, {f['open_nets']} open, "
        f"{f['violations']} violations, WL {f['wirelength_um']:,.1f} um, {f['vias']:,} vias, "
        f"{_seconds(f['runtime_seconds'])} s, {f['peak_rss_mb']:.0f} MB -> {out_dir}"
    )


def summary_table(outputs: RouteOutputs) -> Table:
    f = outputs.final
    m = outputs.metrics
    table = Table(title=f"Routed {escape(m['design'])}", caption="checked on the written DEF",
                  show_header=False, title_justify="left", caption_justify="left")
    table.add_column("item", style="bold")
    table.add_column("value", justify="right")
    table.add_row("policy", escape(m["policy"]))
    table.add_row("iterations run", f"{f['iterations_run']} of {m['settings']['iterations']}")
    table.add_row("wirelength (µm)", f"{f['wirelength_um']:,.1f}")
    table.add_row("vias", f"{f['vias']:,}")
    table.add_row("violations", str(f["violations"]))
    for kind, count in f["violations_by_type"].items():
        if count:
            table.add_row(f"  {kind}", str(count))
    table.add_row("nets (routed / with >= 2 pins)", f"{f['nets_routed']} / {f['nets_checked']}")
    table.add_row("open nets", str(f["open_nets"]), style="red" if f["open_nets"] else None)
    table.add_row("route time (s)", _seconds(f["route_seconds"]))
    table.add_row("total time (s)", _seconds(f["runtime_seconds"]))
    table.add_row("peak memory (MB)", f"{f['peak_rss_mb']:.0f}")
    return table


def route(
    testcase: TestcaseArg = None,
    lef: LefOption = None,
    def_: DefOption = None,
    guide: GuideOption = None,
    out: Annotated[
        Path | None,
        typer.Option("--out", help="Output folder (created if needed). Default: ./out/<design>.", show_default=False),
    ] = None,
    region_size: Annotated[int, typer.Option("--region-size", help="Region side in GCells.")] = DEFAULT_REGION_SIZE,
    iterations: Annotated[
        int, typer.Option("--iterations", help=f"Iteration limit (1..{MAX_ITERATIONS}); stops early at 0 violations.")
    ] = DEFAULT_ITERATIONS,
    threads: Annotated[int, typer.Option("--threads", help="Worker threads (the result does not depend on it).")] = 1,
    policy: Annotated[
        str,
        typer.Option("--policy", help="Net-order policy: heuristic, random, or a .py file defining order(region, features)."),
    ] = "heuristic",
    seed: Annotated[int, typer.Option("--seed", help="Seed of the random policy.")] = 1,
    as_json: Annotated[bool, typer.Option("--json", help="Print the metrics JSON on stdout, nothing else.")] = False,
    quiet: Annotated[bool, typer.Option("--quiet", "-q", help="Print only the final line.")] = False,
) -> None:
    """Route a design (a testcase name, or --lef and --def files) and write <design>.routed.def,
    <design>.metrics.json and <design>.drc.rpt. Without a route guide, the built-in global router
    makes one first. Opens are checked on the written DEF: exit status 0 when there are none, 1
    when some remain."""
    check_design_args(testcase, lef, def_, guide)
    started = time.perf_counter()

    from policies.registry import get_policy
    from xroute_cli.outputs import write_route_outputs
    from xroute_cli.router import route_design

    RouteSettings(region_size=region_size, iterations=iterations, threads=threads, seed=seed)  # fail before loading
    pol = get_policy(policy, seed)
    design = load_design_args(testcase, lef, def_, guide)
    out_dir = out if out is not None else Path("out") / design.name
    out_dir.mkdir(parents=True, exist_ok=True)  # fail before routing, not after

    console = stdout_console()
    mode = "off" if (as_json or quiet) else ("rich" if console.is_terminal else "lines")
    if not design.has_guides:
        from xroute_cli.groute import global_route

        stats = global_route(design)
        if mode != "off":
            typer.echo(f"no route guide for {design.name}: guides from the built-in global router "
                       f"({global_route_summary(stats)})")
    if mode == "lines":
        typer.echo(f"routing {design.name}: {design.counts()['nets']} nets, region size {region_size}, "
                   f"up to {iterations} iterations, {threads} thread(s), policy {pol.name}")
    with ProgressDisplay(console, mode, iterations) as display:
        # A progress callback even when nothing is shown: Ctrl-C is handled there.
        result = route_design(design, region_size=region_size, iterations=iterations, threads=threads,
                              policy=pol, seed=seed, progress=display)
    outputs = write_route_outputs(design, result, out_dir, started=started)

    if as_json:
        print_json(outputs.metrics)
    elif quiet:
        typer.echo(final_line(outputs, out_dir))
    else:
        console.print(summary_table(outputs))
        typer.echo(final_line(outputs, out_dir))
    if outputs.open_nets:
        opens = outputs.final["opens"]
        for o in opens[:MAX_OPENS_PRINTED]:
            typer.echo(f"open net {o['net']}: {o['pin_groups']} unconnected pin groups", err=True)
        if outputs.open_nets > MAX_OPENS_PRINTED:
            typer.echo(f"... and {outputs.open_nets - MAX_OPENS_PRINTED} more (see {outputs.metrics_path})", err=True)
        raise typer.Exit(EXIT_OPENS)
