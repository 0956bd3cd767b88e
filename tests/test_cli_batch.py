"""``xroute batch``: the CI smoke batch on the samples, gates, resume, errors, JUnit and summaries."""

from __future__ import annotations

import csv
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from conftest import make_runner, require_testcase
from xroute_cli.app import app

REPO = Path(__file__).resolve().parent.parent
SMOKE = REPO / "configs" / "ci-smoke.yaml"
SMOKE_JOBS = [f"{t}__{p}__rs5" for t in ("ispd18_sample", "ispd18_sample2", "ispd19_sample4") for p in ("heuristic", "random")]



def smoke_variant(tmp_path: Path, **replace: str) -> Path:
    """ci-smoke.yaml with some lines replaced (key -> new line) and its baseline path made absolute."""
    lines = []
    for line in SMOKE.read_text().splitlines():
        key = line.strip().split(":")[0]
        if key == "baseline":
            line = f"  baseline: {REPO / 'configs' / 'baselines' / 'ci-smoke.json'}"
        if key in replace:
            line = replace.pop(key)
        lines.append(line)
    lines += list(replace.values())
    p = tmp_path / "batch.yaml"
    p.write_text("\n".join(lines) + "\n")
    return p


@pytest.fixture(scope="module")
def smoke(tmp_path_factory) -> tuple[Path, object]:
    """The CI-style run, once: CI=true xroute batch configs/ci-smoke.yaml (2 parallel jobs)."""
    for name in ("ispd18_sample", "ispd18_sample2", "ispd19_sample4"):
        require_testcase(name)
    out = tmp_path_factory.mktemp("smoke")
    result = make_runner().invoke(app, ["batch", str(SMOKE), "--out", str(out), "--jobs", "2"], env={"CI": "true"})
    return out, result


def junit_cases(path: Path) -> dict[str, ET.Element]:
    root = ET.parse(path).getroot()
    return {c.get("name"): c for c in root.iter("testcase")}


def test_ci_smoke_batch_passes_and_writes_junit_and_summaries(smoke) -> None:
    out, result = smoke
    assert result.exit_code == 0, result.stdout + result.stderr
    assert result.stderr == ""
    # CI=true: plain log lines (no Rich progress), one per job start, iteration and end
    assert "ispd18_sample__heuristic__rs5: started" in result.stdout
    assert "ispd19_sample4__random__rs5: iteration 0:" in result.stdout
    assert "\r" not in result.stdout and "\x1b[" not in result.stdout
    cases = junit_cases(out / "junit.xml")
    assert sorted(cases) == sorted(SMOKE_JOBS)
    assert not any(c.find("failure") is not None or c.find("error") is not None for c in cases.values())
    suite = ET.parse(out / "junit.xml").getroot().find("testsuite")
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("6", "0", "0")
    doc = json.loads((out / "summary.json").read_text())
    assert doc["passed"] is True and doc["counts"] == {"jobs": 6, "failed": 0, "errors": 0, "resumed": 0}
    rows = {r["id"]: r for r in doc["jobs"]}
    stored = json.loads((REPO / "configs" / "baselines" / "ci-smoke.json").read_text())["jobs"]
    for job, figures in stored.items():  # the stored baseline is what this router writes today
        assert {k: rows[job][k] for k in figures} == figures, job
    assert rows["ispd19_sample4__heuristic__rs5"]["violations"] == 0  # was 7 before the PRL-aware footprint
    with open(out / "summary.csv") as f:
        table = list(csv.DictReader(f))
    assert [r["id"] for r in table] == [r["id"] for r in doc["jobs"]] and {r["gates"] for r in table} == {"pass"}
    md = (out / "summary.md").read_text()
    assert all(f"| {j} |" in md for j in SMOKE_JOBS)
    for job in SMOKE_JOBS:  # each job folder is complete, and names itself (not its temporary folder)
        folder = out / "jobs" / job
        design = job.split("__")[0]
        metrics = json.loads((folder / f"{design}.metrics.json").read_text())
        assert metrics["outputs"]["def"] == str(folder / f"{design}.routed.def")
        assert json.loads((folder / "job.json").read_text())["status"] == "done"
    assert not [p for p in (out / "jobs").iterdir() if p.name.startswith(".")]


def test_rerun_resumes_finished_jobs(smoke) -> None:
    out, first = smoke
    assert first.exit_code == 0
    stale = out / "jobs" / ".ispd18_sample__heuristic__rs5.tmp-999999999"  # an interrupted job (its process is gone)
    stale.mkdir()
    (stale / "ispd18_sample.routed.def").write_text("half")
    result = make_runner().invoke(app, ["batch", str(SMOKE), "--out", str(out), "--json"], env={"CI": "true"})
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["counts"]["resumed"] == 6 and all(r["resumed"] for r in doc["jobs"])
    assert not stale.exists()


