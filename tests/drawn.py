"""Helpers for tests that draw tiny designs: LEF/DEF text written to a temporary folder and
loaded, contest inputs (found on the testcase search path) loaded without guide, and int32 shape rows.

Imported as ``from drawn import ...`` (pytest puts tests/ on ``sys.path``).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from xroute import _engine


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
    """The testcase's files without their .lef / .def suffix (``<folder>/<name>.input`` for contest
    files, ``<folder>/<name>`` for generated ones) from the search path, or skip the test."""
    from conftest import require_testcase

    found = require_testcase(name)
    base = found.def_.with_suffix("")
    assert found.lef == base.with_suffix(base.suffix + ".lef")
    return base


def load_contest(name: str) -> Any:
    """The engine Database of a contest design's LEF and DEF (no guide), or skip."""
    base = contest_input(name)
    return _engine.load([str(base) + ".lef"], str(base) + ".def")


def shape_rows(rows: Any) -> np.ndarray:
    """(layer, xlo, ylo, xhi, yhi, net) rows as an int32 array shaped (n, 6), also when empty."""
    return np.array(rows, dtype=np.int32).reshape(-1, 6)
