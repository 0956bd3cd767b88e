"""The ``xroute`` command through Typer's CliRunner (and once through a real process)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import xroute.cli
from xroute.testcases import ENV_VAR, find_testcase
from conftest import nets_of, pick, sample_lef
from xroute.cli.app import app
from xroute.cli.console import error_line
from xroute.errors import InputError
from xroute.errors import TestcaseNotFound as NotFound


WIDE = {"COLUMNS": "200"}  # tables wide enough that no cell wraps, whatever the caller's terminal



def _line(output: str, label: str) -> str:
    """The table row whose first cell is ``label``."""
    for line in output.splitlines():
        cells = [c.strip() for c in line.replace("│", "|").split("|")]
        cells = [c for c in cells if c]
        if cells and cells[0] == label:
            return line
    raise AssertionError(f"no row {label!r} in:\n{output}")


# -- help -------------------------------------------------------------------------------------


@pytest.mark.parametrize("args", [[], ["info"], ["testcases"]])
def test_help(runner: CliRunner, args: list[str]) -> None:
    result = runner.invoke(app, [*args, "--help"])
    assert result.exit_code == 0, result.output
    assert "Usage" in result.output
    if not args:
        assert "info" in result.output and "testcases" in result.output


def test_no_arguments_shows_help(runner: CliRunner) -> None:
    result = runner.invoke(app, [])
    assert "Usage" in result.output
    assert result.exit_code in (0, 2)  # Click >= 8.2 exits 2 when no_args_is_help prints help


# -- info ---------------------------------------------------------------------------------------


def def_figures(path: Path) -> tuple[int, tuple[int, ...]]:
    """(components, die area) from a DEF's text, for a generated stand-in."""
    import re

    text = path.read_text()
    die = re.search(r"^DIEAREA \( (\d+) (\d+) \) \( (\d+) (\d+) \) ;", text, re.M)
    return int(re.search(r"^COMPONENTS (\d+) ;", text, re.M).group(1)), tuple(int(v) for v in die.groups())


def test_info_table_of_ispd18_sample(runner: CliRunner, testcase) -> None:
    name = pick("ispd18_sample")  # without the contest data: its stand-in, with figures read from its DEF
    found = testcase(name)
    result = runner.invoke(app, ["info", name], env=WIDE)
    assert result.exit_code == 0, result.output + result.stderr
    out = result.output
    assert "2000" in _line(out, "DBU per micron")
    assert "Metal1" in out and "ROUTING" in out
    if name != "ispd18_sample":
        comps, (x0, y0, x1, y1) = def_figures(found.def_)
        assert str(comps) in _line(out, "components") and str(nets_of(name)) in _line(out, "nets")
        assert f"({x0}, {y0}) - ({x1}, {y1})" in _line(out, "die area (DBU)")
        return
    assert "22" in _line(out, "components")
    assert "11" in _line(out, "nets")
    assert "(83600, 71820) - (104400, 91200)" in _line(out, "die area (DBU)")
    assert "10.4 x 9.69" in _line(out, "die area (µm)")
    assert "49" in _line(out, "warnings")


def test_info_json_of_ispd18_sample(runner: CliRunner, testcase) -> None:
    name = pick("ispd18_sample")  # without the contest data: its stand-in, with figures read from its DEF
    found = testcase(name)
    result = runner.invoke(app, ["info", name, "--json"])
    assert result.exit_code == 0, result.output + result.stderr
    data = json.loads(result.stdout)
    assert data["design"] == name
    assert data["dbu_per_micron"] == 2000
    assert data["files"]["def"] == str(found.def_)
    assert sum(data["pins"]["histogram"].values()) == data["nets"]
    assert data["pins"]["total"] == data["counts"]["net_pins"]
    assert isinstance(data["guides"], int) and data["guides"] > 0
    assert [layer["name"] for layer in data["layers"] if layer["type"] == "ROUTING"][0] == "Metal1"
    if name != "ispd18_sample":
        comps, die = def_figures(found.def_)
        assert (data["components"], data["nets"], tuple(data["die_area"]["dbu"])) == (comps, nets_of(name), die)
        assert data["routing_layers"] == 6  # the generator's technology
        return
    assert data["components"] == 22
    assert data["nets"] == 11
    assert data["die_area"]["dbu"] == [83600, 71820, 104400, 91200]
    assert data["io_pins"] == 0
    assert data["routing_layers"] == 9
    # LEF: USEMINSPACING 1 + FOREIGN 16 + PIN SHAPE 32 skipped, each a warning.
    assert data["warnings"] == 49
    assert data["skipped_statements"] == {"LEF.USEMINSPACING": 1, "MACRO.FOREIGN": 16, "PIN.SHAPE": 32}


