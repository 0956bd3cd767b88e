"""``xroute plot-region``: a PNG of a routed region (needs the optional extra ``plot``: matplotlib)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import pick
from png import distinct_colours, read_png
from xroute.cli.app import app


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
    width, height, _, _ = read_png(png)
    assert width > 600 and height > 300
    assert distinct_colours(png) > 20  # layers, pins, markers, legend text: not blank


def test_plot_region_by_gcell_from_a_def(runner: CliRunner, routed: Path, testcase, tmp_path: Path) -> None:
    need_matplotlib()
    found = testcase(SAMPLE4)
    png = tmp_path / "g.png"
    result = runner.invoke(app, ["plot-region", str(routed / f"{SAMPLE4}.routed.def"), "--lef", str(found.lef),
                                 "--guide", str(found.guide), "--gcell", "0,0", "--size", "2", "--out", str(png)])
    assert result.exit_code == 0, result.stderr
    assert distinct_colours(png) > 20


def test_plot_region_argument_errors(runner: CliRunner, routed: Path, tmp_path: Path) -> None:
    result = runner.invoke(app, ["plot-region", str(routed), "--box", "1,2,3", "--out", str(tmp_path / "x.png")])
    assert result.exit_code == 2 and result.stderr == "error: --box must be 4 comma-separated integers, got '1,2,3'\n"
    result = runner.invoke(app, ["plot-region", str(tmp_path), "--box", "0,0,1,1"])
    assert result.exit_code == 2 and "no *.metrics.json here" in result.stderr
    assert not (tmp_path / "x.png").exists()
