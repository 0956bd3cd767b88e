"""Odd but readable DEF and LEF text is a warning naming its file and line, shown by every command
that reads it: a MASK that is no mask number, a STYLE no STYLES entry defines, a DEF rectangle
written upper right first, keywords not in upper case, a section count that differs from its
entries, a routing layer without tracks in its preferred direction (which `route` refuses with
the file and line).

Each case changes the shipped demo's DEF (or LEF) by one statement: the routing given to net n1
below, or one line replaced.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import make_runner, one_error
from xroute import _engine
from xroute.cli.app import app

DEMO = Path(__file__).resolve().parents[1] / "testcases" / "data" / "demo"
LEF = DEMO / "demo.lef"
# n1's routing (two Metal3 wires, a via to Metal4, a patch on Metal2), {mask} and {style} to fill
ROUTING = ("  + ROUTED Metal3 {style}( 43890 840 ) {mask}( 43130 840 )\n"
           "    NEW Metal3 ( 43890 840 ) {via_mask}VIA34\n"
           "    NEW Metal2 ( 43060 660 ) RECT ( {rect} )")
PLAIN = {"style": "", "mask": "", "via_mask": "", "rect": "0 0 140 360"}


def demo_def(tmp_path: Path, name: str = "d.def", **routing: str) -> Path:
    """The demo DEF with n1 routed as :data:`ROUTING` (fields from ``routing``), written to tmp_path."""
    text = (DEMO / "demo.def").read_text()
    text = text.replace("- n1\n  ( PIN io0 ) ( u13 A ) ( u13 B ) ;",
                        "- n1\n  ( PIN io0 ) ( u13 A ) ( u13 B )\n" + ROUTING.format(**{**PLAIN, **routing}) + " ;")
    path = tmp_path / name
    path.write_text(text)
    return path


def line_of(path: Path, needle: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if needle in line)


def warnings_of(lef: Path, def_: Path) -> list[str]:
    return list(_engine.load([str(lef)], str(def_)).warnings())


def test_the_plain_routing_reads_without_a_warning(tmp_path: Path) -> None:
    assert warnings_of(LEF, demo_def(tmp_path)) == []


@pytest.mark.parametrize("field, value, needle, message", [
    ("via_mask", "MASK 9999 ", "VIA34", "MASK '9999' before a via: a via's mask is three digits <top><cut><bottom> "
     "(not kept)"),
    ("mask", "MASK -2 ", "( 43130 840 )", "MASK '-2': a mask number is a positive integer (not kept)"),
    ("style", "STYLE 7 ", "STYLE 7", "STYLE '7' is not defined in a STYLES section before it (not kept)"),
    ("rect", "140 360 0 0", "RECT ( 140", "RECT with corners 140 360 and 0 0: the first is not the lower left one "
     "(read as the rectangle between them)"),
])
def test_an_odd_routing_value_is_a_warning_with_file_and_line(tmp_path: Path, field: str, value: str, needle: str,
                                                             message: str) -> None:
    def_ = demo_def(tmp_path, **{field: value})
    assert warnings_of(LEF, def_) == [f"{def_}:{line_of(def_, needle)}: {message}"]


def test_a_style_from_the_styles_section_is_no_warning(tmp_path: Path) -> None:
    def_ = demo_def(tmp_path, style="STYLE 7 ")
    text = def_.read_text().replace("NETS 317 ;", "STYLES 1 ;\n- STYLE 7 ( 30 10 ) ( 10 30 ) ( -10 30 ) ;\n"
                                    "END STYLES\n\nNETS 317 ;")
    def_.write_text(text)
    assert warnings_of(LEF, def_) == []


def test_keywords_not_in_upper_case_are_one_warning_per_file(tmp_path: Path) -> None:
    def_ = demo_def(tmp_path)
    text = re.sub(r"^NETS 317 ;", "nets 317 ;", def_.read_text(), flags=re.M).replace("    NEW Metal3", "    new Metal3")
    def_.write_text(text)
    first = line_of(def_, "nets 317 ;")
    assert warnings_of(LEF, def_) == [f"{def_}:{first}: keyword 'nets' not in upper case (LEF and DEF keywords "
                                      "are; read all the same) (the first of 2 in the file)"]
    lef = tmp_path / "l.lef"
    lef.write_text(LEF.read_text().replace("  DIRECTION HORIZONTAL ;", "  direction HORIZONTAL ;", 1))
    assert warnings_of(lef, DEMO / "demo.def")[0].startswith(f"{lef}:{line_of(lef, 'direction')}: keyword "
                                                              "'direction' not in upper case")


@pytest.mark.parametrize("count", [0, 400])
def test_check_shows_a_nets_count_that_differs(tmp_path: Path, count: int) -> None:
    def_ = demo_def(tmp_path)
    def_.write_text(def_.read_text().replace("NETS 317 ;", f"NETS {count} ;"))
    result = make_runner().invoke(app, ["check", "--lef", str(LEF), "--def", str(def_), "--out",
                                        str(tmp_path / "o"), "--quiet"])
    assert result.exit_code == 1, result.output  # the demo's DEF is not routed: opens
    warnings = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
    assert warnings == [f"warning: {def_}:{line_of(def_, 'END NETS')}: NETS {count} declared, 317 found"]


def test_a_layer_without_preferred_tracks_is_a_warning_and_a_route_error(tmp_path: Path) -> None:
    """Metal1 is horizontal: without its TRACKS Y only the TRACKS X line (vertical lines) is left."""
    def_ = tmp_path / "d.def"
    def_.write_text((DEMO / "demo.def").read_text().replace("TRACKS Y 280 DO 219 STEP 280 LAYER Metal1 ;\n", ""))
    line = line_of(def_, "LAYER Metal1 ;")
    assert warnings_of(LEF, def_) == [f"{def_}:{line}: routing layer 'Metal1' has TRACKS X only, none in its "
                                      "preferred (horizontal) direction: it cannot be routed without TRACKS Y"]
    result = make_runner().invoke(app, ["route", "--lef", str(LEF), "--def", str(def_), "--out", str(tmp_path / "o"),
                                        "--quiet"])
    one_error(result, f"{def_}:{line}: routing layer Metal1 has no tracks in its preferred direction",
              "TRACKS Y ... LAYER Metal1")
    assert not (tmp_path / "o").exists() or not any((tmp_path / "o").iterdir())
