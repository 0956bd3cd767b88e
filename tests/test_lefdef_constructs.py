"""Valid LEF/DEF constructs from real files, each drawn small: the figure read
(a rescaled coordinate, a layer offset, a warning's text), not only "no error". The corpus triage
that found them: OpenROAD's and KLayout's test data, the Si2 5.8 examples, asap7, gf180, ihp."""

from __future__ import annotations

import gzip
from pathlib import Path

import pytest

from lef_text import library, macro, pin, routing, site, stack, write_lef
from xroute import _engine
from xroute.errors import InputError

TECH = library(stack(), site("core", 0.2, 1.0))  # UNITS 1000: M1 V1 M2 V2 M3, vias V12 V23


def design(body: str, units: int = 1000) -> str:
    """A DEF around `body` (DIEAREA 0 0 .. 20000 20000 in DEF units when units=1000)."""
    return (f"VERSION 5.8 ;\nDESIGN t ;\nUNITS DISTANCE MICRONS {units} ;\n"
            "DIEAREA ( 0 0 ) ( 20000 20000 ) ;\n" + body + "END DESIGN\n")


def load(tmp_path: Path, lef: str, def_text: str, name: str = "t.def") -> _engine.Database:
    lef_path = write_lef(tmp_path, lef)
    def_path = tmp_path / name
    def_path.write_text(def_text)
    return _engine.load([lef_path], str(def_path), "")


def load_error(tmp_path: Path, lef: str, def_text: str) -> InputError:
    with pytest.raises(InputError) as info:
        load(tmp_path, lef, def_text)
    return info.value


# ------------------------------------------------------------------ keywords in any case (ihp-sg13g2)
def test_keywords_in_mixed_case(tmp_path):
    cells = """
        Via VX DEFAULT
          layer M1 ;
            Rect -0.1 -0.05 0.1 0.05 ;
          Layer V1 ;
            RECT -0.03 -0.03 0.03 0.03 ;
          layer M2 ;
            rect -0.05 -0.1 0.05 0.1 ;
        End VX
        Macro INV
          Class core ;
          size 0.4 by 1 ;
          pin a
            direction input ;
            port
              layer M1 ;
                rect 0 0 0.1 0.1 ;
            end
          end a
        end INV
        """
    path = write_lef(tmp_path, TECH.replace("END LIBRARY\n", "") + cells.replace("\n        ", "\n") + "END LIBRARY\n")
    db = _engine.load_lef([path])
    v = db.via("VX")
    assert (v["bottom"], v["cut"], v["top"]) == ("M1", "V1", "M2")
    assert ("M1", -100, -50, 100, 50) in v["shapes"]
    m = db.macro("INV")
    assert m["size"] == (400, 1000)
    assert list(m["pins"]) == ["a"] and m["pins"]["a"]["direction"] == "INPUT"


def test_lower_case_def_keywords(tmp_path):
    db = load(tmp_path, TECH, design("tracks x 100 do 10 step 200 layer M2 ;\n").replace("DIEAREA", "diearea"))
    assert db.die_area == (0, 0, 20000, 20000)
    assert [(t["layer"], t["count"]) for t in db.tracks()] == [("M2", 10)]


# ------------------------------------------------------------------ gzip (OpenROAD odb/rsz, KLayout)
def test_gzip_inputs_are_read_by_their_magic_bytes(tmp_path):
    plain = load(tmp_path, TECH, design("TRACKS Y 100 DO 7 STEP 200 LAYER M1 ;\n"))
    lef = tmp_path / "tech.lef.gz"
    lef.write_bytes(gzip.compress(TECH.encode()))
    packed = tmp_path / "t.def.gz"
    packed.write_bytes(gzip.compress(design("TRACKS Y 100 DO 7 STEP 200 LAYER M1 ;\n").encode()))
    unnamed = tmp_path / "t.def"  # a gzip stream without the suffix is recognised too
    unnamed.write_bytes(packed.read_bytes())
    for path in (packed, unnamed):
        db = _engine.load([str(lef)], str(path), "")
        assert db.tracks() == plain.tracks() and db.die_area == plain.die_area


def test_corrupt_gzip_is_one_error_naming_the_file(tmp_path):
    bad = tmp_path / "t.def.gz"
    bad.write_bytes(gzip.compress(design("").encode())[:30])  # cut short
    lef = write_lef(tmp_path, TECH)
    with pytest.raises(InputError) as info:
        _engine.load([lef], str(bad), "")
    assert info.value.path == str(bad)
    assert "invalid gzip stream" in info.value.message


