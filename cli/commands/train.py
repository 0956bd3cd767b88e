"""``xroute train ppo|dqn|imitate|finetune``: train a net-order policy on a testcase's regions (``train`` extra).

``imitate`` trains the set scorer (:mod:`xroute.policies.rl.imitation`) instead: teacher orders
routed on the first pass's training regions in context (``--testcase`` may list several, comma
separated; ``--orders`` random orders besides the heuristic's, ``--workers`` processes; or
``--teacher`` an .npz made before; ``--backend ray`` runs the shards as Ray tasks), then
``--episodes`` gradient steps of imitation; it writes ``teacher.npz``, ``set-final.pt``,
``set.onnx`` (ready for ``--policy``) and ``log.json``.
``finetune`` goes on from there (:mod:`xroute.policies.rl.finetune`): ``--episodes`` iterations of
PPO on the set scorer's own orders routed on the training regions (``--init`` a checkpoint, default
an untrained scorer, whose order is the heuristic's); it writes ``set-final.pt`` (the iteration
best on the validation regions), ``set.onnx`` and ``log.json``. ``--device`` picks the torch device
(``auto``: CUDA when torch sees one; for ppo and dqn it overrides the config's ``device``).

Writes into ``--out`` (default ``runs/train-<algorithm>-<testcase>``): ``metrics.jsonl`` (one line
per episode = region) and checkpoints ``<algorithm>-epNNNNN.pt`` / ``<algorithm>-final.pt``, which
``xroute export`` turns into an ONNX model. Exit status 2 for user errors (unknown testcase, bad
config file, torch not installed).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

from xroute.atomic_files import atomic_write_text
from xroute.cli.console import print_json, stdout_console
from xroute.errors import XrouteError
from xroute.policies.rl.device import DEVICES

ALGORITHMS = ("ppo", "dqn", "imitate", "finetune")


class TrainError(XrouteError):
    """Training cannot start (missing extra, bad option)."""


def parse_location(text: str | None) -> tuple[int, int] | None:
    """``"X,Y"`` (GCell column, row) -> (X, Y)."""
    if text is None:
        return None
    parts = text.split(",")
    try:
        x, y = (int(p) for p in parts)
    except ValueError:
        raise typer.BadParameter(f"expected X,Y (two GCell indices), got {text!r}", param_hint="--region-location")
    if x < 0 or y < 0:
        raise typer.BadParameter(f"GCell indices must be >= 0, got {text!r}", param_hint="--region-location")
    return x, y


def training_env_factory(testcase: str, region_size: int | None, location: tuple[int, int] | None, order: str,
                         max_candidates: int, region_loop: int = 1, hold_out_every: int = 0,
                         min_candidates: int = 1, in_context: bool = False) -> Any:
    """A function making the training env (``xroute/NetOrdering-v0``) for these options, wrapped in
    a :class:`~xroute.policies.rl.region_filter.RegionFilter` when regions are held out or skipped
    (``region_size`` None: 1, or the router's region size in context)."""

    def make() -> Any:
        import gymnasium

        import xroute.envs  # noqa: F401 - registers the env IDs
        from xroute.policies.rl.region_filter import RegionFilter

        env = gymnasium.make("xroute/NetOrdering-v0", disable_env_checker=True, testcase_name=testcase,
                             region_size=region_size, testcase_loop=1_000_000, region_location=location,
                             region_loop=region_loop, max_candidates=max_candidates, region_order=order,
                             in_context=in_context).unwrapped
        if hold_out_every > 0 or min_candidates > 1:
            return RegionFilter(env, hold_out_every, min_candidates)
        return env

    return make


def _require_torch() -> None:
    try:
        import gymnasium  # noqa: F401
        import torch  # noqa: F401
    except ImportError as exc:
        raise TrainError(f"training needs the train extra: pip install 'xroute[train]' ({exc.name} is missing)") from exc


AlgorithmArg = Annotated[str, typer.Argument(
    help="ppo, dqn, imitate or finetune (the set scorer).", show_default=False)]
TestcaseOpt = Annotated[str, typer.Option("--testcase", help="Testcase whose regions are the episodes.")]
EpisodesOpt = Annotated[int, typer.Option(
    "--episodes", min=1, help="Episodes (regions) to train on; imitate: gradient steps; finetune: iterations.")]
OrdersOpt = Annotated[int, typer.Option("--orders", min=1, help="imitate: random teacher orders per region.")]
WorkersOpt = Annotated[int, typer.Option("--workers", min=1, help="imitate, finetune: processes routing orders.")]
TeacherOpt = Annotated[Path | None, typer.Option(
    "--teacher", help="imitate: teacher .npz to train on instead of routing one.", show_default=False)]
InitOpt = Annotated[Path | None, typer.Option(
    "--init", help="finetune: set-scorer checkpoint to start from (set-final.pt).", show_default=False)]
BackendOpt = Annotated[str, typer.Option(
    "--backend", help="imitate, finetune: route in local processes or on Ray (local or ray).")]
RayAddressOpt = Annotated[str | None, typer.Option(
    "--ray-address", help="with --backend ray: the cluster (default: a local Ray instance).", show_default=False)]
ConfigOpt = Annotated[Path | None, typer.Option(
    "--config", help="YAML settings (configs/train-<algorithm>.yaml lists them).", show_default=False)]
OutOpt = Annotated[Path | None, typer.Option(
    "--out", help="Output folder (default: runs/train-<algorithm>-<testcase>).", show_default=False)]
SeedOpt = Annotated[int, typer.Option("--seed", min=0, help="Seed of torch, the env and exploration.")]
SizeOpt = Annotated[int | None, typer.Option(
    "--region-size", min=1, help="Region size in GCells (default 1; in context the router's, 5).", show_default=False)]
LocationOpt = Annotated[str | None, typer.Option(
    "--region-location", help="Train on one region: X,Y of its lower-left GCell.", show_default=False)]
OrderOpt = Annotated[str, typer.Option("--region-order", help="Walk of the regions: sequential or random.")]
LoopOpt = Annotated[int, typer.Option("--region-loop", min=1, help="Episodes per region (replays from one state).")]
HoldOutOpt = Annotated[int, typer.Option(
    "--hold-out-every", min=0,
    help="Hold out regions whose column and row (lower-left GCell / region size) are both K//2 mod K (0: none).")]
InContextOpt = Annotated[bool, typer.Option(
    "--in-context", help="Episodes are regions of the router's first pass, opened with the earlier colours routed.")]
MinCandOpt = Annotated[int, typer.Option("--min-candidates", min=1, help="Skip regions with fewer candidate nets.")]
DeviceOpt = Annotated[str | None, typer.Option(
    "--device", help="Torch device: auto (cuda if present), cpu or cuda (ppo, dqn: overrides the config's).",
    show_default=False)]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print the per-episode log and summary as JSON only.")]


def train(
    algorithm: AlgorithmArg,
    testcase: TestcaseOpt,
    episodes: EpisodesOpt,
    config: ConfigOpt = None,
    out: OutOpt = None,
    seed: SeedOpt = 1,
    region_size: SizeOpt = None,
    region_location: LocationOpt = None,
    region_order: OrderOpt = "sequential",
    region_loop: LoopOpt = 1,
    hold_out_every: HoldOutOpt = 0,
    min_candidates: MinCandOpt = 1,
    in_context: InContextOpt = False,
    json_out: JsonOpt = False,
    orders: OrdersOpt = 8,
    workers: WorkersOpt = 2,
    teacher: TeacherOpt = None,
    init: InitOpt = None,
    backend: BackendOpt = "local",
    ray_address: RayAddressOpt = None,
    device: DeviceOpt = None,
) -> None:
    """Train a PPO or DQN net-order policy (or imitate / finetune: the set scorer) on a testcase's regions."""
    if algorithm not in ALGORITHMS:
        raise typer.BadParameter(f"unknown algorithm {algorithm!r}: use ppo, dqn, imitate or finetune",
                                 param_hint="ALGORITHM")
    if backend not in ("local", "ray"):
        raise typer.BadParameter(f"use local or ray, got {backend!r}", param_hint="--backend")
    if device is not None and device not in DEVICES:
        raise typer.BadParameter(f"use {', '.join(DEVICES[:-1])} or {DEVICES[-1]}, got {device!r}", param_hint="--device")
    if algorithm == "imitate":
        _require_torch()
        _imitate(testcase, episodes, out, seed, region_size, hold_out_every, min_candidates, orders, workers, teacher,
                 backend, ray_address, device or "auto", json_out)
        return
    if algorithm == "finetune":
        _require_torch()
        _finetune(testcase, episodes, out, seed, region_size, hold_out_every, min_candidates, workers, init, backend,
                  ray_address, device or "auto", json_out)
        return
    if region_order not in ("sequential", "random"):
        raise typer.BadParameter(f"use sequential or random, got {region_order!r}", param_hint="--region-order")
    location = parse_location(region_location)
    _require_torch()
    from xroute.policies.rl.train import train as run_training
    from xroute.policies.rl.train_config import load_config
    from xroute.testcases import find_testcase

    cfg = load_config(algorithm, config)
    if device is not None:
        cfg.device = device
    _check_device(cfg.device)
    find_testcase(testcase)  # unknown testcase: one-line error before any work
    out_dir = out or Path("runs") / f"train-{algorithm}-{testcase}"
    make_env = training_env_factory(testcase, region_size, location, region_order, cfg.max_candidates, region_loop,
                                    hold_out_every, min_candidates, in_context)
    console = stdout_console()
    if json_out:
        result = run_training(algorithm, make_env, episodes, cfg, out_dir, seed)
    else:
        with Progress(TextColumn("[bold]train " + algorithm), BarColumn(), MofNCompleteColumn(),
                      TextColumn("{task.fields[status]}"), TimeElapsedColumn(), console=console) as progress:
            task = progress.add_task("episodes", total=episodes, status="")

            def on_episode(row: dict[str, Any]) -> None:
                status = f"steps {row['total_steps']}  last cost {row['cost'] or 0:,.1f}"
                progress.update(task, advance=1, status=status)

            result = run_training(algorithm, make_env, episodes, cfg, out_dir, seed, on_episode)
    costs = [r["cost"] or 0.0 for r in result.episodes]
    summary = {"algorithm": algorithm, "testcase": testcase, "episodes": episodes,
               "steps": result.episodes[-1]["total_steps"] if result.episodes else 0,
               "seconds": round(result.seconds, 2), "mean_cost": sum(costs) / max(1, len(costs)),
               "metrics_log": str(result.out_dir / "metrics.jsonl"), "checkpoint": str(result.final_checkpoint)}
    if json_out:
        print_json({"summary": summary, "episodes": result.episodes})
        return
    console.print(f"trained {algorithm} on {testcase}: {episodes} episodes, {summary['steps']} steps, "
                  f"{summary['seconds']:.1f} s, mean region cost {summary['mean_cost']:,.1f}")
    console.print(f"checkpoint {summary['checkpoint']}  log {summary['metrics_log']}", highlight=False)


def _check_device(name: str) -> None:
    """A one-line error, before any work, for a device torch cannot give (cuda without CUDA)."""
    from xroute.policies.rl.device import pick_device

    try:
        pick_device(name)
    except ValueError as exc:
        raise TrainError(str(exc)) from exc


def _set_scorer_run(testcase: str, device: str) -> list[str]:
    """The testcases of an imitate or finetune run (``testcase``: names, comma separated), each looked up and the
    device checked, so that a bad one is a one-line error before any work; torch on one thread."""
    import torch

    from xroute.testcases import find_testcase

    names = [t.strip() for t in testcase.split(",") if t.strip()]
    for name in names:
        find_testcase(name)
    _check_device(device)
    torch.set_num_threads(1)
    return names


def _imitate(testcase: str, steps: int, out: Path | None, seed: int, region_size: int | None, hold_out_every: int,
             min_candidates: int, orders: int, workers: int, teacher: Path | None, backend: str,
             ray_address: str | None, device: str, json_out: bool) -> None:
    """``xroute train imitate``: teacher orders (or ``--teacher``), imitation, checkpoint and ONNX model."""
    import json
    import time

    from xroute.policies.rl import teacher as teacher_data
    from xroute.policies.rl.imitation import ImitationConfig, train as imitate
    from xroute.policies.rl.set_scorer import export_onnx, save_checkpoint

    names = _set_scorer_run(testcase, device)
    out_dir = out or Path("runs") / f"imitate-{'-'.join(names)}"
    console = stdout_console()
    t0 = time.perf_counter()
    if teacher is not None:
        if not teacher.is_file():
            raise TrainError(f"teacher data not found: {teacher}")
        try:
            regions = teacher_data.load(teacher)
        except (OSError, ValueError, KeyError) as exc:
            raise TrainError(f"{teacher}: not teacher data of xroute train imitate ({exc})") from exc
    else:
        if not json_out:
            console.print(f"routing teacher orders on {', '.join(names)} ({orders} random + heuristic per region, "
                          f"{workers} workers)")
        regions = teacher_data.collect(names, workers=workers, backend=backend, ray_address=ray_address,
                                       region_size=region_size, hold_out_every=hold_out_every, orders=orders,
                                       min_candidates=min_candidates, seed=seed)
    teacher_seconds = time.perf_counter() - t0
    cfg = ImitationConfig(steps=steps, seed=seed, device=device)
    try:
        model, log = imitate(regions, cfg, on_log=None if json_out else lambda row: console.print(
            f"step {row['step']}  loss {row['loss']:.4f}  {row['seconds']:.1f} s", highlight=False))
    except ValueError as exc:
        raise TrainError(str(exc)) from exc
    out_dir.mkdir(parents=True, exist_ok=True)  # after training: a run that fails leaves no folder
    if teacher is None:
        teacher_data.save(regions, out_dir / "teacher.npz")
    save_checkpoint(model, out_dir / "set-final.pt", {"imitation": cfg.__dict__, "log": log})
    onnx_path = export_onnx(model, out_dir / "set.onnx", {"xroute_steps": str(steps),
                                                          "xroute_teacher_regions": str(len(regions))})
    atomic_write_text(out_dir / "log.json", json.dumps(log, indent=1))
    summary = {"algorithm": "imitate", "testcases": names, "teacher_regions": len(regions),
               "teacher_seconds": round(teacher_seconds, 2), "steps": steps,
               "seconds": round(time.perf_counter() - t0, 2), "checkpoint": str(out_dir / "set-final.pt"),
               "model": str(onnx_path)}
    if json_out:
        print_json({"summary": summary, "log": log})
        return
    console.print(f"imitated {len(regions)} teacher regions of {', '.join(names)}: {steps} steps, "
                  f"{summary['seconds']:.1f} s; model {onnx_path}", highlight=False)


def _finetune(testcase: str, iterations: int, out: Path | None, seed: int, region_size: int | None,
              hold_out_every: int, min_candidates: int, workers: int, init: Path | None, backend: str,
              ray_address: str | None, device: str, json_out: bool) -> None:
    """``xroute train finetune``: PPO on the set scorer's orders routed in context; checkpoint and ONNX model."""
    import json
    import pickle
    import time
    from dataclasses import asdict

    from xroute.policies.rl.finetune import FinetuneConfig, finetune
    from xroute.policies.rl.set_scorer import export_onnx, load_checkpoint, save_checkpoint

    names = _set_scorer_run(testcase, device)
    model = None
    if init is not None:
        if not init.is_file():
            raise TrainError(f"checkpoint not found: {init}")
        try:
            model = load_checkpoint(init)
        except (OSError, ValueError, KeyError, RuntimeError, pickle.UnpicklingError) as exc:
            raise TrainError(f"{init}: not a set-scorer checkpoint ({str(exc).splitlines()[0]})") from exc
    out_dir = out or Path("runs") / f"finetune-{'-'.join(names)}"
    console = stdout_console()
    t0 = time.perf_counter()
    cfg = FinetuneConfig(iterations=iterations, seed=seed, region_size=region_size or 0,
                         hold_out_every=hold_out_every, min_candidates=max(2, min_candidates), device=device)

    def show(row: dict[str, Any]) -> None:
        console.print(f"iteration {row['iteration']}  validation cost {row['val_cost']:,.1f} "
                      f"({100 * row['val_vs_heuristic']:+.1f}% vs heuristic)  {row['seconds']:.1f} s", highlight=False)

    try:
        model, log = finetune(names, cfg, model=model, workers=workers, backend=backend, ray_address=ray_address,
                              on_log=None if json_out else show)
    except ValueError as exc:
        raise TrainError(str(exc)) from exc
    out_dir.mkdir(parents=True, exist_ok=True)  # after training: a run that fails leaves no folder
    save_checkpoint(model, out_dir / "set-final.pt", {"finetune": asdict(cfg), "log": log})
    onnx_path = export_onnx(model, out_dir / "set.onnx", {"xroute_finetune_iterations": str(iterations)})
    atomic_write_text(out_dir / "log.json", json.dumps(log, indent=1))
    best = min(log, key=lambda row: row["val_cost"]) if log else None
    summary = {"algorithm": "finetune", "testcases": names, "iterations": iterations,
               "seconds": round(time.perf_counter() - t0, 2), "checkpoint": str(out_dir / "set-final.pt"),
               "model": str(onnx_path), "best_iteration": best["iteration"] if best else None,
               "val_vs_heuristic": best["val_vs_heuristic"] if best else None}
    if json_out:
        print_json({"summary": summary, "log": log})
        return
    console.print(f"fine-tuned on {', '.join(names)}: {iterations} iterations, {summary['seconds']:.1f} s; "
                  f"kept iteration {summary['best_iteration']}; model {onnx_path}", highlight=False)
