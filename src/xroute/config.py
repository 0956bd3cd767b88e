"""xroute's settings as YAML: ``load_config("configs/default.yaml")`` -> :class:`XrouteConfig`.

One section per concern (``testcase``, ``region``, ``router``, ``policy``, ``cost``, ``output``),
each a frozen dataclass whose fields carry the XRoute paper's parameter names
(``testcase_name``, ``testcase_loop``, ``region_size``, ``region_location``, ``region_loop``,
``iteration_count``, ``thread_count``, ``net_loop``) and the cost weights (0.5 per µm of
wirelength, 4 per via, 500 per design-rule violation). ``configs/default.yaml`` documents every
key with its unit and default. The file is validated once, when loaded; any problem raises
:class:`~xroute.config_schema.ConfigError` with the file, the line and the dotted key.

Paths *read* from a config (policy files, baseline files) are relative to the config file's
folder; output folders are relative to the current directory. A leading ``~`` is expanded in both,
as the shell expands it on the command line.

Other commands compose these sections with their own into a dataclass and load it with
:func:`xroute.config_schema.load_sections` (passing :data:`CHECKS`), e.g.::

    @dataclass(frozen=True)
    class TrainConfig:
        testcase: TestcaseSection = TestcaseSection()
        region: RegionSection = RegionSection()
        ppo: PpoSection = PpoSection()          # their own section

    cfg = load_sections(TrainConfig, "configs/train_ppo.yaml", CHECKS)
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Literal

from xroute.config_schema import ConfigError, Context, load_sections, setting
from xroute.errors import XrouteError, did_you_mean
from xroute.defaults import (MAX_REGION_SIZE, MAX_REPAIR_ROUNDS, MAX_SEARCH_BUDGET, MAX_THREADS, REGION_COST_WEIGHTS,
                             REPAIR_ROUNDS, SEARCH_BUDGET)
from xroute.router import (DEFAULT_ITERATIONS, DEFAULT_REGION_SIZE, MAX_ITERATIONS, RouterSettings, check_seed,
                           router_settings)

__all__ = [
    "CHECKS",
    "ConfigError",
    "CostSection",
    "OutputSection",
    "PolicySection",
    "RegionSection",
    "RouterSection",
    "RunSettings",
    "ScheduleEntry",
    "TestcaseSection",
    "XrouteConfig",
    "load_config",
    "run_settings",
]


# -- checks run on values (name -> function), shared with other commands' configs -------------------
def check_testcase(value: str, ctx: Context) -> tuple[Any, str | None]:
    from xroute.testcases.registry import find_testcase
    from xroute.errors import TestcaseNotFound

    try:
        find_testcase(value)
    except TestcaseNotFound:
        return value, f"testcase '{value}' not found on the search path (see `xroute testcases`)"
    return value, None


def check_policy(value: str, ctx: Context) -> tuple[Any, str | None]:
    """A built-in policy name stays as it is; anything else is a policy file, which must be
    readable (relative to the config file's folder). Its format is checked when it is loaded."""
    from xroute.net_order import BUILTIN_POLICIES, is_builtin_name  # noqa: F401 - both used below

    if is_builtin_name(value):
        if value.startswith("best-of-") and not 1 <= int(value[len("best-of-"):]) <= MAX_SEARCH_BUDGET:
            return value, f"best-of-K: K must be in 1..{MAX_SEARCH_BUDGET}, got {value!r}"
        return value, None
    path = ctx.resolve(value)
    if not path.suffix and os.sep not in value and "/" not in value and not path.exists():
        names = ", ".join(BUILTIN_POLICIES)
        return value, (f"unknown policy '{value}'{did_you_mean(value, BUILTIN_POLICIES)}: use {names}, best-of-K, "
                       "or the path of a policy file (.py, .onnx)")
    if os.path.lexists(path) and not path.is_file():
        return value, f"policy file {path} is not a file"
    if not path.is_file():
        return value, f"policy file not found: {path}"
    try:
        with open(path, "rb") as f:
            f.read(1)
    except OSError as exc:
        return value, f"policy file {path} is not readable: {exc.strerror or exc}"
    return str(path), None


def check_schedule_policy(value: str, ctx: Context) -> tuple[Any, str | None]:
    """``rule`` stays as it is; anything else is a schedule policy file (.py or a .json model,
    relative to the config file's folder) that must be readable. It is checked when it is loaded."""
    if value == "rule":
        return value, None
    path = ctx.resolve(value)
    if path.suffix.lower() not in (".py", ".json"):
        return value, (f"unknown schedule policy '{value}': use rule, the path of a .py file defining plan(history, rule) "
                       "or a .json schedule model")
    if os.path.lexists(path) and not path.is_file():
        return value, f"schedule policy file {path} is not a regular file"
    if not path.is_file():
        return value, f"schedule policy file not found: {path}"
    if not os.access(path, os.R_OK):
        return value, f"schedule policy file is not readable: {path}"
    return str(path), None


def check_input_file(value: str, ctx: Context) -> tuple[Any, str | None]:
    path = ctx.resolve(value)
    if os.path.lexists(path) and not path.is_file():
        return value, f"{path} is not a regular file"
    if not path.is_file():
        return value, f"file not found: {path}"
    if not os.access(path, os.R_OK):
        return value, f"file is not readable: {path}"
    return str(path), None


def check_output_dir(value: str, ctx: Context) -> tuple[Any, str | None]:
    """An output folder: ``~`` expanded as the shell does for a command-line path; a relative one
    stays relative to the current directory (not the file's folder). Checked when it is created."""
    return os.path.expanduser(value), None


CHECKS = {"testcase": check_testcase, "policy": check_policy, "schedule_policy": check_schedule_policy,
          "input_file": check_input_file, "output_dir": check_output_dir}


# -- sections ----------------------------------------------------------------------------------------
@dataclass(frozen=True)
class TestcaseSection:
    """Which design (XRoute: testcase_name, testcase_loop)."""

    __test__ = False  # not a pytest test class
    testcase_name: str | None = setting(None, check="testcase", help="testcase on the search path")
    testcase_loop: int = setting(1, min=1, help="passes over the testcase's regions (training environments)")


@dataclass(frozen=True)
class RegionSection:
    """How the design is cut into regions (XRoute: region_size, region_location, region_loop)."""

    region_size: int = setting(DEFAULT_REGION_SIZE, min=0, max=MAX_REGION_SIZE, unit="GCells", help="0: auto")
    region_location: tuple[int, int] | None = setting(None, items={"min": 0}, unit="GCell index (x, y)")
    region_loop: int = setting(1, min=1, help="episodes per region (training environments)")

    def __post_init__(self) -> None:
        if self.region_location is not None and min(self.region_location) < 0:
            raise ValueError(f"region_location must be GCell indices >= 0, got {list(self.region_location)}")


@dataclass(frozen=True)
class ScheduleEntry:
    """One iteration of an iteration schedule: its region size and region offset."""

    region_size: int = setting(min=1, max=MAX_REGION_SIZE, unit="GCells")
    offset: int = setting(0, min=0, unit="GCells")

    def __post_init__(self) -> None:
        if self.region_size is not None and self.offset is not None and self.offset >= self.region_size:
            raise ValueError(f"offset {self.offset} must be smaller than region_size {self.region_size}")


@dataclass(frozen=True)
class RouterSection:
    """The routing flow (XRoute: iteration_count, thread_count, net_loop)."""

    iteration_count: int = setting(DEFAULT_ITERATIONS, min=1, max=MAX_ITERATIONS)
    thread_count: int = setting(1, min=1, max=MAX_THREADS)
    repair_rounds: int = setting(REPAIR_ROUNDS, min=0, max=MAX_REPAIR_ROUNDS,
                                 help="check-and-reroute rounds inside each region (iterations after the first)")
    net_loop: int = setting(1, min=1, help="orderings of each region's nets per visit (training environments)")
    iteration_schedule: tuple[ScheduleEntry, ...] = ()  # empty: region_size with the default offsets
    schedule_policy: str | None = setting(None, check="schedule_policy",
                                          help="each iteration's plan: rule, or a .py file defining plan(history, rule)")


@dataclass(frozen=True)
class PolicySection:
    """The net-order policy."""

    policy: str = setting("heuristic", check="policy")
    seed: int = setting(1, min=0, max=2**64 - 1)
    call_timeout: float = setting(300.0, min=0.0, max=86400.0, unit="seconds",
                                  help="time limit of one order() call of a policy file (0: none)")
    search_budget: int = setting(SEARCH_BUDGET, min=1, max=MAX_SEARCH_BUDGET,
                                 help="trial routings per region of the rollout and victims policies (and bestof's K)")


@dataclass(frozen=True)
class CostSection:
    """The XRoute paper's cost: wirelength_weight * WL(µm) + via_weight * vias + drv_weight * DRVs.

    Commands, reports and the environments' rewards use it. The defaults are the engine's
    (RegionCostWeights, engine_cpp/order/search_policy.hpp); the rollout / victims / best-of-K searches score
    trial routings with those defaults, not with values changed here."""

    wirelength_weight: float = setting(REGION_COST_WEIGHTS[0], min=0.0, unit="per µm")
    via_weight: float = setting(REGION_COST_WEIGHTS[1], min=0.0, unit="per via")
    drv_weight: float = setting(REGION_COST_WEIGHTS[2], min=0.0, unit="per violation")

    def cost(self, wirelength_um: float, vias: int, violations: int) -> float:
        return self.wirelength_weight * wirelength_um + self.via_weight * vias + self.drv_weight * violations

    def region_cost(self, metrics: dict[str, Any], dbu_per_micron: int) -> float:
        """The cost of a region's metrics (``Region.metrics()``: wirelength in DBU, vias, violations)."""
        wl_um = float(metrics["wirelength_dbu"]) / max(1, int(dbu_per_micron))
        return self.cost(wl_um, int(metrics["vias"]), int(metrics["violations"]))


@dataclass(frozen=True)
class OutputSection:
    """Where results go and how progress is shown."""

    out_dir: str | None = setting(None, check="output_dir", help="default ./out/<design>; ~ is expanded")
    mode: Literal["auto", "rich", "lines", "quiet", "json"] = "auto"


@dataclass(frozen=True)
class XrouteConfig:
    """The whole configuration (every section optional; defaults as in configs/default.yaml)."""

    testcase: TestcaseSection = TestcaseSection()
    region: RegionSection = RegionSection()
    router: RouterSection = RouterSection()
    policy: PolicySection = PolicySection()
    cost: CostSection = CostSection()
    output: OutputSection = OutputSection()


def load_config(path: str | os.PathLike[str] | None) -> XrouteConfig:
    """The validated config in ``path`` (None: all defaults). Raises ConfigError."""
    if path is None:
        return XrouteConfig()
    return load_sections(XrouteConfig, path, CHECKS)


# -- the settings of one routing run: config values, overridden by command-line flags -----------------
@dataclass(frozen=True)
class RunSettings:
    """What one routing run uses (after the command-line flags override the config): the engine's
    settings struct and what only Python knows (none of these is a field of RouterSettings). Built by
    :func:`run_settings`, which checks every value; ``router`` is not to be changed afterwards."""

    router: RouterSettings  # region size, iterations, threads, schedule, repair rounds (the engine's own struct)
    policy: str = "heuristic"  # a name or a policy file path
    seed: int = 1  # of the random policy and of the searches' random orders
    net_loop: int = 1
    policy_timeout: float | None = None  # seconds per policy call (None: the default)
    search_budget: int = SEARCH_BUDGET  # trial routings per region (rollout, victims; bestof's K)
    schedule_policy: str | None = None  # "rule", a schedule policy file, or None (the rule)

    def to_dict(self) -> dict[str, Any]:
        r = self.router
        return {"region_size": r.region_size, "iterations": r.iterations, "threads": r.threads,
                "policy": self.policy, "seed": self.seed, "schedule": [list(s) for s in r.schedule],
                "net_loop": self.net_loop, "repair_rounds": r.repair_rounds, "search_budget": self.search_budget,
                "schedule_policy": self.schedule_policy}


def run_settings(cfg: XrouteConfig, *, region_size: int | None = None, iterations: int | None = None,
                 threads: int | None = None, policy: str | None = None, seed: int | None = None,
                 schedule: tuple[tuple[int, int], ...] | None = None,
                 repair_rounds: int | None = None, search_budget: int | None = None,
                 schedule_policy: str | None = None) -> RunSettings:
    """The run's settings: each flag that was given (not None) overrides the config value. Every value is
    checked here (the flags are not checked before): RouteArgumentError for a routing setting out of the
    engine's limits (:func:`xroute.router.router_settings`), XrouteError for ``net_loop`` above 1."""
    if cfg.router.net_loop != 1:
        raise XrouteError(f"net_loop {cfg.router.net_loop}: the full-design router orders each region's nets "
                          "once per visit; net_loop > 1 applies to the training environments only")
    if schedule is None:
        schedule = tuple((e.region_size, e.offset) for e in cfg.router.iteration_schedule)
    router = router_settings(
        region_size=region_size if region_size is not None else cfg.region.region_size,
        iterations=iterations if iterations is not None else cfg.router.iteration_count,
        threads=threads if threads is not None else cfg.router.thread_count,
        schedule=schedule or None,
        repair_rounds=repair_rounds if repair_rounds is not None else cfg.router.repair_rounds,
    )
    return RunSettings(
        router=router,
        policy=policy if policy is not None else cfg.policy.policy,
        seed=check_seed(seed if seed is not None else cfg.policy.seed),
        net_loop=cfg.router.net_loop,
        policy_timeout=cfg.policy.call_timeout,
        search_budget=search_budget if search_budget is not None else cfg.policy.search_budget,
        schedule_policy=schedule_policy if schedule_policy is not None else cfg.router.schedule_policy,
    )
