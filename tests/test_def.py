"""DEF reader on the contest testcases: counts and exact placed geometry (without the contest
data: the counts of generated designs, and the geometry on drawn DEFs holding the statements the
comments quote).

Every count in EXPECTED was taken from the DEF/guide text with grep/awk (not
from xroute), e.g. for COMPONENTS:
    awk '$1=="COMPONENTS" && $2~/^[0-9]+$/ {on=1; next} $1=="END" && $2=="COMPONENTS" {on=0}
         on && /^- /' X.input.def | wc -l
net pins: the "( a b )" groups inside NETS; rows/tracks/gcell: grep -c '^ROW ' etc.;
guides: grep -cE '^[0-9-]+ [0-9-]+ [0-9-]+ [0-9-]+ ' X.input.guide.
_text_counts() below recomputes them from the text in Python and the tests
check both against the reader.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import STANDINS, contest_found, require_testcase, sample_lef, standin_root
from xroute.testcases import find_testcase
from xroute import load_design
from xroute import errors

EXPECTED = {
    # name: components, nets, io_pins, special_nets, rows, tracks, gcell_patterns, def_vias, net_pins, guides
    "ispd18_sample": (22, 11, 0, 0, 5, 18, 0, 0, 22, 52),
    "ispd18_sample2": (23, 16, 0, 0, 5, 18, 0, 0, 32, 66),
    "ispd18_sample3": (6, 7, 5, 0, 1116, 32, 0, 0, 17, 58),
    "ispd19_sample4": (67, 22, 0, 2, 115, 18, 6, 248, 74, 142),
    "ispd18_test1": (8879, 3153, 0, 0, 112, 18, 0, 0, 17203, 26598),
    "ispd19_test1": (8879, 3153, 0, 2, 120, 18, 6, 0, 17203, 32223),
    "ispd19_test3": (8283, 8953, 57, 2, 115, 18, 46, 248, 30271, 0),
}
KEYS = ("components", "nets", "io_pins", "special_nets", "rows", "tracks", "gcell_patterns", "def_vias",
        "net_pins", "guides")


def _found(name: str):
    try:
        return find_testcase(name)
    except errors.TestcaseNotFound:
        pytest.skip(f"testcase {name} not found on the search path (set XROUTE_TESTCASES)")


_designs: dict[str, object] = {}


def _design(name: str):
    if name not in _designs:
        _found(name)
        _designs[name] = load_design(name)
    return _designs[name]


# Without the contest data, tests of geometry that their comments derive by hand from one
# statement of a contest DEF run on a drawn DEF holding those statements, with
# tests/data/lef/sample_names.lef (our LEF giving the cells involved the size and pin RECT the
# comments quote).
DRAWN_HEAD = """VERSION 5.8 ;
DIVIDERCHAR "/" ;
BUSBITCHARS "[]" ;
DESIGN {name} ;
UNITS DISTANCE MICRONS 2000 ;
DIEAREA {die} ;
"""
DRAWN = {
    "ispd18_sample": DRAWN_HEAD.format(name="drawn_sample", die="( 83600 71820 ) ( 104400 91200 )") + """\
COMPONENTS 2 ;
- inst2908 OR4X1 + PLACED ( 85600 75240 ) FS ;
- inst2015 NAND3X2 + PLACED ( 88000 78660 ) N ;
END COMPONENTS
NETS 1 ;
- net1 ( inst2908 D ) ( inst2015 A ) ;
END NETS
END DESIGN
""",
    "ispd19_test3": DRAWN_HEAD.format(name="drawn_pads", die="( 0 0 ) ( 390600 390000 )") + """\
COMPONENTS 5 ;
- inst6961 PDIDGZ + PLACED ( 0 292333 ) E ;
- inst6993 PDIDGZ + PLACED ( 157456 343000 ) S ;
- inst8014 PDIDGZ + PLACED ( 343600 56883 ) W ;
- inst8048 PDIDGZ + FIXED ( 0 100000 ) E ;
- inst4169 PDIDGZ + PLACED ( 343600 300000 ) W ;
END COMPONENTS
PINS 3 ;
- pin9 + NET net5719 + DIRECTION OUTPUT + USE SIGNAL
  + LAYER Metal2 ( -180 0 ) ( 180 260 ) + PLACED ( 390600 311200 ) W ;
