"""``xroute evaluate``: policy vs baseline per iteration, evaluation.json, each run's outputs, the paper's cost."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import pick
from xroute.cli.app import app

REPO = Path(__file__).resolve().parent.parent
PY_POLICY = REPO / "examples" / "python_heuristic_policy.py"
# The contest samples, or their generated stand-ins when the contest data is missing.
SAMPLE, SAMPLE4 = pick("ispd18_sample"), pick("ispd19_sample4")



def test_evaluate_python_policy_against_heuristic(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE4)
    out = tmp_path / "ev"
    result = runner.invoke(app, ["evaluate", "--policy", str(PY_POLICY), SAMPLE4, "--iterations", "3",
                                 "--out", str(out)])
    assert result.exit_code == 0, result.stdout + result.stderr
    doc = json.loads((out / "evaluation.json").read_text())
    pol, base = doc["runs"]["policy"], doc["runs"]["baseline"]
    # The Python heuristic orders exactly like the built-in one: the same routing, iteration by iteration.
    strip = lambda its: [{k: v for k, v in it.items() if k != "seconds"} for it in its]  # noqa: E731
    assert strip(pol["iterations"]) == strip(base["iterations"])
    n = len(pol["iterations"])  # up to 3: the flow stops at zero violations (after iteration 1 today)
    assert 1 <= n <= 3 and (n == 3 or pol["final"]["violations"] == 0)
    f = pol["final"]
    assert f["cost"] == pytest.approx(0.5 * f["wirelength_um"] + 4 * f["vias"] + 500 * f["violations"])
    assert doc["comparison"]["cost_delta"] == pytest.approx(0.0)
    assert f["policy_seconds"] is not None and 0 <= f["policy_share"] < 1
    assert base["final"]["policy_seconds"] is None  # built-in: runs in C++
    for sub in ("policy-python_heuristic_policy", "baseline-heuristic"):
        assert (out / sub / f"{SAMPLE4}.routed.def").is_file()
        assert (out / sub / f"{SAMPLE4}.metrics.json").is_file()
    # the table: one row per iteration, then final and cost
    for row in [f"{i} │" for i in range(n)] + ["final │", "paper cost │"]:
        assert row in result.stdout
    assert "% )" not in result.stdout and "s in the policy of" in result.stdout


def test_evaluate_json_is_one_document(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE)
    result = runner.invoke(app, ["evaluate", "--policy", "random", "--seed", "3", SAMPLE, "--json",
                                 "--out", str(tmp_path)])
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc == json.loads((tmp_path / "evaluation.json").read_text())
    assert doc["runs"]["policy"]["policy"] == "random" and doc["runs"]["baseline"]["policy"] == "heuristic"
    assert doc["settings"]["seed"] == 3


def test_evaluate_bad_policy_is_one_line(runner: CliRunner, tmp_path: Path) -> None:
    result = runner.invoke(app, ["evaluate", "--policy", str(tmp_path / "nope.py"), "ispd18_sample",
                                 "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert result.stderr.startswith("error: policy file not found") and result.stderr.count("\n") == 1
    assert not (tmp_path / "o").exists()


def test_evaluate_needs_policy(runner: CliRunner) -> None:
    result = runner.invoke(app, ["evaluate", "ispd18_sample"])
    assert result.exit_code == 2 and "--policy" in result.stderr + result.stdout
