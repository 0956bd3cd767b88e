"""PLACEHOLDER registry: replaced by the full one (published sizes, static regions)."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from xroute_cli.errors import TestcaseNotFound

ENV_VAR = "XROUTE_TESTCASES"


@dataclass(frozen=True)
class KnownTestcase:
    name: str


@dataclass(frozen=True)
class StaticRegion:
    name: str


@dataclass(frozen=True)
class FoundTestcase:
    name: str
    folder: Path
    lef: Path
    def_: Path
    guide: Path | None


KNOWN_TESTCASES: tuple[KnownTestcase, ...] = ()
STATIC_REGIONS: tuple[StaticRegion, ...] = ()


def search_path() -> list[Path]:
    paths = [Path(p) for p in os.environ.get(ENV_VAR, "").split(os.pathsep) if p]
    paths.append(Path(__file__).resolve().parent.parent.parent / "shared" / "testcases")
    return paths


def find_testcase(name: str) -> FoundTestcase:
    for root in search_path():
        folder = root / name
        lef, def_, guide = (folder / f"{name}.input.{ext}" for ext in ("lef", "def", "guide"))
        if lef.is_file() and def_.is_file():
            return FoundTestcase(name, folder, lef, def_, guide if guide.is_file() else None)
    raise TestcaseNotFound(f"testcase {name} not found")
