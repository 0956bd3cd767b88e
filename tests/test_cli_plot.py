"""``xroute plot``: a picture of a whole routed design (markers by type, wire per GCell, out-of-guide wire)."""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import available
from png import distinct_colours, png_size
from test_cli_plot_region import need_matplotlib
from xroute.cli.app import app
from xroute.cli.plot_data import read_drc_report
from xroute.cli.plot_design import _outside_guides, _uncovered

MARKED = "standin_marked"  # a generated design that ends its second iteration at region size 2 with markers


@pytest.fixture
def marked(runner: CliRunner, testcase, tmp_path: Path) -> Path:
    testcase(MARKED)
    out = tmp_path / "marked"
    args = ["route", MARKED, "--iterations", "2", "--region-size", "2", "--quiet", "--out", str(out)]
    assert runner.invoke(app, args).exit_code == 0
    return out


@pytest.mark.slow
def test_plot_shows_the_violations_by_type(runner: CliRunner, marked: Path, tmp_path: Path) -> None:
    need_matplotlib()
    counts = Counter(m.kind for m in read_drc_report(marked / f"{MARKED}.drc.rpt"))
    assert counts, "the stand-in is expected to end its second iteration with markers"
    svg = tmp_path / "d.svg"
    result = runner.invoke(app, ["plot", str(marked), "--out", str(svg)])
    assert result.exit_code == 0, result.stderr
    total = sum(counts.values())
    said = re.fullmatch(rf"plot: {MARKED}: {total:,} violations, ([\d,]+\.\d) um out of guide -> "
                        rf"{re.escape(str(svg))}\n", result.stdout)
    assert said, result.stdout
    text = svg.read_text()
    assert f"{total:,} violations; out-of-guide wire {said.group(1)} µm" in text
    for kind, n in counts.items():
        assert f"{kind} ({n:,})" in text  # the legend of the points
        assert re.search(rf">\s*{n:,}\s*<", text)  # the count written on its bar
    # one point per marker: matplotlib writes each scatter point as a <use> of the marker's path
    assert text.count("<use ") >= total
    png = tmp_path / "d.png"
    assert runner.invoke(app, ["plot", str(marked), "--out", str(png)]).exit_code == 0
    width, height = png_size(png)
    assert width > 1000 and height > 500 and distinct_colours(png) > 50


def test_out_of_guide_pieces() -> None:
    # a horizontal wire at y=5 from x=0 to 100; guides cover 10..40 and 30..60 at that y, and 70..90 at y=50
    assert _uncovered(0, 100, [(10, 40), (30, 60)]) == [(0, 10), (60, 100)]
    assert _outside_guides((100, 5, 0, 5), [(10, 0, 40, 10), (30, 0, 60, 10), (70, 45, 90, 55)]) == [
        (0, 5, 10, 5), (60, 5, 100, 5)]
    # a vertical wire inside a guide: nothing outside; on the guide's edge counts as inside (closed boxes)
    assert _outside_guides((10, 0, 10, 50), [(0, 0, 10, 50)]) == []
    assert _outside_guides((11, 0, 11, 50), [(0, 0, 10, 50)]) == [(11, 0, 11, 50)]


def test_plot_errors_are_one_line(runner: CliRunner, marked: Path, tmp_path: Path) -> None:
    result = runner.invoke(app, ["plot", str(tmp_path / "nowhere"), "--out", str(tmp_path / "a.png")])
    assert result.exit_code == 2 and result.stderr == (f"error: {tmp_path / 'nowhere'}: no such folder or file: give a "
                                                       "route output folder, or a DEF file with --lef\n")
    result = runner.invoke(app, ["plot", str(marked / f"{MARKED}.routed.def"), "--lef", str(tmp_path / "no.lef"),
                                 "--out", str(tmp_path / "a.png")])
    assert result.exit_code == 2 and "no.lef" in result.stderr and result.stderr.count("\n") == 1
    result = runner.invoke(app, ["plot", str(marked / f"{MARKED}.routed.def"), "--out", str(tmp_path / "a.png")])
    assert result.exit_code == 2 and "a DEF file needs --lef" in result.stderr and result.stderr.count("\n") == 1
    result = runner.invoke(app, ["plot", str(tmp_path), "--out", str(tmp_path / "a.png")])
    assert result.exit_code == 2 and "no *.metrics.json here" in result.stderr and result.stderr.count("\n") == 1
    result = runner.invoke(app, ["plot", str(marked), "--out", str(tmp_path / "a.pdf")])
    assert result.exit_code == 2 and result.stderr == "error: --out must be a .png or .svg file, got 'a.pdf'\n"
    assert not list(tmp_path.glob("a.*"))


def test_plot_of_a_def_with_its_lef_guide_and_drc_report(runner: CliRunner, marked: Path, tmp_path: Path) -> None:
    # another router's DEF has no metrics JSON beside it: its LEF, guide and DRC report are given
    need_matplotlib()
    import json

    inputs = json.loads((marked / f"{MARKED}.metrics.json").read_text())["inputs"]
    folder = runner.invoke(app, ["plot", str(marked), "--out", str(tmp_path / "a.svg")])
    assert folder.exit_code == 0, folder.stderr
    args = ["plot", str(marked / f"{MARKED}.routed.def"), "--out", str(tmp_path / "b.svg")]
    for lef in inputs["lef"]:
        args += ["--lef", lef]
    given = runner.invoke(app, args + ["--guide", inputs["guide"], "--drc", str(marked / f"{MARKED}.drc.rpt")])
    assert given.exit_code == 0, given.stderr
    assert given.stdout.replace("b.svg", "a.svg") == folder.stdout
    bare = runner.invoke(app, args)  # no guide, no report: no out-of-guide wire, no markers
    assert bare.exit_code == 0
    assert bare.stdout == f"plot: {MARKED}: 0 violations, no guide file -> {tmp_path / 'b.svg'}\n"


@pytest.mark.slow
def test_plot_of_ispd19_test1_shows_its_violations(runner: CliRunner, testcase, tmp_path: Path) -> None:
    """The contest design after its first iteration (hundreds of markers; the stand-in without the data)."""
    need_matplotlib()
    name = available("ispd19_test1")[0]
    testcase(name)
    run = tmp_path / "run"
    result = runner.invoke(app, ["route", name, "--iterations", "1", "--threads", "2", "--quiet", "--out", str(run)])
    assert result.exit_code == 0, result.stderr
    counts = Counter(m.kind for m in read_drc_report(run / f"{name}.drc.rpt"))
    assert sum(counts.values()) > 0
    svg = tmp_path / "design.svg"
    assert runner.invoke(app, ["plot", str(run), "--out", str(svg)]).exit_code == 0
    text = svg.read_text()
    for kind, n in counts.items():
        assert f"{kind} ({n:,})" in text and re.search(rf">\s*{n:,}\s*<", text)
    assert text.count("<use ") >= sum(counts.values())