def test_info_without_guide_says_so(runner: CliRunner, testcase) -> None:
    name = pick("ispd19_test3")  # without the contest data: a generated design without guide
    testcase(name)
    result = runner.invoke(app, ["info", name, "--json"])
    assert result.exit_code == 0, result.output + result.stderr
    data = json.loads(result.stdout)
    assert data["guides"] is None and data["files"]["guide"] is None
    if name == "ispd19_test3":
        assert (data["components"], data["nets"], data["io_pins"]) == (8283, 8953, 57)
    assert data["gcell_grid"] is not None


def test_info_missing_testcase(runner: CliRunner) -> None:
    result = runner.invoke(app, ["info", "no_such_testcase_xyz"])
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("error: testcase 'no_such_testcase_xyz' not found")
    assert ENV_VAR in lines[0]
    assert "Traceback" not in result.output + result.stderr


def test_info_missing_def_file(runner: CliRunner, tmp_path: Path) -> None:
    lef = tmp_path / "x.lef"
    lef.write_text("")
    missing = tmp_path / "missing.def"
    result = runner.invoke(app, ["info", "--lef", str(lef), "--def", str(missing)])
    assert result.exit_code == 2
    line = result.stderr.strip()
    assert line.startswith(f"error: {missing}: ") and "not found" in line and "\n" not in line


def test_info_malformed_def_names_file_and_line(runner: CliRunner, testcase, tmp_path: Path) -> None:
    lef = sample_lef()
    bad = tmp_path / "bad.def"
    bad.write_text(
        "VERSION 5.8 ;\n"
        "DESIGN bad ;\n"
        "UNITS DISTANCE MICRONS 2000 ;\n"
        "DIEAREA ( 0 0 ) ( 1000 oops ) ;\n"
        "END DESIGN\n"
    )
    result = runner.invoke(app, ["info", "--lef", str(lef), "--def", str(bad)])
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith(f"error: {bad}:4: ")
    assert "Traceback" not in result.output + result.stderr


@pytest.mark.parametrize(
    "args",
    [
        ["info"],  # nothing to read
        ["info", "--lef", "a.lef"],  # no DEF
        ["info", "ispd18_sample", "--def", "a.def"],  # both a name and files
        ["info", "--bogus"],
    ],
)
def test_info_usage_errors(runner: CliRunner, args: list[str]) -> None:
    result = runner.invoke(app, args)
    assert result.exit_code == 2
    assert "Traceback" not in result.output + result.stderr


# -- testcases --------------------------------------------------------------------------------


def test_testcases_lists_found_and_missing(runner: CliRunner, testcase) -> None:
    found = testcase("ispd18_test1")
    try:
        find_testcase("ispd18_test5")
        pytest.skip("ispd18_test5 is on the search path here")
    except NotFound:
        pass
    result = runner.invoke(app, ["testcases"], env=WIDE)
    assert result.exit_code == 0, result.output
    assert str(found.folder.parent) in _line(result.output, "ispd18_test1")
    assert "not found" in _line(result.output, "ispd18_test5")
    assert "XROUTE_TESTCASES" in result.output and "ispd.cc/contests/18" in result.output
    assert "Region10" in result.output

    data = json.loads(runner.invoke(app, ["testcases", "--json"]).stdout)
    rows = {row["name"]: row for row in data["testcases"]}
    assert rows["ispd18_test1"]["found"] == str(found.folder)
    assert rows["ispd18_test5"]["found"] is None
    assert rows["ispd18_test5"]["nets"] == 72394


