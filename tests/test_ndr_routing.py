"""Routing nets of a NONDEFAULTRULE: the rule's width on the layers it names, its spacing kept
clear of other nets, judged the same way by the router's own check and by ``xroute check``.

The technology is the drawn stack of ``lef_text`` (UNITS 1000: 1 DBU = 1 nm): M1 horizontal, M2
vertical, M3 horizontal, tracks every 200 from 100, wires 60 wide, spacing 70. The rule ``wide``
doubles both on M2 and M3 (width 120, spacing 140). The cell PIN1 (200 x 200) has one M1 pin A at
its centre, so a cell placed at (x, y) has its pin on the track crossing (x + 100, y + 100).

    x =   500 700           1500        1900       2700
    y=2900  a2
    y=2500      b2  (long net a: a1-a2 on column x=500; short net b: b1-b2 on column x=700,
    y=1500      b1   y 1500..2500, beside it)
    y=1100  a1                          d (d1-d2 on column x=1900)
    y= 700                  c1 ======== c2

Default rules: a and b each run straight up their M2 column, 200 apart; the gap between the wires
is 200 - 30 - 30 = 140 >= 70. b's pins are 1,000 apart: at 800 a wrong-way M1 wire (4 x 800)
costs what two vias and the M2 wire cost (2 x 1200 + 800), and the maze may take either. With either of them on the rule the gap would be 200 - 60 - 30 =
110 < 140, so the router must move one of them a track further away.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from conftest import make_runner
from drawn import write_design
from lef_text import library, macro, pin, stack, via
from xroute import _engine
from xroute.check import check_design
from xroute.cli.app import app
from xroute.design import load_design
from xroute.pipeline import prepare_design
from xroute.router import route_design

RULE = ("NONDEFAULTRULES 1 ;\n- wide + LAYER M2 WIDTH 120 SPACING 140 + LAYER M3 WIDTH 120 SPACING 140 ;\n"
        "END NONDEFAULTRULES\n")
CELLS = {"a1": (400, 1000), "a2": (400, 2800), "b1": (600, 1400), "b2": (600, 2400),
         "c1": (1400, 600), "c2": (2600, 600), "d1": (1800, 3000), "d2": (1800, 1000)}
NETS = {"a": ["a1", "a2"], "b": ["b1", "b2"], "c": ["c1", "c2"], "d": ["d1", "d2"]}
CELL = macro("PIN1", 0.2, 0.2, pin("A", "INPUT", [("M1", (0.07, 0.07, 0.13, 0.13))]))
LEF = library(stack(), CELL)


def def_text(rule_net: str | None, rule: str = RULE, cells: dict[str, tuple[int, int]] = CELLS,
             nets: dict[str, list[str]] = NETS) -> str:
    """The drawn DEF; `rule_net` (if any) carries ``+ NONDEFAULTRULE wide``."""
    comps = "".join(f"- {c} PIN1 + PLACED ( {x} {y} ) N ;\n" for c, (x, y) in cells.items())
    net_lines = "".join(f"- {n} " + " ".join(f"( {c} A )" for c in cs) +
                        (" + NONDEFAULTRULE wide" if n == rule_net else "") + " ;\n" for n, cs in nets.items())
    return ('VERSION 5.8 ;\nDIVIDERCHAR "/" ;\nBUSBITCHARS "[]" ;\nDESIGN ndr ;\nUNITS DISTANCE MICRONS 1000 ;\n'
            "DIEAREA ( 0 0 ) ( 4000 4000 ) ;\n"
            "TRACKS Y 100 DO 20 STEP 200 LAYER M1 M2 M3 ;\nTRACKS X 100 DO 20 STEP 200 LAYER M1 M2 M3 ;\n"
            "GCELLGRID X 0 DO 5 STEP 1000 ;\nGCELLGRID Y 0 DO 5 STEP 1000 ;\n"
            + (rule if rule_net else "") +
            f"COMPONENTS {len(cells)} ;\n{comps}END COMPONENTS\nNETS {len(nets)} ;\n{net_lines}END NETS\nEND DESIGN\n")


def route_cli(tmp_path: Path, def_: str, out: str) -> tuple[Path, Path, dict[str, Any]]:
    """``xroute route --lef --def`` on the drawn files: (LEF, routed DEF, the --json document)."""
    lef, def_path = write_design(tmp_path, LEF, def_, stem="ndr")
    result = make_runner().invoke(app, ["route", "--lef", str(lef), "--def", str(def_path), "--out",
                                        str(tmp_path / out), "--json"])
    assert result.exit_code == 0, result.output
    return lef, tmp_path / out / "ndr.routed.def", json.loads(result.stdout)


def check_cli(lef: Path, routed: Path, out: Path) -> dict[str, Any]:
    result = make_runner().invoke(app, ["check", "--lef", str(lef), "--def", str(routed), "--out", str(out),
                                        "--json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.stdout)


def wires(db: Any, net: str) -> list[tuple[Any, ...]]:
    return db.net_routing(db.net_names().index(net))["wires"]


@pytest.mark.parametrize("rule_net", ["a", "b"])
def test_a_rule_net_routes_at_the_rules_width_and_keeps_its_spacing(tmp_path: Path, rule_net: str) -> None:
    # a on the rule: routed after b (its bounding box is larger), it keeps clear of b by the
    # extra costs of its own wide metal; b on the rule: routed first, its marks keep a away.
    lef, routed, doc = route_cli(tmp_path, def_text(rule_net), "r")
    db = _engine.load([str(lef)], str(routed))
    assert "+ NONDEFAULTRULE wide" in routed.read_text()
    on_rule = wires(db, rule_net)
    assert any(w[0] == "M2" for w in on_rule)
    for layer, *_pts, width, _e0, _e1 in on_rule:
        assert width == (120 if layer in ("M2", "M3") else 0)  # the reader gives the rule's width
    for net in set(NETS) - {rule_net}:
        assert all(w[5] == 0 for w in wires(db, net))
    # Either way a steps one track west on M1 at both pins and takes the column x=300; b keeps
    # its column. Only M2 and M3 wires of the rule's net are 120 wide.
    wa = 120 if rule_net == "a" else 0
    assert wires(db, "a") == [("M1", 500, 1100, 300, 1100, 0, -1, -1), ("M2", 300, 1100, 300, 2900, wa, -1, -1),
                              ("M1", 300, 2900, 500, 2900, 0, -1, -1)]
    assert wires(db, "b") == [("M2", 700, 1500, 700, 2500, 120 - wa, -1, -1)]
    checked = check_cli(lef, routed, tmp_path / "c")
    assert (checked["opens"], checked["violations"]) == (0, 0)
    assert doc["final"]["violations"] == 0
    # clean from the first pass (no rip-up needed); the router's own count is check's
    result = route_design(prepare_design(lef=lef, def_=tmp_path / "ndr.def"))
    assert result.iterations[0].violations == 0
    assert result.violations == check_design(load_design(lef=lef, def_=routed)).violations == 0


def test_default_width_routing_of_the_rule_net_breaks_the_rules_spacing(tmp_path: Path) -> None:
    # Routed without the rule, a and b take their straight columns; the same wires judged with
    # a on the rule are 110 apart where the rule asks 140: the case the router must avoid.
    lef, routed, _ = route_cli(tmp_path, def_text(None), "plain")
    db = _engine.load([str(lef)], str(routed))
    assert wires(db, "a") == [("M2", 500, 1100, 500, 2900, 0, -1, -1)]
    assert wires(db, "b") == [("M2", 700, 1500, 700, 2500, 0, -1, -1)]
    text = routed.read_text().replace("COMPONENTS", RULE + "COMPONENTS", 1)
    text = text.replace("( a1 A ) ( a2 A )", "( a1 A ) ( a2 A ) + NONDEFAULTRULE wide")
    as_rule = tmp_path / "as_rule.def"
    as_rule.write_text(text)
    checked = check_cli(lef, as_rule, tmp_path / "c")
    assert checked["violations_by_type"] == {"MetalSpacing": 1}
    marker = check_design(load_design(lef=lef, def_=as_rule)).markers[0]
    assert (marker["layer"], marker["box"]) == ("M2", (560, 1450, 670, 2550))  # a's wire edge to b's


def test_the_router_and_check_count_an_unavoidable_rule_violation_alike(tmp_path: Path) -> None:
    # On M1 the rule asks 300 from a's metal, but b's pin sits 140 from a's pin: whatever a
    # puts on its pin is too close to b's pin. Both counts see it.
    rule = "NONDEFAULTRULES 1 ;\n- wide + LAYER M1 WIDTH 60 SPACING 300 ;\nEND NONDEFAULTRULES\n"
    cells = {"a1": (400, 1000), "a2": (400, 2800), "b1": (600, 1000), "b2": (2600, 1000)}
    lef, def_path = write_design(tmp_path, LEF, def_text("a", rule, cells, {"a": ["a1", "a2"], "b": ["b1", "b2"]}),
                                 stem="ndr")
    design = prepare_design(lef=lef, def_=def_path)
    result = route_design(design, iterations=2)
    routed = tmp_path / "routed.def"
    design.write_def(routed)
    checked = check_design(load_design(lef=lef, def_=routed))
    assert result.violations >= 1
    assert {k: v for k, v in result.violations_by_type.items() if v} == checked.violations_by_type


def test_the_routed_def_does_not_depend_on_the_thread_count(tmp_path: Path) -> None:
    lef, def_path = write_design(tmp_path, LEF, def_text("a"), stem="ndr")
    texts = []
    for threads in (1, 2):
        design = prepare_design(lef=lef, def_=def_path)
        route_design(design, threads=threads, region_size=2)
        out = tmp_path / f"t{threads}.def"
        design.write_def(out)
        texts.append(out.read_bytes())
    assert texts[0] == texts[1]


LEF_RULE = """NONDEFAULTRULE wide
  LAYER M2
    WIDTH 0.12 ;
    SPACING 0.14 ;
  END M2
  LAYER M3
    WIDTH 0.12 ;
    SPACING 0.14 ;
  END M3
  VIA V23W
    LAYER M2 ; RECT -0.06 -0.06 0.06 0.06 ;
    LAYER V2 ; RECT -0.03 -0.03 0.03 0.03 ;
    LAYER M3 ; RECT -0.06 -0.06 0.06 0.06 ;
  END V23W
