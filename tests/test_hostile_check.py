"""Hostile routed DEFs: `check` on them, and coordinates at the ends of int32 in every reader.

The routed DEFs are the demo routed once per session, then changed by :func:`add_routing`: extra
routing statements appended to one net (repeated segments, shifted overlapping copies, shapes at
the engine's range). Timings are printed by ``bench/`` and the fuzz harness, never asserted here:
the tests assert behaviour (the same markers and opens as one copy; one error line naming file and
line; no crash).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import make_runner
from xroute.cli.app import app

DEMO = Path(__file__).resolve().parents[1] / "testcases" / "data" / "demo"
LIMIT = 2**28 - 1  # kMaxDbu: the largest coordinate magnitude the readers take
NET = "n1"  # the demo net the tests add routing to: its pins sit near (43000, 500)
SEGMENT = "NEW Metal3 ( 43890 840 ) ( 43130 840 )"  # one of n1's own wires


@pytest.fixture(scope="session")
def routed_demo(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("routed")
    result = make_runner().invoke(app, ["route", "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output
    return out / "demo.routed.def"


def add_routing(routed: Path, dest: Path, lines: list[str], net: str = NET) -> Path:
    """A copy of the routed DEF ``routed`` at ``dest`` with ``lines`` (``NEW layer ...`` path
    statements) appended to the routing of ``net``."""
    text = routed.read_text()
    start = re.search(rf"^- {re.escape(net)}\s*$", text, re.M)
    assert start is not None, net
    end = text.index("\n ;", start.end())  # the net's closing ';'
    dest.write_text(text[:end] + "".join(f"\n    {line}" for line in lines) + text[end:])
    return dest


def check(runner: CliRunner, def_path: Path, out: Path):
    return runner.invoke(app, ["check", "demo", "--def", str(def_path), "--out", str(out), "--quiet"])


def figures(out: Path, stem: str) -> dict:
    return json.loads((out / f"{stem}.check.json").read_text())


def assert_one_error(result, prefix: str, contains: str) -> None:
    text = result.output + (result.stderr or "")
    assert "Traceback" not in text, text
    assert result.exit_code == 2, text
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: " + prefix) and contains in lines[0], lines


def line_of(path: Path, needle: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if needle in line)


# ----------------------------------------------------------------------------- repeated segments
@pytest.mark.parametrize("copies", [2000])
def test_repeated_segments_give_the_markers_and_opens_of_one_copy(routed_demo: Path, tmp_path: Path,
                                                                  copies: int) -> None:
    runner = make_runner()
    one = add_routing(routed_demo, tmp_path / "one.def", [SEGMENT])
    many = add_routing(routed_demo, tmp_path / "many.def", [SEGMENT] * copies)
    assert check(runner, one, tmp_path / "o1").exit_code == 0
    assert check(runner, many, tmp_path / "o2").exit_code == 0
    a, b = figures(tmp_path / "o1", "one"), figures(tmp_path / "o2", "many")
    for key in ("opens", "open_nets", "violations", "violations_by_type", "markers", "vias", "nets_checked"):
        assert a[key] == b[key], key
    # Wirelength is the sum over the pieces as written: each copy adds its 760 DBU (0.38 um).
    assert b["wirelength_um"] - a["wirelength_um"] == pytest.approx((copies - 1) * 760 / 2000)


def test_overlapping_collinear_copies_are_one_wire_for_the_opens(routed_demo: Path, tmp_path: Path) -> None:
    # Shifted copies that overlap each other, joined end to end along y = 840: one conductor.
    shifted = [f"NEW Metal3 ( {43130 + i} 840 ) ( {43890 + i} 840 )" for i in range(0, 3000, 3)]
    path = add_routing(routed_demo, tmp_path / "shift.def", shifted)
    result = check(make_runner(), path, tmp_path / "o")
    assert result.exit_code == 0, result.output
    got = figures(tmp_path / "o", "shift")
    assert got["opens"] == 0 and got["nets_checked"] == 317


def test_a_disjoint_copy_is_still_a_floating_piece(routed_demo: Path, tmp_path: Path) -> None:
    """Merging keeps pieces apart that do not touch: a far segment stays a piece of its own."""
    from xroute.design import load_design

    path = add_routing(routed_demo, tmp_path / "far.def", [SEGMENT] * 50 + ["NEW Metal3 ( 10000 840 ) ( 10760 840 )"] * 50)
    conn = load_design(lef=DEMO / "demo.lef", def_=path).engine.check_connectivity()
    assert conn["open_nets"] == 0 and conn["floating_pieces"] == 1


def test_a_band_of_shifted_copies_is_checked_in_time(routed_demo: Path, tmp_path: Path) -> None:
    """50,000 copies of a 25,000 DBU wire, each 1 DBU above the last, overlap into a band across
    the design (the DRC once scanned the band once per copy, 84 s; now about 1 s). The
    subprocess timeout is the failure detector; the markers are the drawn tests' business."""
    import subprocess
    import sys

    band = [f"NEW Metal3 ( 1000 {840 + i} ) ( 26000 {840 + i} )" for i in range(50000)]
    path = add_routing(routed_demo, tmp_path / "band.def", band)
    proc = subprocess.run([sys.executable, "-m", "xroute", "check", "demo", "--def", str(path), "--out",
                           str(tmp_path / "o"), "--json"], capture_output=True, text=True, timeout=30)
    assert proc.returncode in (0, 1) and "Traceback" not in proc.stderr, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["violations_by_type"]["Short"] > 0 and doc["opens"] == 0


