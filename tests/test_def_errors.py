"""Bad DEF / guide input: each error is an InputError naming the file and the
exact line of the offending token; a failed write leaves no file behind."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import sample_lef
from xroute import _engine, load_design
from xroute.errors import InputError

# A small valid design for ispd18_sample's LEF (or tests/data/lef/sample_names.lef, which has the
# same names, when the contest data is missing); tests break one line of it.
GOOD = [
    "VERSION 5.8 ;",                                                              # 1
    'DIVIDERCHAR "/" ;',                                                          # 2
    'BUSBITCHARS "[]" ;',                                                         # 3
    "DESIGN tiny ;",                                                              # 4
    "UNITS DISTANCE MICRONS 2000 ;",                                              # 5
    "DIEAREA ( 0 0 ) ( 20000 20000 ) ;",                                          # 6
    "ROW CORE_ROW_0 CoreSite 0 0 N DO 10 BY 1 STEP 400 0 ;",                      # 7
    "TRACKS X 200 DO 50 STEP 400 LAYER Metal1 Metal2 ;",                          # 8
    "COMPONENTS 2 ;",                                                             # 9
    "- u1 OR4X1 + PLACED ( 400 0 ) N ;",                                          # 10
    "- u2 NAND3X2 + PLACED ( 4000 0 ) FS ;",                                      # 11
    "END COMPONENTS",                                                             # 12
    "PINS 1 ;",                                                                   # 13
    "- in1 + NET n1 + DIRECTION INPUT + USE SIGNAL",                              # 14
    "  + LAYER Metal2 ( -70 0 ) ( 70 140 )",                                      # 15
    "  + PLACED ( 0 5000 ) E ;",                                                  # 16
    "END PINS",                                                                   # 17
    "NETS 2 ;",                                                                   # 18
    "- n1 ( PIN in1 ) ( u1 D ) ;",                                                # 19
    "- n2 ( u1 Y ) ( u2 A )",                                                     # 20
    "  + ROUTED Metal1 ( 1000 1000 ) ( 3000 1000 ) VIA12_1C ( 3000 2000 )",      # 21
    "  + USE SIGNAL ;",                                                           # 22
    "END NETS",                                                                   # 23
    "END DESIGN",                                                                 # 24
]


@pytest.fixture(scope="module")
def lef() -> Path:
    return sample_lef()


def _write(tmp_path: Path, lines: list[str], name: str = "bad.def") -> Path:
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


def _error(lef: Path, tmp_path: Path, lines: list[str]) -> InputError:
    path = _write(tmp_path, lines)
    with pytest.raises(InputError) as info:
        load_design(lef=lef, def_=path)
    assert info.value.path == str(path)
    return info.value


def _with(line: int, text: str) -> list[str]:
    lines = list(GOOD)
    lines[line - 1] = text
    return lines


def test_good_design_loads(lef: Path, tmp_path: Path) -> None:
    d = load_design(lef=lef, def_=_write(tmp_path, GOOD))
    assert d.counts()["components"] == 2 and d.counts()["route_wires"] == 2


@pytest.mark.parametrize(
    "line, text, message",
    [
        (10, "- u1 OR4X1 + PLACED ( 400 0 ) N @@ ;", "expected '+' or ';', found '@@'"),
        (10, "- u1 NOPE + PLACED ( 400 0 ) N ;", "unknown macro 'NOPE'"),
        (10, "- u1 OR4X1 + PLACED ( 400 0 ) Q ;", "bad orientation 'Q'"),
        (10, "- u1 OR4X1 + PLACED ( 400.5 0 ) N ;", "expected an integer, found '400.5'"),
        (11, "- u1 NAND3X2 + PLACED ( 4000 0 ) FS ;", "duplicate component 'u1'"),
        (15, "  + LAYER Metal99 ( -70 0 ) ( 70 140 )", "unknown layer 'Metal99'"),
        (8, "TRACKS X 200 DO 50 STEP 400 LAYER Metal1 Poly ;", "unknown layer 'Poly'"),
        (19, "- n1 ( PIN in1 ) ( u9 D ) ;", "unknown component 'u9'"),
        (19, "- n1 ( PIN in1 ) ( u1 ZZ ) ;", "has no pin 'ZZ'"),
        (19, "- n1 ( PIN nope ) ( u1 D ) ;", "unknown pin 'nope'"),
        (21, "  + ROUTED Metal1 ( 1000 1000 ) ( 3000 1000 ) VIA_NOPE ( 3000 2000 )", "unknown via 'VIA_NOPE'"),
        (21, "  + ROUTED Metal1 ( 1000 1000 ) ( 3000 2000 )", "diagonal wire"),
        (21, "  + ROUTED Metal3 ( 1000 1000 ) ( 3000 1000 ) VIA12_1C ( 3000 2000 )", "does not connect"),
        (5, "UNITS DISTANCE MICRONS 3000 ;", "have no integer ratio"),
        (7, "FOO bar ;", "expected a DEF statement, found 'FOO'"),
        (2, "DIVIDERCHAR / ;", "expected a divider character in double quotes, found '/'"),
        (3, 'BUSBITCHARS "[" ;', "expected bus bit characters in double quotes, found '['"),
        (4, 'DESIGN "tiny" ;', "expected a design name, found the quoted string 'tiny'"),
        (10, '- "u 1" OR4X1 + PLACED ( 400 0 ) N ;', "expected a component name, found the quoted string 'u 1'"),
        (19, '- "n1" ( PIN in1 ) ( u1 D ) ;', "expected a net name, found the quoted string 'n1'"),
    ],
)
def test_bad_line(lef: Path, tmp_path: Path, line: int, text: str, message: str) -> None:
    e = _error(lef, tmp_path, _with(line, text))
    assert e.line == line
    assert message in e.message


def test_section_count_mismatch_warns(lef: Path, tmp_path: Path) -> None:
    # OpenROAD and the Si2 parser warn and go on; so do we, naming the END line.
    path = _write(tmp_path, _with(9, "COMPONENTS 3 ;"))
    d = load_design(lef=lef, def_=path)
    assert d.counts()["components"] == 2
    assert f"{path}:12: COMPONENTS 3 declared, 2 found" in d.warnings()
    path = _write(tmp_path, _with(18, "NETS 1 ;"))
    assert f"{path}:23: NETS 1 declared, 2 found" in load_design(lef=lef, def_=path).warnings()


def test_missing_end_section(lef: Path, tmp_path: Path) -> None:
    lines = GOOD[:11] + GOOD[12:]  # drop "END COMPONENTS"; "PINS 1 ;" is now line 12
    e = _error(lef, tmp_path, lines)
    assert e.line == 12
    assert "END COMPONENTS" in e.message and "'PINS'" in e.message


def test_truncated(lef: Path, tmp_path: Path) -> None:
    e = _error(lef, tmp_path, GOOD[:11])  # stops inside COMPONENTS, after line 11
    assert e.line == 12  # end of file: the line after the last one
    assert "unexpected end of file" in e.message
    e = _error(lef, tmp_path, GOOD[:23])  # no END DESIGN
    assert e.line == 23
    assert "END DESIGN" in e.message
    # A statement cut in the middle.
    lines = GOOD[:9] + ["- u1 OR4X1 + PLACED ( 400"]
    e = _error(lef, tmp_path, lines)
    assert e.line == 11 and "unexpected end of file" in e.message


def test_missing_design_statement(lef: Path, tmp_path: Path) -> None:
    e = _error(lef, tmp_path, _with(4, "# no DESIGN statement"))
    assert e.line == 24 and e.message == "missing DESIGN statement before END DESIGN"


def test_garbage_after_end_design(lef: Path, tmp_path: Path) -> None:
    e = _error(lef, tmp_path, GOOD + ["junk"])
    assert e.line == 25 and "after END DESIGN" in e.message


def test_guide_with_unknown_net(lef: Path, tmp_path: Path) -> None:
    guide = tmp_path / "bad.guide"
    guide.write_text("n1\n(\n0 0 400 400 Metal1\n)\nghost\n(\n0 0 400 400 Metal1\n)\n")
    with pytest.raises(InputError) as info:
        load_design(lef=lef, def_=_write(tmp_path, GOOD), guide=guide)
    assert info.value.line == 5 and info.value.path == str(guide)
    assert "'ghost' is not in the DEF" in info.value.message


def test_missing_file(lef: Path, tmp_path: Path) -> None:
    missing = str(tmp_path / "nothere.def")
    with pytest.raises(InputError) as info:
        _engine.load([str(lef)], missing, None)
    assert info.value.line == 0 and info.value.path == missing
    with pytest.raises(InputError) as info:
        load_design(lef=lef, def_=missing)
    assert info.value.line == 0


def test_failed_write(lef: Path, tmp_path: Path) -> None:
    d = load_design(lef=lef, def_=_write(tmp_path, GOOD, "good.def"))
    target = tmp_path / "no" / "such" / "dir" / "out.def"
    with pytest.raises(InputError) as info:
        d.write_def(target)
    assert info.value.line == 0 and "cannot write" in info.value.message
    assert not (tmp_path / "no").exists()
    # The target is an existing directory: the rename fails, the temporary file is removed.
    (tmp_path / "adir").mkdir()
    (tmp_path / "adir" / "keep").write_text("x")
    with pytest.raises(InputError) as info:
        d.write_def(tmp_path / "adir")
    assert "cannot write" in info.value.message
    assert sorted(p.name for p in tmp_path.iterdir()) == ["adir", "good.def"]
    assert [p.name for p in (tmp_path / "adir").iterdir()] == ["keep"]
