"""The testcase registry: search path order, lookup on disk, the known list and the static regions."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

import xroute.testcases.registry as registry
from xroute.testcases import (
    ENV_VAR,
    KNOWN_BY_NAME,
    KNOWN_TESTCASES,
    STATIC_REGIONS,
    find_testcase,
    known_testcase,
    locate_all,
    search_path,
)
from xroute.errors import TestcaseNotFound as NotFound
from xroute.errors import XrouteError


def _make(root: Path, name: str, *exts: str, pattern: str = "{n}.input.{e}") -> Path:
    folder = root / name
    folder.mkdir(parents=True, exist_ok=True)
    for ext in exts:
        (folder / pattern.format(n=name, e=ext)).write_text("")
    return folder


@pytest.fixture
def isolated(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    """Run from tmp/proj with the cache under tmp/cache and no XROUTE_TESTCASES."""
    proj = tmp_path / "proj"
    proj.mkdir()
    monkeypatch.chdir(proj)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.delenv(ENV_VAR, raising=False)
    return tmp_path


# -- search path --------------------------------------------------------------------------


def test_search_path_order(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    a, b = isolated / "a", isolated / "b"
    monkeypatch.setenv(ENV_VAR, f"{a}{os.pathsep}{b}")
    paths = search_path()
    checkout = Path(registry.__file__).resolve().parent.parent  # the repository root, if a source checkout
    in_checkout = (checkout / "pyproject.toml").is_file()
    project_shared = [(checkout / ".." / "shared" / "testcases").resolve()] if in_checkout else []
    cwd_shared = (isolated / "shared" / "testcases").resolve()  # tmp/proj/../shared/testcases
    cache = (isolated / "cache" / "xroute" / "testcases").resolve()
    assert paths == [a.resolve(), b.resolve(), *project_shared, cwd_shared, cache]


def test_installed_package_searches_beside_the_current_directory(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(registry, "_checkout_root", lambda: None)  # as in site-packages
    assert search_path() == [
        (isolated / "shared" / "testcases").resolve(),
        (isolated / "cache" / "xroute" / "testcases").resolve(),
    ]


def test_search_path_dedupes_and_ignores_empty_entries(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    a = isolated / "a"
    cwd_shared = isolated / "proj" / ".." / "shared" / "testcases"
    monkeypatch.setenv(ENV_VAR, os.pathsep.join(["", str(a), str(a), " ", str(cwd_shared)]))
    paths = search_path()
    assert len(paths) == len(set(paths))
    assert paths[0] == a.resolve()
    assert paths[1] == cwd_shared.resolve()  # listed by the user first, so not repeated later
    assert Path.cwd().resolve() not in paths  # "" does not mean the current directory


def test_default_cache_is_under_home(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(isolated / "home"))
    assert search_path()[-1] == (isolated / "home" / ".cache" / "xroute" / "testcases").resolve()


# -- lookup -------------------------------------------------------------------------------------


def test_find_testcase_in_fake_folder(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = isolated / "root"
    folder = _make(root, "foo", "lef", "def")
    monkeypatch.setenv(ENV_VAR, str(root))
    found = find_testcase("foo")
    assert found.name == "foo"
    assert found.folder == folder.resolve()
    assert found.lef == folder.resolve() / "foo.input.lef"
    assert found.def_ == folder.resolve() / "foo.input.def"
    assert found.guide is None
    (folder / "foo.input.guide").write_text("")
    assert find_testcase("foo").guide == folder.resolve() / "foo.input.guide"


def test_find_testcase_accepts_plain_names(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = isolated / "root"
    folder = _make(root, "bar", "lef", "def", "guide", pattern="{n}.{e}")
    monkeypatch.setenv(ENV_VAR, str(root))
    found = find_testcase("bar")
    assert (found.lef.name, found.def_.name, found.guide) == ("bar.lef", "bar.def", folder.resolve() / "bar.guide")


def test_first_complete_folder_wins(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first, second, third = isolated / "r1", isolated / "r2", isolated / "r3"
    _make(first, "foo", "lef")  # no DEF: skipped
    _make(second, "foo", "lef", "def")
    _make(third, "foo", "lef", "def", "guide")
    monkeypatch.setenv(ENV_VAR, os.pathsep.join(map(str, (first, second, third))))
    found = find_testcase("foo")
    assert found.folder == (second / "foo").resolve()
    assert found.guide is None


def test_not_found_names_the_search_path(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = isolated / "root"
    monkeypatch.setenv(ENV_VAR, str(root))
    with pytest.raises(NotFound) as info:
        find_testcase("no_such_testcase")
    message = str(info.value)
    assert isinstance(info.value, XrouteError)
    assert "\n" not in message
    assert "no_such_testcase" in message
    for path in search_path():
        assert str(path) in message
    assert ENV_VAR in message and "../shared/testcases" in message


@pytest.mark.parametrize("name", ["", ".", "..", "../foo", "a/b"])
def test_path_like_names_are_not_looked_up(isolated: Path, monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    _make(isolated / "root", "foo", "lef", "def")
    monkeypatch.setenv(ENV_VAR, str(isolated / "root" / "sub"))
    with pytest.raises(NotFound):
        find_testcase(name)


def test_locate_all_reports_each_known_testcase(isolated: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    root = isolated / "root"
    _make(root, "ispd18_test5", "lef", "def", "guide")
    monkeypatch.setenv(ENV_VAR, str(root))
    located = dict((known.name, found) for known, found in locate_all())
    assert list(located) == [t.name for t in KNOWN_TESTCASES]
    assert located["ispd18_test5"] is not None
    assert located["ispd18_test5"].folder == (root / "ispd18_test5").resolve()


# -- the known list ---------------------------------------------------------------------------


def test_known_list_has_24_unique_testcases() -> None:
    names = [t.name for t in KNOWN_TESTCASES]
    assert len(names) == 24
    assert len(set(names)) == 24
    expected = {f"ispd18_test{i}" for i in range(1, 11)} | {f"ispd19_test{i}" for i in range(1, 11)}
    expected |= {"ispd18_sample", "ispd18_sample2", "ispd18_sample3", "ispd19_sample4"}
    assert set(names) == expected
    assert {t.name for t in KNOWN_TESTCASES if t.sample} == {n for n in expected if "sample" in n}
    for t in KNOWN_TESTCASES:
        assert t.contest == ("ISPD-2018" if t.name.startswith("ispd18") else "ISPD-2019")
        if t.components is not None and t.macros is not None:
            assert 0 <= t.macros <= t.components
    assert KNOWN_BY_NAME["ispd18_test3"] is known_testcase("ispd18_test3")
    assert known_testcase("not_a_testcase") is None


def test_known_figures_of_the_testcases_we_hold() -> None:
    t1, t19, t3 = (KNOWN_BY_NAME[n] for n in ("ispd18_test1", "ispd19_test1", "ispd19_test3"))
    assert (t1.components, t1.nets, t1.io_pins, t1.metal_layers) == (8879, 3153, 0, 9)
    assert (t19.components, t19.nets, t19.io_pins) == (8879, 3153, 0)
    assert (t3.components, t3.nets, t3.io_pins, t3.has_guide) == (8283, 8953, 57, False)
    assert (KNOWN_BY_NAME["ispd18_sample"].components, KNOWN_BY_NAME["ispd18_sample"].nets) == (22, 11)


def test_registry_matches_the_files(loaded_design) -> None:
    """Figures counted from the files ([DEF] source, and ispd18_test1) agree with the reader."""
    checked = 0
    for known in KNOWN_TESTCASES:
        if known.source != "DEF" and known.name != "ispd18_test1":
            continue
        try:
            find_testcase(known.name)
        except NotFound:
            continue
        design = loaded_design(known.name)
        counts = design.counts()
        assert counts["components"] == known.components, known.name
        assert counts["nets"] == known.nets, known.name
        assert counts["io_pins"] == known.io_pins, known.name
        assert counts["routing_layers"] == known.metal_layers, known.name
        xlo, ylo, xhi, yhi = design.die_area
        width_mm = (xhi - xlo) / design.dbu_per_micron / 1000
        height_mm = (yhi - ylo) / design.dbu_per_micron / 1000
        assert known.die_mm == pytest.approx((width_mm, height_mm), abs=0.005), known.name
        checked += 1
    if checked == 0:
        pytest.skip("none of the testcases counted from files is on the search path")


# -- static regions ---------------------------------------------------------------------------


def test_static_regions() -> None:
    assert [r.name for r in STATIC_REGIONS] == [f"Region{i}" for i in range(1, 11)]
    for r in STATIC_REGIONS:
        assert r.testcase in KNOWN_BY_NAME
        xlo, ylo, xhi, yhi = r.bbox
        assert xlo < xhi and ylo < yhi
        # GCells are square in all four testcases: the same GCell size along x and y.
        assert (xhi - xlo) % r.size_gcells[0] == 0 and (yhi - ylo) % r.size_gcells[1] == 0
        assert (xhi - xlo) // r.size_gcells[0] == (yhi - ylo) // r.size_gcells[1]
    assert STATIC_REGIONS[0].bbox == (199500, 245100, 205200, 250800)
    assert STATIC_REGIONS[9].size_gcells == (3, 3)


def test_static_regions_match_the_shared_readme() -> None:
    readmes = [root / "README.md" for root in search_path() if (root / "README.md").is_file()]
    if not readmes:
        pytest.skip("no README.md of the shared testcases on the search path")
    text = readmes[0].read_text()
    pattern = re.compile(r"(Region\d+) (\w+) (\d+)x(\d+) \((\d+),(\d+)\)-\((\d+),(\d+)\)")
    parsed = [
        (m[1], m[2], (int(m[3]), int(m[4])), (int(m[5]), int(m[6])), (int(m[7]), int(m[8])))
        for m in pattern.finditer(text)
    ]
    ours = [(r.name, r.testcase, r.size_gcells, r.lower_left, r.upper_right) for r in STATIC_REGIONS]
    assert parsed == ours


def test_static_regions_lie_inside_their_die(loaded_design) -> None:
    checked = 0
    for region in STATIC_REGIONS:
        try:
            find_testcase(region.testcase)
        except NotFound:
            continue
        xlo, ylo, xhi, yhi = loaded_design(region.testcase).die_area
        rxlo, rylo, rxhi, ryhi = region.bbox
        assert xlo <= rxlo < rxhi <= xhi and ylo <= rylo < ryhi <= yhi, region.name
        checked += 1
    if checked == 0:
        pytest.skip("no testcase of a static region is on the search path")
