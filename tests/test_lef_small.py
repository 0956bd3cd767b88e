"""LEF reader on small hand-written LEFs: statement forms the contest files
do not use, several files into one Tech, and skipped-statement counting.
Lengths in DBU (UNITS 1000 unless a test says otherwise).
"""

from __future__ import annotations

from lef_text import TECH, write_lef
from xroute import _engine


def layers_by_name(db) -> dict:
    return {layer["name"]: layer for layer in db.layers()}


def test_small_tech_lef(tmp_path):
    db = _engine.load_lef([write_lef(tmp_path, TECH)])
    layers = layers_by_name(db)
    assert layers["M1"]["pitch"] == (200, 200) and layers["M1"]["offset"] == (100, 100)
    assert layers["V1"]["width"] == 100
    assert db.manufacturing_grid == 5
    via = db.via("V12")
    assert (via["bottom"], via["cut"], via["top"]) == ("M1", "V1", "M2")  # from LEF order, not shape order
    assert via["shapes"][2] == ("M1", -100, -50, 100, 50)  # corners given high-to-low
    assert db.skipped_statements() == {} and db.warning_count == 0


def test_cell_lef_after_tech_lef(tmp_path):
    tech = write_lef(tmp_path, TECH, "tech.lef")
    cells = write_lef(tmp_path, """
        VIA VP
          RESISTANCE 2.5 ;
          LAYER M2 ;
            POLYGON -0.1 0 0 0.2 0.1 0 0 -0.3 ;
          LAYER V1 ;
            RECT -0.05 -0.05 0.05 0.05 ;
        END VP
        MACRO INV
          CLASS CORE ;
          ORIGIN 0.1 0.2 ;
          SIZE 0.6 BY 1.8 ;
          SYMMETRY X Y ;
          SITE core ;
          PIN A
            DIRECTION INPUT ;
            USE SIGNAL ;
            PORT
              LAYER M1 ;
                RECT 0.3 0.4 0.1 0.2 ;
              VIA 0 0 V12 ;
            END
            PORT
              LAYER M2 ;
                POLYGON 0 0 0.2 0 0.2 0.3 0.1 0.3 ;
            END
          END A
          OBS
            LAYER M1 DESIGNRULEWIDTH 0.2 ;
              RECT -0.1 -0.2 0.5 1.6 ;
          END
        END INV
        END LIBRARY
        """, "cells.lef")
    db = _engine.load_lef([tech, cells])
    assert db.counts()["macros"] == 1 and db.counts()["layers"] == 3 and db.counts()["lef_vias"] == 2
    inv = db.macro("INV")
    assert inv["origin"] == (100, 200)
    a = inv["pins"]["A"]
    assert a["port_count"] == 2
    # Every shape moved by the ORIGIN (100, 200); the via's shapes placed at (0,0) first.
    assert a["shapes"] == [
        ("M1", 200, 400, 400, 600),
        ("V1", 50, 150, 150, 250),
        ("M2", 50, 100, 150, 300),
        ("M1", 0, 150, 200, 250),
        ("M2", 100, 200, 300, 500),  # POLYGON bounding box
    ]
    assert inv["obstructions"] == [("M1", 0, 0, 600, 1800)]
    assert db.skipped_statements() == {"OBS.LAYER.DESIGNRULEWIDTH": 1, "VIA.RESISTANCE": 1}
    vp = db.via("VP")
    assert vp["default"] is False
    assert (vp["bottom"], vp["cut"], vp["top"]) == ("", "V1", "M2")  # no shape below the cut
    assert vp["shapes"] == [("M2", -100, -300, 100, 200), ("V1", -50, -50, 50, 50)]  # POLYGON -> bounding box


