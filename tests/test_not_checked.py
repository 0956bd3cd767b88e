"""The rules a LEF states that the checker does not judge are named, never silently passed.

A drawn LEF states, besides rules the checker models (SPACING, a cut SPACING), one of each kind the
reader keeps or skips without judging: a skipped statement (MINSTEP, ENCLOSURE), a skipped form
(SPACING ... NOTCHLENGTH, SPACINGTABLE TWOWIDTHS), an antenna ratio and a density limit, LEF58
properties (LEF58_SPACING, LEF58_MINSTEP, a CONCAVECORNER corner spacing) and a value kept for the
router only (MINWIDTH). Electrical values (RESISTANCE, THICKNESS), the parameters of another
rule (ANTENNAMODEL, DENSITYCHECKWINDOW), a cut layer's PITCH and the rules of a masterslice layer
are not listed. ``xroute check`` prints one "not checked" line per rule and carries the list in its JSON;
``xroute info`` lists the same.
"""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from xroute.cli.app import app

LEF = """VERSION 5.8 ;
UNITS
  DATABASE MICRONS 1000 ;
END UNITS
LAYER NW
  TYPE MASTERSLICE ;
  PROPERTY LEF58_TYPE "TYPE NWELL ;" ;
  MINSTEP 0.3 ;
END NW
LAYER M1
  TYPE ROUTING ;
  DIRECTION HORIZONTAL ;
  PITCH 0.2 ;
  WIDTH 0.1 ;
  SPACING 0.1 ;
  SPACING 0.2 NOTCHLENGTH 0.3 ;
  MINSTEP 0.05 ;
  RESISTANCE RPERSQ 0.38 ;
  THICKNESS 0.1 ;
  ANTENNAMODEL OXIDE1 ;
  ANTENNACUMAREARATIO 400 ;
  MAXIMUMDENSITY 70 ;
  DENSITYCHECKWINDOW 700 700 ;
  PROPERTY LEF58_SPACING "SPACING 0.1 SAMEMASK ;" ;
END M1
LAYER V1
  TYPE CUT ;
  WIDTH 0.1 ;
  PITCH 0.2 ;
  SPACING 0.1 ;
  ENCLOSURE BELOW 0.01 0.02 ;
END V1
LAYER M2
  TYPE ROUTING ;
  DIRECTION VERTICAL ;
  PITCH 0.2 ;
  WIDTH 0.1 ;
  MINWIDTH 0.1 ;
  SPACINGTABLE TWOWIDTHS WIDTH 0.0 0.1 WIDTH 0.2 0.2 ;
  PROPERTY LEF58_CORNERSPACING "CORNERSPACING CONCAVECORNER WIDTH 0.0 SPACING 0.1 ;" LEF58_MINSTEP "MINSTEP 0.05 ;" ;
  MINSTEP 0.05 ;
END M2
END LIBRARY
"""

DEF = """VERSION 5.8 ;
DESIGN drawn ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 2000 2000 ) ;
TRACKS Y 100 DO 10 STEP 200 LAYER M1 ;
TRACKS X 100 DO 10 STEP 200 LAYER M2 ;
END DESIGN
"""

EXPECTED = [
    {"rule": "SPACING NOTCHLENGTH", "layers": ["M1"]},
    {"rule": "MINSTEP", "layers": ["M1", "M2"]},
    {"rule": "ANTENNACUMAREARATIO", "layers": ["M1"]},
    {"rule": "MAXIMUMDENSITY", "layers": ["M1"]},
    {"rule": "LEF58_SPACING", "layers": ["M1"]},
    {"rule": "ENCLOSURE", "layers": ["V1"]},
    {"rule": "MINWIDTH", "layers": ["M2"]},
    {"rule": "SPACINGTABLE TWOWIDTHS", "layers": ["M2"]},
    {"rule": "LEF58_CORNERSPACING CONCAVECORNER", "layers": ["M2"]},
    {"rule": "LEF58_MINSTEP", "layers": ["M2"]},
]


def _files(tmp_path: Path) -> tuple[Path, Path]:
    lef, def_ = tmp_path / "drawn.lef", tmp_path / "drawn.def"
    lef.write_text(LEF)
    def_.write_text(DEF)
    return lef, def_


def test_check_names_every_rule_it_does_not_judge(tmp_path: Path) -> None:
    lef, def_ = _files(tmp_path)
    result = CliRunner().invoke(app, ["check", "--lef", str(lef), "--def", str(def_), "--out", str(tmp_path / "o"),
                                      "--quiet"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.strip().splitlines()
    assert lines[:-1] == [f"not checked: {e['rule']} on {', '.join(e['layers'])}" for e in EXPECTED]
    assert lines[-1].startswith("drawn: 0 open, 0 violations")
    assert json.loads((tmp_path / "o" / "drawn.check.json").read_text())["not_checked"] == EXPECTED


def test_check_json_and_info_carry_the_same_list(tmp_path: Path) -> None:
    lef, def_ = _files(tmp_path)
    runner = CliRunner()
    checked = runner.invoke(app, ["check", "--lef", str(lef), "--def", str(def_), "--out", str(tmp_path / "o"), "--json"])
    assert checked.exit_code == 0, checked.output
    assert json.loads(checked.stdout)["not_checked"] == EXPECTED
    info = runner.invoke(app, ["info", "--lef", str(lef), "--def", str(def_), "--json"])
    assert info.exit_code == 0, info.output
    assert json.loads(info.stdout)["not_modelled_rules"] == EXPECTED


def test_a_lef_of_modelled_rules_only_lists_nothing(tmp_path: Path) -> None:
    lef, def_ = _files(tmp_path)
    keep = ("NOTCHLENGTH", "MINSTEP", "LEF58_SPACING", "ENCLOSURE", "MINWIDTH", "TWOWIDTHS", "PROPERTY LEF58_CORNER",
            "ANTENNACUM", "MAXIMUMDENSITY")
    lef.write_text("\n".join(line for line in LEF.splitlines() if not any(k in line for k in keep)) + "\n")
    result = CliRunner().invoke(app, ["check", "--lef", str(lef), "--def", str(def_), "--out", str(tmp_path / "o"),
                                      "--json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["not_checked"] == []