# ----------------------------------------------------------------------------- int32 extremes in routed DEFs
@pytest.mark.parametrize(
    "line",
    [
        "NEW Metal3 ( 43890 -2147483000 ) ( 43890 2147483000 )",  # an earlier hostile run found a segmentation fault
        "NEW Metal2 ( -2147483648 660 ) RECT ( 0 0 140 360 )",  # an earlier hostile run found a segmentation fault
        f"NEW Metal2 ( -{LIMIT} 660 ) RECT ( -1000 0 0 360 )",  # the placed patch is beyond
        f"NEW Metal2 ( {LIMIT} {LIMIT} ) VIA23",  # the via's shapes stick out
    ],
)
def test_routing_beyond_the_range_is_one_error_line(routed_demo: Path, tmp_path: Path, line: str) -> None:
    path = add_routing(routed_demo, tmp_path / "x.def", [line])
    result = check(make_runner(), path, tmp_path / "o")
    assert_one_error(result, f"{path}:{line_of(path, line)}: ", "beyond the engine's range, |v| <= 268435455 DBU")


def test_routing_at_the_edge_of_the_range_is_checked(routed_demo: Path, tmp_path: Path) -> None:
    far = LIMIT - 1000
    lines = [f"NEW Metal3 ( 43890 -{LIMIT} ) ( 43890 {LIMIT} )", f"NEW Metal3 ( -{LIMIT} -{LIMIT} ) ( {LIMIT} -{LIMIT} )",
             f"NEW Metal2 ( -{LIMIT} 660 ) RECT ( 0 0 {LIMIT} 140 )", f"NEW Metal2 ( {far} {far} ) VIA23"]
    path = add_routing(routed_demo, tmp_path / "edge.def", lines)
    result = check(make_runner(), path, tmp_path / "o")
    assert result.exit_code in (0, 1), result.output  # judged: markers (and maybe opens), no crash
    assert figures(tmp_path / "o", "edge")["violations"] > 0
    info = make_runner().invoke(app, ["info", "--lef", str(DEMO / "demo.lef"), "--def", str(path)])
    assert info.exit_code == 0 and "reach outside the die area" in info.output + (info.stderr or "")


# ----------------------------------------------------------------------------- int32 extremes in LEF, DEF, guide
def inputs(tmp_path: Path, kind: str, old: str, new: str) -> dict[str, Path]:
    paths = {}
    for k in ("lef", "def", "guide"):
        text = (DEMO / f"demo.{k}").read_text()
        if k == kind:
            assert old in text, old
            text = text.replace(old, new, 1)
        paths[k] = tmp_path / f"demo.{k}"
        paths[k].write_text(text)
    return paths


IO_PIN = "+ LAYER Metal4 ( -70 0 ) ( 70 360 ) + PLACED ( 43890 0 ) N"
EXTREMES = [
    ("def", IO_PIN, "+ LAYER Metal4 ( -2147483648 0 ) ( 2147483647 360 ) + PLACED ( 43890 0 ) N", "-2147483648",
     "coordinate '-2147483648' is beyond"),  # once segfaults and a vector max_size() traceback in route
    ("def", IO_PIN, f"+ LAYER Metal4 ( -70 0 ) ( 70 360 ) + PLACED ( {LIMIT} 0 ) N", "- io0", "pin shape ("),
    ("def", "- u13 XOR2_X1 + PLACED ( 42180 0 ) N", f"- u13 XOR2_X1 + PLACED ( {LIMIT - 100} 0 ) N", "- u13",
     "placed component ("),
    ("def", "TRACKS Y 280 DO 219 STEP 280", "TRACKS Y 280 DO 219 STEP 2000000", "TRACKS Y 280", "TRACKS run beyond"),
    ("def", "DIEAREA ( 0 0 ) ( 62700 61600 )", "DIEAREA ( 0 0 ) ( 62700 2147483647 )", "DIEAREA", "is beyond"),
    ("guide", "39900 0 45600 5600 Metal1", "-2147483648 0 2147483647 5600 Metal1", "-2147483648", "is beyond"),
    ("lef", "SIZE 0.5700 BY 1.4000", "SIZE 200000 BY 1.4000", "SIZE 200000", "length '200000' (400000000 DBU) is beyond"),
]