- pin8 + NET net2 + DIRECTION INPUT + USE SIGNAL
  + LAYER Metal2 ( -180 0 ) ( 180 260 ) + PLACED ( 0 313200 ) E ;
- pin7 + NET net3 + DIRECTION INPUT + USE SIGNAL
  + LAYER Metal2 ( -180 0 ) ( 180 260 ) + PLACED ( 246100 390000 ) S ;
END PINS
NETS 3 ;
- net5719 ( PIN pin9 ) ( inst4169 PAD ) ;
- net2 ( PIN pin8 ) ( inst6961 PAD ) ;
- net3 ( PIN pin7 ) ( inst6993 PAD ) ;
END NETS
END DESIGN
""",
    "ispd18_sample3": DRAWN_HEAD.format(name="drawn_io", die="( 0 0 ) ( 2000000 2000000 )") + """\
PINS 1 ;
- iopin5 + NET ionet5 + DIRECTION INPUT + USE SIGNAL
  + LAYER Metal2 ( -70 0 ) ( 70 140 ) + PLACED ( 0 1810944 ) E ;
END PINS
NETS 2 ;
- ionet1 ;
- ionet5 ( PIN iopin5 ) ;
END NETS
END DESIGN
""",
    "ispd19_sample4": DRAWN_HEAD.format(name="drawn_grid", die="( 0 0 ) ( 390600 390000 )") + """\
TRACKS X 200 DO 976 STEP 400 LAYER Metal2 ;
TRACKS Y 190 DO 1026 STEP 380 LAYER Metal1 ;
GCELLGRID X 390100 DO 2 STEP 500 ;
GCELLGRID X 100 DO 196 STEP 2000 ;
GCELLGRID X 0 DO 2 STEP 100 ;
GCELLGRID Y 0 DO 196 STEP 2000 ;
END DESIGN
""",
}


def _design_or_drawn(name: str):
    """The contest design, or without the contest data its drawn stand-in (DRAWN) with our LEF."""
    if contest_found(name):
        return _design(name)
    key = f"drawn:{name}"
    if key not in _designs:
        path = standin_root() / f"{key.replace(':', '_')}.def"
        path.write_text(DRAWN[name])
        _designs[key] = load_design(lef=sample_lef(), def_=path)
    return _designs[key]


def _section_lines(lines: list[str], section: str) -> list[str]:
    out, on = [], False
    for line in lines:
        f = line.split()
        if len(f) >= 2 and f[0] == section and f[1].isdigit():
            on = True
            continue
        if len(f) >= 2 and f[0] == "END" and f[1] == section:
            on = False
        if on:
            out.append(line)
    return out


def _text_counts(def_path: Path, guide_path: Path | None) -> tuple[int, ...]:
    lines = def_path.read_text().splitlines()

    def items(section: str) -> int:
        return sum(1 for line in _section_lines(lines, section) if line.startswith("- "))

    net_pins = sum(len(re.findall(r"\( \S+ \S+ \)", line)) for line in _section_lines(lines, "NETS"))
    guides = 0
    if guide_path is not None:
        guides = sum(1 for line in guide_path.read_text().splitlines() if re.match(r"^-?\d+ -?\d+ -?\d+ -?\d+ ", line))
    return (
        items("COMPONENTS"), items("NETS"), items("PINS"), items("SPECIALNETS"),
        sum(line.startswith("ROW ") for line in lines), sum(line.startswith("TRACKS ") for line in lines),
        sum(line.startswith("GCELLGRID ") for line in lines), items("VIAS"), net_pins, guides,
    )


@pytest.mark.parametrize("name", list(EXPECTED))
def test_counts(name: str) -> None:
    found = _found(name)
    counts = _design(name).counts()
    got = tuple(counts[k] for k in KEYS)
    assert got == EXPECTED[name]
    assert _text_counts(found.def_, found.guide) == EXPECTED[name]
    # Flat net -> pin array is consistent with the per-net counts.
    d = _design(name)
    assert len(d.net_pin_start) == counts["nets"] + 1
    assert int(d.net_pin_start[-1]) == counts["net_pins"]


@pytest.mark.parametrize("name", sorted(STANDINS))
def test_counts_of_generated_designs_match_their_text(name: str) -> None:
    """test_counts' check of the reader against the text, on the generated stand-ins (no contest data needed)."""
    found = require_testcase(name)
    d = load_design(lef=found.lef, def_=found.def_, guide=found.guide)
    counts = d.counts()
    assert tuple(counts[k] for k in KEYS) == _text_counts(found.def_, found.guide)
    assert counts["nets"] >= 10 and counts["io_pins"] > 0 and counts["special_nets"] == 2
    assert (counts["guides"] > 0) == (found.guide is not None)
    assert len(d.net_pin_start) == counts["nets"] + 1
    assert int(d.net_pin_start[-1]) == counts["net_pins"]