# ------------------------------------------------------------------ units
@pytest.mark.parametrize(("units", "die"), [(500, 40000), (250, 80000), (2000, 10000)])
def test_def_units_rescaled_to_the_lefs(tmp_path, units, die):
    db = load(tmp_path, TECH, design("", units))
    assert db.die_area == (0, 0, die, die)
    assert db.dbu_per_micron == 1000  # coordinates are in the LEF's units now
    assert f"DEF UNITS DISTANCE MICRONS {units} and the LEF's DATABASE MICRONS 1000 differ" in db.warnings()[0]


def test_def_units_without_integer_ratio_or_exact_value(tmp_path):
    e = load_error(tmp_path, TECH, design("", 300))
    assert (e.line, "have no integer ratio") == (3, e.message[-len("have no integer ratio: the coordinates "
                                                                       "cannot be rescaled exactly"):][:21])
    e = load_error(tmp_path, TECH, design("TRACKS Y 101 DO 7 STEP 200 LAYER M1 ;\n", 2000))
    assert e.line == 5 and "coordinate '101' is not a multiple of 2" in e.message


def test_lef_without_units_assumes_1000(tmp_path):
    path = write_lef(tmp_path, "VERSION 5.8 ;\n" + stack() + "END LIBRARY\n")
    db = _engine.load_lef([path])
    assert db.lef_dbu_per_micron == 1000
    m1 = next(l for l in db.layers() if l["name"] == "M1")
    assert (m1["width"], m1["pitch"]) == (60, (200, 200))
    assert "database units per micron assumed" in db.warnings()[0]


def test_negative_layer_offset(tmp_path):
    lef = library(routing("M2", "VERTICAL", 0.054, 0.018, rules=["OFFSET -0.27 ;"]))
    db = _engine.load_lef([write_lef(tmp_path, lef)])
    assert db.layers()[0]["offset"] == (-270, -270)


# ------------------------------------------------------------------ LEF blocks
def test_lef_nondefaultrule_with_bare_end_and_its_via_in_a_def(tmp_path):
    ndr = """NONDEFAULTRULE wide
  LAYER M1
    WIDTH 0.2 ;
    SPACING 0.3 ;
  END M1
  VIA NDRV12
    LAYER M1 ; RECT -0.1 -0.1 0.1 0.1 ;
    LAYER V1 ; RECT -0.03 -0.03 0.03 0.03 ;
    LAYER M2 ; RECT -0.1 -0.1 0.1 0.1 ;
  END NDRV12
  USEVIA V12 ;
  MINCUTS V1 2 ;
END
"""
    lef = TECH.replace("END LIBRARY\n", ndr + "END LIBRARY\n")
    nets = ("NETS 1 ;\n- n + NONDEFAULTRULE wide + ROUTED M1 ( 1000 1000 ) ( 3000 1000 ) NDRV12 ;\n"
            "END NETS\n")
    db = load(tmp_path, lef, design(nets))
    assert any("NONDEFAULTRULE 'wide' closed by a bare END" in w for w in db.warnings())
    r = db.net_routing(0)
    assert r["wires"] == [("M1", 1000, 1000, 3000, 1000, 200, -1, -1)]  # the LEF rule's width
    assert r["vias"] == [("NDRV12", 3000, 1000)]


def test_electrical_tables_and_macro_timing_are_skipped(tmp_path):
    extra = """NOISETABLE 1 ;
  EDGERATE 20 ;
  OUTPUTRESISTANCE 3 ;
END NOISETABLE
IRDROP
  TABLE DROP1 0.0001 -0.7 0.001 -0.8 ;
END IRDROP
MACRO T
  SIZE 1 BY 1 ;
  TIMING
    FROMPIN a ; TOPIN z ; RISE INTRINSIC 0.1 0.2 ;
  END TIMING
  SITE core 0 0 N DO 5 BY 1 STEP 0.2 0 ;
  OBS
    LAYER M1 ;
    RECT MASK 2 ITERATE 0 0 0.1 0.1 DO 2 BY 1 STEP 0.2 0 ;
    POLYGON ( 0 0 ) ( 0.3 0 ) ( 0.3 0.2 ) ;
  END
END T
"""
    db = _engine.load_lef([write_lef(tmp_path, TECH.replace("END LIBRARY\n", extra + "END LIBRARY\n"))])
    skipped = db.skipped_statements()
    assert skipped["LEF.NOISETABLE"] == skipped["LEF.IRDROP"] == skipped["MACRO.TIMING"] == 1
    assert skipped["MACRO.SITE.PATTERN"] == 1 and skipped["OBS.RECT"] == 1  # the ITERATE, after its MASK
    assert db.macro("T")["obstructions"] == [("M1", 0, 0, 300, 200)]  # the '( x y )' polygon's box


