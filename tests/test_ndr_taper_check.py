"""Where a NONDEFAULTRULE's SPACING holds, as OpenROAD's checker reads it: around the net's routing,
not around its pins (fixed shapes) nor around routing drawn to the default rule (DEF ``TAPER``: a
tapered wire, a via or RECT patch on a tapered path).

The drawn stack of ``lef_text`` (UNITS 1000: 1 DBU = 1 nm; M1 horizontal, wires 60 wide, spacing
70; via V12's M1 pad 100 x 60). The rule ``wide`` asks M1 WIDTH 100 SPACING 300. Net n (rule
``wide``) joins the M1 pins of u1 (470..530 square) and u2; net m is an M1 wire at y 670..730,
x 970..2030, whatever else it does. Every gap below is under 300 and at least 70: a marker exactly
where the rule holds. Routing wholly on the net's own pins adds no metal there: OpenROAD judges the
union of a net's metal by its maximal rectangles, and a pin's are the pin's own (fixed) ones.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from drawn import write_design
from lef_text import library, macro, pin, stack
from xroute.check import check_design
from xroute.design import load_design

CELL = macro("PIN1", 0.2, 0.2, pin("A", "INPUT", [("M1", (0.07, 0.07, 0.13, 0.13))]))
LEF = library(stack(), CELL)
RULE = "NONDEFAULTRULES 1 ;\n- wide + LAYER M1 WIDTH 100 SPACING 300 ;\nEND NONDEFAULTRULES\n"
M_WIRE = "+ ROUTED M1 ( 1000 700 ) ( 2000 700 )"


BIG = macro("PIN2", 0.4, 0.2, pin("A", "INPUT", [("M1", (0.05, 0.05, 0.35, 0.15))]))


def drawn(n_routing: str, big_pin: bool = False) -> str:
    """The DEF; with big_pin, n also joins w1's pin A, M1 1050..1350 x 450..550 (120 below m's wire)."""
    cells = {"u1": (400, 400), "u2": (2400, 400), "v1": (400, 2400), "v2": (2400, 2400)}
    comps = "".join(f"- {c} PIN1 + PLACED ( {x} {y} ) N ;\n" for c, (x, y) in cells.items())
    if big_pin:
        cells["w1"] = (1000, 400)
        comps += "- w1 PIN2 + PLACED ( 1000 400 ) N ;\n"
    return ('VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN taper ;\nUNITS DISTANCE MICRONS 1000 ;\n'
            "DIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
            "TRACKS Y 100 DO 20 STEP 200 LAYER M1 M2 M3 ;\nTRACKS X 100 DO 20 STEP 200 LAYER M1 M2 M3 ;\n"
            + RULE + f"COMPONENTS {len(cells)} ;\n{comps}END COMPONENTS\nNETS 2 ;\n"
            f"- n ( u1 A ) ( u2 A ){' ( w1 A )' if big_pin else ''} + NONDEFAULTRULE wide {n_routing} ;\n"
            f"- m ( v1 A ) ( v2 A ) {M_WIRE} ;\nEND NETS\nEND DESIGN\n")


def spacing_markers(tmp_path: Path, n_routing: str, big_pin: bool = False) -> list[tuple[str, tuple[int, ...]]]:
    lef, def_path = write_design(tmp_path, library(stack(), CELL, BIG), drawn(n_routing, big_pin), stem="taper")
    result = check_design(load_design(lef=lef, def_=def_path))
    assert set(result.violations_by_type) <= {"MetalSpacing"}
    return sorted((m["layer"], tuple(m["box"])) for m in result.markers)


@pytest.mark.parametrize(("n_routing", "expected"), [
    # the rule's wire (100 wide: y 450..550) 120 from m's: the rule holds around it
    ("+ ROUTED M1 ( 500 500 ) ( 2500 500 )", [("M1", (970, 550, 2030, 670))]),
    # the same wire tapered: 60 wide (y 470..530), 140 from m's, the default rule's 70 holds
    ("+ ROUTED M1 TAPER ( 500 500 ) ( 2500 500 )", []),
    # n unrouted: its pin u1 A (y 470..530) is 140 below m's wire; a pin does not carry the rule
    ("", []),
    # a via of the rule's net: its M1 pad (1450..1550, 470..530) 140 below m's wire
    ("+ ROUTED M1 ( 1500 500 ) V12", [("M1", (1450, 530, 1550, 670))]),
    # the via on a tapered path
    ("+ ROUTED M1 TAPER ( 1500 500 ) V12", []),
    # a RECT patch on the rule's path (1200..1400, 480..540), 130 below m's wire; tapered: none
    ("+ ROUTED M1 ( 1300 500 ) RECT ( -100 -20 100 40 )", [("M1", (1200, 540, 1400, 670))]),
    ("+ ROUTED M1 TAPER ( 1300 500 ) RECT ( -100 -20 100 40 )", []),
])
def test_the_rules_spacing_holds_around_untapered_routing_only(tmp_path: Path, n_routing: str,
                                                               expected: list) -> None:
    assert spacing_markers(tmp_path, n_routing) == expected


@pytest.mark.parametrize(("n_routing", "expected"), [
    # the via's M1 pad (1150..1250, 470..530) wholly on n's own pin w1 A: the pin's metal, no rule
    ("+ ROUTED M1 ( 1200 500 ) V12", []),
    # the pad (1280..1380) reaching past the pin's edge (1350): the rule holds around it
    ("+ ROUTED M1 ( 1330 500 ) V12", [("M1", (1280, 530, 1380, 670))]),
])
def test_routing_wholly_on_the_nets_own_pin_adds_no_rule_spacing(tmp_path: Path, n_routing: str,
                                                                  expected: list) -> None:
    assert spacing_markers(tmp_path, n_routing, big_pin=True) == expected


@pytest.mark.parametrize("n_routing", ["+ ROUTED M1 TAPER ( 1500 500 ) V12",
                                       "+ ROUTED M1 TAPER ( 1300 500 ) RECT ( -100 -20 100 40 )"])
def test_a_tapered_via_or_patch_is_written_tapered(tmp_path: Path, n_routing: str) -> None:
    lef, def_path = write_design(tmp_path, LEF, drawn(n_routing), stem="taper")
    design = load_design(lef=lef, def_=def_path)
    written = tmp_path / "written.def"
    design.write_def(written)
    assert "NEW M1 TAPER" in written.read_text() or "ROUTED M1 TAPER" in written.read_text()
    assert check_design(load_design(lef=lef, def_=written)).markers == []
