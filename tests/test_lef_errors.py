"""LEF reader on bad input: every error is an InputError naming the file and
the exact line of the offending token (marked "# <-- here" in each snippet).
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from xroute import _engine
from lef_text import TECH, write_lef
from xroute.errors import InputError


def marked_line(text: str, marker: str = "<-- here") -> int:
    """1-based line of the (comment) marker in the dedented text."""
    lines = textwrap.dedent(text).lstrip("\n").splitlines()
    return next(i for i, line in enumerate(lines, 1) if marker in line)


def load_error(tmp_path: Path, text: str) -> InputError:
    path = write_lef(tmp_path, text)
    with pytest.raises(InputError) as info:
        _engine.load_lef([path])
    assert info.value.path == path
    return info.value


# ------------------------------------------------------------- bad input --

BAD_INPUTS = {
    "truncated inside a layer": (True, """
        LAYER M3
          TYPE ROUTING ;
          WIDTH 0.1 ;   # <-- here
        """, "unexpected end of file inside LAYER 'M3' (opened at line 36)"),
    "truncated inside a statement": (True, """
        MACRO X
          SIZE 1 BY   # <-- here
        """, "unexpected end of file inside MACRO 'X'"),
    "truncated inside a pin port": (True, """
        MACRO X
          PIN A
            PORT
              LAYER M1 ;
              RECT 0 0 1 1 ;   # <-- here
        """, "unexpected end of file inside PORT"),
    "garbage where a number belongs": (True, """
        LAYER M3
          TYPE ROUTING ;
          WIDTH 0.1x ;   # <-- here
        END M3
        """, "expected a number, found '0.1x'"),
    "name where a number belongs": (True, """
        MACRO X
          SIZE 1 BY ONE ;   # <-- here
        END X
        """, "expected a number, found 'ONE'"),
    "number where a layer name belongs": (True, """
        LAYER 3   # <-- here
          TYPE ROUTING ;
        END 3
        """, "expected a layer name, found the number '3'"),
    "number where a statement belongs": (True, """
        LAYER M3
          TYPE ROUTING ;
          0.5 0.5 ;   # <-- here
        END M3
        """, "expected a statement in LAYER, found '0.5'"),
    "unknown layer in a via": (True, """
        VIA V23
          LAYER M2 ;
            RECT 0 0 1 1 ;
          LAYER V2 ;   # <-- here
        END V23
        """, "unknown layer 'V2'"),
    "unknown layer in a pin": (True, """
        MACRO X
          PIN A
            PORT
              LAYER Metal1 ;   # <-- here
            END
          END A
        END X
        """, "unknown layer 'Metal1'"),
    "unknown via in a pin": (True, """
        MACRO X
          PIN A
            PORT
              VIA 0 0 V99 ;   # <-- here
            END
          END A
        END X
        """, "unknown via 'V99'"),
    "unknown site in a macro": (True, """
        MACRO X
          SITE CoreSite ;   # <-- here
        END X
        """, "unknown site 'CoreSite'"),
    "unknown layer in a via rule": (True, """
        VIARULE R GENERATE
          LAYER M9 ;   # <-- here
        END R
        """, "unknown layer 'M9'"),
    "END name mismatch": (True, """
        LAYER M3
          TYPE ROUTING ;
        END M2   # <-- here
        """, "END 'M2' does not close LAYER 'M3' (opened at line 36)"),
    "END pin name mismatch": (True, """
        MACRO X
          PIN A
          END B   # <-- here
        END X
        """, "END 'B' does not close PIN 'A'"),
    "duplicate layer": (True, """
        LAYER M1   # <-- here
          TYPE ROUTING ;
        END M1
        """, "duplicate LAYER 'M1'"),
    "RECT before LAYER": (True, """
        MACRO X
          OBS
            RECT 0 0 1 1 ;   # <-- here
          END
        END X
        """, "RECT before LAYER in OBS"),
    "WIDTH before TYPE": (False, """
        UNITS
          DATABASE MICRONS 1000 ;
        END UNITS
        LAYER M1
          WIDTH 0.1 ;   # <-- here
        END M1
        """, "WIDTH before TYPE in LAYER 'M1'"),
    "layer without TYPE": (False, """
        LAYER M1   # <-- here
          PROPERTY LEF58_TYPE "TYPE DIFFUSION ;" ;
        END M1
        """, "LAYER 'M1' has no TYPE"),
    "unknown layer TYPE": (False, """
        LAYER M1
          TYPE WIRE ;   # <-- here
        END M1
        """, "unknown layer TYPE 'WIRE'"),
    "bad UNITS value": (False, """
        UNITS
          DATABASE MICRONS 0 ;   # <-- here
        END UNITS
        """, "UNITS DATABASE MICRONS must be a positive integer, found '0'"),
    "garbage UNITS value": (False, """
        UNITS
          DATABASE MICRONS many ;   # <-- here
        END UNITS
        """, "expected a number, found 'many'"),
    "length before UNITS": (False, """
        VERSION 5.8 ;
        MANUFACTURINGGRID 0.005 ;
        UNITS
          DATABASE MICRONS 2000 ;   # <-- here
        END UNITS
        """, "UNITS DATABASE MICRONS 2000 after a length at line 2, read with the default of 1000"),
    "short spacing table row": (True, """
        LAYER M3
          TYPE ROUTING ;
          SPACINGTABLE
            PARALLELRUNLENGTH 0 0.5
            WIDTH 0 0.1
            WIDTH 0.2 0.1 0.2 ;   # <-- here
        END M3
        """, "SPACINGTABLE row WIDTH 0 has 1 spacing values, expected 2"),
    "bad number inside LEF58_CORNERSPACING": (True, """
        LAYER M3
          TYPE ROUTING ;
          PROPERTY LEF58_CORNERSPACING "CORNERSPACING CONVEXCORNER
            WIDTH 0.0 SPACING zero ;" ;   # <-- here
        END M3
        """, "in LEF58_CORNERSPACING: expected a number, found 'zero'"),
    "missing semicolon": (True, """
        LAYER M3
          TYPE ROUTING ;
          WIDTH 0.1 0.2 ;   # <-- here
        END M3
        """, "expected ';', found '0.2'"),
    "bad END LIBRARY": (True, """
        END LIBRARIES   # <-- here
        """, "expected END LIBRARY"),
}


@pytest.mark.parametrize("case", sorted(BAD_INPUTS))
def test_bad_input_names_the_line(tmp_path, case):
    with_tech, snippet, message = BAD_INPUTS[case]
    # TECH is 35 lines, so a snippet after it starts on line 36.
    text = (TECH if with_tech else "") + textwrap.dedent(snippet).lstrip("\n")
    err = load_error(tmp_path, text)
    assert err.line == marked_line(text), err
    assert message in err.message


def test_units_differing_from_an_earlier_file(tmp_path):
    tech = write_lef(tmp_path, TECH, "tech.lef")
    cells = write_lef(tmp_path, "UNITS\n  DATABASE MICRONS 2000 ;\nEND UNITS\n", "cells.lef")
    # LEF lengths are microns whatever a file's UNITS: OpenROAD keeps the first units and warns.
    db = _engine.load_lef([tech, cells])
    assert db.lef_dbu_per_micron == 1000
    assert db.warnings() == [f"{cells}:2: UNITS DATABASE MICRONS 2000 differs from 1000 read before: "
                             "lengths are converted with 1000"]
    same = write_lef(tmp_path, "UNITS\n  DATABASE MICRONS 1000 ;\nEND UNITS\n", "same.lef")
    assert _engine.load_lef([tech, same]).lef_dbu_per_micron == 1000


def test_duplicate_across_files(tmp_path):
    tech = write_lef(tmp_path, TECH, "tech.lef")
    again = write_lef(tmp_path, "VERSION 5.8 ;\nVIA V12\nEND V12\n", "again.lef")
    with pytest.raises(InputError) as info:
        _engine.load_lef([tech, again])
    assert (info.value.path, info.value.line) == (again, 2)
    assert "duplicate VIA 'V12'" in info.value.message


def test_missing_file(tmp_path):
    missing = str(tmp_path / "nope.lef")
    with pytest.raises(InputError) as info:
        _engine.load_lef([missing])
    assert (info.value.path, info.value.line) == (missing, 0)
