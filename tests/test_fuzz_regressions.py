"""Inputs found by the libFuzzer targets (fuzz/fuzz.sh), kept as regression files.

Every file under tests/fuzz_regressions/<lef|def|guide>/ goes through the Python
API: a LEF alone, a DEF with the ispd18_sample LEF, a guide with the ispd18_sample
LEF and DEF (without the contest data: tests/data/lef/sample_names.lef, a LEF with the same
names, and the generated stand-in of ispd18_sample for the guides). Each must either load or raise xroute.errors.InputError with the
fuzz file and a line inside it - never crash, hang or raise anything else. A DEF
that loads must also survive the round trip the DEF fuzz target checks: written
back, re-read, and equal.

The DEF files named after a bug (see test_fixed_bugs) failed the round trip
before that bug was fixed: no_design_statement.def is the fuzzer's minimized
crash; the other three are minimal hand-written inputs of the same bug classes
(the fuzzer's own were not kept, or, for quoted names, found by reviewing the
code after those crashes). The other files are libFuzzer corpus inputs that
reach error paths of the readers.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import pick, require_testcase, sample_lef
from xroute import _engine
from xroute.errors import InputError

HERE = Path(__file__).resolve().parent / "fuzz_regressions"


def _files(kind: str) -> list[Path]:
    return sorted(p for p in (HERE / kind).iterdir() if p.is_file())


def _loads_or_input_error(path: Path, load):
    """What ``load()`` returns, or None after an InputError."""
    try:
        return load()
    except InputError as e:
        # The error names a file we passed; if it is the fuzz input, the line lies inside it.
        if Path(e.path) == path:
            lines = path.read_bytes().count(b"\n") + 1
            assert 0 <= e.line <= lines, f"{e} (the file has {lines} lines)"
        return None


def test_there_are_regression_files() -> None:
    assert all(_files(kind) for kind in ("lef", "def", "guide"))


@pytest.mark.parametrize("path", _files("lef"), ids=lambda p: p.name)
def test_lef(path: Path) -> None:
    _loads_or_input_error(path, lambda: _engine.load_lef([str(path)]))


@pytest.mark.parametrize("path", _files("def"), ids=lambda p: p.name)
def test_def(path: Path, tmp_path: Path) -> None:
    lef = str(sample_lef())
    db = _loads_or_input_error(path, lambda: _engine.load([lef], str(path)))
    if db is not None:
        out = tmp_path / "written.def"
        db.write_def(str(out))
        assert db.compare(_engine.load([lef], str(out))) == []


@pytest.mark.parametrize("path", _files("guide"), ids=lambda p: p.name)
def test_guide(path: Path) -> None:
    sample = require_testcase(pick("ispd18_sample"))
    _loads_or_input_error(path, lambda: _engine.load([str(sample.lef)], str(sample.def_), str(path)))


def test_fixed_bugs(tmp_path: Path) -> None:
    """The DEF round-trip bugs the fuzzer found, each with its exact outcome now."""
    lef = str(sample_lef())
    # A DEF without DESIGN was read with an empty name and written as "DESIGN  ;".
    with pytest.raises(InputError) as e:
        _engine.load([lef], str(HERE / "def" / "no_design_statement.def"))
    assert (e.value.line, e.value.message) == (2, "missing DESIGN statement before END DESIGN")
    # An unquoted DIVIDERCHAR holding a '"' was written inside quotes and broke the file.
    with pytest.raises(InputError) as e:
        _engine.load([lef], str(HERE / "def" / "dividerchar_with_quote.def"))
    assert e.value.line == 2 and "divider character in double quotes" in e.value.message
    # A quoted (here empty) name was kept and written without quotes: "DESIGN  ;".
    with pytest.raises(InputError) as e:
        _engine.load([lef], str(HERE / "def" / "quoted_design_name.def"))
    assert (e.value.line, e.value.message) == (1, "expected a design name, found the quoted string ''")
    # A DEF without UNITS and DIEAREA was written with "UNITS DISTANCE MICRONS 0", which did not re-read.
    db = _engine.load([lef], str(HERE / "def" / "no_units_no_diearea.def"))
    assert (db.design_name, db.dbu_per_micron, db.die_area) == ("d", 0, (0, 0, 0, 0))
    text = db.def_text()
    assert "UNITS" not in text and "DIEAREA" not in text and "DESIGN d ;" in text
