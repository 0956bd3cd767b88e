"""``xroute plot-region``: a PNG of a routed region (needs the optional extra ``plot``: matplotlib)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import pick
from png import distinct_colours, png_size
from xroute.cli.app import app
from xroute.cli.plot_data import Marker, layer_colours, read_drc_report


def need_matplotlib() -> None:
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail("matplotlib is missing in CI (.ci/run installs the 'plot' extra)")
        pytest.skip("matplotlib not installed (pip install 'xroute[plot]')")



SAMPLE4 = pick("ispd19_sample4")  # or its generated stand-in (die 34200 x 33600) without the contest data
BOX = "240000,340000,252000,350000" if SAMPLE4 == "ispd19_sample4" else "10000,10000,22000,20000"


@pytest.fixture
def routed(runner: CliRunner, testcase, tmp_path: Path) -> Path:
    testcase(SAMPLE4)
    out = tmp_path / "run"
    assert runner.invoke(app, ["route", SAMPLE4, "--iterations", "2", "--quiet", "--out", str(out)]).exit_code == 0
    return out


def test_plot_region_box_with_markers(runner: CliRunner, routed: Path, tmp_path: Path) -> None:
    need_matplotlib()
    png = tmp_path / "region.png"
    result = runner.invoke(app, ["plot-region", str(routed), "--box", BOX, "--out", str(png)])
    assert result.exit_code == 0, result.stderr
    x0, y0, x1, y1 = BOX.split(",")
    assert result.stdout == f"plot-region: {SAMPLE4} ({x0},{y0})-({x1},{y1}) -> {png}\n"
    width, height = png_size(png)
    assert width > 600 and height > 300
    assert distinct_colours(png) > 20  # layers, pins, markers, legend text: not blank


def test_plot_region_by_gcell_from_a_def(runner: CliRunner, routed: Path, testcase, tmp_path: Path) -> None:
    need_matplotlib()
    found = testcase(SAMPLE4)
    from bisect import bisect_right

    from xroute.cli.plot_data import gcell_lines
    from xroute.design import load_design

    routed_def = routed / f"{SAMPLE4}.routed.def"
    design = load_design(lef=[str(found.lef)], def_=str(routed_def), guide=str(found.guide))
    _, x, y, *_ = next(w for n in range(design.num_nets) for w in design.net_routing(n)["wires"])
    gx = bisect_right(gcell_lines(design, 0), x) - 1  # the GCell of a wire's end: not empty
    gy = bisect_right(gcell_lines(design, 1), y) - 1
    png = tmp_path / "g.png"
    result = runner.invoke(app, ["plot-region", str(routed_def), "--lef", str(found.lef),
                                 "--guide", str(found.guide), "--gcell", f"{gx},{gy}", "--size", "2", "--out", str(png)])
    assert result.exit_code == 0, result.stderr
    assert distinct_colours(png) > 20


def test_plot_region_argument_errors(runner: CliRunner, routed: Path, tmp_path: Path) -> None:
    result = runner.invoke(app, ["plot-region", str(routed), "--box", "1,2,3", "--out", str(tmp_path / "x.png")])
    assert result.exit_code == 2 and result.stderr == "error: --box must be 4 comma-separated integers, got '1,2,3'\n"
    result = runner.invoke(app, ["plot-region", str(tmp_path), "--box", "0,0,1,1"])
    assert result.exit_code == 2 and "no *.metrics.json here" in result.stderr
    assert not (tmp_path / "x.png").exists()


# A generated design that ends its second iteration at region size 2 with markers (EndOfLine between
# two nets): the contest samples route clean, so the marker tests draw this one wherever the contest
# data is.
MARKED = "standin_marked"


@pytest.fixture
def marked(runner: CliRunner, testcase, tmp_path: Path) -> Path:
    testcase(MARKED)
    out = tmp_path / "marked"
    args = ["route", MARKED, "--iterations", "2", "--region-size", "2", "--quiet", "--out", str(out)]
    assert runner.invoke(app, args).exit_code == 0
    return out


def _two_net_marker(run: Path) -> Marker:
    markers = [m for m in read_drc_report(run / f"{MARKED}.drc.rpt")
               if len(m.net_names) == 2 and not {"VDD", "VSS"} & set(m.net_names)]  # two signal nets
    assert markers, "the stand-in is expected to end its second iteration with a two-net marker"
    return markers[0]


def test_plot_region_net_labels_the_marker_nets(runner: CliRunner, marked: Path, tmp_path: Path) -> None:
    need_matplotlib()
    m = _two_net_marker(marked)
    first, second = m.net_names
    box = f"{m.box[0] - 1500},{m.box[1] - 1500},{m.box[2] + 1500},{m.box[3] + 1500}"
    svg = tmp_path / "n.svg"
    result = runner.invoke(app, ["plot-region", str(marked), "--box", box, "--net", first, "--out", str(svg)])
    assert result.exit_code == 0, result.stderr
    text = svg.read_text()
    assert f"net {first}" in text and f"net {second}" in text  # both nets of the marker labelled on their shapes
    assert f": {m.kind} {m.layer}: {first} × {second}" in text  # the marker, numbered: type, layer, nets
    assert f"net {first} (others dimmed)" in text  # the legend names the highlighted net
    assert "x (µm; 2000 DBU per µm)" in text or "x (µm;" in text  # µm axes by default
    png = tmp_path / "n.png"
    assert runner.invoke(app, ["plot-region", str(marked), "--box", box, "--dbu", "--out", str(png)]).exit_code == 0
    assert distinct_colours(png) > 20


def test_plot_region_colours_each_via_layer(loaded_design) -> None:
    design = loaded_design(MARKED)
    colours = layer_colours(design)
    cuts = [layer.name for layer in design.cut_layers]
    named = [colours[n] for n in [layer.name for layer in design.routing_layers] + cuts]
    assert len(cuts) >= 2 and len(set(named)) == len(named)  # Via1 and Via2 differ, and differ from the metals


def test_plot_region_empty_box_warns_and_exits_2(runner: CliRunner, marked: Path, tmp_path: Path) -> None:
    png = tmp_path / "empty.png"
    result = runner.invoke(app, ["plot-region", str(marked), "--box", "0,0,10,10", "--out", str(png)])
    assert result.exit_code == 2
    assert result.stderr == (f"warning: {marked / (MARKED + '.routed.def')}: nothing in the box (0,0)-(10,10) "
                             "(no wire, via, pin or marker): no picture written\n")
    assert not png.exists()


def test_plot_region_unknown_net_and_format_are_one_line(runner: CliRunner, marked: Path, tmp_path: Path) -> None:
    result = runner.invoke(app, ["plot-region", str(marked), "--box", "0,0,9000,9000", "--net", "nope",
                                 "--out", str(tmp_path / "a.png")])
    assert result.exit_code == 2 and result.stderr.count("\n") == 1 and "no net named 'nope'" in result.stderr
    result = runner.invoke(app, ["plot-region", str(marked), "--box", "0,0,9000,9000", "--out", str(tmp_path / "a.jpg")])
    assert result.exit_code == 2 and result.stderr == "error: --out must be a .png or .svg file, got 'a.jpg'\n"
    assert list(tmp_path.glob("a.*")) == []


def test_plot_region_draws_vias_of_the_defs_vias_section(runner: CliRunner, routed: Path, testcase,
                                                           tmp_path: Path) -> None:
    # Other routers write their vias in the DEF's VIAS section; a net names them there first.
    need_matplotlib()
    import re

    from xroute.cli.plot_region import collect_shapes
    from xroute.design import load_design

    found = testcase(SAMPLE4)
    text = (routed / f"{SAMPLE4}.routed.def").read_text()
    design = load_design(lef=[str(found.lef)], def_=str(routed / f"{SAMPLE4}.routed.def"))
    lef_via = next(name for n in range(design.num_nets) for name, _x, _y in design.net_routing(n)["vias"])
    rects = " ".join(f"+ RECT {layer} ( {x0} {y0} ) ( {x1} {y1} )"
                     for layer, x0, y0, x1, y1 in design.via(lef_via)["shapes"])
    text = re.sub(rf"\) {re.escape(lef_via)}(\s*)$", r") DVIA\1", text, flags=re.M)
    text = text.replace("\nCOMPONENTS ", f"\nVIAS 1 ;\n- DVIA {rects} ;\nEND VIAS\n\nCOMPONENTS ", 1)
    moved = tmp_path / "dvia.def"
    moved.write_text(text)
    redrawn = load_design(lef=[str(found.lef)], def_=str(moved))
    assert redrawn.routed_via_shapes("DVIA") == [tuple(s) for s in design.via(lef_via)["shapes"]]
    whole = (-10**9, -10**9, 10**9, 10**9)
    assert sorted(map(repr, collect_shapes(redrawn, whole))) == sorted(map(repr, collect_shapes(design, whole)))
    png = tmp_path / "dvia.png"
    result = runner.invoke(app, ["plot-region", str(moved), "--lef", str(found.lef), "--box", BOX, "--out", str(png)])
    assert result.exit_code == 0, result.stderr
