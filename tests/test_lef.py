"""LEF reader on the seven contest LEFs: counts and exact values, checked by
hand against the files with grep/awk. Skipped when the testcases are not on the
search path (../shared/testcases, $XROUTE_TESTCASES, ...: see xroute.testcases).

All lengths are DBU (LEF microns x UNITS DATABASE MICRONS), areas DBU^2.
"""

from __future__ import annotations

import pytest

from conftest import require_testcase
from xroute import _engine


def contest_lef(name: str) -> str:
    """The contest testcase's LEF from the search path, or skip the test."""
    return str(require_testcase(name).lef)


def layers_by_name(db) -> dict:
    return {layer["name"]: layer for layer in db.layers()}


# ---------------------------------------------------------------- counts --

# (layers, routing, cut, vias, via rules, macros, sites), from grep -c of
# "^LAYER ", "TYPE ROUTING", "TYPE CUT", "^VIA ", "^VIARULE ", "^MACRO ",
# "^SITE " (comment lines such as ispd18_test1's "#MACRO ANTENNA" excluded).
COUNTS = {
    "ispd18_sample": (18, 9, 8, 22, 0, 16, 1),
    "ispd18_sample2": (18, 9, 8, 22, 0, 17, 1),
    "ispd18_sample3": (32, 16, 15, 30, 0, 3, 1),
    "ispd18_test1": (18, 9, 8, 22, 0, 487, 1),
    "ispd19_sample4": (18, 9, 8, 67, 5, 27, 3),
    "ispd19_test1": (18, 9, 8, 25, 0, 93, 1),
    "ispd19_test3": (18, 9, 8, 67, 5, 208, 3),
}

# (pins, ports, pin RECTs, OBS RECTs), from an awk pass over MACRO blocks.
MACRO_TOTALS = {
    "ispd18_sample": (106, 106, 262, 0),
    "ispd18_sample2": (113, 113, 290, 6),
    "ispd18_sample3": (85, 85, 324, 6),
    "ispd18_test1": (3156, 3156, 8369, 0),
    "ispd19_sample4": (156, 156, 525, 571),
    "ispd19_test1": (548, 548, 1946, 931),
    "ispd19_test3": (1393, 1393, 6663, 5099),
}


@pytest.mark.parametrize("name", sorted(COUNTS))
def test_contest_lef_counts(name):
    db = _engine.load_lef([contest_lef(name)])
    c = db.counts()
    got = (c["layers"], c["routing_layers"], c["cut_layers"], c["lef_vias"], c["via_rules"], c["macros"], c["sites"])
    assert got == COUNTS[name]
    assert db.lef_dbu_per_micron == 2000
    assert db.manufacturing_grid == 1  # 0.0005 um


def macro_totals(db) -> tuple[int, int, int, int]:
    """(pins, ports, pin rects, obstruction rects) over every macro of a loaded LEF."""
    pins = ports = pin_rects = obs_rects = 0
    for macro_name in db.macro_names():
        macro = db.macro(macro_name)
        for pin in macro["pins"].values():
            pins += 1
            ports += pin["port_count"]
            pin_rects += len(pin["shapes"])
        obs_rects += len(macro["obstructions"])
    return pins, ports, pin_rects, obs_rects


@pytest.mark.parametrize("name", sorted(MACRO_TOTALS))
def test_contest_lef_macro_totals(name):
    db = _engine.load_lef([contest_lef(name)])
    assert macro_totals(db) == MACRO_TOTALS[name]


@pytest.mark.parametrize("name", sorted(COUNTS))
def test_contest_lef_layer_numbering(name):
    db = _engine.load_lef([contest_lef(name)])
    layers = db.layers()
    routing = [l for l in layers if l["type"] == "ROUTING"]
    cuts = [l for l in layers if l["type"] == "CUT"]
    assert [l["routing_index"] for l in routing] == list(range(len(routing)))
    assert [l["cut_index"] for l in cuts] == list(range(len(cuts)))
    assert [l["name"] for l in routing] == [f"Metal{i}" for i in range(1, len(routing) + 1)]
    assert [l["name"] for l in cuts] == [f"Via{i}" for i in range(1, len(cuts) + 1)]
    # Metal/Via alternate, then the OVERLAP layer closes the list.
    assert [l["type"] for l in layers[:-1]] == ["ROUTING", "CUT"] * len(cuts) + ["ROUTING"]
    assert layers[-1]["name"] == "OVERLAP" and layers[-1]["type"] == "OVERLAP"
    assert all(l["routing_index"] == -1 for l in cuts)


def test_ispd18_test1_skipped_statements():
    db = _engine.load_lef([contest_lef("ispd18_test1")])
    assert db.skipped_statements() == {
        "UNITS.CAPACITANCE": 1,
        "MACRO.FOREIGN": 487,
        "PIN.SHAPE": 972,
        "PIN.NETEXPR": 972,
        "PIN.ANTENNADIFFAREA": 1,
    }
    assert db.warning_count == 1 + 487 + 972 + 972 + 1
    # MACRO ANTENNA is followed by a commented-out copy ("#MACRO ANTENNA" ...):
    # read once, or it would be a duplicate.
    assert db.macro_names().count("ANTENNA") == 1
    assert db.macro("ANTENNA")["pins"]["A"]["shapes"] == [("Metal1", 520, 780, 680, 2540)]