def test_ispd18_test1_basics() -> None:
    d = _design("ispd18_test1")
    c = d.counts()
    assert (c["components"], c["nets"], c["guides"]) == (8879, 3153, 26598)
    assert (c["routing_layers"], c["cut_layers"]) == (9, 8)
    assert d.dbu_per_micron == 2000
    # "- inst8551 BUFX3 + SOURCE TIMING + PLACED ..." : 21 SOURCE options skipped and counted.
    assert d.skipped_statements()["COMPONENTS.SOURCE"] == 21
    # Warnings: every skipped LEF statement (1 + 487 + 972 + 972 + 1); DEF options skipped are not warnings.
    assert d.warning_count == 2433
    assert d.component("inst8551") == {
        "name": "inst8551", "macro": "BUFX3", "location": (357200, 266760), "orient": "FS", "status": "PLACED"}


def test_ispd18_sample_component_and_nets() -> None:
    d = _design("ispd18_sample")
    assert d.name == "ispd18_sample"
    assert d.die_area == (83600, 71820, 104400, 91200)
    assert d.component("inst2908") == {
        "name": "inst2908", "macro": "OR4X1", "location": (85600, 75240), "orient": "FS", "status": "PLACED"}
    assert d.net_pins("net1237") == [("inst5638", "A"), ("inst4678", "Y")]
    assert d.net_names[0] == "net1237"


def test_lef_wrappers() -> None:
    d = _design("ispd18_sample")
    via = d.via("VIA12_1C")
    assert (via["default"], via["bottom"], via["cut"], via["top"]) == (True, "Metal1", "Via1", "Metal2")
    assert via["shapes"][1] == ("Via1", -70, -70, 70, 70)  # RECT -0.035 ... at 2000 DBU/um
    assert d.sites() == [{"name": "CoreSite", "class": "CORE", "size": (400, 3420), "symmetry": ""}]
    # VIARULE M4_M3 GENERATE: ENCLOSURE 0.005 0.03, cut RECT +-0.025, SPACING 0.11 BY 0.11.
    rule = _design("ispd19_sample4").via_rule("M4_M3")
    assert [layer["layer"] for layer in rule["layers"]] == ["Metal3", "Via3", "Metal4"]
    assert rule["layers"][0]["enclosure"] == (10, 60)
    assert (rule["layers"][1]["rect"], rule["layers"][1]["spacing"]) == ((-50, -50, 50, 50), (220, 220))
    for lookup in (d.via, d.via_rule, d.def_via, d.io_pin, d.special_net):
        with pytest.raises(KeyError):
            lookup("no_such_name")
    with pytest.raises(KeyError):
        d.net_routing("no_such_net")


def test_placed_pin_fs_and_n() -> None:
    d = _design_or_drawn("ispd18_sample")
    # OR4X1: SIZE 1.4 BY 1.71 -> 2800 x 3420 DBU (2000/um), ORIGIN 0 0.
    # PIN D first RECT 0.06 0.59 0.16 0.795 -> (120 1180 320 1590).
    # inst2908 FS at (85600 75240): FS maps (x, y) -> (x, h - y):
    #   x 120..320, y 3420-1590 .. 3420-1180 = 1830..2240 -> (85720 77070 85920 77480).
    assert d.component_pin_shapes("inst2908", "D")[0] == ("Metal1", 85720, 77070, 85920, 77480)
    # NAND3X2 PIN A first RECT 0.26 0.6 0.37 0.735 -> (520 1200 740 1470);
    # inst2015 N at (88000 78660) -> (88520 79860 88740 80130).
    assert d.component_pin_shapes("inst2015", "A")[0] == ("Metal1", 88520, 79860, 88740, 80130)


