"""``xroute batch``: run a matrix of testcases x policies x settings, write summaries, check gates.

Exit status: 0 when every job finished and passed its gates; 1 when a job failed (error) or a
gate failed (each named on stderr: ``gate failed: job <id>: <figure> > <gate> <limit>``);
2 for a bad batch file (one line naming the file, line and key).
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Annotated, Any, Callable

import typer
from rich.markup import escape
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn
from rich.table import Table

from xroute.cli.console import json_output, stdout_console
from xroute.cli.options import JsonOption, QuietOption
from xroute.cli.progress import output_mode

EXIT_FAILED = 1


class BatchDisplay:
    """Rich progress (one bar per running job: iteration, regions, violations), plain lines, or nothing."""

    def __init__(self, console: Any, mode: str, total: int) -> None:
        self.console, self.mode, self.total = console, mode, total
        self.progress: Progress | None = None
        self.tasks: dict[str, Any] = {}
        self.done = 0

    def __enter__(self) -> BatchDisplay:
        if self.mode == "rich":
            self.progress = Progress(SpinnerColumn(), TextColumn("[bold]{task.description}"), BarColumn(),
                                     TextColumn("{task.fields[status]}"), TimeElapsedColumn(), console=self.console)
            self.progress.__enter__()
            self.tasks["_all"] = self.progress.add_task("jobs", total=self.total, status=f"0/{self.total}")
        return self

    def __exit__(self, *exc: Any) -> None:
        if self.progress is not None:
            self.progress.__exit__(*exc)

    def line(self, text: str) -> None:
        if self.mode == "lines":
            typer.echo(text)
        elif self.progress is not None:
            self.progress.console.print(escape(text))

    def on_start(self, job: Any) -> None:
        if self.mode == "lines":
            typer.echo(f"{job.id}: started")
        elif self.progress is not None and job.id not in self.tasks:
            self.tasks[job.id] = self.progress.add_task(job.id, total=1, status="")

    def on_event(self, ev: tuple) -> None:
        job_id, iteration, done, total, violations, iteration_done, text = ev
        if iteration_done:
            self.line(f"{job_id}: {text}")
        if self.progress is not None and job_id in self.tasks:
            viol = "" if violations is None else f"violations {violations}"
            self.progress.update(self.tasks[job_id], completed=done, total=max(total, 1),
                                 status=f"iteration {iteration}  regions {done}/{total}  {viol}".rstrip())

    def on_done(self, job: Any, record: dict[str, Any]) -> None:
        self.done += 1
        if record["status"] == "done":
            f = record["summary"]["final"]
            text = (f"{job.id}: done in {record['seconds']:.1f} s: WL {f['wirelength_um']:,.1f} um, {f['vias']:,} vias, "
                    f"{f['violations']} violations, {f['open_nets']} opens")
        else:
            text = f"{job.id}: ERROR: {record['message']}"
        self.line(f"[{self.done}/{self.total}] {text}")
        if self.progress is not None:
            if job.id in self.tasks:
                self.progress.remove_task(self.tasks.pop(job.id))
            self.progress.update(self.tasks["_all"], completed=self.done, status=f"{self.done}/{self.total}")


def summary_table(doc: dict[str, Any]) -> Table:
    table = Table(title=f"xroute batch {escape(doc['batch'])}", title_justify="left")
    for col, right in (("job", False), ("WL (µm)", True), ("vias", True), ("DRVs", True), ("opens", True),
                       ("route (s)", True), ("cost", True), ("gates", False)):
        table.add_column(col, justify="right" if right else "left")
    for r in doc["jobs"]:
        if r["status"] != "done":
            table.add_row(escape(r["id"]), "", "", "", "", "", "", f"[red]ERROR[/red] {escape(r['message'])}")
            continue
        gates = "[red]FAIL[/red]" if r["gate_failures"] else "pass"
        table.add_row(escape(r["id"]) + (" (resumed)" if r["resumed"] else ""), f"{r['wirelength_um']:,.1f}",
                      f"{r['vias']:,}", str(r["violations"]), str(r["open_nets"]), f"{r['route_seconds']:.2f}",
                      f"{r['cost']:,.1f}", gates)
    return table


def batch(
    batch_file: Annotated[Path, typer.Argument(help="Batch YAML (see configs/batch.yaml).", show_default=False)],
    jobs: Annotated[int | None, typer.Option("--jobs", "-j", help="Parallel jobs (processes). Default: the file's jobs, else 1.",
                                             show_default=False, min=1)] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Output folder. Default: the file's out_dir.",
                                             show_default=False)] = None,
    backend: Annotated[str, typer.Option("--backend", help="local (processes on this machine) or ray (optional extra).")] = "local",
    ray_address: Annotated[str | None, typer.Option("--ray-address", help="Existing Ray cluster (with --backend ray); "
                                                    "default: start a local Ray instance.", show_default=False)] = None,
    force: Annotated[bool, typer.Option("--force", help="Rerun every job, even those already finished.")] = False,
    write_baseline: Annotated[Path | None, typer.Option("--write-baseline", help="Also write the figures of this run "
                                                        "as a baseline file for the wirelength/vias gates.",
                                                        show_default=False)] = None,
    as_json: JsonOption = False,
    quiet: QuietOption = False,
) -> None:
    """Run a batch matrix of testcases x policies x settings, with summaries, JUnit and gates.

    Runs every job in parallel processes (or Ray tasks) and writes OUT/summary.json, summary.csv, summary.md and junit.xml (one testcase per job). Jobs whose
    folder OUT/jobs/<job id> already holds a finished result with the same settings are skipped
    (resumable); an interrupted job leaves no partial folder. Gates in the YAML (max_violations,
    max_opens, max_wirelength_increase_pct over a baseline file, ...) make the exit status 1 and name
    the failing job and gate.

    Example (CI): CI=true xroute batch configs/ci-smoke.yaml --jobs 2
    """
    from xroute.cli.batch import BatchProgress, completed_record
    from xroute.cli.batch_config import load_batch_config
    from xroute.cli.batch_summary import baseline_doc, load_baseline, write_summary
    from xroute.atomic_files import atomic_write_text

    if backend not in ("local", "ray"):
        raise typer.BadParameter("use local or ray", param_hint="--backend")
    if write_baseline is not None:
        from xroute.regular_files import check_output

        check_output(write_baseline, "baseline file")  # refused before any job runs
    cwd = Path.cwd()  # the output folder is resolved against it, whatever a policy's code (a thread's os.chdir) does later
    cfg = load_batch_config(batch_file)
    baseline = load_baseline(cfg.batch.gates.baseline)
    if backend == "ray" and ray_address:
        from xroute.ray_backend import check_address

        check_address(ray_address)  # an unreachable cluster fails at once, before OUT is made
    console = stdout_console()
    mode = output_mode(console, as_json=as_json, quiet=quiet, configured=cfg.base.output.mode)
    # From here on stdout is the JSON's alone with --json: policies are loaded (and may print) next.
    shown = out if out is not None else Path(cfg.batch.out_dir)  # as printed
    out_root = cwd / shown
    with json_output(mode == "json") as print_json:
        job_list = _checked_jobs(cfg)
        _prepare_out(out_root)
        workers = jobs if jobs is not None else cfg.batch.jobs
        wall = time.perf_counter()
        resumed = {} if force else {j.id: r for j in job_list if (r := completed_record(out_root, j)) is not None}
        todo = [j for j in job_list if j.id not in resumed]
        display = BatchDisplay(console, mode if mode in ("rich", "lines") else "off", len(todo))
        if mode == "lines":
            typer.echo(f"batch {batch_file}: {len(job_list)} jobs ({len(resumed)} already done), {workers} parallel, "
                       f"backend {backend} -> {shown}")
        with display:
            progress = BatchProgress(on_start=display.on_start, on_event=display.on_event, on_done=display.on_done)
            records = _run(backend, todo, out_root, workers, progress, ray_address)

        doc = summary_doc(batch_file, shown, backend, time.perf_counter() - wall, cfg, job_list, resumed, records,
                          baseline)
        paths = write_summary(out_root, doc)
        if write_baseline is not None:
            atomic_write_text(write_baseline, json.dumps(baseline_doc(doc), indent=2) + "\n")
        _print_summary(console, mode, batch_file, doc, {k: shown / p.name for k, p in paths.items()}, print_json)
    if not doc["passed"]:
        raise typer.Exit(EXIT_FAILED)


def _checked_jobs(cfg: Any) -> list[Any]:
    """The batch's jobs; every job's settings and every policy checked before the first job starts."""
    from xroute.cli.batch import plan_jobs
    from xroute.policies import get_policy

    job_list = plan_jobs(cfg)  # every job's settings checked (run_settings)
    for spec in dict.fromkeys(job.run.policy for job in job_list):
        get_policy(spec)
    return job_list


def _prepare_out(out_root: Path) -> None:
    """Creates OUT/jobs and removes what killed batches left (partial job folders, temporaries such
    as .summary.json.<pid>.<hex>.tmp)."""
    from xroute.cli.batch import clean_stale_job_folders
    from xroute.outputs import clean_stale_temporaries

    (out_root / "jobs").mkdir(parents=True, exist_ok=True)
    clean_stale_job_folders(out_root)
    clean_stale_temporaries(out_root)


def _run(backend: str, todo: list[Any], out_root: Path, workers: int, progress: Any,
         ray_address: str | None) -> dict[str, Any]:
    if backend == "ray":
        from xroute.cli.batch_ray import run_ray

        return run_ray(todo, out_root, workers, progress, ray_address)
    from xroute.cli.batch import run_local

    return run_local(todo, out_root, workers, progress)


def summary_doc(batch_file: Path, out_root: Path, backend: str, wall_seconds: float, cfg: Any, job_list: list[Any],
                resumed: dict[str, Any], records: dict[str, Any], baseline: Any) -> dict[str, Any]:
    """summary.json: one row per job (resumed or run now) with its gate failures, the counts."""
    from xroute.cli.batch_summary import check_gates, job_row

    rows = []
    for job in job_list:
        row = job_row(resumed.get(job.id) or records[job.id], resumed=job.id in resumed)
        row["gate_failures"] = check_gates(row, cfg.batch.gates, baseline)
        rows.append(row)
    failed = [r for r in rows if r["gate_failures"]]
    errors = [r for r in rows if r["status"] != "done"]
    return {
        "format": 1,
        "batch": str(batch_file),
        "out_dir": str(out_root),
        "backend": backend,
        "wall_seconds": wall_seconds,
        "counts": {"jobs": len(rows), "failed": len(failed), "errors": len(errors), "resumed": len(resumed)},
        "passed": not failed and not errors,
        "jobs": rows,
    }


def _print_summary(console: Any, mode: str, batch_file: Path, doc: dict[str, Any], paths: dict[str, Path],
                   print_json: Callable[[Any], None]) -> None:
    rows = doc["jobs"]
    failed = [r for r in rows if r["gate_failures"]]
    errors = [r for r in rows if r["status"] != "done"]
    if mode == "json":
        print_json(doc)
    elif mode != "quiet":
        console.print(summary_table(doc))
    if mode != "json":
        typer.echo(f"batch {batch_file}: {len(rows)} jobs, {len(failed)} failed gates, {len(errors)} errors, "
                   f"{doc['counts']['resumed']} resumed, {doc['wall_seconds']:.1f} s -> {paths['md']}, {paths['junit']}")
    for r in errors:
        typer.echo(f"job failed: {r['id']}: {r['message']}", err=True)
    for r in failed:
        for message in r["gate_failures"]:
            typer.echo(f"gate failed: {message}", err=True)