# ------------------------------------------------------------ exact values --

def test_ispd19_test1_metal1_spacing_table():
    db = _engine.load_lef([contest_lef("ispd19_test1")])
    m1 = layers_by_name(db)["Metal1"]
    assert m1["direction"] == "VERTICAL"
    assert m1["pitch"] == (200, 200)
    assert m1["width"] == 100 and m1["min_width"] == 100
    assert m1["min_area"] == 46000  # 0.0115 um^2 * 2000^2
    table = m1["spacing_table"]
    assert table["prls"] == [0, 440, 940, 1260, 3000]
    assert table["widths"] == [0, 200, 560, 940, 1260, 3000]
    assert table["spacing"] == [
        [100, 100, 100, 100, 100],
        [100, 120, 120, 120, 120],
        [100, 200, 200, 200, 200],
        [100, 200, 260, 260, 260],
        [100, 200, 260, 300, 300],
        [100, 200, 260, 300, 1000],
    ]
    assert m1["min_spacing"] == 100
    assert m1["eol_rules"] == [dict(space=120, eol_width=120, within=50, parallel_edge=False, par_space=0,
                                    par_within=0, two_edges=False)]
    assert m1["corner_spacing_rules"] == []


def test_ispd19_test1_metal2_eol_and_corner_spacing():
    db = _engine.load_lef([contest_lef("ispd19_test1")])
    m2 = layers_by_name(db)["Metal2"]
    assert m2["eol_rules"] == [
        dict(space=160, eol_width=160, within=50, parallel_edge=False, par_space=0, par_within=0, two_edges=False),
        dict(space=200, eol_width=160, within=50, parallel_edge=True, par_space=200, par_within=50, two_edges=False),
    ]
    assert m2["corner_spacing_rules"] == [
        dict(convex_corner=True, concave_corner=False, except_eol=True, eol_width=160, widths=[0, 400, 1000],
             spacings=[200, 400, 600])
    ]
    (prop_name, prop_value), = m2["properties"]
    assert prop_name == "LEF58_CORNERSPACING"
    assert prop_value.startswith("CORNERSPACING CONVEXCORNER EXCEPTEOL 0.08\n    WIDTH 0.00 SPACING 0.10")
    assert prop_value.endswith("WIDTH 0.50 SPACING 0.30 ;")
    assert m2["spacing_table"]["widths"] == [0, 180, 320, 940, 1260, 3000]


def test_ispd19_test1_cut_layers():
    db = _engine.load_lef([contest_lef("ispd19_test1")])
    layers = layers_by_name(db)
    v1, v2, v8 = layers["Via1"], layers["Via2"], layers["Via8"]
    plain = dict(space=150, center_to_center=False, same_net=False, adjacent_cuts=0, cut_within=0)
    assert v1["cut_spacing_rules"] == [plain]
    assert v2["width"] == 100
    assert v2["cut_spacing_rules"] == [
        plain,
        dict(space=310, center_to_center=False, same_net=False, adjacent_cuts=3, cut_within=400),
    ]
    assert v8["cut_spacing_rules"] == [dict(plain, space=300)]
    assert (v2["cut_index"], v2["routing_index"]) == (1, -1)


def test_ispd18_test1_via_macro_and_area():
    db = _engine.load_lef([contest_lef("ispd18_test1")])
    via = db.via("VIA12_1C")
    assert via["default"] is True
    assert (via["bottom"], via["cut"], via["top"]) == ("Metal1", "Via1", "Metal2")
    assert via["shapes"] == [
        ("Metal1", -130, -70, 130, 70),
        ("Via1", -70, -70, 70, 70),
        ("Metal2", -70, -130, 70, 130),
    ]
    macro = db.macro("OAI2BB1X4")
    assert macro["class"] == "CORE"
    assert macro["size"] == (5200, 3420)
    assert macro["site"] == "CoreSite"
    y = macro["pins"]["Y"]
    assert (y["direction"], y["use"], y["port_count"]) == ("OUTPUT", "SIGNAL", 1)
    assert len(y["shapes"]) == 10
    assert y["shapes"][0] == ("Metal1", 230, 1180, 350, 2440)  # RECT 0.115 0.59 0.175 1.22
    layers = layers_by_name(db)
    assert layers["Metal1"]["min_area"] == 80000  # AREA 0.02
    assert layers["Metal1"]["spacing_table"] == {
        "prls": [0], "widths": [0, 200, 1500, 3000], "spacing": [[120], [200], [500], [900]]}