def test_placed_pin_e_w_s() -> None:
    d = _design_or_drawn("ispd19_test3")
    # PDIDGZ: SIZE 4 BY 23.5 -> w 8000, h 47000; PIN PAD RECT 1.877 0 2.224 0.136
    # -> (3754 0 4448 272) on Metal1 (and Metal2).
    # E: (x, y) -> (y, w - x): x 0..272, y 8000-4448 .. 8000-3754 = 3552..4246.
    #   inst6961 E at (0 292333) -> (0 295885 272 296579): on the left die edge.
    assert d.component_pin_shapes("inst6961", "PAD")[0] == ("Metal1", 0, 295885, 272, 296579)
    # S: (x, y) -> (w - x, h - y): x 3552..4246, y 46728..47000.
    #   inst6993 S at (157456 343000) -> (161008 389728 161702 390000): top edge (die yhi 390000).
    assert d.component_pin_shapes("inst6993", "PAD")[0] == ("Metal1", 161008, 389728, 161702, 390000)
    # W: (x, y) -> (h - y, x): x 47000-272 .. 47000 = 46728..47000, y 3754..4448.
    #   inst8014 W at (343600 56883) -> (390328 60637 390600 61331): right edge (die xhi 390600).
    assert d.component_pin_shapes("inst8014", "PAD")[0] == ("Metal1", 390328, 60637, 390600, 61331)
    assert d.component("inst8048")["status"] == "FIXED"
    assert d.component("inst8048")["orient"] == "E"


def test_io_pin_orientation() -> None:
    d = _design_or_drawn("ispd19_test3")
    # "- pin9 + NET net5719 ... + LAYER Metal2 ( -180 0 ) ( 180 260 ) + PLACED ( 390600 311200 ) W":
    # oriented about the pin point, W maps (x, y) -> (-y, x): (-180 0)->(0 -180), (180 260)->(-260 180)
    # -> x -260..0, y -180..180 -> (390340 311020 390600 311380).
    p = d.io_pin("pin9")
    assert p["net"] == "net5719" and p["direction"] == "OUTPUT" and p["orient"] == "W"
    assert p["shapes"] == [("Metal2", 390340, 311020, 390600, 311380)]
    assert p["net_id"] == d.net_id("net5719")
    # E maps (x, y) -> (y, -x): x 0..260, y -180..180 at (0 313200).
    assert d.io_pin("pin8")["shapes"] == [("Metal2", 0, 313020, 260, 313380)]
    # S maps (x, y) -> (-x, -y): x -180..180, y -260..0 at (246100 390000).
    assert d.io_pin("pin7")["shapes"] == [("Metal2", 245920, 389740, 246280, 390000)]
    # The net's pin list holds the IO pin as ('PIN', name).
    assert d.net_pins("net5719") == [("PIN", "pin9"), ("inst4169", "PAD")]


def test_special_nets() -> None:
    d = _design("ispd19_test3")
    vss = d.special_net("VSS")
    assert vss["use"] == "GROUND"
    assert vss["pins"] == [("*", "VSS"), ("*", "AVSS")]
    # Wires: the "( .. ) ( .. )" pairs of the VSS entry; vias: the path pieces ending in a via name.
    assert (len(vss["wires"]), len(vss["vias"]), len(vss["rects"])) == (143, 850, 0)
    # "+ ROUTED Metal8 3600 + SHAPE RING ( 49700 47900 ) ( * 342100 )": '*' repeats x.
    assert vss["wires"][0] == ("Metal8", 3600, "RING", 49700, 47900, 49700, 342100)
    vdd = d.special_net("VDD")
    assert (len(vdd["wires"]), len(vdd["vias"])) == (67, 722)
    t1 = _design("ispd19_test1")
    # "NEW Metal8 0 ( 500 500 ) VIA78_PG": a via alone, no wire.
    assert ("VIA78_PG", 500, 500, "") in t1.special_net("VSS")["vias"] or \
        ("VIA78_PG", 500, 500, "") in t1.special_net("VDD")["vias"]