def test_defines_are_skipped_with_a_warning(tmp_path):
    lef = TECH.replace("MANUFACTURINGGRID", '&defines &site = "core" ;\nMANUFACTURINGGRID')
    db = load(tmp_path, lef, design('&defines &x = "y" ;\n'))
    assert sum("'&defines' skipped" in w or "&DEFINES skipped" in w for w in db.warnings()) == 2


def test_macro_site_and_pin_defined_twice_warn_and_keep_the_first(tmp_path):
    inv = macro("INV", 0.4, 1.0, pin("a", "INPUT", [("M1", (0, 0, 0.1, 0.1))]),
                pin("a", "INPUT", [("M1", (0.2, 0, 0.3, 0.1))]))
    db = _engine.load_lef([write_lef(tmp_path, TECH.replace("END LIBRARY\n", inv + inv + site("core", 0.2, 1.0)
                                                            + "END LIBRARY\n"))])
    warnings = db.warnings()
    assert any("PIN 'a' defined again in MACRO 'INV'" in w for w in warnings)
    assert any("MACRO 'INV' defined again, identically: read once" in w for w in warnings)
    assert any("SITE 'core' defined again, identically" in w for w in warnings)
    m = db.macro("INV")
    assert m["size"] == (400, 1000)
    assert list(m["pins"]) == ["a"] and len(m["pins"]["a"]["shapes"]) == 2  # both ports of 'a'


def test_macro_defined_again_differently_is_an_error(tmp_path):
    lef = TECH.replace("END LIBRARY\n", macro("INV", 0.4, 1.0) + macro("INV", 0.6, 1.0) + "END LIBRARY\n")
    path = write_lef(tmp_path, lef)
    with pytest.raises(InputError) as info:
        _engine.load_lef([path])
    assert info.value.line == lef.split("\n").index("MACRO INV", lef.split("\n").index("MACRO INV") + 1) + 1
    assert "MACRO 'INV' defined again with different pins, geometry or size" in info.value.message


# ------------------------------------------------------------------ DEF constructs
def test_def_tracks_without_layer_polygon_stars_45_degree_and_maskshift(tmp_path):
    body = """COMPONENTMASKSHIFT M1 M2 ;
TRACKS X 100 DO 10 STEP 200 ;
TRACKS X 100 DO 10 STEP 200 LAYER M2 ;
SPECIALNETS 1 ;
- VDD + ROUTED M1 200 ( 0 0 ) ( 1000 1000 ) ( 3000 * )
  + POLYGON M2 ( 0 0 ) ( 100 * ) ( * 50 ) + USE POWER ;
END SPECIALNETS
"""
    db = load(tmp_path, TECH, design(body))
    assert [(t["layer"], t["count"]) for t in db.tracks()] == [("M2", 10)]
    assert db.skipped_statements()["COMPONENTMASKSHIFT"] == 1
    vdd = db.special_net("VDD")
    assert vdd["wires"] == [("M1", 200, "", 1000, 1000, 3000, 1000)]  # the 45-degree piece is not kept
    assert vdd["rects"] == [("M2", 0, 0, 100, 50)]
    w = db.warnings()
    assert any(x.endswith(":6: TRACKS without a LAYER: ignored") for x in w)
    assert any(x.endswith(":9: 45-degree special wire not kept") for x in w)


def test_def_via_layers_with_the_cut_last_and_a_quoted_pattern(tmp_path):
    rule = """VIARULE R12 GENERATE
  LAYER M1 ; ENCLOSURE 0 0 ;
  LAYER M2 ; ENCLOSURE 0 0 ;
  LAYER V1 ; RECT -0.03 -0.03 0.03 0.03 ; SPACING 0.14 BY 0.14 ;
END R12
"""
    vias = ("VIAS 1 ;\n- v + VIARULE R12 + CUTSIZE 60 60 + LAYERS M1 M2 V1 + CUTSPACING 80 80 "
            "+ ENCLOSURE 0 0 0 0 + ROWCOL 1 2 + PATTERN '1_2' ;\nEND VIAS\n")
    db = load(tmp_path, TECH.replace("END LIBRARY\n", rule + "END LIBRARY\n"), design(vias))
    v = db.def_via("v")
    assert (v["bottom"], v["cut"], v["top"]) == ("M1", "V1", "M2")
    out = tmp_path / "out.def"
    db.write_def(str(out))
    assert "+ LAYERS M1 V1 M2" in out.read_text() and "+ PATTERN 1_2\n" in out.read_text()  # quotes dropped


