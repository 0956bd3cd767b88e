"""``xroute evaluate``: route a testcase with a policy and with a baseline, compare them side by side.

Like Table 1 of the XRoute paper: per iteration the wirelength (µm), vias, design-rule
violations (DRVs) and runtime (s) of both runs, then the final figures checked on each written
DEF and the paper cost (0.5·WL + 4·vias + 500·violations by default; weights from ``--config``; xroute.glossary).
Writes ``evaluation.json`` and each run's routed DEF, metrics JSON and DRC report in its own
subfolder of ``--out``. Exit status: 0, or 1 when either written DEF has open nets.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any, Callable

import typer
from rich.markup import escape
from rich.table import Table

from xroute.cli.console import TestcaseArg, json_output, stdout_console
from xroute.cli.options import (
    ConfigOption,
    IterationsOption,
    JsonOption,
    OutOption,
    QuietOption,
    RegionSizeOption,
    SeedOption,
    ThreadsOption,
)
from xroute.cli.progress import ProgressDisplay, output_mode

from xroute.config import CostSection
from xroute.glossary import COST_NAME, cost_line

EVALUATION_FORMAT = 1


def comparison_table(testcase: str, runs: dict[str, dict[str, Any]], glossary: str = "") -> Table:
    """Per iteration WL / vias / DRVs / runtime of each run side by side, then final and paper cost rows;
    ``glossary``: the paper cost's line (xroute.glossary) under the table."""
    labels = list(runs)
    table = Table(title=f"{escape(testcase)}: " + " vs ".join(f"{k} ({escape(v['policy'])})" for k, v in runs.items()),
                  title_justify="left", caption=escape("final: checked on the written DEF" +
                                                       (f"; {glossary}" if glossary else "")),
                  caption_justify="left")
    table.add_column("iteration", justify="right")
    for label in labels:
        for col in ("WL (µm)", "vias", "DRVs", "time (s)"):
            table.add_column(f"{label}\n{col}", justify="right")
    depth = max(len(r["iterations"]) for r in runs.values())
    for i in range(depth):
        row = [str(i)]
        for label in labels:
            its = runs[label]["iterations"]
            if i < len(its):
                it = its[i]
                row += [f"{it['wirelength_um']:,.1f}", f"{it['vias']:,}", f"{it['violations']:,}", f"{it['seconds']:.2f}"]
            else:
                row += ["", "", "", ""]
        table.add_row(*row)
    final = ["final"]
    cost = [COST_NAME]
    for label in labels:
        f = runs[label]["final"]
        final += [f"{f['wirelength_um']:,.1f}", f"{f['vias']:,}", f"{f['violations']:,}", f"{f['route_seconds']:.2f}"]
        cost += [f"{f['cost']:,.1f}", "", "", ""]
    table.add_row(*final, style="bold", end_section=False)
    table.add_row(*cost, style="bold")
    return table


def policy_share_line(label: str, final: dict[str, Any]) -> str:
    if final["policy_seconds"] is None:
        return f"{label}: built-in policy (runs inside the engine; its time is not measured separately)"
    return (f"{label}: {final['policy_seconds']:.3f} s in the policy of {final['route_seconds']:.2f} s routing "
            f"({100 * final['policy_share']:.1f}%)")