def test_tightened_threshold_fails_naming_job_and_gate(smoke, tmp_path: Path) -> None:
    # Every sample now ends with 0 violations, so the tightened gate is the via count over a
    # baseline that claims fewer vias for ispd19_sample4 (it ended with 7 violations before and
    # max_violations 6 was the gate tightened here).
    out, first = smoke
    assert first.exit_code == 0
    base = json.loads((REPO / "configs" / "baselines" / "ci-smoke.json").read_text())
    for job in ("ispd19_sample4__heuristic__rs5", "ispd19_sample4__random__rs5"):
        base["jobs"][job]["vias"] = 100
    (tmp_path / "base.json").write_text(json.dumps(base))
    batch = smoke_variant(tmp_path, baseline=f"  baseline: {tmp_path / 'base.json'}")
    result = make_runner().invoke(app, ["batch", str(batch), "--out", str(out)], env={"CI": "true"})
    assert result.exit_code == 1
    failures = sorted(line for line in result.stderr.splitlines() if line.startswith("gate failed:"))
    assert [f.split(": vias ")[0] for f in failures] == [
        "gate failed: job ispd19_sample4__heuristic__rs5",
        "gate failed: job ispd19_sample4__random__rs5",
    ]
    assert all(f.endswith("over the baseline 100 > max_vias_increase_pct 2.0") for f in failures), failures
    cases = junit_cases(out / "junit.xml")
    failure = cases["ispd19_sample4__heuristic__rs5"].find("failure")
    assert failure is not None and failure.get("message").startswith("job ispd19_sample4__heuristic__rs5: vias ")
    assert cases["ispd18_sample__heuristic__rs5"].find("failure") is None


def test_wirelength_gate_against_a_baseline(smoke, tmp_path: Path) -> None:
    out, first = smoke
    assert first.exit_code == 0
    base = json.loads((REPO / "configs" / "baselines" / "ci-smoke.json").read_text())
    base["jobs"]["ispd18_sample2__random__rs5"]["wirelength_um"] = 100.0  # the job now looks longer
    (tmp_path / "base.json").write_text(json.dumps(base))
    batch = smoke_variant(tmp_path, baseline=f"  baseline: {tmp_path / 'base.json'}")
    result = make_runner().invoke(app, ["batch", str(batch), "--out", str(out), "--quiet"], env={"CI": "true"})
    assert result.exit_code == 1
    wl = json.loads((out / "summary.json").read_text())
    wl = {r["id"]: r for r in wl["jobs"]}["ispd18_sample2__random__rs5"]["wirelength_um"]
    assert wl > 101.0
    assert result.stderr == (f"gate failed: job ispd18_sample2__random__rs5: wirelength_um {wl} is +{wl - 100.0:.2f}% over "
                             "the baseline 100.0 > max_wirelength_increase_pct 1.0\n")


def test_failing_job_is_an_error_in_junit(tmp_path: Path, testcase) -> None:
    testcase("ispd18_sample")
    (tmp_path / "bad.py").write_text("def order(region, features):\n    return [0] * len(features)\n")
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [ispd18_sample]\npolicies: [heuristic, bad.py]\nout_dir: {tmp_path / 'out'}\n")
    result = make_runner().invoke(app, ["batch", str(batch), "--quiet"], env={"CI": "true"})
    assert result.exit_code == 1
    assert result.stderr.startswith("job failed: ispd18_sample__bad__default: net-order policy 'bad' returned index 0 twice")
    cases = junit_cases(tmp_path / "out" / "junit.xml")
    assert cases["ispd18_sample__bad__default"].find("error") is not None
    assert cases["ispd18_sample__heuristic__default"].find("error") is None
    assert sorted(p.name for p in (tmp_path / "out" / "jobs").iterdir()) == ["ispd18_sample__heuristic__default"]


@pytest.mark.parametrize("text, line, message", [
    ("testcases: [ispd18_sample]\nsettings:\n  - {name: a, region_sise: 3}\n", 3,
     "settings[0].region_sise: unknown key"),
    ("testcases: [ispd18_nope]\n", 1, "testcases[0]: testcase 'ispd18_nope' not found"),
    ("testcases: [ispd18_sample]\njobs: two\n", 2, "jobs: expected an integer, found 'two'"),
    ("testcases: [ispd18_sample]\npolicies: [gone.py]\n", 2, "policies[0]: policy file not found"),
    ("testcases: [ispd18_sample]\ngates: {max_wirelength_increase_pct: 1}\n", 2,
     "gates: max_wirelength_increase_pct and max_vias_increase_pct need a baseline file"),
])
def test_bad_batch_file_is_one_line_exit_2(tmp_path: Path, testcase, text: str, line: int, message: str) -> None:
    testcase("ispd18_sample")
    p = tmp_path / "b.yaml"
    p.write_text(text)
    result = make_runner().invoke(app, ["batch", str(p), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {p}:{line}: {message}") and result.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


def test_ray_backend_on_a_local_instance(tmp_path: Path, testcase) -> None:
    pytest.importorskip("ray", reason="ray is an optional extra (pip install 'xroute[ray]')")
    testcase("ispd18_sample")
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [ispd18_sample]\npolicies: [heuristic, random]\nout_dir: {tmp_path / 'out'}\n")
    result = make_runner().invoke(app, ["batch", str(batch), "--backend", "ray", "--jobs", "2", "--json"],
                                  env={"CI": "true"})
    assert result.exit_code == 0, result.stdout + result.stderr
    doc = json.loads(result.stdout)
    assert doc["backend"] == "ray" and doc["counts"] == {"jobs": 2, "failed": 0, "errors": 0, "resumed": 0}
    stored = json.loads((REPO / "configs" / "baselines" / "ci-smoke.json").read_text())["jobs"]
    assert [r["wirelength_um"] for r in doc["jobs"]] == [stored["ispd18_sample__heuristic__rs5"]["wirelength_um"]] * 2