def test_ispd19_sample4_via_rule_and_sites():
    db = _engine.load_lef([contest_lef("ispd19_sample4")])
    rule = db.via_rule("M4_M3")
    assert rule["generate"] is True and rule["default"] is True
    assert [l["layer"] for l in rule["layers"]] == ["Metal3", "Via3", "Metal4"]
    bottom, cut, top = rule["layers"]
    assert bottom["enclosure"] == (10, 60) and top["enclosure"] == (10, 60)
    assert cut["rect"] == (-50, -50, 50, 50)
    assert cut["spacing"] == (220, 220)
    assert bottom["width"] is None
    assert db.via_rule("M8_M7")["layers"][1]["rect"] == (-70, -70, 70, 70)
    assert db.sites() == [
        dict(name="CoreSite", **{"class": "CORE"}, size=(200, 2400), symmetry=""),
        dict(name="pad", **{"class": "pad"}, size=(20, 47000), symmetry="x y r90"),
        dict(name="corner", **{"class": "pad"}, size=(47000, 47000), symmetry="x y r90"),
    ]


def test_ispd19_test3_origin_shift_and_pad_class():
    db = _engine.load_lef([contest_lef("ispd19_test3")])
    pll = db.macro("pllclk")  # ORIGIN 0.06 0 ; pin refclk RECT 0.000 15.000 0.260 15.200
    assert pll["origin"] == (120, 0)
    assert pll["size"] == (30012, 54718)
    assert pll["pins"]["refclk"]["shapes"][0] == ("Metal2", 120, 30000, 640, 30400)
    pad = db.macro("PVDD1DGZ")
    assert pad["class"] == "PAD POWER"
    assert pad["pins"]["VDD"]["use"] == "POWER"  # written 'USE power ;'


def test_ispd18_sample3_sixteen_routing_layers():
    db = _engine.load_lef([contest_lef("ispd18_sample3")])
    layers = layers_by_name(db)
    m1 = layers["Metal1"]
    assert m1["pitch"] == (260, 200)  # PITCH 0.13 0.10
    assert m1["spacing_rules"] == [dict(space=100, range=None, same_net=False)]
    assert layers["Metal16"]["routing_index"] == 15


# ------------------------------------------------- the generated technology --


def _macro_totals_from_text(text: str) -> tuple[int, int, int, int]:
    """(pins, ports, pin RECTs, OBS RECTs) counted from LEF text, as MACRO_TOTALS was with awk."""
    pins = ports = pin_rects = obs_rects = 0
    block = None  # "PIN" or "OBS" inside a MACRO
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "MACRO":
            block = None
        elif f[0] == "PIN":
            pins, block = pins + 1, "PIN"
        elif f[0] == "PORT":
            ports += 1
        elif f[0] == "OBS":
            block = "OBS"
        elif f[0] == "RECT":
            if block == "PIN":
                pin_rects += 1
            elif block == "OBS":
                obs_rects += 1
        elif f[0] == "END" and len(f) > 1 and block == "PIN" and f[1] not in ("PORT",):
            block = None
        elif f == ["END"] and block == "OBS":
            block = None
    return pins, ports, pin_rects, obs_rects


def test_generated_lef_counts_numbering_and_macros(tmp_path):
    """The checks of the contest-LEF tests above on the generator's LEF (runs without contest data):
    counts and macro totals against its text, layer numbering (no OVERLAP layer in it)."""
    import re

    from xroute.testcases.gen_tech import technology_lef

    text = technology_lef()
    path = tmp_path / "generated.lef"
    path.write_text(text)
    db = _engine.load_lef([str(path)])
    c = db.counts()
    got = (c["layers"], c["routing_layers"], c["cut_layers"], c["lef_vias"], c["via_rules"], c["macros"], c["sites"])
    grep = tuple(len(re.findall(p, text, re.M)) for p in
                 (r"^LAYER ", r"TYPE ROUTING", r"TYPE CUT", r"^VIA ", r"^VIARULE ", r"^MACRO ", r"^SITE "))
    assert got == grep == (11, 6, 5, 5, 0, 9, 1)
    assert db.lef_dbu_per_micron == 2000
    assert db.manufacturing_grid == 10  # 0.005 um

    pins, ports, pin_rects, obs_rects = macro_totals(db)
    assert (pins, ports, pin_rects, obs_rects) == _macro_totals_from_text(text)
    assert pins > 0 and obs_rects > 0

    layers = db.layers()
    routing = [l for l in layers if l["type"] == "ROUTING"]
    cuts = [l for l in layers if l["type"] == "CUT"]
    assert [l["routing_index"] for l in routing] == list(range(len(routing)))
    assert [l["cut_index"] for l in cuts] == list(range(len(cuts)))
    assert [l["name"] for l in routing] == [f"Metal{i}" for i in range(1, 7)]
    assert [l["name"] for l in cuts] == [f"Via{i}" for i in range(1, 6)]
    assert [l["type"] for l in layers] == ["ROUTING", "CUT"] * len(cuts) + ["ROUTING"]
    assert all(l["routing_index"] == -1 for l in cuts)
