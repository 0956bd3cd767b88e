"""Bad input, hostile input and interruptions - never a crash, never a write outside --out.

Each case of hostile input is a test here, on the shipped demo design (mutated copies in a
temporary folder) or tiny YAML / policy files: the expected exit status and the one error line
(``error: <file>:<line>: <message>``), no traceback, no output file when the input is bad, no file
outside the output folder.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import load_file
from xroute import _engine
from xroute.cli.app import app
from xroute.errors import InputError

DEMO = Path(__file__).resolve().parents[1] / "testcases" / "data" / "demo"
REGRESSIONS = Path(__file__).resolve().parent / "fuzz_regressions"


# ----------------------------------------------------------------------------- helpers
def demo_inputs(tmp_path: Path, *, lef=None, def_=None, guide=None) -> dict[str, Path]:
    """The demo's LEF/DEF/guide copied under tmp_path/in, each optionally changed by a function of
    its text (or replaced by bytes)."""
    folder = tmp_path / "in"
    folder.mkdir(exist_ok=True)
    paths = {}
    for kind, change in (("lef", lef), ("def", def_), ("guide", guide)):
        text = (DEMO / f"demo.{kind}").read_text()
        data = change(text) if callable(change) else change if change is not None else text
        p = folder / f"demo.{kind}"
        p.write_bytes(data if isinstance(data, bytes) else data.encode())
        paths[kind] = p
    return paths


def design_args(paths: dict[str, Path], guide: bool = True) -> list[str]:
    args = ["--lef", str(paths["lef"]), "--def", str(paths["def"])]
    return args + (["--guide", str(paths["guide"])] if guide else [])


def line_of(path: Path, needle: str) -> int:
    for i, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
        if needle in line:
            return i
    raise AssertionError(f"{needle!r} not in {path}")


def assert_one_error(result, prefix: str, contains: str = "") -> str:
    """Exit 2 and exactly one stderr line ``error: <prefix>...`` holding ``contains``; no traceback."""
    text = result.output + (result.stderr or "")
    assert "Traceback" not in text, text
    assert result.exit_code == 2, text
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("error: " + prefix), (lines[0], prefix)
    assert contains in lines[0], (lines[0], contains)
    return lines[0]


def files_under(folder: Path) -> set[str]:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")}


def sub(pattern: str, repl: str, count: int = 1):
    return lambda text: re.sub(pattern, repl, text, count=count, flags=re.M)


# ----------------------------------------------------------------------------- mutated LEF/DEF/guide via info
def test_invalid_utf8_in_a_skipped_lef_keyword_is_an_error_line(runner: CliRunner, tmp_path: Path) -> None:
    # A statement the reader skips, whose keyword holds invalid UTF-8: it used to reach Python as
    # a skipped-statement name and raise UnicodeDecodeError.
    bad = lambda t: t.replace("SITE core", "FOO\xff\xfeBAR 1 ;\nSITE core", 1)  # noqa: E731
    paths = demo_inputs(tmp_path, lef=lambda t: bad(t).encode("latin-1"))
    line = line_of(paths["lef"], "FOO")
    result = runner.invoke(app, ["info", *design_args(paths)])
    assert_one_error(result, f"{paths['lef']}:{line}: ", "invalid UTF-8")


@pytest.mark.parametrize("where", ["def", "guide"])
def test_invalid_utf8_in_a_name_is_an_error_line(runner: CliRunner, tmp_path: Path, where: str) -> None:
    if where == "def":
        paths = demo_inputs(tmp_path, def_=lambda t: t.replace("DESIGN demo", "DESIGN de\xffmo").encode("latin-1"))
        needle = "DESIGN"
    else:
        paths = demo_inputs(tmp_path, guide=lambda t: t.replace("n1\n", "n\xc31\n", 1).encode("latin-1"))
        needle = "n\ufffd1"
    result = runner.invoke(app, ["info", *design_args(paths)])
    assert_one_error(result, f"{paths[where]}:{line_of(paths[where], needle)}: ", "invalid UTF-8")


# "About 170 clearly invalid inputs accepted silently": one of each kind.
INVALID = [
    ("lef", "zero pitch", sub(r"PITCH 0\.1400 ;", "PITCH 0 ;"), "PITCH 0 ;", "PITCH of LAYER 'Metal1' must be positive"),
    ("lef", "negative pitch", sub(r"PITCH 0\.1400 ;", "PITCH -0.14 ;"), "PITCH -0.14", "must be positive"),
    ("lef", "zero width", sub(r"WIDTH 0\.0700 ;", "WIDTH 0 ;"), "WIDTH 0 ;", "WIDTH of LAYER 'Metal1' must be positive"),
    ("lef", "negative width", sub(r"WIDTH 0\.0700 ;", "WIDTH -0.07 ;"), "WIDTH -0.07", "must be positive"),
    ("lef", "negative spacing", sub(r"SPACING 0\.0700 ;", "SPACING -0.07 ;"), "SPACING -0.07", "must not be negative"),
    ("lef", "zero minwidth", sub(r"MINWIDTH 0\.0700 ;", "MINWIDTH 0 ;"), "MINWIDTH 0 ;", "must be positive"),
    ("lef", "routing layer without pitch", sub(r"  PITCH 0\.1400 ;\n", ""), "LAYER Metal1", "has no positive PITCH"),
    ("lef", "empty file", lambda t: "", None, "empty LEF file"),
    ("lef", "comments only", lambda t: "# nothing here\n", None, "empty LEF file"),
    ("def", "TRACKS step 0", sub(r"TRACKS Y 280 DO 219 STEP 280", "TRACKS Y 280 DO 219 STEP 0"), "STEP 0",
     "TRACKS STEP must be positive"),
    ("def", "TRACKS step negative", sub(r"TRACKS Y 280 DO 219 STEP 280", "TRACKS Y 280 DO 219 STEP -280"), "STEP -280",
     "TRACKS STEP must be positive"),
    ("def", "GCELLGRID step 0", sub(r"(GCELLGRID X \S+ DO \S+) STEP \d+", r"\1 STEP 0"), "GCELLGRID X",
     "GCELLGRID STEP must be positive"),
    ("def", "billions of GCells", lambda t: re.sub(r"(?m)^GCELLGRID.*\n", "", t).replace(
        "COMPONENTS", "GCELLGRID X 0 DO 62701 STEP 1 ;\nGCELLGRID Y 0 DO 61601 STEP 1 ;\nCOMPONENTS", 1),
     "GCELLGRID X 0 DO 62701", "GCELLGRID makes 62700 x 61600 GCells; at most 25000000 are supported"),
    ("def", "TRACKS count too large", sub(r"TRACKS Y 280 DO 219", "TRACKS Y 280 DO 200000000"), "DO 200000000",
     "bad track count '200000000' (1..10000000)"),
    ("def", "inverted die", sub(r"DIEAREA \( 0 0 \) \( 62700 61600 \)", "DIEAREA ( 62700 61600 ) ( 0 0 )"), "DIEAREA",
     "DIEAREA corners are inverted"),
    ("def", "zero-width die", sub(r"DIEAREA \( 0 0 \) \( 62700 61600 \)", "DIEAREA ( 0 0 ) ( 0 61600 )"), "DIEAREA",
     "DIEAREA has zero width"),
    ("guide", "inverted guide", sub(r"^39900 0 45600 5600 Metal1", "45600 5600 39900 0 Metal1"), "45600 5600 39900 0",
     "guide rectangle is inverted"),
    ("guide", "zero-width guide", sub(r"^39900 0 45600 5600 Metal1", "39900 0 39900 5600 Metal1"), "39900 0 39900",
     "guide rectangle has zero width"),
    ("guide", "guide outside the die", sub(r"^39900 0 45600 5600 Metal1", "90000 90000 95000 95000 Metal1"),
     "90000 90000", "lies outside the die area"),
    ("guide", "guide on an unknown layer", sub(r"^39900 0 45600 5600 Metal1", "39900 0 45600 5600 Metal99"), "Metal99",
     "unknown layer"),
    ("guide", "guide for an unknown net", sub(r"^n1$", "no_such_net"), "no_such_net", "is not in the DEF"),
    ("guide", "empty guide file", lambda t: "", None, "empty guide file"),
]


@pytest.mark.parametrize(("kind", "what", "change", "needle", "message"), INVALID, ids=[r[1] for r in INVALID])
def test_clearly_invalid_input_is_one_error_line(runner: CliRunner, tmp_path: Path, kind: str, what: str, change,
                                                 needle: str | None, message: str) -> None:
    paths = demo_inputs(tmp_path, **{"def_" if kind == "def" else kind: change})
    line = line_of(paths[kind], needle) if needle else 1
    result = runner.invoke(app, ["info", *design_args(paths)])
    assert_one_error(result, f"{paths[kind]}:{line}: ", message)
    # The same through route: exit 2, nothing written.
    out = tmp_path / "out"
    result = runner.invoke(app, ["route", *design_args(paths), "--out", str(out), "--iterations", "1", "--quiet"])
    assert_one_error(result, f"{paths[kind]}:{line}: ", message)
    assert not out.exists() or not any(out.iterdir())


def test_odd_but_routable_input_is_a_warning_listed_by_info(runner: CliRunner, tmp_path: Path) -> None:
    paths = demo_inputs(tmp_path, guide=sub(r"^39900 0 45600 5600 Metal1", "-5000 0 45600 5600 Metal1"))
    line = line_of(paths["guide"], "-5000 0")
    result = runner.invoke(app, ["info", *design_args(paths)])
    assert result.exit_code == 0, result.output + result.stderr
    assert f"warning: {paths['guide']}:{line}: 1 guide rectangle(s) reach past the die area" in result.output
    data = json.loads(runner.invoke(app, ["info", *design_args(paths), "--json"]).output)
    assert data["warnings"] >= 1 and any("reach past the die area" in w for w in data["warning_messages"])


def test_a_rule_nothing_models_is_read_and_warned_once_by_route(runner: CliRunner, tmp_path: Path) -> None:
    # MINSTEP on both metal layers: read, one warning line naming the rule and its layers, and the
    # route made. MINWIDTH (every layer of the demo states it) is read by the router: no warning.
    paths = demo_inputs(tmp_path, lef=sub(r"^  MINWIDTH 0.0700 ;", "  MINWIDTH 0.0700 ;\n  MINSTEP 0.05 ;", count=2))
    out = tmp_path / "out"
    result = runner.invoke(app, ["route", *design_args(paths), "--out", str(out), "--iterations", "1", "--quiet"])
    assert result.exit_code in (0, 1), result.output + result.stderr
    warned = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
    assert warned == ["warning: MINSTEP on Metal1, Metal2: not modelled (routed and checked without it; "
                      "see xroute check's not-checked list)"]
    assert (out / "demo.routed.def").is_file()
    # A bad output folder (a file) is still the one error line: the warning comes after that check.
    (tmp_path / "taken").write_text("")
    result = runner.invoke(app, ["route", *design_args(paths), "--out", str(tmp_path / "taken"), "--quiet"])
    assert result.exit_code == 2 and "Traceback" not in result.output + result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines


# ----------------------------------------------------------------------------- DIEAREA (was 7 segfaults, 2 SIGFPE)
DIE = {
    "zero width": ("( 0 0 ) ( 0 61600 )", "DIEAREA has zero width"),
    "zero height": ("( 0 0 ) ( 62700 0 )", "DIEAREA has zero height"),
    "a point off the origin": ("( 100 100 ) ( 100 100 )", "DIEAREA has zero width"),
    "inverted": ("( 62700 61600 ) ( 0 0 )", "DIEAREA corners are inverted"),
    "inverted x": ("( 62700 0 ) ( 0 61600 )", "DIEAREA corners are inverted"),
    "inverted y": ("( 0 61600 ) ( 62700 0 )", "DIEAREA corners are inverted"),
    "flat polygon": ("( 0 0 ) ( 62700 0 ) ( 100 0 ) ( 0 0 )", "DIEAREA has zero height"),
    "one point": ("( 0 0 )", "DIEAREA needs at least 2 points"),
}


@pytest.mark.parametrize("guide", [True, False], ids=["guide", "no-guide"])
@pytest.mark.parametrize("case", sorted(DIE))
def test_degenerate_diearea_through_route(runner: CliRunner, tmp_path: Path, case: str, guide: bool) -> None:
    box, message = DIE[case]
    paths = demo_inputs(tmp_path, def_=sub(r"^DIEAREA .*;", f"DIEAREA {box} ;"))
    out = tmp_path / "out"
    result = runner.invoke(app, ["route", *design_args(paths, guide), "--out", str(out), "--iterations", "1"])
    assert_one_error(result, f"{paths['def']}:{line_of(paths['def'], 'DIEAREA')}: ", message)
    assert not out.exists() or not any(out.iterdir())


# ----------------------------------------------------------------------------- writes outside --out
@pytest.mark.parametrize("name", ["../escaped", "ABS", "a/../../up", "..", "x/y", ".hidden", "a" * 300, "-rf"])
def test_design_name_cannot_choose_where_outputs_go(runner: CliRunner, tmp_path: Path, name: str) -> None:
    if name == "ABS":
        name = str(tmp_path / "abs_escape")
    paths = demo_inputs(tmp_path, def_=sub(r"^DESIGN demo ;", f"DESIGN {name} ;"))
    out = tmp_path / "work" / "out"
    before = files_under(tmp_path)
    result = runner.invoke(app, ["route", *design_args(paths), "--out", str(out), "--iterations", "1", "--quiet"])
    assert result.exit_code in (0, 1), result.output + result.stderr
    new = files_under(tmp_path) - before
    assert new and all(p == "work" or p.startswith("work/out") for p in new), sorted(new)
    outputs = sorted(p.name for p in out.iterdir())
    assert len(outputs) == 3 and all(not n.startswith(".") and "/" not in n for n in outputs), outputs
    stems = {n.split(".")[0] for n in outputs}
    assert len(stems) == 1


def test_default_out_folder_uses_the_safe_design_name(runner: CliRunner, tmp_path: Path, monkeypatch) -> None:
    paths = demo_inputs(tmp_path, def_=sub(r"^DESIGN demo ;", "DESIGN ../../escaped ;"))
    work = tmp_path / "a" / "b"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    result = runner.invoke(app, ["route", *design_args(paths), "--iterations", "1", "--quiet"])
    assert result.exit_code in (0, 1), result.output + result.stderr
    assert not (tmp_path / "escaped").exists() and not (tmp_path / "escaped.routed.def").exists()
    assert [p.parent.name for p in (work / "out").glob("*/*.routed.def")]


def test_safe_stem_and_inside() -> None:
    from xroute.safe_paths import OutputPathError, inside, safe_stem

    assert safe_stem("ispd18_test1") == "ispd18_test1"
    for hostile in ("../x", "/tmp/x", "..", ".", "a/b", "", "é", "x" * 500, "\0"):
        s = safe_stem(hostile)
        assert s and "/" not in s and not s.startswith(".") and ".." not in s and len(s) <= 120, (hostile, s)
    assert safe_stem("../x") != safe_stem("..x")  # changed names keep a hash of the original
    with pytest.raises(OutputPathError):
        inside("/tmp/out", "/tmp/out/../x")
    with pytest.raises(OutputPathError):
        inside("/tmp/out", "/tmp/x")
    assert inside("/tmp/out", "/tmp/out/a.def") == Path("/tmp/out/a.def").resolve()


# ----------------------------------------------------------------------------- symlinks and exclusive temp files
def test_def_writer_does_not_follow_planted_symlinks(tmp_path: Path) -> None:
    db = _engine.load([str(DEMO / "demo.lef")], str(DEMO / "demo.def"))
    out = tmp_path / "out"
    out.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    target = out / "demo.routed.def"
    # The old writer opened "<path>.tmp.<pid>" with fopen: a link planted there was followed.
    (out / f"demo.routed.def.tmp.{os.getpid()}").symlink_to(victim)
    db.write_def(str(target))
    assert victim.read_text() == "precious\n"
    assert target.is_file() and not target.is_symlink()
    # A link at the final name is replaced, not written through.
    target.unlink()
    target.symlink_to(victim)
    db.write_def(str(target))
    assert victim.read_text() == "precious\n" and not target.is_symlink()
    assert target.read_text().rstrip().endswith("END DESIGN")
    leftovers = [p.name for p in out.iterdir() if p.name.startswith(".")]
    assert not leftovers, leftovers


def test_python_writer_does_not_follow_planted_symlinks(tmp_path: Path) -> None:
    from xroute.atomic_files import atomic_write_text

    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    target = tmp_path / "m.json"
    target.symlink_to(victim)
    atomic_write_text(target, "{}\n")
    assert victim.read_text() == "precious\n" and target.read_text() == "{}\n" and not target.is_symlink()


def test_route_into_folder_with_planted_symlinks(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    for name in ("demo.routed.def", "demo.metrics.json", "demo.drc.rpt"):
        (out / name).symlink_to(victim)
    result = runner.invoke(app, ["route", "demo", "--out", str(out), "--iterations", "1", "--quiet"])
    assert result.exit_code in (0, 1), result.output + result.stderr
    assert victim.read_text() == "precious\n"
    assert not any(p.is_symlink() for p in out.iterdir())


# ----------------------------------------------------------------------------- YAML
YAML_CASES = {
    "merge key": ("base: &b {region_size: 3}\nregion:\n  <<: *b\n", 3, "merge keys (<<) are not supported"),
    "custom tag": ("region: !custom {region_size: 3}\n", 1, "YAML tag '!custom' is not allowed"),
    "python name": ("router: !!python/name:os.system\n", 1, "YAML tag 'tag:yaml.org,2002:python/name:os.system'"),
    "python object": ("router: !!python/object/apply:os.system ['echo hi']\n", 1, "is not allowed"),
    "binary": ("policy: {seed: !!binary aGVsbG8=}\n", 1, "is not allowed"),
    "5000 deep": ("a: " + "[" * 5000 + "]" * 5000 + "\n", 1, "YAML nested deeper than 64 levels"),
    "3000 deep mappings": ("a: " + "{b: " * 3000 + "1" + "}" * 3000 + "\n", 1, "YAML nested deeper than 64 levels"),
    "alias bomb": ("a: &a [x, x, x, x, x, x, x, x, x, x]\n"
                   + "".join(f"{c}: &{c} [{', '.join(['*' + p] * 10)}]\n" for p, c in zip("abcdef", "bcdefg")),
                   0, "more than 50,000 nodes"),
    "bad date": ("output: {out_dir: 2020-13-45}\nregion: {region_size: 2020-01-01}\n", 2, "expected an integer"),
    "two documents": ("--- {}\n--- {}\n", 2, "invalid YAML"),
    "huge region size": ("region: {region_size: 2147483648}\n", 1, "must be between 0 and 1000"),
    "huge schedule": ("router: {iteration_schedule: [{region_size: 99999999999999999999, offset: 0}]}\n", 1,
                      "must be between 1 and 1000"),
}


@pytest.mark.parametrize("case", sorted(YAML_CASES))
def test_hostile_yaml_config_is_one_error_line(runner: CliRunner, tmp_path: Path, case: str) -> None:
    text, line, message = YAML_CASES[case]
    cfg = tmp_path / "c.yaml"
    cfg.write_text(text)
    out = tmp_path / "out"
    result = runner.invoke(app, ["route", "demo", "--config", str(cfg), "--out", str(out), "--iterations", "1"])
    error = assert_one_error(result, f"{cfg}:{line}: " if line else f"{cfg}", message)
    assert len(error) < 400
    assert not out.exists()


def test_oversized_yaml_is_an_error(runner: CliRunner, tmp_path: Path) -> None:
    cfg = tmp_path / "big.yaml"
    cfg.write_text("# " + "x" * (2 << 20) + "\n")
    result = runner.invoke(app, ["route", "demo", "--config", str(cfg), "--out", str(tmp_path / "o")])
    assert_one_error(result, f"{cfg}: ", "YAML file too large")


def test_hostile_batch_yaml_is_one_error_line(runner: CliRunner, tmp_path: Path) -> None:
    cfg = tmp_path / "b.yaml"
    cfg.write_text("testcases: [demo]\nbase: &b [heuristic]\npolicies: !!python/name:os.system\n")
    result = runner.invoke(app, ["batch", str(cfg), "--out", str(tmp_path / "o")])
    assert_one_error(result, f"{cfg}:3: ", "is not allowed")


@pytest.mark.slow
def test_batch_matrix_300_by_300_is_checked_in_linear_time(runner: CliRunner, tmp_path: Path) -> None:
    # 300 testcases x 300 policies = 90,000 jobs whose ids repeat: the old duplicate check
    # (list.count in a loop) took minutes; now the repeat is reported at once.
    pols = tmp_path / "pols"
    pols.mkdir()
    names = []
    for i in range(300):
        p = pols / f"p{i}.py"
        p.write_text("def order(region, features):\n    return range(len(features))\n")
        names.append(f"pols/p{i}.py")
    cfg = tmp_path / "b.yaml"
    cfg.write_text("testcases: [" + ", ".join(["demo"] * 300) + "]\npolicies: [" + ", ".join(names) + "]\n")
    start = time.perf_counter()
    result = runner.invoke(app, ["batch", str(cfg), "--out", str(tmp_path / "o")])
    took = time.perf_counter() - start
    assert_one_error(result, f"{cfg}: ", "two jobs would share the id demo__p0__default")
    assert took < 30, took


@pytest.mark.slow
def test_batch_config_settings_names_checked_in_linear_time(tmp_path: Path) -> None:
    from xroute.cli.batch_config import load_batch_config
    from xroute.config_schema import ConfigError

    cfg = tmp_path / "b.yaml"
    entries = "".join(f"  - {{name: s{i}}}\n" for i in range(5000)) + "  - {name: s7}\n"
    cfg.write_text("testcases: [demo]\nsettings:\n" + entries)
    start = time.perf_counter()
    with pytest.raises(ConfigError, match="settings names must be unique, repeated: s7"):
        load_batch_config(cfg)
    assert time.perf_counter() - start < 30


@pytest.mark.parametrize("path", sorted((REGRESSIONS / "yaml").glob("*.yaml")), ids=lambda p: p.name)
def test_yaml_fuzz_regressions(path: Path) -> None:
    load_file("fuzz/fuzz_yaml.py").one_input(path.read_bytes())


# ----------------------------------------------------------------------------- policies
def write_policy(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def test_policy_that_raises_is_one_line_naming_file_and_line(runner: CliRunner, tmp_path: Path) -> None:
    pol = write_policy(tmp_path, "bad.py", "def helper():\n    return 1 / 0\n\ndef order(region, features):\n"
                                           "    return helper()\n")
    out = tmp_path / "out"
    result = runner.invoke(app, ["route", "demo", "--policy", str(pol), "--out", str(out), "--iterations", "1"])
    assert_one_error(result, f"{pol}:2: ", "policy 'bad' raised ZeroDivisionError: division by zero")
    assert not out.exists() or not any(out.iterdir())
    # --debug adds the traceback.
    result = runner.invoke(app, ["--debug", "route", "demo", "--policy", str(pol), "--out", str(out), "--iterations", "1"])
    assert result.exit_code == 2 and "Traceback" in result.stderr and "ZeroDivisionError" in result.stderr


def test_policy_sys_exit_inside_order_is_an_error(runner: CliRunner, tmp_path: Path) -> None:
    pol = write_policy(tmp_path, "quits.py", "import sys\ndef order(region, features):\n    sys.exit(0)\n")
    out = tmp_path / "out"
    result = runner.invoke(app, ["route", "demo", "--policy", str(pol), "--out", str(out), "--iterations", "1"])
    assert_one_error(result, f"{pol}:3: ", "called sys.exit(0) inside order(): a policy cannot end the run")
    assert not out.exists() or not any(out.iterdir())


def test_policy_sys_exit_on_import_is_an_error(runner: CliRunner, tmp_path: Path) -> None:
    pol = write_policy(tmp_path, "quits.py", "import sys\nsys.exit(0)\n")
    result = runner.invoke(app, ["route", "demo", "--policy", str(pol), "--out", str(tmp_path / "o")])
    assert_one_error(result, f"{pol}:2: ", "failed to load: SystemExit")


def test_policy_that_hangs_in_python_ends_with_a_clear_error(runner: CliRunner, tmp_path: Path) -> None:
    pol = write_policy(tmp_path, "spins.py", "def order(region, features):\n    while True:\n        pass\n")
    cfg = tmp_path / "c.yaml"
    cfg.write_text("policy: {call_timeout: 0.5}\n")
    start = time.perf_counter()
    result = runner.invoke(app, ["route", "demo", "--config", str(cfg), "--policy", str(pol), "--out",
                                 str(tmp_path / "o"), "--iterations", "1"])
    assert time.perf_counter() - start < 30
    assert_one_error(result, "", "an order() call ran longer than 0.5 s (policy.call_timeout)")


@pytest.mark.slow
def test_policy_blocked_outside_python_ends_the_process(tmp_path: Path) -> None:
    pol = write_policy(tmp_path, "sleeps.py", "import time\ndef order(region, features):\n    time.sleep(3600)\n")
    cfg = tmp_path / "c.yaml"
    cfg.write_text("policy: {call_timeout: 0.5}\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in sys.path if p), "CI": "true"}
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "xroute", "route", "demo", "--config", str(cfg), "--policy",
                           str(pol), "--out", str(tmp_path / "o"), "--iterations", "1", "--quiet"],
                          capture_output=True, text=True, env=env, timeout=120)
    assert time.perf_counter() - start < 60
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines()[-1].startswith("error: policy 'sleeps'")
    assert "ran longer than 0.5 s" in proc.stderr
    out = tmp_path / "o"
    assert not out.exists() or not [p for p in out.iterdir() if not p.name.startswith(".")]


def test_library_callers_still_get_their_policy_exception() -> None:
    from xroute.design import load_design
    from xroute.net_order import CallablePolicy
    from xroute.router import route_design

    def order(region, features):
        raise KeyError("mine")

    with pytest.raises(KeyError, match="mine"):
        route_design(load_design("demo"), policy=CallablePolicy(order), iterations=1)


def test_policy_that_raises_in_a_batch_job_is_that_job_s_error(runner: CliRunner, tmp_path: Path) -> None:
    pol = write_policy(tmp_path, "bad.py", "def order(region, features):\n    raise ValueError('nope')\n")
    cfg = tmp_path / "b.yaml"
    cfg.write_text(f"testcases: [demo]\npolicies: [{pol}]\nsettings:\n  - {{name: one, iteration_count: 1}}\n")
    out = tmp_path / "o"
    result = runner.invoke(app, ["batch", str(cfg), "--out", str(out), "--json"])
    assert "Traceback" not in result.output + result.stderr
    assert result.exit_code == 1, result.output + result.stderr
    rows = json.loads(result.stdout)["jobs"]
    assert rows[0]["status"] == "error" and f"{pol}:2: policy 'bad' raised ValueError: nope" in rows[0]["message"]


# ----------------------------------------------------------------------------- kill -9: one run, one set
def test_partial_publish_of_a_killed_rerun_is_cleaned(runner: CliRunner, tmp_path: Path) -> None:
    """A rerun killed after its new DEF replaced the old one (metrics and DRC report still the first
    run's): the next run removes the mixed set, then writes a whole new one."""
    from xroute.output_set import NOTE, STAGE_PREFIX, file_sha256

    out = tmp_path / "out"
    assert runner.invoke(app, ["route", "demo", "--out", str(out), "--iterations", "1", "--quiet"]).exit_code in (0, 1)
    first = json.loads((out / "demo.metrics.json").read_text())
    assert first["run"]["sha256"]["def"] == file_sha256(out / "demo.routed.def")
    # What a killed second run leaves: its staging folder (a dead pid) with the note, the new DEF in place.
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stage = out / f"{STAGE_PREFIX}{dead.pid}.deadbeef"
    stage.mkdir()
    new_def = (out / "demo.routed.def").read_text().replace("END DESIGN", "# second run\nEND DESIGN")
    (out / "demo.routed.def").write_text(new_def)
    (stage / NOTE).write_text(json.dumps({"files": ["demo.routed.def", "demo.drc.rpt", "demo.metrics.json"],
                                          "sha256": {"demo.routed.def": file_sha256(out / "demo.routed.def"),
                                                     "demo.drc.rpt": "0" * 64, "demo.metrics.json": "1" * 64}}))
    from xroute.outputs import clean_stale_temporaries

    removed = {p.name for p in clean_stale_temporaries(out)}
    assert {"demo.routed.def", "demo.drc.rpt", "demo.metrics.json", stage.name} <= removed
    assert not any(out.iterdir())
    assert runner.invoke(app, ["route", "demo", "--out", str(out), "--iterations", "1", "--quiet"]).exit_code in (0, 1)
    m = json.loads((out / "demo.metrics.json").read_text())
    assert m["run"]["sha256"] == {"def": file_sha256(out / "demo.routed.def"),
                                  "drc_report": file_sha256(out / "demo.drc.rpt")}


def test_complete_set_of_a_killed_run_is_kept(tmp_path: Path) -> None:
    from xroute.output_set import NOTE, STAGE_PREFIX, clean_leftovers, file_sha256

    out = tmp_path / "out"
    out.mkdir()
    for n in ("a.routed.def", "a.drc.rpt"):
        (out / n).write_text(n)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stage = out / f"{STAGE_PREFIX}{dead.pid}.0000"
    stage.mkdir()
    (stage / NOTE).write_text(json.dumps({"files": ["a.routed.def", "a.drc.rpt"],
                                          "sha256": {n: file_sha256(out / n) for n in ("a.routed.def", "a.drc.rpt")}}))
    assert clean_leftovers(out) == [stage]
    assert sorted(p.name for p in out.iterdir()) == ["a.drc.rpt", "a.routed.def"]


def test_stale_summary_temporary_of_a_killed_batch_is_cleaned(runner: CliRunner, tmp_path: Path) -> None:
    out = tmp_path / "batch"
    out.mkdir()
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = out / f".summary.json.{dead.pid}.0123abcd.tmp"
    stale.write_text("{")
    cfg = tmp_path / "b.yaml"
    cfg.write_text("testcases: [demo]\nsettings:\n  - {name: one, iteration_count: 1}\n")
    result = runner.invoke(app, ["batch", str(cfg), "--out", str(out), "--quiet"])
    assert result.exit_code in (0, 1), result.output + result.stderr
    assert not stale.exists()
    assert (out / "summary.json").is_file()


# ----------------------------------------------------------------------------- odd flags
@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--region-size", "2147483648"], "error: region size must be at most 1000 GCells, got 2147483648"),
        (["--region-size", "99999999999999999999"], "error: region size must be at most 1000 GCells, got 99999999999999999999"),
        (["--schedule", "99999999999999999999:0"],
         "error: schedule step 0: region size must be at most 1000 GCells, got 99999999999999999999"),
        (["--threads", "4294967297"], "error: threads must be at most 1024, got 4294967297"),
        (["--seed", "18446744073709551616"], "error: seed must be between 0 and 2^64 - 1, got 18446744073709551616"),
        (["--iterations", "99999999999999999999"], "error: iterations must be between 1 and 64, got 99999999999999999999"),
    ],
)
def test_odd_flags_are_one_error_line(runner: CliRunner, tmp_path: Path, args: list[str], message: str) -> None:
    out = tmp_path / "o"
    result = runner.invoke(app, ["route", "demo", "--out", str(out), *args])
    assert "Traceback" not in result.output + result.stderr
    assert result.exit_code == 2
    assert result.stderr.strip() == message
    assert not out.exists()


# ----------------------------------------------------------------------------- a clean run stays clean
def test_clean_demo_has_no_warning_and_loads(tmp_path: Path) -> None:
    db = _engine.load([str(DEMO / "demo.lef")], str(DEMO / "demo.def"), str(DEMO / "demo.guide"))
    assert list(db.warnings()) == []


def test_input_error_lines_lie_inside_the_file(tmp_path: Path) -> None:
    # A DEF without DIEAREA reads (DIEAREA is optional); the warning names its END DESIGN line.
    paths = demo_inputs(tmp_path, def_=sub(r"^DIEAREA .*\n", ""))
    db = _engine.load([str(paths["lef"])], str(paths["def"]), "")
    end = line_of(paths["def"], "END DESIGN")
    assert any(w.startswith(f"{paths['def']}:{end}: no DIEAREA") for w in db.warnings())
