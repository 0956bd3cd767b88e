"""The testcase generator, the shipped demo and ``xroute make-testcase --cells``."""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from xroute.testcases import DEMO, EMBEDDED_ROOT, ENV_VAR, find_testcase
from xroute.testcases.gen_netlist import GCELL_H, GCELL_W
from xroute.testcases.gen_tech import CELL_BY_NAME, ROW_H, SITE_W
from xroute.testcases.generator import DEMO_CELLS, DEMO_SEED, make_testcase
from xroute.cli.app import app

EXTS = ("lef", "def", "guide")



def _files(folder: Path) -> dict[str, bytes]:
    return {ext: (folder / f"{folder.name}.{ext}").read_bytes() for ext in EXTS}


def _load(folder: Path):
    from xroute.design import load_design

    f = {ext: str(folder / f"{folder.name}.{ext}") for ext in EXTS}
    return load_design(lef=[f["lef"]], def_=f["def"], guide=f["guide"])


def test_shipped_demo_is_what_the_generator_writes(tmp_path: Path) -> None:
    """Regenerate with `python -m xroute.testcases.generator` when this fails after a generator change."""
    fresh = make_testcase(DEMO_CELLS, DEMO_SEED, tmp_path / DEMO)
    assert _files(fresh) == _files(EMBEDDED_ROOT / DEMO)


def test_same_seed_same_bytes_other_seed_other_design(tmp_path: Path) -> None:
    a = _files(make_testcase(60, 2, tmp_path / "a" / "g"))
    b = _files(make_testcase(60, 2, tmp_path / "b" / "g"))
    c = _files(make_testcase(60, 3, tmp_path / "c" / "g"))
    assert a == b
    assert a["lef"] == c["lef"] and a["def"] != c["def"]


def test_generated_design_is_legal_and_guided(tmp_path: Path) -> None:
    folder = make_testcase(300, 5, tmp_path / "g300")
    d = _load(folder)
    counts = d.counts()
    assert (counts["routing_layers"], counts["cut_layers"], counts["special_nets"]) == (6, 5, 2)
    assert d.skipped_statements() == {"PIN.SHAPE": 18}  # SHAPE ABUTMENT of the rails, nothing else
    x0, y0, x1, y1 = d.die_area
    assert (x0, y0) == (0, 0) and x1 % GCELL_W == 0 and y1 % GCELL_H == 0
    # Placement: on the site grid, inside the die, no overlap within a row.
    rows: dict[int, list[tuple[int, int]]] = {}
    logic = 0
    for line in (folder / "g300.def").read_text().splitlines():
        if " + PLACED " in line and line.startswith("- ") and "NET" not in line:
            words = line.split()
            cell, x, y = CELL_BY_NAME[words[2]], int(words[6]), int(words[7])
            logic += cell.name != "FILL_X1"
            assert x % SITE_W == 0 and y % ROW_H == 0 and x + cell.width <= x1 and y + ROW_H <= y1
            rows.setdefault(y, []).append((x, x + cell.width))
    assert logic == 300
    for spans in rows.values():
        spans.sort()
        assert all(a[1] <= b[0] for a, b in zip(spans, spans[1:]))
    # Nets: 2 pins or more, mostly 2-5, some large fanout.
    pins = np.diff(d.net_pin_start)
    assert pins.min() >= 2
    assert 0.8 < np.mean((pins >= 2) & (pins <= 5)) < 1.0 and pins.max() >= 6
    # Every pin shape of every net touches a guide of its layer.
    for net in range(d.num_nets):
        rects, layers = d.net_guides(net)
        for _, layer, px0, py0, px1, py1 in d.net_pin_shapes(net):
            hit = (layers == layer) & (rects[:, 0] <= px1) & (rects[:, 2] >= px0) & (rects[:, 1] <= py1) & (rects[:, 3] >= py0)
            assert hit.any(), d.net_names[net]
    # Nothing fixed breaks a rule before routing (pins, OBS, rails, IO pins).
    assert d.engine.check_drc(skip_fixed_pairs=False) == []


def test_route_without_argument_routes_the_shipped_demo(runner: CliRunner, tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    empty = tmp_path / "empty"
    empty.mkdir()
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["route", "--quiet"], env={ENV_VAR: str(empty)})
    assert result.exit_code == 0, result.output + result.stderr
    out = tmp_path / "out" / DEMO
    assert (out / "demo.routed.def").is_file() and (out / "demo.drc.rpt").is_file()
    final = json.loads((out / "demo.metrics.json").read_text())["final"]
    assert final["open_nets"] == 0 and final["nets"] == 317 and final["nets_routed"] == 317
    assert final["violations"] <= 5


def test_a_user_folder_named_demo_wins(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    mine = make_testcase(20, 9, tmp_path / DEMO)
    monkeypatch.setenv(ENV_VAR, str(tmp_path))
    assert find_testcase(DEMO).folder == mine.resolve()
    monkeypatch.setenv(ENV_VAR, str(tmp_path / "nothing_here"))
    assert find_testcase(DEMO).folder == (EMBEDDED_ROOT / DEMO).resolve()


def test_make_testcase_cli(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "g40"
    result = runner.invoke(app, ["make-testcase", "--cells", "40", "--seed", "4", "--out", str(out), "--json"])
    assert result.exit_code == 0, result.output + result.stderr
    info = json.loads(result.stdout)
    assert info["name"] == "g40" and sorted(info["files"]) == sorted(EXTS)
    assert info["components"] >= 40 and info["nets"] > 20
    assert _files(out) == _files(make_testcase(40, 4, tmp_path / "again" / "g40"))


@pytest.mark.parametrize("args", [[], ["--cells", "10", "--tile", "demo"], ["--cells", "1"], ["--tile", "demo", "--by", "0x2"],
                                  ["--tile", "demo", "--by", "3"], ["--tile", "no_such_testcase_xyz"]])
def test_make_testcase_usage_errors(runner: CliRunner, tmp_path: Path, args: list[str]) -> None:
    result = runner.invoke(app, ["make-testcase", *args, "--out", str(tmp_path / "x")])
    assert result.exit_code == 2
    assert "Traceback" not in result.output + result.stderr
    assert not (tmp_path / "x").exists()


def test_generator_cell_mix(tmp_path: Path) -> None:
    text = (make_testcase(500, 11, tmp_path / "g") / "g.def").read_text()
    used = Counter(line.split()[2] for line in text.splitlines() if line.startswith("- ") and "PLACED" in line
                   and "NET" not in line)
    assert {"INV_X1", "NAND2_X1", "NOR2_X1", "DFF_X1", "BUF_X1", "FILL_X1"} <= set(used)