def test_def_nondefaultrule_widens_the_nets_wires(tmp_path):
    body = """NONDEFAULTRULES 1 ;
- wide + LAYER M1 WIDTH 200 SPACING 300 + LAYER M2 WIDTH 180 + VIA V12 ;
END NONDEFAULTRULES
NETS 2 ;
- n1 + ROUTED M1 ( 1000 1000 ) ( 3000 1000 ) V12 ( 3000 2000 ) + NONDEFAULTRULE wide ;
- n2 + ROUTED M1 ( 1000 5000 ) ( 3000 5000 ) ;
END NETS
"""
    db = load(tmp_path, TECH, design(body))
    assert db.net_routing(0)["wires"] == [("M1", 1000, 1000, 3000, 1000, 200, -1, -1),
                                          ("M2", 3000, 1000, 3000, 2000, 180, -1, -1)]
    assert db.net_routing(1)["wires"][0][5] == 0  # the default rule: the layer's width
    out = tmp_path / "out.def"
    db.write_def(str(out))
    text = out.read_text()
    assert "NONDEFAULTRULES 1 ;\n- wide\n  + LAYER M1 WIDTH 200 SPACING 300\n  + LAYER M2 WIDTH 180" in text
    assert "+ NONDEFAULTRULE wide" in text
    again = _engine.load([str(tmp_path / "t.lef")], str(out), "")
    assert again.net_routing(0)["wires"] == db.net_routing(0)["wires"]


def test_a_taper_segment_of_a_rule_net_keeps_the_default_width(tmp_path):
    # TAPER: that layer's wires of the path, up to its next via, at the layer's width (60), and
    # that via drawn to the default rule too; the rest of the net at the rule's width. The writer
    # gives the TAPER back (the via on a path of its own); a net without a rule reads TAPER as its
    # default width anyway.
    body = """NONDEFAULTRULES 1 ;
- wide + LAYER M1 WIDTH 200 + LAYER M2 WIDTH 180 ;
END NONDEFAULTRULES
NETS 2 ;
- n1 + NONDEFAULTRULE wide + ROUTED M1 TAPER ( 1000 1000 ) ( 3000 1000 ) V12 ( 3000 2000 )
    NEW M1 ( 1000 1000 ) ( 1000 3000 ) ;
- n2 + ROUTED M1 TAPER ( 1000 5000 ) ( 3000 5000 ) ;
END NETS
"""
    db = load(tmp_path, TECH, design(body))
    assert db.skipped_statements().get("NETS.TAPER") is None
    assert db.net_routing(0)["wires"] == [("M1", 1000, 1000, 3000, 1000, 60, -1, -1),
                                          ("M2", 3000, 1000, 3000, 2000, 180, -1, -1),
                                          ("M1", 1000, 1000, 1000, 3000, 200, -1, -1)]
    assert db.net_routing(1)["wires"] == [("M1", 1000, 5000, 3000, 5000, 60, -1, -1)]
    out = tmp_path / "out.def"
    db.write_def(str(out))
    text = out.read_text()
    assert "+ ROUTED M1 TAPER ( 1000 1000 ) ( 3000 1000 )\n    NEW M2 ( 3000 1000 ) ( 3000 2000 )" in text
    assert "NEW M1 TAPER ( 3000 1000 ) V12" in text
    assert text.count("TAPER") == 2
    again = _engine.load([str(tmp_path / "t.lef")], str(out), "")
    assert again.net_routing(0)["wires"] == db.net_routing(0)["wires"]


def test_unknown_nondefaultrule_is_an_error(tmp_path):
    e = load_error(tmp_path, TECH, design("NETS 1 ;\n- n + NONDEFAULTRULE nope ;\nEND NETS\n"))
    assert e.line == 6 and "unknown NONDEFAULTRULE 'nope'" in e.message