@pytest.mark.parametrize("kind, old, new, needle, message", EXTREMES, ids=[e[4][:24] for e in EXTREMES])
def test_info_and_route_refuse_values_beyond_the_range_alike(tmp_path: Path, kind: str, old: str, new: str,
                                                             needle: str, message: str) -> None:
    paths = inputs(tmp_path, kind, old, new)
    args = ["--lef", str(paths["lef"]), "--def", str(paths["def"]), "--guide", str(paths["guide"])]
    prefix = f"{paths[kind]}:{line_of(paths[kind], needle)}: "
    runner = make_runner()
    assert_one_error(runner.invoke(app, ["info", *args]), prefix, message)
    out = tmp_path / "out"
    assert_one_error(runner.invoke(app, ["route", *args, "--out", str(out), "--quiet"]), prefix, message)
    assert not out.exists() or not any(out.iterdir())


# A macro whose pin or OBS shapes stick out of its SIZE (2,280 DBU wide): the LEF change, u13's placement.
PIN_Y = "RECT 1.0100 0.2450 1.0800 1.0150 ;"  # XOR2_X1's pin Y
OBS = "  OBS\n    LAYER Metal1 ;\n      RECT -5.0000 0.0000 0.0000 0.1000 ;\n  END\nEND XOR2_X1"
STICKING_OUT = {
    "pin": ((PIN_Y, PIN_Y.replace("1.0800", "6.0800")), f"PLACED ( {LIMIT - 3000} 0 ) N"),  # to x + 12,160
    "obs flipped": (("END XOR2_X1", OBS), f"PLACED ( {LIMIT - 5000} 0 ) FN"),  # mirrored: to x + 2,280 + 10,000
}


def macro_inputs(tmp_path: Path, lef_change: tuple[str, str], placement: str) -> tuple[Path, Path]:
    lef = tmp_path / "demo.lef"
    text = (DEMO / "demo.lef").read_text()
    assert lef_change[0] in text
    lef.write_text(text.replace(*lef_change, 1))
    def_ = tmp_path / "demo.def"
    text = (DEMO / "demo.def").read_text()
    assert "- u13 XOR2_X1 + PLACED ( 42180 0 ) N" in text
    def_.write_text(text.replace("- u13 XOR2_X1 + PLACED ( 42180 0 ) N", f"- u13 XOR2_X1 + {placement}"))
    return lef, def_


@pytest.mark.parametrize("case", list(STICKING_OUT))
def test_placed_macro_shapes_beyond_the_range_are_refused(tmp_path: Path, case: str) -> None:
    """The placed component's SIZE box is within the range, its pin or OBS shapes are not."""
    lef, def_ = macro_inputs(tmp_path, *STICKING_OUT[case])
    args = ["--lef", str(lef), "--def", str(def_)]
    prefix = f"{def_}:{line_of(def_, '- u13 ')}: "
    message = "component 'u13' of macro 'XOR2_X1': its pin and OBS shapes placed here span ("
    runner = make_runner()
    assert_one_error(runner.invoke(app, ["info", *args]), prefix, message)
    out = tmp_path / "out"
    assert_one_error(runner.invoke(app, ["route", *args, "--out", str(out), "--quiet"]), prefix, message)
    assert not out.exists() or not any(out.iterdir())


def test_placed_macro_shapes_up_to_the_range_are_read(tmp_path: Path) -> None:
    lef, def_ = macro_inputs(tmp_path, STICKING_OUT["pin"][0], f"PLACED ( {LIMIT - 12160} 0 ) N")  # ends at LIMIT
    result = make_runner().invoke(app, ["info", "--lef", str(lef), "--def", str(def_)])
    assert result.exit_code == 0 and "placed outside the die area" in result.output + result.stderr


# ----------------------------------------------------------------------------- odd values: warned or refused
ODD = [
    ("lef", "SIZE 0.5700 BY 1.4000", "SIZE -0.5700 BY 1.4000", None, "MACRO SIZE width must not be negative"),
    ("lef", "MANUFACTURINGGRID 0.0050", "MANUFACTURINGGRID 0", "MANUFACTURINGGRID 0 is not a positive", None),
    ("lef", "RECT 0.0600 0.3850 0.1300 0.8750", "RECT 0.0600 0.3850 0.0600 0.8750", "RECT without area", None),
    ("def", "( -70 0 ) ( 70 360 ) + PLACED ( 43890 0 )", "( 70 0 ) ( 70 360 ) + PLACED ( 43890 0 )",
     "pin RECT without area", None),
]


@pytest.mark.parametrize("kind, old, new, warning, error", ODD, ids=[(o[3] or o[4])[:24] for o in ODD])
def test_odd_values_are_warned_or_refused(tmp_path: Path, kind: str, old: str, new: str, warning, error) -> None:
    paths = inputs(tmp_path, kind, old, new)
    result = make_runner().invoke(app, ["info", "--lef", str(paths["lef"]), "--def", str(paths["def"])])
    text = result.output + (result.stderr or "")
    assert "Traceback" not in text
    if error:
        assert result.exit_code == 2 and error in text, text
    else:
        assert result.exit_code == 0 and warning in text, text