def test_unknown_and_unmodelled_statements_are_counted(tmp_path):
    path = write_lef(tmp_path, """
        UNITS
          TIME NANOSECONDS 100 ;
          DATABASE MICRONS 1000 ;
        END UNITS
        PROPERTYDEFINITIONS
          LAYER LEF58_CORNERSPACING STRING ;
          LAYER LEF58_EOLKEEPOUT STRING ;
        END PROPERTYDEFINITIONS
        NOWIREEXTENSIONATPIN ON ;
        LAYER M1
          TYPE ROUTING ;
          DIRECTION HORIZONTAL ;
          RESISTANCE RPERSQ 0.38 ;
          WIDTH 0.1 ;
          FROBNICATE 1 2 "x ; y" ;
          SPACING 0.1 ;
          SPACING 0.2 RANGE 0.3 0.4 ;
          SPACING 0.12 SAMENET ;
          SPACING 0.5 LENGTHTHRESHOLD 0.9 ;
          SPACING 0.15 ENDOFLINE 0.1 WITHIN 0.03 PARALLELEDGE 0.14 WITHIN 0.05 TWOEDGES ;
          ACCURRENTDENSITY PEAK
            FREQUENCY 100 400 ;
            WIDTH 0.1 1 10 ;
            TABLEENTRIES 1 2 3 4 5 6 ;
          AREA 0.05 ;
          SPACINGTABLE TWOWIDTHS WIDTH 0 0.1 WIDTH 0.2 0.2 ;
          PROPERTY LEF58_EOLKEEPOUT "EOLKEEPOUT 0.1 EXTENSION 0 0 0 ;" ;
          PROPERTY LEF58_CORNERSPACING "CORNERSPACING CONVEXCORNER CORNERONLY 0.1 WIDTH 0 SPACING 0.1 ;
                                        CORNERSPACING CONCAVECORNER WIDTH 0 SPACING 0.2 ;" ;
        END M1
        LAYER V1
          TYPE CUT ;
          SPACING 0.1 CENTERTOCENTER ;
          SPACING 0.2 LAYER M1 ;
          ENCLOSURE BELOW 0 0.03 ;
        END V1
        LAYER M2
          TYPE ROUTING ;
          RESISTANCE RPERSQ 0.38 ;
        END M2
        LAYER poly
          TYPE MASTERSLICE ;
        END poly
        NONDEFAULTRULE wide
          LAYER M1
            WIDTH 0.4 ;
          END M1
        END wide
        VIARULE TURN1
          LAYER M1 ;
            DIRECTION HORIZONTAL ;
            WIDTH 0.1 TO 1.0 ;
          VIA V12 ;
        END TURN1
        END LIBRARY
        """)
    db = _engine.load_lef([path])
    skipped = db.skipped_statements()
    assert skipped == {
        "UNITS.TIME": 1,
        "PROPERTYDEFINITIONS.LAYER": 2,
        "LEF.NOWIREEXTENSIONATPIN": 1,
        "LAYER.RESISTANCE": 2,
        "LAYER.FROBNICATE": 1,
        "LAYER.SPACING.LENGTHTHRESHOLD": 1,
        "LAYER.ACCURRENTDENSITY": 1,
        "LAYER.SPACINGTABLE.TWOWIDTHS": 1,
        "LAYER.PROPERTY.LEF58_EOLKEEPOUT": 1,
        "LAYER.LEF58_CORNERSPACING.CORNERONLY": 1,
        "LAYER.SPACING.LAYER": 1,
        "LAYER.ENCLOSURE": 1,
        "VIARULE.DIRECTION": 1,
        "VIARULE.VIA": 1,
    }
    assert db.warning_count == sum(skipped.values())
    layers = layers_by_name(db)
    m1 = layers["M1"]
    assert m1["width"] == 100  # not the ACCURRENTDENSITY table's WIDTH line
    assert m1["min_area"] == 50000
    assert m1["spacing_rules"] == [
        dict(space=100, range=None, same_net=False),
        dict(space=200, range=(300, 400), same_net=False),
        dict(space=120, range=None, same_net=True),
    ]
    assert m1["eol_rules"] == [dict(space=150, eol_width=100, within=30, parallel_edge=True, par_space=140,
                                    par_within=50, two_edges=True)]
    assert m1["spacing_table"]["widths"] == []
    assert m1["corner_spacing_rules"] == [
        dict(convex_corner=False, concave_corner=True, except_eol=False, eol_width=0, widths=[0], spacings=[200])
    ]
    assert [name for name, _ in m1["properties"]] == ["LEF58_EOLKEEPOUT", "LEF58_CORNERSPACING"]
    assert layers["V1"]["cut_spacing_rules"] == [
        dict(space=100, center_to_center=True, same_net=False, adjacent_cuts=0, cut_within=0)]
    assert layers["poly"]["type"] == "MASTERSLICE"
    assert db.counts()["routing_layers"] == 2 and db.counts()["cut_layers"] == 1
    rule = db.via_rule("TURN1")
    assert rule["generate"] is False
    assert rule["layers"] == [dict(layer="M1", enclosure=(0, 0), width=(100, 1000), rect=(0, 0, 0, 0),
                                   spacing=(0, 0))]


def test_counts_merge_across_files(tmp_path):
    tech = write_lef(tmp_path, TECH + "USEMINSPACING OBS ON ;\n", "a.lef")
    more = write_lef(tmp_path, "USEMINSPACING OBS OFF ;\nLAYER M3\n  TYPE ROUTING ;\n  THICKNESS 1 ;\nEND M3\n", "b.lef")
    db = _engine.load_lef([tech, more])
    assert db.skipped_statements() == {"LEF.USEMINSPACING": 2, "LAYER.THICKNESS": 1}
    assert db.warning_count == 3
    assert layers_by_name(db)["M3"]["routing_index"] == 2
