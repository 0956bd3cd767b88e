"""Helpers for tests that draw tiny designs: LEF/DEF text written to a temporary folder and
loaded, contest inputs loaded straight from ../shared/testcases, and int32 shape rows.

Imported as ``from drawn import ...`` (pytest puts tests/ on ``sys.path``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from xroute import _engine

TESTCASES = Path(__file__).resolve().parents[1].parent / "shared" / "testcases"


def write_design(tmp_path: Path, lef_text: str, def_text: str, stem: str = "tiny",
                 def_stem: str | None = None) -> tuple[Path, Path]:
    """Writes ``<stem>.lef`` and ``<def_stem or stem>.def`` under tmp_path; returns their paths."""
    lef = tmp_path / f"{stem}.lef"
    lef.write_text(lef_text)
    def_ = tmp_path / f"{def_stem or stem}.def"
    def_.write_text(def_text)
    return lef, def_


def load_drawn(tmp_path: Path, lef_text: str, def_text: str, stem: str = "tiny", def_stem: str | None = None) -> Any:
    """The engine Database of the LEF and DEF text (written as by :func:`write_design`)."""
    lef, def_ = write_design(tmp_path, lef_text, def_text, stem, def_stem)
    return _engine.load([str(lef)], str(def_))


def contest_input(name: str) -> Path:
    """``<testcases>/<name>/<name>.input`` (add .lef, .def), or skip the test when its DEF is missing."""
    base = TESTCASES / name / f"{name}.input"
    if not Path(str(base) + ".def").exists():
        pytest.skip(f"{name} not available")
    return base


def load_contest(name: str) -> Any:
    """The engine Database of a contest design's LEF and DEF (no guide), or skip."""
    base = contest_input(name)
    return _engine.load([str(base) + ".lef"], str(base) + ".def")


def shape_rows(rows: Any) -> np.ndarray:
    """(layer, xlo, ylo, xhi, yhi, net) rows as an int32 array shaped (n, 6), also when empty."""
    return np.array(rows, dtype=np.int32).reshape(-1, 6)
