"""Routing metrics (wirelength, vias) on a drawn routed DEF and the unrouted
contest designs; the DRC report file (exact content, atomic write)."""

from __future__ import annotations

import os

import pytest

import test_drc_design
from conftest import STANDINS, available
from drawn import load_contest
from test_connectivity import load as load_conn
from xroute.errors import InputError


# Cells u1, u2, u3 and layers M1/M2/M3, V12/V23 of test_connectivity.
ROUTED_NETS = [
    # n1: V12 at (800,500); M2 (800,500)-(800,1500) = 1000; V23; M3 (800,1500)-(2200,1500)
    # = 1400; V23; M2 (2200,1500)-(2200,500) = 1000; V12.
    "- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) V12 ( 800 1500 ) V23 ( 2200 1500 ) V23"
    " NEW M2 ( 2200 1500 ) ( 2200 500 ) V12 ;",
    # n2: M1 (4100,300)-(4500,300) = 400 (the 100 extension is not counted), then
    # (4500,300)-(4500,900) = 600.
    "- n2 ( u3 A ) ( u3 Y ) + ROUTED M1 ( 4100 300 ) ( 4500 300 100 ) ( 4500 900 ) ;",
    # n3: a patch only: routed, no length.
    "- n3 ( u1 A ) ( u2 Y ) + ROUTED M1 ( 0 0 ) RECT ( 0 0 100 100 ) ;",
    # n4: not routed.
    "- n4 ( u1 B ) ( u2 B ) ;",
]


def test_metrics_of_a_drawn_routed_design(tmp_path):
    m = load_conn(tmp_path, ROUTED_NETS).metrics()
    # M1 400 + 600 = 1000; M2 1000 + 1000 = 2000; M3 1400: 4400 DBU = 4.4 um at 1000 DBU/um.
    assert m == {
        "wirelength_dbu": 4400,
        "wirelength_um": pytest.approx(4.4),
        "wirelength_by_layer": {"M1": 1000, "M2": 2000, "M3": 1400},
        "vias": 4,
        "vias_by_cut_layer": {"V1": 2, "V2": 2},
        "nets_routed": 3,
    }


def test_metrics_empty_design(tmp_path):
    m = load_conn(tmp_path, ["- n4 ( u1 B ) ( u2 B ) ;"]).metrics()
    assert (m["wirelength_dbu"], m["wirelength_um"], m["vias"], m["nets_routed"]) == (0, 0.0, 0, 0)
    assert m["wirelength_by_layer"] == {"M1": 0, "M2": 0, "M3": 0}
    assert m["vias_by_cut_layer"] == {"V1": 0, "V2": 0}


@pytest.mark.parametrize("name", available("ispd18_sample", "ispd18_test1"))
def test_unrouted_contest_design_metrics_are_zero(name):
    m = load_contest(name).metrics()  # contest designs: 9 metal layers; the generated one: 6
    metals = 6 if name in STANDINS else 9
    assert (m["wirelength_dbu"], m["wirelength_um"], m["vias"], m["nets_routed"]) == (0, 0.0, 0, 0)
    assert list(m["wirelength_by_layer"]) == [f"Metal{i}" for i in range(1, metals + 1)]
    assert set(m["wirelength_by_layer"].values()) == {0}
    assert list(m["vias_by_cut_layer"]) == [f"Via{i}" for i in range(1, metals)]
    assert set(m["vias_by_cut_layer"].values()) == {0}


# ---------------------------------------------------------------------------
# DRC report

# test_drc_design's tiny design (u1, u2 INV; special net VDD; net n1 with an
# M1 wire and a V12) plus three more n1 pieces: into u1's OBS, onto the VDD
# special wire at y 3000 and u1/VDD, and onto u2's VDD pin (on no net: "*/VDD").
DIRTY = (" NEW M1 ( 1800 1500 ) ( 1500 1500 ) NEW M1 ( 2000 2900 ) ( 2000 2000 )"
         " NEW M1 ( 2500 1200 ) ( 2500 1000 )")

HEADER = "# markers {n} Short {short} MetalSpacing {spacing} EndOfLine 0 CutShort 0 CutSpacing 0 AdjacentCuts 0 MinArea {area} CornerSpacing 0\n"
ROUTED_MARKERS = (
    "Short M1 1450 1450 1600 1550 n1 -\n"        # wire into u1's OBS
    "Short M1 1950 1950 2000 2100 n1 VDD\n"      # wire onto u1/VDD (a VDD special-net pin)
    "Short M1 1950 2900 2050 2950 n1 VDD\n"      # wire onto the VDD special wire
    "Short M1 2450 950 2550 1100 n1 */VDD\n"     # wire onto u2/VDD (POWER pin on no net)
    "MetalSpacing M1 2450 1250 2550 1300 n1 -\n"  # its end 50 below u2's OBS
)


