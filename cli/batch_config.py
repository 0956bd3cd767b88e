"""The YAML of ``xroute batch``: a matrix of testcases x policies x settings, and the gates.

Example (configs/batch.yaml documents every key)::

    testcases: [ispd18_sample, ispd18_sample2]
    policies: [heuristic, random]
    settings:
      - {name: rs5}
      - {name: rs3, region_size: 3, iteration_count: 4}
    gates: {max_violations: 0, max_opens: 0, max_wirelength_increase_pct: 2.0,
            baseline: baselines/ci-smoke.json}

Each job routes one testcase with one policy and one settings entry; a settings entry overrides
the base config (``config:``, a file like configs/default.yaml; defaults without one).
"""

from __future__ import annotations

import os
from collections import Counter
from dataclasses import dataclass

from xroute.config import CHECKS, ScheduleEntry, XrouteConfig, load_config
from xroute.config_schema import Context, load_sections, setting
from xroute.router import MAX_ITERATIONS


def check_name(value: str, ctx: Context) -> tuple[str, str | None]:
    if not value or any(not (c.isalnum() or c in "-_.") for c in value) or value.startswith("."):
        return value, f"name {value!r} may hold only letters, digits, '-', '_' and '.' (it names folders)"
    return value, None


BATCH_CHECKS = {**CHECKS, "name": check_name}


@dataclass(frozen=True)
class SettingsEntry:
    """One column of the matrix: a name and the settings it overrides (None: the base config's)."""

    name: str = setting(check="name")
    region_size: int | None = setting(None, min=0, max=1000, unit="GCells")
    iteration_count: int | None = setting(None, min=1, max=MAX_ITERATIONS)
    thread_count: int | None = setting(None, min=1, max=1024)
    seed: int | None = setting(None, min=0, max=2**64 - 1)
    iteration_schedule: tuple[ScheduleEntry, ...] | None = None


@dataclass(frozen=True)
class Gates:
    """Thresholds checked on every finished job (None: not checked). Figures are those of the written DEF."""

    max_violations: int | None = setting(None, min=0)
    max_opens: int | None = setting(None, min=0)
    max_wirelength_increase_pct: float | None = setting(None, min=0.0, unit="% over the baseline")
    max_vias_increase_pct: float | None = setting(None, min=0.0, unit="% over the baseline")
    baseline: str | None = setting(None, check="input_file", help="JSON written by `xroute batch --write-baseline`")

    def __post_init__(self) -> None:
        if (self.max_wirelength_increase_pct is not None or self.max_vias_increase_pct is not None) and not self.baseline:
            raise ValueError("max_wirelength_increase_pct and max_vias_increase_pct need a baseline file (gates.baseline)")


@dataclass(frozen=True)
class BatchFile:
    """The batch YAML as written."""

    testcases: tuple[str, ...] = setting(min_items=1, items={"check": "testcase"})
    policies: tuple[str, ...] = setting(("heuristic",), min_items=1, items={"check": "policy"})
    settings: tuple[SettingsEntry, ...] = ()  # empty: one entry named "default" with the base config's settings
    config: str | None = setting(None, check="input_file", help="base config (like configs/default.yaml)")
    jobs: int = setting(1, min=1, max=256, help="parallel jobs (processes); --jobs overrides")
    out_dir: str = setting("runs/batch", check="output_dir", help="relative to the current directory (~ expanded); "
                           "--out overrides")
    gates: Gates = Gates()

    def __post_init__(self) -> None:
        names = [s.name for s in self.settings]
        dupes = sorted(n for n, k in Counter(names).items() if k > 1)  # linear in the entries
        if dupes:
            raise ValueError(f"settings names must be unique, repeated: {', '.join(dupes)}")


@dataclass(frozen=True)
class BatchConfig:
    """A loaded batch: the file's content and its base config."""

    path: str
    batch: BatchFile
    base: XrouteConfig


def load_batch_config(path: str | os.PathLike[str]) -> BatchConfig:
    """Loads and validates a batch YAML and the base config it names. Raises ConfigError."""
    batch = load_sections(BatchFile, path, BATCH_CHECKS)
    base = load_config(batch.config)
    return BatchConfig(path=str(path), batch=batch, base=base)