END wide
"""


@pytest.mark.parametrize("where", ["def", "lef"])
def test_a_rule_net_places_the_via_its_rule_names(tmp_path: Path, where: str) -> None:
    # The rule (in the DEF, naming a LEF VIA; or a LEF NONDEFAULTRULE defining it) names V23W,
    # M2 and M3 metal 120 x 120: a net of the rule going from M2 to M3 places it; at its pins the
    # vias stay the ones pin access checked (V12). Another net keeps the default V23.
    wide_via = via("V23W", [("M2", (-0.06, -0.06, 0.06, 0.06)), ("V2", (-0.03, -0.03, 0.03, 0.03)),
                            ("M3", (-0.06, -0.06, 0.06, 0.06))], default=False)
    lef_text = library(stack(), wide_via, CELL) if where == "def" else library(stack(), LEF_RULE, CELL)
    rule = RULE.replace(" ;\nEND", " + VIA V23W ;\nEND") if where == "def" else ""
    cells = {"a1": (400, 1000), "a2": (2400, 2800), "b1": (400, 3400), "b2": (2400, 400)}
    # M1 is blocked between the pins' columns: both nets need M3 to cross.
    blockage = "BLOCKAGES 1 ;\n- LAYER M1 RECT ( 640 0 ) ( 2360 4000 ) ;\nEND BLOCKAGES\n"
    text = def_text("a", rule, cells, {"a": ["a1", "a2"], "b": ["b1", "b2"]})
    text = text.replace("NETS 2", blockage + "NETS 2")
    lef, def_path = write_design(tmp_path, lef_text, text, stem="ndr")
    design = prepare_design(lef=lef, def_=def_path)
    result = route_design(design)
    routed = tmp_path / "routed.def"
    design.write_def(routed)
    db = _engine.load([str(lef)], str(routed))
    assert wires(db, "a")[0] == ("M2", 500, 1100, 500, 2900, 120, -1, -1)
    a_vias = {v[0] for v in db.net_routing(0)["vias"]}
    b_vias = {v[0] for v in db.net_routing(1)["vias"]}
    assert a_vias == {"V12", "V23W"} and b_vias == {"V12", "V23"}
    assert result.violations == check_design(load_design(lef=lef, def_=routed)).violations == 0