def counts(short: int, spacing: int, area: int) -> dict:
    return {"Short": short, "MetalSpacing": spacing, "EndOfLine": 0, "CutShort": 0, "CutSpacing": 0,
            "AdjacentCuts": 0, "MinArea": area, "CornerSpacing": 0}


def test_drc_report_content(tmp_path):
    db = test_drc_design.load(tmp_path, DIRTY)
    path = tmp_path / "out" / "drc.rpt"
    path.parent.mkdir()
    assert db.write_drc_report(str(path)) == counts(4, 1, 1)
    assert path.read_text() == (HEADER.format(n=6, short=4, spacing=1, area=1) + ROUTED_MARKERS
                                + "MinArea M1 2450 950 2550 1250 n1 -\n")  # the 100 x 300 piece alone
    assert os.listdir(path.parent) == ["drc.rpt"]
    # With fixed-only markers: the two small pins on no net, named comp/pin.
    assert db.write_drc_report(str(path), skip_fixed_pairs=False) == counts(4, 1, 3)
    assert path.read_text() == (HEADER.format(n=8, short=4, spacing=1, area=3) + ROUTED_MARKERS
                                + "MinArea M1 1100 1400 1300 1600 u1/A -\n"
                                + "MinArea M1 2450 950 2550 1250 n1 -\n"
                                + "MinArea M1 2700 1400 2900 1600 u2/Y -\n")
    assert os.listdir(path.parent) == ["drc.rpt"]


def test_drc_report_clean_design(tmp_path):
    db = test_drc_design.load(tmp_path)
    path = tmp_path / "clean.rpt"
    path.write_text("old content that must go\n" * 100)
    assert db.write_drc_report(str(path)) == counts(0, 0, 0)
    assert path.read_text() == HEADER.format(n=0, short=0, spacing=0, area=0)


def test_drc_report_names_an_io_pin_on_no_net(tmp_path):
    # io2 (on no net) at (1000,500): M1 (1000,500)-(1100,600), under n1's M1 wire
    # (750,450)-(2250,550). Net ids: n1 0; no special nets; pins on no net
    # u1/A, u1/B, u2/Y, u2/B, u3/A, u3/Y, u3/B, then io2.
    pins = "PINS 1 ;\n- io2 + DIRECTION INPUT + LAYER M1 ( 0 0 ) ( 100 100 ) + PLACED ( 1000 500 ) N ;\nEND PINS\n"
    db = load_conn(tmp_path, ["- n1 ( u1 Y ) ( u2 A ) + ROUTED M1 ( 800 500 ) ( 2200 500 ) ;"], pins)
    path = tmp_path / "io.rpt"
    assert db.write_drc_report(str(path)) == counts(1, 0, 0)
    assert path.read_text() == (
        "# markers 1 Short 1 MetalSpacing 0 EndOfLine 0 CutShort 0 CutSpacing 0 AdjacentCuts 0 MinArea 0 CornerSpacing 0\n"
        "Short M1 1000 500 1100 550 n1 PIN/io2\n")


def test_drc_report_write_failure_leaves_nothing(tmp_path):
    db = test_drc_design.load(tmp_path, DIRTY)
    before = sorted(os.listdir(tmp_path))
    # The target is a directory: the temporary file is written, the rename fails.
    target = tmp_path / "a_dir"
    target.mkdir()
    with pytest.raises(InputError) as info:
        db.write_drc_report(str(target))
    assert info.value.line == 0 and "cannot write DRC report" in info.value.message
    assert sorted(os.listdir(tmp_path)) == sorted(before + ["a_dir"])
    assert os.listdir(target) == []
    # The folder does not exist: nothing is created.
    with pytest.raises(InputError):
        db.write_drc_report(str(tmp_path / "missing" / "drc.rpt"))
    assert sorted(os.listdir(tmp_path)) == sorted(before + ["a_dir"])


def test_route_outputs_figures_are_typed(tmp_path) -> None:
    """RouteOutputs.figures: the metrics JSON's final figures as a typed record."""
    from xroute import RouterSettings, prepare_design, route_to_outputs
    from xroute.outputs import FinalFigures

    outputs = route_to_outputs(prepare_design("demo"), tmp_path, RouterSettings(iterations=1))
    figures = outputs.figures
    assert isinstance(figures, FinalFigures)
    assert (figures.wirelength_um, figures.vias, figures.violations, figures.open_nets) == (
        outputs.final["wirelength_um"], outputs.final["vias"], outputs.final["violations"], 0)
    assert figures.violations == sum(figures.violations_by_type.values())
