"""``xroute route``: route a design, write the routed DEF, metrics JSON and DRC report, check opens.

Exit status: 0 when the written DEF has no open net, 1 when opens remain (they are listed on
stderr), 2 for user errors (bad files, unknown testcase or policy, invalid settings).
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

import typer
from rich.markup import escape
from rich.table import Table

from xroute.cli.console import (
    DefOption,
    GuideOption,
    LefOption,
    TestcaseArg,
    check_design_args,
    counted,
    json_output,
    load_design_args,
    print_read_warnings,
    print_unmodelled_rules,
    stdout_console,
)
from xroute.cli.options import (
    ConfigOption,
    IterationsOption,
    JsonOption,
    NetRouterOption,
    OutOption,
    PolicyOption,
    QuietOption,
    RepairRoundsOption,
    RegionSizeOption,
    ScheduleOption,
    SchedulePolicyOption,
    SearchBudgetOption,
    SeedOption,
    ThreadsOption,
)
from xroute.cli.progress import ProgressDisplay, output_mode

if TYPE_CHECKING:
    from rich.console import Console

    from xroute.config import RunSettings, XrouteConfig
    from xroute.groute import GlobalRouteStats
    from xroute.outputs import RouteOutputs

EXIT_OPENS = 1
MAX_OPENS_PRINTED = 20


def parse_schedule(text: str) -> tuple[tuple[int, int], ...]:
    """``'5:0,5:2'`` -> ``((5, 0), (5, 2))``; a malformed step raises RouteArgumentError."""
    from xroute.router import RouteArgumentError

    steps = []
    for item in text.split(","):
        size, sep, offset = item.strip().partition(":")
        try:
            steps.append((int(size), int(offset) if sep else 0))
        except ValueError:
            raise RouteArgumentError(f"--schedule: '{item.strip()}' is not SIZE:OFFSET (two integers, GCells)") from None
    return tuple(steps)


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
        f"{outputs.metrics['design']}: {status}: {counted(f['nets'], 'net')}, {f['open_nets']} open, "
        f"{counted(f['violations'], 'violation')}, WL {f['wirelength_um']:,.1f} um, {counted(f['vias'], 'via')}, "
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
    config: ConfigOption = None,
    out: OutOption = None,
    region_size: RegionSizeOption = None,
    iterations: IterationsOption = None,
    threads: ThreadsOption = None,
    repair_rounds: RepairRoundsOption = None,
    policy: PolicyOption = None,
    search_budget: SearchBudgetOption = None,
    seed: SeedOption = None,
    schedule: ScheduleOption = None,
    schedule_policy: SchedulePolicyOption = None,
    net_router: NetRouterOption = None,
    as_json: JsonOption = False,
    quiet: QuietOption = False,
) -> None:
    """Route a design and write the routed DEF, metrics JSON and DRC report.

    The design is a testcase name, or --lef and --def files (nothing: the shipped demo); the
    outputs are <design>.routed.def, <design>.metrics.json and <design>.drc.rpt. Without a route
    guide, the built-in global router makes one first. Opens are checked on the written DEF: exit
    status 0 when there are none, 1 when some remain.

    Settings come from --config (YAML, see configs/default.yaml) when given; flags override it.
    On a terminal a Rich progress bar shows the iteration, regions done and current violations;
    when stdout is not a terminal (or CI=true) one plain line per iteration is printed instead.
    """
    from xroute.config import load_config, run_settings

    cfg = load_config(config)  # validated before anything else
    cwd = Path.cwd()  # the output folder is resolved against it, whatever a policy's code does later
    if testcase is None and not lef and def_ is None:
        testcase = cfg.testcase.testcase_name
    if testcase is None and not lef and def_ is None and guide is None:
        from xroute.testcases import DEMO

        testcase = DEMO
    check_design_args(testcase, lef, def_, guide)
    if net_router is not None and policy is not None:
        raise typer.BadParameter("--net-router routes the nets itself (in the heuristic order): not with --policy",
                                 param_hint="--net-router")
    if net_router is not None and not net_router.is_file():
        raise typer.BadParameter(f"no such model file: {net_router}", param_hint="--net-router")
    started = time.perf_counter()
    steps = parse_schedule(schedule) if schedule is not None else None
    rs = run_settings(cfg, region_size=region_size, iterations=iterations, threads=threads, policy=policy, seed=seed,
                      repair_rounds=repair_rounds, search_budget=search_budget,
                      schedule=steps, schedule_policy=schedule_policy)  # checked: fails before loading
    console = stdout_console()
    mode = output_mode(console, as_json=as_json, quiet=quiet, configured=cfg.output.mode)
    with json_output(mode == "json") as print_json:  # stdout holds the JSON only, whatever a policy prints
        outputs, out_dir, pol = _route(cfg, rs, mode, console, (testcase, lef, def_, guide), out, cwd,
                                       net_router, started)
        _report(outputs, out_dir, pol, mode, console, net_router is not None, print_json)


def _route(cfg: XrouteConfig, rs: RunSettings, mode: str, console: Console,
           design_args: tuple[str | None, list[Path] | None, Path | None, Path | None], out: Path | None, cwd: Path,
           net_router: Path | None, started: float) -> tuple[RouteOutputs, Path, Any]:
    """Loads the policies and the design, routes and writes the outputs: (outputs, out_dir, policy)."""
    from xroute import pipeline
    from xroute.policies import get_policy, get_schedule_policy
    from xroute.regular_files import make_output_folder
    from xroute.safe_paths import safe_stem

    pol = get_policy(rs.policy, rs.seed, rs.search_budget)
    planner = get_schedule_policy(rs.schedule_policy)
    design = load_design_args(*design_args, prepare=True)
    print_read_warnings(design)
    if net_router is not None:
        from xroute.policies.net_router import NetRouterPolicy

        pol = NetRouterPolicy(net_router, design.dbu_per_micron)
    if out is None and cfg.output.out_dir is not None:
        out = Path(cfg.output.out_dir)
    out_dir = out if out is not None else Path("out") / safe_stem(design.name)  # as printed
    write_dir = make_output_folder(cwd / out_dir)  # fail before routing, not after
    print_unmodelled_rules(design)  # here, not at reading: a bad argument's error stays one line
    if design.global_route_stats is not None and mode in ("rich", "lines"):
        typer.echo(f"no route guide for {design.name}: guides from the built-in global router "
                   f"({global_route_summary(design.global_route_stats)})")
    if mode == "lines":
        # The size a run resolves for 0 comes with each iteration's line: resolving it here would
        # compute the design's pin access twice (4.0 s on ispd19_test3, 2026-11-27).
        size = rs.router.region_size or "auto"
        typer.echo(f"routing {design.name}: {design.counts()['nets']} nets, region size {size}, "
                   f"up to {rs.router.iterations} iterations, {rs.router.threads} thread(s), policy {pol.name}")
    with ProgressDisplay(console, mode, rs.router.iterations) as display:
        # A progress callback even when nothing is shown: Ctrl-C is handled there.
        outputs = pipeline.route_to_outputs(design, write_dir, rs.router, pol, progress=display, started=started,
                                            schedule_policy=planner, seed=rs.seed, policy_timeout=rs.policy_timeout)
    return outputs, out_dir, pol


def _report(outputs: RouteOutputs, out_dir: Path, pol: Any, mode: str, console: Console, net_router: bool,
            print_json: Callable[[Any], None]) -> None:
    """What the command prints once the outputs are written; exit status 1 when opens remain."""
    if net_router and mode in ("rich", "lines"):
        st = pol.stats
        typer.echo(f"net router: {st['agent_connected']} nets connected by the model, "
                   f"{st['astar_fallback']} taken over by A*")
    if mode == "json":
        print_json(outputs.metrics)
    elif mode == "quiet":
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