def test_generated_def_vias() -> None:
    d = _design("ispd19_test3")
    # via5Array_2: VIARULE M6_M5, CUTSIZE 720 720, CUTSPACING 700 700, ENCLOSURE 410 410 410 410,
    # ROWCOL 14 14: array 14*720 + 13*700 = 19180 wide, centred -> -9590..9590; metal grows by
    # 410 -> -10000..10000.
    v = d.def_via("via5Array_2")
    assert v["generated"] and v["rule"] == "M6_M5" and v["rowcol"] == (14, 14)
    assert (v["bottom"], v["cut"], v["top"]) == ("Metal5", "Via5", "Metal6")
    cuts = [s for s in v["shapes"] if s[0] == "Via5"]
    assert len(cuts) == 14 * 14
    assert cuts[0] == ("Via5", -9590, -9590, -8870, -8870)
    assert ("Metal5", -10000, -10000, 10000, 10000) in v["shapes"]
    assert ("Metal6", -10000, -10000, 10000, 10000) in v["shapes"]
    # via3Array_1: CUTSIZE 520, CUTSPACING 520, ROWCOL 15 8, ENCLOSURE 7950 460, ORIGIN 7800 0,
    # OFFSET -7800 0 -7800 0: cut array 7800 x 15080 centred then moved +7800 in x -> x 3900..11700,
    # y -7540..7540; metal = array grown by (7950, 460) then moved back by the OFFSET
    # -> (-11850 -8000 11850 8000).
    v = d.def_via("via3Array_1")
    cuts = [s for s in v["shapes"] if s[0] == "Via3"]
    assert len(cuts) == 15 * 8
    assert min(s[1] for s in cuts) == 3900 and max(s[3] for s in cuts) == 11700
    assert ("Metal3", -11850, -8000, 11850, 8000) in v["shapes"]
    # M4_M3_12: ROWCOL 6 2, PATTERN 5_F_1_0: the 5 lower rows have both cuts, the top row none.
    v = d.def_via("M4_M3_12")
    cuts = [s for s in v["shapes"] if s[0] == "Via3"]
    assert len(cuts) == 10
    # CUTSPACING 400 150: array height 6*100 + 5*150 = 1350 -> rows at y -675, -425, -175, 75, 325,
    # 575; the top one (575..675) is missing, so the highest cut ends at 425.
    assert max(s[4] for s in cuts) == 425
    assert min(s[2] for s in cuts) == -675
    # M4_M3_13: PATTERN 1_0_5_F: the bottom row is the empty one.
    cuts = [s for s in d.def_via("M4_M3_13")["shapes"] if s[0] == "Via3"]
    assert len(cuts) == 10 and min(s[2] for s in cuts) == -425 and max(s[4] for s in cuts) == 675
    # A fixed DEF via: "- via1Array_22 + RECT Metal1 ( -800 -800 ) ( 800 800 ) ...".
    s4 = _design("ispd19_sample4")
    v = s4.def_via("via1Array_22")
    assert not v["generated"]
    assert v["shapes"][0] == ("Metal1", -800, -800, 800, 800)
    assert (v["bottom"], v["cut"], v["top"]) == ("Metal1", "Via1", "Metal2")


def test_gcell_grid_and_tracks() -> None:
    d = _design_or_drawn("ispd19_sample4")
    # GCELLGRID X 390100 DO 2 STEP 500 ; X 100 DO 196 STEP 2000 ; X 0 DO 2 STEP 100
    xs = d.gcell_lines("x")
    assert xs[0] == 0 and xs[1] == 100 and xs[-1] == 390600
    assert len(xs) == len(set([0, 100] + [100 + 2000 * i for i in range(196)] + [390100, 390600]))
    t = d.tracks()[0]
    assert t["layer"] and t["count"] > 0 and t["step"] > 0


def test_io_pin_nets_resolved() -> None:
    d = _design_or_drawn("ispd18_sample3")
    p = d.io_pin("iopin5")
    assert p["net"] == "ionet5" and p["net_id"] == d.net_id("ionet5")
    assert p["orient"] == "E" and p["location"] == (0, 1810944)


