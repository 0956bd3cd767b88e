"""Generated designs on real technology LEFs (``xroute make-testcase --lef``, ``xroute.testcases.real_generator``).

The LEFs are the ISPD contest technologies in ``../shared/techs`` beside the repository root
(never copied into the repository); the tests that need them skip without that folder. The error
cases draw their own tiny LEFs.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from xroute.cli.app import app

TECHS = Path(__file__).resolve().parent.parent.parent / "shared" / "techs"
ISPD18 = TECHS / "ispd18_test2.input.lef"  # 9 layers, CoreSite 400 x 3420, 2000 DBU/um, VDD/VSS rails
ISPD19 = TECHS / "ispd19_test4.input.lef"  # 5 layers metal1-5, site core 200 x 2000, 1000 DBU/um, no supply pins
TWO_TECHS = pytest.mark.parametrize("lef", [ISPD18, ISPD19], ids=["ispd18_test2", "ispd19_test4"])
CELLS = 300

tiny_lef_header = "VERSION 5.8 ;\nUNITS\n  DATABASE MICRONS 1000 ;\nEND UNITS\n"
tiny_layers = "".join(
    f"LAYER M{k}\n  TYPE ROUTING ;\n  DIRECTION {'HORIZONTAL' if k % 2 else 'VERTICAL'} ;\n  PITCH 0.2 ;\n"
    f"  WIDTH 0.1 ;\n  SPACING 0.1 ;\nEND M{k}\n" for k in (1, 2, 3)
)


@pytest.fixture(autouse=True)
def _need_techs(request: pytest.FixtureRequest) -> None:
    if "lef" in request.fixturenames and not TECHS.is_dir():
        pytest.skip(f"no technology LEFs: {TECHS} is absent (the ISPD techs folder beside the repository)")


def _generate(lef: Path, out: Path, seed: int = 3, cells: int = CELLS) -> Path:
    from xroute.testcases.real_generator import make_real_testcase

    return make_real_testcase([lef], cells, seed, out)


def _files(folder: Path) -> dict[str, bytes]:
    return {ext: (folder / f"{folder.name}.{ext}").read_bytes() for ext in ("def", "guide")}


@TWO_TECHS
def test_same_seed_same_bytes_other_seed_other_design(lef: Path, tmp_path: Path) -> None:
    a = _files(_generate(lef, tmp_path / "a" / "g"))
    b = _files(_generate(lef, tmp_path / "b" / "g"))
    c = _files(_generate(lef, tmp_path / "c" / "g", seed=4))
    assert a == b
    assert a["def"] != c["def"]
    assert not (tmp_path / "a" / "g" / "g.lef").exists()  # the LEF is referenced, never copied


def _rows(def_path: Path) -> dict[int, tuple[int, str, int, int]]:
    """ROW statements by y: (x, orient, sites, step), from the DEF text."""
    rows = {}
    for line in def_path.read_text().splitlines():
        if line.startswith("ROW "):
            w = line.split()
            rows[int(w[4])] = (int(w[3]), w[5], int(w[7]), int(w[11]))
    return rows


@TWO_TECHS
def test_generated_design_is_legal(lef: Path, tmp_path: Path) -> None:
    from xroute.design import load_design

    folder = _generate(lef, tmp_path / "g")
    d = load_design(lef=[lef], def_=folder / "g.def", guide=folder / "g.guide")
    assert d.counts()["components"] == CELLS and d.has_guides
    rows = _rows(folder / "g.def")
    site_w = next(iter(rows.values()))[3]
    # Cells: usable core cells, on a row, in its orientation, on its site grid, no overlap.
    spans: dict[int, list[tuple[int, int]]] = {}
    for k in range(1, CELLS + 1):
        comp = d.component(f"u{k}")
        macro = d.macro(comp["macro"])
        (x, y), (w, h) = comp["location"], macro["size"]
        assert macro["class"] == "CORE" and y in rows, comp
        rx, orient, sites, _ = rows[y]
        assert comp["orient"] == orient and (x - rx) % site_w == 0 and rx <= x and x + w <= rx + sites * site_w
        spans.setdefault(y, []).append((x, x + w))
    for row in spans.values():
        row.sort()
        assert all(a[1] <= b[0] for a, b in zip(row, row[1:]))
    # Nets: one driver (a cell output or an input IO pin) and at least one sink.
    for net in range(d.num_nets):
        pins = d.net_pins(net)
        drivers = 0
        for comp, pin in pins:
            if comp == "PIN":
                drivers += d.io_pin(pin)["direction"] == "INPUT"
            else:
                drivers += d.macro(d.component(comp)["macro"])["pins"][pin]["direction"] == "OUTPUT"
        assert drivers == 1 and len(pins) >= 2, (d.net_names[net], pins)
    # IO pins: inside the die, each touching its edge.
    x0, y0, x1, y1 = d.die_area
    for line in (folder / "g.def").read_text().splitlines():
        if line.startswith("- io"):
            shapes = d.io_pin(line.split()[1])["shapes"]
            for _, a, b, c, e in shapes:
                assert x0 <= a and y0 <= b and c <= x1 and e <= y1
                assert a == x0 or b == y0 or c == x1 or e == y1
    # Fixed shapes: IO pins and rails break no rule (the library's own Metal1 pins may: ispd18_test1 has
    # 613 such markers, MinArea of small pins and EndOfLine between abutted cells).
    specials = range(d.num_nets, d.num_nets + d.counts()["special_nets"])
    for m in d.engine.check_drc(skip_fixed_pairs=False):
        assert m["layer"] == d.routing_layers[0].name and not set(m["nets"]) & set(specials), m


def test_a_small_generated_design_routes_without_opens(tmp_path: Path) -> None:
    if not TECHS.is_dir():
        pytest.skip(f"no technology LEFs: {TECHS} is absent (the ISPD techs folder beside the repository)")
    folder = _generate(ISPD18, tmp_path / "r", seed=1, cells=150)
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["route", "--lef", str(ISPD18), "--def", str(folder / "r.def"), "--guide",
                                      str(folder / "r.guide"), "--threads", "2", "--quiet", "--out", str(out)])
    assert result.exit_code == 0, result.output + result.stderr
    final = json.loads((out / "r.metrics.json").read_text())["final"]
    assert final["open_nets"] == 0 and final["nets_routed"] == final["nets"] > 100


def test_make_testcase_cli_on_a_real_lef(tmp_path: Path) -> None:
    if not TECHS.is_dir():
        pytest.skip(f"no technology LEFs: {TECHS} is absent (the ISPD techs folder beside the repository)")
    out = tmp_path / "c"
    result = CliRunner().invoke(app, ["make-testcase", "--lef", str(ISPD19), "--cells", "80", "--seed", "2",
                                      "--utilization", "0.6", "--out", str(out), "--json"])
    assert result.exit_code == 0, result.output + result.stderr
    info = json.loads(result.stdout)
    assert info["components"] == 80 and info["lef"] == [str(ISPD19)] and sorted(info["files"]) == ["def", "guide"]


@pytest.mark.parametrize("body, message", [
    (tiny_layers, "no SITE of CLASS CORE"),
    (tiny_layers + "SITE core\n  CLASS CORE ;\n  SIZE 0.2 BY 2 ;\nEND core\n"
     "MACRO FILL\n  CLASS CORE ;\n  SIZE 0.2 BY 2 ;\n  SITE core ;\nEND FILL\n", "no usable core cell"),
], ids=["no-site", "no-core-cell"])
def test_a_lef_without_site_or_cells_is_one_line_and_exit_2(tmp_path: Path, body: str, message: str) -> None:
    lef = tmp_path / "bad.lef"
    lef.write_text(tiny_lef_header + body + "END LIBRARY\n")
    result = CliRunner().invoke(app, ["make-testcase", "--lef", str(lef), "--cells", "20", "--out", str(tmp_path / "x")])
    assert result.exit_code == 2
    text = result.output + result.stderr
    assert message in text and str(lef) in text and "Traceback" not in text
    assert not (tmp_path / "x").exists()


def test_utilization_needs_a_lef(tmp_path: Path) -> None:
    result = CliRunner().invoke(app, ["make-testcase", "--cells", "20", "--utilization", "0.5", "--out", str(tmp_path / "x")])
    assert result.exit_code == 2 and not (tmp_path / "x").exists()


def test_ndr_nets_are_spread_evenly_and_none_asked_none_given() -> None:
    from xroute.testcases.real_generator import ndr_net_indices

    assert ndr_net_indices(10, 2) == {2, 7} and ndr_net_indices(3, 5) == {0, 1, 2} and ndr_net_indices(9, 0) == set()


def test_generated_nets_of_a_nondefaultrule_route_as_check_judges_them(tmp_path: Path) -> None:
    # --ndr-nets 6: six nets of NDR_2W2S (twice the width and spacing above metal1); routed,
    # their wires above metal1 are 200 wide, no net is open, and the router's own count of
    # violations is the count of check on the written DEF.
    if not TECHS.is_dir():
        pytest.skip(f"no technology LEFs: {TECHS} is absent (the ISPD techs folder beside the repository)")
    from xroute.check import check_design
    from xroute.design import load_design
    from xroute.pipeline import prepare_design
    from xroute.router import route_design
    from xroute.testcases.real_generator import make_real_testcase

    folder = make_real_testcase([ISPD19], 300, 3, tmp_path / "g", ndr_nets=6)
    text = (folder / "g.def").read_text()
    assert text.count("+ NONDEFAULTRULE NDR_2W2S") == 6
    assert "- NDR_2W2S\n  + LAYER metal2 WIDTH 200 SPACING 200\n" in text  # metal2: width 100, spacing 100
    design = prepare_design(lef=[ISPD19], def_=folder / "g.def", guide=folder / "g.guide")
    result = route_design(design, threads=2)
    routed = tmp_path / "routed.def"
    design.write_def(routed)
    written = load_design(lef=[ISPD19], def_=routed)
    checked = check_design(written)
    assert checked.opens == 0 and result.violations == checked.violations
    ruled = re.findall(r"^- (\S+)\n[^;]*\+ NONDEFAULTRULE NDR_2W2S", routed.read_text(), re.M)
    assert len(ruled) == 6
    names = written.net_names
    for net in ruled:
        for layer, *_pts, width, _e0, _e1 in written.net_routing(names.index(net))["wires"]:
            assert width == (0 if layer == "metal1" else 200)
