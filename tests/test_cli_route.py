"""``xroute route`` through Typer's CliRunner: outputs, --json, --quiet, policies, errors and the
exit status (0 routed, 1 opens on the written DEF, 2 user errors)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import nets_of, pick
from xroute.cli.app import app

# The contest samples, or their generated stand-ins when they are not on the search path.
SAMPLE, SAMPLE2, SAMPLE4 = (pick(n) for n in ("ispd18_sample", "ispd18_sample2", "ispd19_sample4"))


def outputs(folder: Path, design: str) -> list[Path]:
    return [folder / f"{design}.routed.def", folder / f"{design}.metrics.json", folder / f"{design}.drc.rpt"]


def test_route_quiet_writes_three_files_and_one_line(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE)
    out = tmp_path / "tmp"
    result = runner.invoke(app, ["route", SAMPLE, "--out", str(out), "--quiet"])
    assert result.exit_code == 0, result.output + result.stderr
    assert all(p.is_file() for p in outputs(out, SAMPLE))
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in outputs(out, SAMPLE))  # no temp left
    lines = result.stdout.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"{SAMPLE}: routed: {nets_of(SAMPLE)} nets, 0 open, 0 violations")
    assert result.stderr == ""


def test_route_json_parses_and_matches_the_file(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE4)
    result = runner.invoke(app, ["route", SAMPLE4, "--out", str(tmp_path), "--json", "--iterations", "3",
                                 "--threads", "2", "--region-size", "4", "--repair-rounds", "2"])
    assert result.exit_code == 0, result.output + result.stderr
    data = json.loads(result.stdout)
    assert data == json.loads((tmp_path / f"{SAMPLE4}.metrics.json").read_text())
    assert data["settings"] == {"region_size": 4, "iterations": 3, "threads": 2, "seed": 1, "schedule": None,
                                "repair_rounds": 2, "policy": "heuristic", "schedule_policy": "rule",
                                "sole_landing_penalty": 0}
    assert 1 <= len(data["iterations"]) <= 3
    assert data["final"]["open_nets"] == 0 and data["final"]["nets"] == nets_of(SAMPLE4)


def test_route_default_output_folder_and_progress_lines(runner: CliRunner, testcase, tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    found = testcase(SAMPLE2)
    # The default output folder is relative to the working directory; moving
    # there must not lose the testcases (an installed package finds them
    # relative to the working directory), so name their folder explicitly.
    monkeypatch.setenv("XROUTE_TESTCASES", str(found.folder.parent))
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["route", SAMPLE2], env={"COLUMNS": "200"})
    assert result.exit_code == 0, result.output + result.stderr
    assert all(p.is_file() for p in outputs(tmp_path / "out" / SAMPLE2, SAMPLE2))
    out = result.stdout
    # Not a terminal: plain progress lines, then the table, then the final line.
    assert out.startswith(f"routing {SAMPLE2}: {nets_of(SAMPLE2)} nets, region size auto, up to 16 iterations, "
                          "1 thread(s), policy heuristic\niteration 0: region size 10, ")
    assert "open nets" in out and "wirelength (µm)" in out
    assert out.strip().splitlines()[-1].startswith(f"{SAMPLE2}: routed: {nets_of(SAMPLE2)} nets, 0 open")


def test_route_schedule_option(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE4)
    result = runner.invoke(app, ["route", SAMPLE4, "--out", str(tmp_path), "--json", "--iterations", "3",
                                 "--schedule", "2:0,3:1"])
    assert result.exit_code == 0, result.output + result.stderr
    data = json.loads(result.stdout)
    assert data["settings"]["schedule"] == [[2, 0], [3, 1]]
    steps = [(it["region_size"], it["offset"]) for it in data["iterations"]]
    assert steps == [(2, 0), (3, 1), (2, 0)][: len(steps)]


def test_route_with_lef_def_files(runner: CliRunner, testcase, tmp_path: Path) -> None:
    found = testcase(SAMPLE)
    result = runner.invoke(app, ["route", "--lef", str(found.lef), "--def", str(found.def_), "--guide",
                                 str(found.guide), "--out", str(tmp_path), "--json"])
    assert result.exit_code == 0, result.output + result.stderr
    data = json.loads(result.stdout)
    assert data["testcase"] is None and data["inputs"]["def"] == str(found.def_)
    assert data["final"]["open_nets"] == 0


def test_route_python_policy_file(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE)
    policy = tmp_path / "longest_first.py"
    policy.write_text(
        "def order(region, features):\n"
        "    hp = (features[:, 6] - features[:, 4]) + (features[:, 7] - features[:, 5])\n"
        "    return sorted(range(len(features)), key=lambda i: (-int(hp[i]), i))\n"
    )
    result = runner.invoke(app, ["route", SAMPLE, "--out", str(tmp_path / "o"), "--policy", str(policy),
                                 "--json"])
    assert result.exit_code == 0, result.output + result.stderr
    data = json.loads(result.stdout)
    assert data["policy"] == "longest_first" and data["final"]["open_nets"] == 0


@pytest.mark.parametrize("spec", ["missing.onnx", "model.onnx", "nonexistent.py", "greedy"])
def test_route_bad_policy_is_a_one_line_error(runner: CliRunner, testcase, tmp_path: Path, spec: str) -> None:
    testcase(SAMPLE)
    if spec == "model.onnx":
        (tmp_path / spec).write_bytes(b"\0")
    out = tmp_path / "o"
    policy = spec if spec == "greedy" else str(tmp_path / spec)
    result = runner.invoke(app, ["route", SAMPLE, "--out", str(out), "--policy", policy])
    assert result.exit_code == 2, result.output + result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    expected = {"missing.onnx": "ONNX model not found", "model.onnx": "not a readable ONNX model", "nonexistent.py": "policy file not found",
                "greedy": "unknown policy 'greedy'"}[spec]
    assert expected in lines[0]
    assert "Traceback" not in result.output + result.stderr
    assert not out.exists()  # nothing routed, nothing written


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--region-size", "-1"], "error: region size must be at least 1 GCell (0: auto), got -1"),
        (["--iterations", "65"], "error: iterations must be between 1 and 64, got 65"),
        (["--threads", "0"], "error: threads must be at least 1, got 0"),
        (["--schedule", "5:0,x"], "error: --schedule: 'x' is not SIZE:OFFSET (two integers, GCells)"),
        (["--schedule", "5:5"], "error: schedule step 0: offset must be in 0..4 GCells, got 5"),
    ],
)
def test_route_bad_settings(runner: CliRunner, tmp_path: Path, args: list[str], message: str) -> None:
    result = runner.invoke(app, ["route", SAMPLE, "--out", str(tmp_path / "o"), *args])
    assert result.exit_code == 2
    assert result.stderr.strip() == message


def test_route_output_folder_that_is_a_file(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE)
    blocker = tmp_path / "file"
    blocker.write_text("")
    result = runner.invoke(app, ["route", SAMPLE, "--out", str(blocker / "sub")])
    assert result.exit_code == 2 and result.stderr.startswith(f"error: {blocker / 'sub'}: ")


def test_route_unknown_testcase_and_usage_errors(runner: CliRunner, tmp_path: Path) -> None:
    result = runner.invoke(app, ["route", "no_such_testcase_xyz", "--out", str(tmp_path)])
    assert result.exit_code == 2 and result.stderr.startswith("error: testcase 'no_such_testcase_xyz' not found")
    result = runner.invoke(app, ["route", "--guide", str(tmp_path / "a.guide")])  # no argument at all routes the demo
    assert result.exit_code == 2 and "give a testcase name" in result.output + result.stderr


def test_route_exit_1_when_the_written_def_has_opens(runner: CliRunner, testcase, tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    """A router that claims success but routes nothing: the check of the written DEF finds the opens."""
    testcase(SAMPLE)
    import xroute.router as router

    def no_routing(design, **kw):
        fake = router.IterationReport(iteration=0, region_size=5, offset=0, regions=0, net_routes=0, unreached=0,
                                      wirelength_dbu=0, wirelength_um=0.0, vias=0,
                                      violations_by_type={t: 0 for t in router.VIOLATION_TYPES})
        return router.RouteResult(iterations=(fake,), policy="none", settings=router.RouterSettings(), seconds=0.0,
                                  violations_by_type=dict(fake.violations_by_type))

    monkeypatch.setattr(router, "route_design", no_routing)
    result = runner.invoke(app, ["route", SAMPLE, "--out", str(tmp_path), "--quiet"])
    assert result.exit_code == 1, result.output + result.stderr
    n = nets_of(SAMPLE)  # every net of the sample (and of its stand-in) has two or more pins
    assert f"OPENS REMAIN: {n} nets, {n} open" in result.stdout
    opens = result.stderr.strip().splitlines()
    assert len(opens) == n and all(line.startswith("open net ") for line in opens)
    data = json.loads((tmp_path / f"{SAMPLE}.metrics.json").read_text())
    assert data["final"]["open_nets"] == data["final"]["unrouted_nets"] == n
    assert len(data["final"]["opens"]) == n


def test_route_help(runner: CliRunner) -> None:
    result = runner.invoke(app, ["route", "--help"], env={"COLUMNS": "200"})
    assert result.exit_code == 0
    for option in ("--out", "--region-size", "--iterations", "--threads", "--policy", "--seed", "--json", "--quiet"):
        assert option in result.output