def test_def_without_diearea_takes_the_placed_box(tmp_path):
    lef = TECH.replace("END LIBRARY\n", macro("INV", 0.4, 1.0) + "END LIBRARY\n")
    body = "COMPONENTS 1 ;\n- u1 INV + PLACED ( 1000 2000 ) N ;\nEND COMPONENTS\n"
    db = load(tmp_path, lef, design(body).replace("DIEAREA ( 0 0 ) ( 20000 20000 ) ;\n", ""))
    assert db.die_area == (1000, 2000, 1400, 3000)
    assert "no DIEAREA: the box of the rows, placed components and IO pins stands in" in db.warnings()[0]


def test_guides_are_rescaled_with_their_def(tmp_path):
    body = "NETS 1 ;\n- n ;\nEND NETS\n"
    lef = write_lef(tmp_path, TECH)
    def_path = tmp_path / "t.def"
    def_path.write_text(design(body, 500))
    guide = tmp_path / "t.guide"
    guide.write_text("n\n(\n0 0 1000 500 M1\n)\n")
    db = _engine.load([lef], str(def_path), str(guide))
    assert list(db.guide_rects[0]) == [0, 0, 2000, 1000]


def test_check_judges_nondefaultrule_width_and_spacing(tmp_path):
    # Two parallel M1 wires 400 DBU apart (centre to centre). Default width 60 and spacing 70:
    # legal. Under the rule (width 200, spacing 300) the gap is 200 < 300: one spacing marker.
    def nets(rule: str) -> str:
        head = ("NONDEFAULTRULES 1 ;\n- wide + LAYER M1 WIDTH 200 SPACING 300 ;\nEND NONDEFAULTRULES\n"
                if rule else "")
        return head + ("NETS 2 ;\n"
                       f"- a + ROUTED M1 ( 1000 1000 ) ( 5000 1000 ){rule} ;\n"
                       "- b + ROUTED M1 ( 1000 1400 ) ( 5000 1400 ) ;\nEND NETS\n")

    plain = load(tmp_path, TECH, design(nets("")))
    assert [m for m in plain.check_drc() if m["type"] == "MetalSpacing"] == []
    wide = load(tmp_path, TECH, design(nets(" + NONDEFAULTRULE wide")))
    spacing = [m for m in wide.check_drc() if m["type"] == "MetalSpacing"]
    assert len(spacing) == 1 and spacing[0]["layer"] == "M1"


def test_def_without_diearea_and_nothing_placed_keeps_no_die(tmp_path):
    body = "PINS 1 ;\n- p + NET n + LAYER M1 ( 0 0 ) ( 10 10 ) + PLACED ( 500 500 ) N ;\nEND PINS\n"
    db = load(tmp_path, TECH, design(body).replace("DIEAREA ( 0 0 ) ( 20000 20000 ) ;\n", ""))
    assert db.die_area == (0, 0, 0, 0)  # one placed point has no area: no box stands in
    assert not any("no DIEAREA" in w for w in db.warnings())


def test_unknown_def_statement_is_quoted_as_written(tmp_path):
    e = load_error(tmp_path, TECH, design("Bogus 1 ;\n"))
    assert e.line == 5 and "expected a DEF statement, found 'Bogus'" in e.message


# ------------------------------------------------ a spacing-table row out of order (ISPD-2018 test4-10)
def test_spacing_table_row_narrower_than_the_one_before_is_left_out_with_a_warning(tmp_path):
    """ISPD-2018 test4-test10's Metal9 table ends with a WIDTH row narrower than the row before it;
    no ascending lookup can reach it: the table keeps the rows in order, the warning names the row."""
    table = ["SPACINGTABLE", "  PARALLELRUNLENGTH 0 1.0", "  WIDTH 0 0.07 0.08", "  WIDTH 0.3 0.1 0.12",
             "  WIDTH 0.9 0.3 0.35", "  WIDTH 0.3 0.05 0.06 ;"]
    lef = library(stack(spacing=None, rules={"M2": table}), site("core", 0.2, 1.0))
    db = load(tmp_path, lef, design(""))
    m2 = next(l for l in db.layers() if l["name"] == "M2")
    assert m2["spacing_table"]["widths"] == [0, 300, 900]
    assert m2["spacing_table"]["spacing"] == [[70, 80], [100, 120], [300, 350]]
    assert any("SPACINGTABLE row WIDTH 0.3 of LAYER 'M2' is narrower than the row before it: left out" in w
               for w in db.warnings())
