"""The one routing pipeline: load -> global route when there is no guide -> detailed route ->
write and check the outputs.

``xroute route``, ``evaluate``, ``batch`` and the evaluation environment all go through these
functions, so a design without a route guide gets the built-in global router's guides whichever
of them routes it, and every run's outputs are written and checked the same way.

The library never prints: progress goes to the optional callback.
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Sequence

from xroute.design import Design, load_design
from xroute.groute import global_route
from xroute.outputs import RouteOutputs, clean_stale_temporaries, write_route_outputs
from xroute import router
from xroute.router import RouteProgress, RouteResult, RouterSettings

if TYPE_CHECKING:
    from xroute.net_order import NetOrderPolicy
    from xroute.schedule import SchedulePolicy

PathLike = str | os.PathLike[str]


def prepare_design(
    testcase: str | None = None,
    *,
    lef: PathLike | Sequence[PathLike] | None = None,
    def_: PathLike | None = None,
    guide: PathLike | None = None,
) -> Design:
    """Loads a design (a testcase name, or ``lef=``/``def_=`` files) ready for detailed routing:
    when it has no route guide, the built-in global router gives it one (its figures are then in
    ``design.global_route_stats``, and ``design.guide_source == "built-in"``)."""
    design = load_design(testcase, lef=lef, def_=def_, guide=guide)
    if not design.has_guides:
        global_route(design)
    return design


def route(
    design: Design,
    settings: RouterSettings,
    policy: str | NetOrderPolicy = "heuristic",
    progress: Callable[[RouteProgress], None] | None = None,
    schedule_policy: SchedulePolicy | None = None,
    *,
    seed: int = 1,
    policy_timeout: float | None = None,
) -> RouteResult:
    """Detailed-routes a prepared design in place with ``settings``, ``policy`` (each region's net
    order; ``seed`` and ``policy_timeout`` as :func:`xroute.router.route_design` takes them) and
    ``schedule_policy`` (each iteration's plan; None: the settings' rule)."""
    # looked up on the module: tests may replace it
    return router.route_design(design, settings=settings, policy=policy, progress=progress,
                               schedule_policy=schedule_policy, seed=seed, policy_timeout=policy_timeout)


def route_to_outputs(
    design: Design,
    out_dir: PathLike,
    settings: RouterSettings,
    policy: str | NetOrderPolicy = "heuristic",
    progress: Callable[[RouteProgress], None] | None = None,
    started: float | None = None,
    schedule_policy: SchedulePolicy | None = None,
    *,
    seed: int = 1,
    policy_timeout: float | None = None,
) -> RouteOutputs:
    """Routes a prepared design and writes the routed DEF, metrics JSON and DRC report into
    ``out_dir`` (created if needed; leftovers of a killed run cleaned first), checked on the
    written DEF. ``started`` (a ``time.perf_counter()`` value) counts loading in the run time."""
    from xroute.outputs import output_paths
    from xroute.regular_files import check_output, make_output_folder

    started = time.perf_counter() if started is None else started
    out = make_output_folder(out_dir)
    for path in output_paths(out, design.name):
        check_output(path)  # a folder, FIFO or device there: refused before routing
    clean_stale_temporaries(out)
    result = route(design, settings, policy, progress, schedule_policy, seed=seed, policy_timeout=policy_timeout)
    return write_route_outputs(design, result, out, started=started)


def run(
    testcase: str,
    out_dir: PathLike,
    settings: RouterSettings,
    policy: str | NetOrderPolicy = "heuristic",
    progress: Callable[[RouteProgress], None] | None = None,
    *,
    seed: int = 1,
    policy_timeout: float | None = None,
) -> RouteOutputs:
    """The whole pipeline for a testcase name: prepare, route, write and check."""
    started = time.perf_counter()
    design = prepare_design(testcase)
    return route_to_outputs(design, out_dir, settings, policy, progress, started=started, seed=seed,
                            policy_timeout=policy_timeout)