def test_testcases_json(runner: CliRunner, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    folder = tmp_path / "ispd19_test7"
    folder.mkdir()
    for ext in ("lef", "def"):
        (folder / f"ispd19_test7.input.{ext}").write_text("")
    monkeypatch.setenv(ENV_VAR, str(tmp_path))
    result = runner.invoke(app, ["testcases", "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["search_path"][0] == str(tmp_path.resolve())
    assert len(data["testcases"]) == 24
    row = next(r for r in data["testcases"] if r["name"] == "ispd19_test7")
    assert row["found"] == str(folder.resolve())
    assert row["files"]["guide"] is None
    regions = {r["name"]: r for r in data["static_regions"]}
    assert len(regions) == 10
    assert regions["Region9"]["testcase_found"] is True
    assert regions["Region9"]["lower_left"] == [612000, 1314000]


# -- errors ---------------------------------------------------------------------------------------


def test_error_line_format() -> None:
    assert error_line(InputError("expected a number, got 'oops'", "/x/a.def", 12)) == (
        "error: /x/a.def:12: expected a number, got 'oops'"
    )
    assert error_line(InputError("DEF file not found", "/x/a.def", 0)) == "error: /x/a.def: DEF file not found"
    assert error_line(NotFound("testcase 'a' not found;\n  searched b")) == (
        "error: testcase 'a' not found; searched b"
    )
    assert error_line(FileNotFoundError(2, "No such file or directory", "/x/y")) == (
        "error: /x/y: No such file or directory"
    )


def test_real_process_prints_one_line_without_traceback(tmp_path: Path) -> None:
    """The console-script path (``main()``), not only CliRunner, turns user errors into one line."""
    package_parent = str(Path(xroute.cli.__file__).resolve().parent.parent)
    env = {**os.environ, "PYTHONPATH": package_parent, ENV_VAR: str(tmp_path)}
    proc = subprocess.run(
        [sys.executable, "-m", "xroute", "info", "no_such_testcase_xyz"],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert proc.stderr.count("\n") == 1
    assert proc.stderr.startswith("error: testcase 'no_such_testcase_xyz' not found")


def test_error_line_names_every_problem_of_a_config_file(tmp_path: Path) -> None:
    """All of a bad config's problems on the one error line, the first with its line, at most 1 + 9."""
    from xroute.config import ConfigError, load_config

    cfg = tmp_path / "bad.yaml"
    cfg.write_text("router:\n  iteraton_count: 3\n  thread_count: -1\npolicy:\n  policy: victms\n")
    with pytest.raises(ConfigError) as info:
        load_config(cfg)
    line = error_line(info.value)
    assert line.startswith(f"error: {cfg}:2: router.iteraton_count: unknown key (did you mean 'iteration_count'?)")
    assert "; also line 3: router.thread_count: must be between 1 and 1024, found -1; " in line
    assert "line 5: policy.policy: unknown policy 'victms' (did you mean 'victims'?)" in line
    assert "more problem" not in line and "\n" not in line
    many = tmp_path / "many.yaml"
    many.write_text("".join(f"k{i}: 1\n" for i in range(15)))
    with pytest.raises(ConfigError) as info:
        load_config(many)
    line = error_line(info.value)
    assert line.count("unknown key") == 10 and line.endswith("; and 5 more")


@pytest.mark.parametrize("args, hint", [
    (["route", "ispd18_sampel"], "testcase 'ispd18_sampel' not found (did you mean 'ispd18_sample'?)"),
    (["route", "--policy", "victms"], "unknown policy 'victms' (did you mean 'victims'?)"),
])
def test_misspelled_names_get_a_suggestion(runner, args: list[str], hint: str, tmp_path: Path) -> None:
    from xroute.cli.app import app

    res = runner.invoke(app, [*args, "--out", str(tmp_path / "o")])
    assert res.exit_code == 2 and hint in res.output


@pytest.mark.parametrize("command", ["plot", "plot-region"])
def test_help_keeps_the_extras_name(runner, command: str) -> None:
    """Rich markup would eat '[plot]' in pip install 'xroute[plot]' unless it is escaped."""
    from xroute.cli.app import app

    res = runner.invoke(app, [command, "--help"], terminal_width=200)
    assert res.exit_code == 0 and "pip install 'xroute[plot]'" in res.output


@pytest.mark.parametrize("args, start", [
    (["route", "--iterations", "1.5"], "error: xroute route: Invalid value for '--iterations': "),
    (["route", "--bogus"], "error: xroute route: No such option: --bogus"),
    (["nope"], "error: xroute: No such command 'nope'."),
])
def test_usage_errors_are_one_line(args: list[str], start: str, tmp_path) -> None:
    """Found by fuzz/mutate_cli.py (seed 3601): a bad option value gave Click's usage text and a boxed
    message over five lines."""
    done = subprocess.run([sys.executable, "-m", "xroute", *args], capture_output=True, text=True, timeout=120,
                          cwd=tmp_path)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.startswith(start) and done.stderr.count("\n") == 1, done.stderr
    assert done.stderr.rstrip().endswith("--help')")