SKIPPY_DEF = """VERSION 5.8 ;
NAMESCASESENSITIVE ON ;
DESIGN skippy ;
TECHNOLOGY tech ;
UNITS DISTANCE MICRONS 2000 ;
HISTORY made by hand ;
PROPERTYDEFINITIONS
  COMPONENTPIN designRuleWidth REAL ;
  DESIGN FE_CORE_BOX_LL_X REAL 1.0 ;
END PROPERTYDEFINITIONS
DIEAREA ( 0 0 ) ( 20000 20000 ) ;
ROW R0 CoreSite 0 0 N DO 10 BY 1 STEP 400 0 + PROPERTY rowp 1 ;
NONDEFAULTRULES 1 ;
- wide + LAYER Metal1 WIDTH 200 ;
END NONDEFAULTRULES
REGIONS 1 ;
- r1 ( 0 0 ) ( 1000 1000 ) + TYPE FENCE ;
END REGIONS
COMPONENTS 2 ;
- u1 OR4X1 + SOURCE NETLIST + WEIGHT 5 + PLACED ( 400 0 ) N ;
- u2 NAND3X2 + UNPLACED + PROPERTY p "a + b ;" ;
END COMPONENTS
PINS 2 ;
- in1 + NET n1 + SPECIAL + DIRECTION INPUT + USE SIGNAL
  + PORT + LAYER Metal2 ( -70 0 ) ( 70 140 ) + PLACED ( 0 5000 ) E ;
- lonely + NET not_in_nets + DIRECTION OUTPUT ;
END PINS
BLOCKAGES 1 ;
- LAYER Metal2 + PUSHDOWN + SPACING 100 RECT ( 0 0 ) ( 100 100 ) POLYGON ( 0 0 ) ( 10 0 ) ( 0 10 ) ;
END BLOCKAGES
NETS 3 ;
- n1 ( PIN in1 ) ( u1 D ) + NONDEFAULTRULE wide + WEIGHT 2 ;
- MUSTJOIN ( u1 A ) ;
- n2 ( u1 Y ) ( u2 A + SYNTHESIZED ) + SOURCE TEST + PROPERTY q 1 ;
END NETS
GROUPS 1 ;
- g1 u1 u2 + REGION r1 ;
END GROUPS
BEGINEXT "tag"
  CREATOR "me" ;
ENDEXT
END DESIGN
"""


def test_skipped_statements_counted(tmp_path: Path) -> None:
    lef = sample_lef()  # ispd18_sample's, or our LEF with its names
    path = tmp_path / "skippy.def"
    path.write_text(SKIPPY_DEF)
    d = load_design(lef=lef, def_=path)
    skipped = d.skipped_statements()
    for key, count in {
        "NAMESCASESENSITIVE": 1, "TECHNOLOGY": 1, "HISTORY": 1, "PROPERTYDEFINITIONS": 1, "ROW.PROPERTY": 1,
        "REGIONS": 1, "COMPONENTS.SOURCE": 1, "COMPONENTS.WEIGHT": 1,
        "COMPONENTS.PROPERTY": 1, "PINS.SPECIAL": 1, "BLOCKAGES.PUSHDOWN": 1, "BLOCKAGES.SPACING": 1,
        "NETS.WEIGHT": 1, "NETS.MUSTJOIN": 1, "NETS.SYNTHESIZED": 1, "NETS.SOURCE": 1,
        "NETS.PROPERTY": 1, "GROUPS": 1, "BEGINEXT": 1,
    }.items():
        assert skipped.get(key) == count, key
    c = d.counts()
    assert (c["components"], c["io_pins"], c["nets"], c["net_pins"], c["blockages"]) == (2, 2, 2, 4, 1)
    assert d.component("u2")["status"] == "UNPLACED"
    assert d.io_pin("in1")["shapes"] == [("Metal2", 0, 4930, 140, 5070)]
    # A pin whose net NETS lacks is kept with its net name and no net id.
    lonely = d.io_pin("lonely")
    assert lonely["net"] == "not_in_nets" and lonely["net_id"] == -1
    out = d.write_def(tmp_path / "out.def")
    assert load_design(lef=lef, def_=out).compare(d) == []