def evaluate(
    testcase: TestcaseArg = None,
    policy: Annotated[str, typer.Option("--policy", help="Policy to evaluate: heuristic, random, or a policy file.")] = ...,
    baseline: Annotated[str, typer.Option("--baseline", help="Policy to compare with.")] = "heuristic",
    config: ConfigOption = None,
    out: OutOption = None,
    region_size: RegionSizeOption = None,
    iterations: IterationsOption = None,
    threads: ThreadsOption = None,
    seed: SeedOption = None,
    as_json: JsonOption = False,
    quiet: QuietOption = False,
) -> None:
    """Compare a net-order policy with a baseline on one testcase (like the XRoute paper's Table 1).

    Routes TESTCASE with --policy and with --baseline (default heuristic) under the same settings and
    prints, per iteration, wirelength, vias, DRVs and runtime of both side by side, the final figures
    checked on each written DEF, the paper cost (0.5·WL + 4·vias + 500·violations) and the share of
    routing time spent in a Python/ONNX policy. Writes <out>/evaluation.json and each run's outputs
    in <out>/policy-<name>/ and <out>/baseline-<name>/ (default out: ./out/evaluate/<testcase>).

    Example: xroute evaluate --policy examples/python_heuristic_policy.py ispd18_sample --iterations 3
    """
    from xroute.config import load_config
    from xroute.atomic_files import atomic_write_text
    from xroute.cli.runs import policy_label, route_testcase, run_summary

    cfg = load_config(config)
    name = testcase or cfg.testcase.testcase_name
    if name is None:
        raise typer.BadParameter("give a testcase name (or testcase_name in --config)", param_hint="TESTCASE")
    specs = {"policy": policy, "baseline": baseline}
    console = stdout_console()
    mode = output_mode(console, as_json=as_json, quiet=quiet, configured=cfg.output.mode)
    with json_output(mode == "json") as print_json:  # stdout holds the JSON only, whatever a policy prints
        settings = _checked_settings(cfg, specs, name, region_size=region_size, iterations=iterations,
                                     threads=threads, seed=seed)
        if out is None:
            out = Path(cfg.output.out_dir) if cfg.output.out_dir else Path("out") / "evaluate" / name
        out.mkdir(parents=True, exist_ok=True)
        runs: dict[str, dict[str, Any]] = {}
        for label, rs in settings.items():
            folder = out / f"{label}-{policy_label(specs[label])}"
            if mode == "lines":
                typer.echo(f"{label}: routing {name} with policy {specs[label]} -> {folder}")
            with ProgressDisplay(console, mode, rs.router.iterations, label=label) as display:
                outputs = route_testcase(name, rs, folder, progress=display)
            runs[label] = {"spec": specs[label], **run_summary(outputs, cfg.cost)}

        doc = evaluation_doc(name, settings["policy"], cfg.cost, runs)
        path = out / "evaluation.json"
        atomic_write_text(path, json.dumps(doc, indent=2) + "\n")
        _print_evaluation(console, mode, doc, policy, baseline, path, print_json)
    pf, bf = runs["policy"]["final"], runs["baseline"]["final"]
    if pf["open_nets"] or bf["open_nets"]:
        typer.echo(f"open nets: policy {pf['open_nets']}, baseline {bf['open_nets']}", err=True)
        raise typer.Exit(1)


def _checked_settings(cfg: Any, specs: dict[str, str], name: str, **flags: Any) -> dict[str, Any]:
    """Each run's settings (config overridden by the flags, checked by run_settings); both policies and
    the testcase are checked before the first route too."""
    from xroute.config import run_settings
    from xroute.policies import get_policy
    from xroute.testcases.registry import find_testcase

    settings = {k: run_settings(cfg, policy=v, **flags) for k, v in specs.items()}
    for rs in settings.values():
        get_policy(rs.policy, rs.seed)
    find_testcase(name)
    return settings


def evaluation_doc(name: str, settings: Any, cost: Any, runs: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """evaluation.json: the settings, the cost weights, both runs and their differences."""
    pf, bf = runs["policy"]["final"], runs["baseline"]["final"]
    return {
        "format": EVALUATION_FORMAT,
        "testcase": name,
        "settings": {k: v for k, v in settings.to_dict().items() if k != "policy"},
        "cost_weights": {"wirelength_um": cost.wirelength_weight, "via": cost.via_weight,
                         "violation": cost.drv_weight},
        "runs": runs,
        "comparison": {
            "cost_delta": pf["cost"] - bf["cost"],  # policy minus baseline (negative: the policy is better)
            "wirelength_delta_um": pf["wirelength_um"] - bf["wirelength_um"],
            "vias_delta": pf["vias"] - bf["vias"],
            "violations_delta": pf["violations"] - bf["violations"],
            "route_seconds_ratio": pf["route_seconds"] / bf["route_seconds"] if bf["route_seconds"] > 0 else None,
        },
    }


def _print_evaluation(console: Any, mode: str, doc: dict[str, Any], policy: str, baseline: str, path: Path,
                      print_json: Callable[[Any], None]) -> None:
    runs = doc["runs"]
    pf, bf = runs["policy"]["final"], runs["baseline"]["final"]
    c = doc["comparison"]
    verdict = (f"{doc['testcase']}: policy {policy} {COST_NAME} {pf['cost']:,.1f} vs baseline {baseline} {bf['cost']:,.1f} "
               f"(delta {c['cost_delta']:+,.1f}; DRVs {pf['violations']} vs {bf['violations']}) -> {path}")
    if mode == "json":
        print_json(doc)
    elif mode == "quiet":
        typer.echo(verdict)
    else:
        w = doc["cost_weights"]
        weights = CostSection(wirelength_weight=w["wirelength_um"], via_weight=w["via"], drv_weight=w["violation"])
        console.print(comparison_table(doc["testcase"], runs, cost_line(weights)))
        for label in runs:
            typer.echo(policy_share_line(label, runs[label]["final"]))
        typer.echo(verdict)
