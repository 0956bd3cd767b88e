"""The public LEF/DEF corpus check (bench/lefdef_corpus.py) and its independent counter.

The corpus itself (files of other projects) lives outside the repository: at $XROUTE_LEFDEF_CORPUS
or /work/corpus, with its manifest.tsv; bench/lefdef_corpus.tsv is the committed copy of the
manifest (paths and provenance only). Without the corpus the check skips and says where it looked.
"""

from __future__ import annotations

import gzip
import os
from pathlib import Path

import pytest

from conftest import load_file

corpus = load_file("bench/lefdef_corpus.py")

# A tiny technology and design of our own: names, keyword case, a pin named like its macro and a
# quoted property with a `;` inside are the traps a line counter would fall into.
TINY_LEF = """VERSION 5.8 ;
UNITS DATABASE MICRONS 1000 ; END UNITS
PROPERTYDEFINITIONS LAYER LEF58_NOTE STRING ; END PROPERTYDEFINITIONS
LAYER m1 TYPE ROUTING ; DIRECTION HORIZONTAL ; PITCH 0.2 ; WIDTH 0.1 ;
  PROPERTY LEF58_NOTE "SPACING 0.1 ;
    END m1 ;" ;
END m1
LAYER cut1 TYPE CUT ; END cut1
Layer m2 TYPE ROUTING ; DIRECTION VERTICAL ; PITCH 0.2 ; WIDTH 0.1 ; END m2
VIA v1 DEFAULT LAYER m1 ; RECT -0.1 -0.1 0.1 0.1 ; LAYER cut1 ; RECT -0.05 -0.05 0.05 0.05 ;
  LAYER m2 ; RECT -0.1 -0.1 0.1 0.1 ; END v1
VIARULE gen GENERATE LAYER m1 ; ENCLOSURE 0 0 ; END gen
SITE core CLASS CORE ; SIZE 0.2 BY 1.0 ; END core
MACRO pad CLASS PAD ; SIZE 2 BY 2 ;
  PIN pad DIRECTION INOUT ; PORT LAYER m2 ; RECT 0 0 1 1 ; END END pad
  OBS LAYER m1 ; RECT 0 0 2 2 ; END
END pad
MACRO inv SIZE 0.4 BY 1.0 ; PIN a PORT LAYER m1 ; RECT 0 0 0.1 0.1 ; END END a END inv
# MACRO commented_out
END LIBRARY
"""

TINY_DEF = """VERSION 5.8 ;
DESIGN tiny ;
UNITS DISTANCE MICRONS 1000 ;
DIEAREA ( 0 0 ) ( 4000 4000 ) ;
ROW r0 core 0 0 N DO 10 BY 1 STEP 200 0 ;
ROW r1 core 0 1000 FS DO 10 BY 1 STEP 200 0 ;
TRACKS Y 100 DO 20 STEP 200 LAYER m1 ;
VIAS 1 ; - v2 + RECT m1 ( -50 -50 ) ( 50 50 ) ; END VIAS
COMPONENTS 3 ;
  - u1 inv + PLACED ( 0 0 ) N ;
  - u2 inv + PLACED ( 400 0 ) N ; - p1 pad + FIXED ( 2000 2000 ) N ;
END COMPONENTS
PINS 1 ; - in + NET n1 + LAYER m2 ( 0 0 ) ( 100 100 ) + PLACED ( 0 500 ) N ; END PINS
BLOCKAGES 1 ; - LAYER m1 RECT ( 0 0 ) ( 10 10 ) ; END BLOCKAGES
SPECIALNETS 1 ;
  - VDD + ROUTED m1 200 ( 0 0 ) ( 4000 0 )
    NEW m2 200 ( 0 0 ) ( 0 4000 ) + USE POWER ;
END SPECIALNETS
NETS 2 ;
  - n1 ( PIN in ) ( u1 a )
    + ROUTED m1 ( 0 500 ) ( 100 * ) v1 ;
  - n2 ( u1 a ) ( u2 a ) ;
END NETS
END DESIGN
"""


def test_counter_on_tiny_lef_and_def() -> None:
    names = corpus.count_lef(TINY_LEF)
    assert names["LAYER"] == {"m1", "cut1", "m2"}
    assert names["VIA"] == {"v1"}
    assert names["MACRO"] == {"pad", "inv"}
    assert corpus.count_def(TINY_DEF) == {
        "components": 3, "nets": 2, "special_nets": 1, "io_pins": 1, "def_vias": 1, "rows": 2}


def test_counter_reads_gzip_and_a_manifest(tmp_path: Path) -> None:
    (tmp_path / "t.lef.gz").write_bytes(gzip.compress(TINY_LEF.encode()))
    (tmp_path / "t.def").write_text(TINY_DEF)
    (tmp_path / "m.tsv").write_text(
        "# comment\nid\tproject\trepo\tcommit\tdef\tlefs\texpect\n"
        "tiny\tours\town/tests\t0\tt.def\tt.lef.gz\tread\n")
    (pair,) = corpus.read_manifest(tmp_path / "m.tsv")
    assert pair.valid and pair.lefs == ["t.lef.gz"]
    counts = corpus.independent_counts(tmp_path, pair)
    assert counts["macros"] == 2 and counts["layers"] == 3 and counts["nets"] == 2
    assert corpus.compare(counts, dict(counts, nets=3)) == ["nets: info 3, scanner 2"]


CORPUS = Path(os.environ.get("XROUTE_LEFDEF_CORPUS", "/work/corpus"))


@pytest.mark.slow
@pytest.mark.skipif(not (CORPUS / "manifest.tsv").is_file(),
                    reason=f"no LEF/DEF corpus at {CORPUS} (set $XROUTE_LEFDEF_CORPUS to a folder "
                           "with manifest.tsv; bench/lefdef_corpus.tsv lists its sources)")
def test_public_corpus_is_read(capsys: pytest.CaptureFixture[str]) -> None:
    status = corpus.main([str(CORPUS / "manifest.tsv"), "--jobs", "2"])
    report = capsys.readouterr().out
    assert status == 0, report


def test_the_counter_skips_property_definitions_of_rows() -> None:
    """`ROW name TYPE ;` inside PROPERTYDEFINITIONS defines a property, not a row (OpenROAD's
    parser_test.def has six of them beside its one row)."""
    text = ("VERSION 5.8 ;\nDESIGN d ;\nPROPERTYDEFINITIONS\n  ROW strprop STRING ;\n  ROW intprop INTEGER ;\n"
            "END PROPERTYDEFINITIONS\nROW r0 core 0 0 N DO 10 BY 1 STEP 200 0 ;\nEND DESIGN\n")
    assert corpus.count_def(text)["rows"] == 1
