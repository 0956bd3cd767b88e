"""One routing run from settings to written outputs (through :mod:`xroute.pipeline`), shared by evaluate and batch.

The library never prints: progress goes to the optional callback.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

if TYPE_CHECKING:
    from xroute.config import CostSection, RunSettings
    from xroute.outputs import RouteOutputs
    from xroute.router import RouteProgress


def route_testcase(testcase: str, settings: RunSettings, out_dir: str | Path,
                   progress: Callable[[RouteProgress], None] | None = None) -> RouteOutputs:
    """Routes ``testcase`` with ``settings`` through the pipeline and writes the checked outputs into ``out_dir``."""
    from xroute import pipeline
    from xroute.policies import get_policy

    out_dir = Path(out_dir).absolute()  # before the policy's code runs (it may call os.chdir)
    policy = get_policy(settings.policy, settings.seed)
    return pipeline.run(testcase, out_dir, settings.router, policy, progress, seed=settings.seed,
                        policy_timeout=settings.policy_timeout)


def run_summary(outputs: RouteOutputs, cost: CostSection) -> dict[str, Any]:
    """The figures of a run for tables and JSON: per iteration (router's view) and final (checked DEF),
    each with the paper's cost."""
    m = outputs.metrics
    f = m["final"]
    iterations = [
        {
            "iteration": it["iteration"],
            "region_size": it.get("region_size"),
            "offset": it.get("offset"),
            "wirelength_um": it["wirelength_um"],
            "vias": it["vias"],
            "violations": it["violations"],
            "violations_by_type": it["violations_by_type"],
            "seconds": it["seconds"],
            "cost": cost.cost(it["wirelength_um"], it["vias"], it["violations"]),
        }
        for it in m["iterations"]
    ]
    policy_seconds = f.get("policy_seconds")
    route_seconds = f["route_seconds"]
    return {
        "policy": m["policy"],
        "out_dir": str(outputs.metrics_path.parent),
        "metrics": str(outputs.metrics_path),
        "iterations": iterations,
        "final": {
            "wirelength_um": f["wirelength_um"],
            "vias": f["vias"],
            "violations": f["violations"],
            "violations_by_type": f["violations_by_type"],
            "open_nets": f["open_nets"],
            "route_seconds": route_seconds,
            "runtime_seconds": f["runtime_seconds"],
            "policy_seconds": policy_seconds,
            "policy_share": (policy_seconds / route_seconds) if policy_seconds is not None and route_seconds > 0 else None,
            "cost": cost.cost(f["wirelength_um"], f["vias"], f["violations"]),
        },
    }


def safe_name(text: str) -> str:
    """A file-name-safe version of a policy or job name."""
    keep = "".join(c if c.isalnum() or c in "-_." else "-" for c in Path(text).name)
    return keep.strip(".-") or "run"


def policy_label(spec: str) -> str:
    """A policy's short name for folders and tables: a built-in's name, a policy file's stem."""
    p = Path(spec)
    return safe_name(p.stem if p.suffix else spec)
