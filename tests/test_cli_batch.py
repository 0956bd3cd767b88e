"""``xroute batch``: the CI smoke batch on the samples, gates, resume, errors, JUnit and summaries."""

from __future__ import annotations

import csv
import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from conftest import available, make_runner, require_testcase
from xroute.cli.app import app

REPO = Path(__file__).resolve().parent.parent
SMOKE = REPO / "configs" / "ci-smoke.yaml"
BASELINE = REPO / "configs" / "baselines" / "ci-smoke.json"
# The contest samples of the CI smoke batch, or, each one missing, its generated stand-in: then the
# batch runs a copy of ci-smoke.yaml naming the stand-ins, gated against a baseline written by a
# first run of the same jobs (the stored baseline holds the contest samples' figures).
S1, S2, S4 = available("ispd18_sample", "ispd18_sample2", "ispd19_sample4")
CONTEST = (S1, S2, S4) == ("ispd18_sample", "ispd18_sample2", "ispd19_sample4")
SMOKE_JOBS = [f"{t}__{p}__defaults" for t in (S1, S2, S4) for p in ("heuristic", "random")]


def smoke_lines(baseline: Path | None) -> list[str]:
    """ci-smoke.yaml's lines naming this run's testcases and ``baseline`` (absolute); without one,
    the two gates that need it are dropped."""
    lines = []
    for line in SMOKE.read_text().splitlines():
        key = line.strip().split(":")[0]
        if key == "testcases":
            line = f"testcases: [{S1}, {S2}, {S4}]"
        if key == "baseline":
            line = f"  baseline: {baseline}"
        if baseline is None and key in ("baseline", "max_wirelength_increase_pct", "max_vias_increase_pct"):
            continue
        lines.append(line)
    return lines


@pytest.fixture(scope="module")
def smoke_files(tmp_path_factory) -> tuple[Path, Path]:
    """(batch file, its baseline): configs/ci-smoke.yaml and its stored baseline on the contest samples;
    otherwise a copy naming the stand-ins and a baseline written by a first run of that copy."""
    if CONTEST:
        return SMOKE, BASELINE
    folder = tmp_path_factory.mktemp("standin-smoke")
    for name in (S1, S2, S4):
        require_testcase(name)
    first = folder / "first.yaml"
    first.write_text("\n".join(smoke_lines(None)) + "\n")
    baseline = folder / "baseline.json"
    result = make_runner().invoke(app, ["batch", str(first), "--out", str(folder / "first"), "--quiet",
                                        "--write-baseline", str(baseline)], env={"CI": "true"})
    assert result.exit_code == 0, result.stdout + result.stderr
    batch = folder / "ci-smoke.yaml"
    batch.write_text("\n".join(smoke_lines(baseline)) + "\n")
    return batch, baseline


def smoke_variant(tmp_path: Path, smoke_files: tuple[Path, Path], **replace: str) -> Path:
    """The smoke batch file with some lines replaced (key -> new line) and its baseline path made absolute."""
    batch, baseline = smoke_files
    lines = []
    for line in batch.read_text().splitlines():
        key = line.strip().split(":")[0]
        if key == "baseline":
            line = f"  baseline: {baseline}"
        if key in replace:
            line = replace.pop(key)
        lines.append(line)
    lines += list(replace.values())
    p = tmp_path / "batch.yaml"
    p.write_text("\n".join(lines) + "\n")
    return p


@pytest.fixture(scope="module")
def smoke(tmp_path_factory, smoke_files) -> tuple[Path, object]:
    """The CI-style run, once: CI=true xroute batch configs/ci-smoke.yaml (2 parallel jobs)."""
    for name in (S1, S2, S4):
        require_testcase(name)
    out = tmp_path_factory.mktemp("smoke")
    result = make_runner().invoke(app, ["batch", str(smoke_files[0]), "--out", str(out), "--jobs", "2"],
                                  env={"CI": "true"})
    return out, result


def junit_cases(path: Path) -> dict[str, ET.Element]:
    root = ET.parse(path).getroot()
    return {c.get("name"): c for c in root.iter("testcase")}


def test_ci_smoke_batch_passes_and_writes_junit_and_summaries(smoke, smoke_files) -> None:
    out, result = smoke
    assert result.exit_code == 0, result.stdout + result.stderr
    assert result.stderr == ""
    # CI=true: plain log lines (no Rich progress), one per job start, iteration and end
    assert f"{S1}__heuristic__defaults: started" in result.stdout
    assert f"{S4}__random__defaults: iteration 0:" in result.stdout
    assert "\r" not in result.stdout and "\x1b[" not in result.stdout
    cases = junit_cases(out / "junit.xml")
    assert sorted(cases) == sorted(SMOKE_JOBS)
    assert not any(c.find("failure") is not None or c.find("error") is not None for c in cases.values())
    suite = ET.parse(out / "junit.xml").getroot().find("testsuite")
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors")) == ("6", "0", "0")
    doc = json.loads((out / "summary.json").read_text())
    assert doc["passed"] is True and doc["counts"] == {"jobs": 6, "failed": 0, "errors": 0, "resumed": 0}
    rows = {r["id"]: r for r in doc["jobs"]}
    stored = json.loads(smoke_files[1].read_text())["jobs"]
    assert sorted(stored) == sorted(SMOKE_JOBS)
    for job, figures in stored.items():  # the stored baseline is what this router writes today
        assert {k: rows[job][k] for k in figures} == figures, job
    if CONTEST:
        assert rows["ispd19_sample4__heuristic__defaults"]["violations"] == 0  # was 7 before the PRL-aware footprint
    with open(out / "summary.csv") as f:
        table = list(csv.DictReader(f))
    assert [r["id"] for r in table] == [r["id"] for r in doc["jobs"]] and {r["gates"] for r in table} == {"pass"}
    md = (out / "summary.md").read_text()
    assert all(f"| {j} |" in md for j in SMOKE_JOBS)
    assert "| route (s) | paper cost | gates |" in md and "paper cost: the XRoute paper's weighted sum" in md
    for job in SMOKE_JOBS:  # each job folder is complete, and names itself (not its temporary folder)
        folder = out / "jobs" / job
        design = job.split("__")[0]
        metrics = json.loads((folder / f"{design}.metrics.json").read_text())
        assert metrics["outputs"]["def"] == str(folder / f"{design}.routed.def")
        assert json.loads((folder / "job.json").read_text())["status"] == "done"
    assert not [p for p in (out / "jobs").iterdir() if p.name.startswith(".")]


def test_rerun_resumes_finished_jobs(smoke, smoke_files) -> None:
    out, first = smoke
    assert first.exit_code == 0
    stale = out / "jobs" / f".{S1}__heuristic__defaults.tmp-999999999"  # an interrupted job (its process is gone)
    stale.mkdir()
    (stale / f"{S1}.routed.def").write_text("half")
    result = make_runner().invoke(app, ["batch", str(smoke_files[0]), "--out", str(out), "--json"],
                                  env={"CI": "true"})
    assert result.exit_code == 0, result.stderr
    doc = json.loads(result.stdout)
    assert doc["counts"]["resumed"] == 6 and all(r["resumed"] for r in doc["jobs"])
    assert not stale.exists()


def test_tightened_threshold_fails_naming_job_and_gate(smoke, smoke_files, tmp_path: Path) -> None:
    # Every sample ends with 0 violations (ispd19_sample4 had 7 before the PRL-aware footprint, and
    # max_violations 6 was the gate tightened here), so the tightened gate is the via count of S4's
    # jobs over a baseline that claims 10% fewer vias.
    out, first = smoke
    assert first.exit_code == 0
    base = json.loads(smoke_files[1].read_text())
    expected = []
    for policy in ("heuristic", "random"):
        job = f"{S4}__{policy}__defaults"
        vias = base["jobs"][job]["vias"]
        base["jobs"][job]["vias"] = tight = vias * 9 // 10
        pct = 100.0 * (vias - tight) / tight
        expected.append(f"job {job}: vias {vias:,} is {pct:+.2f}% over the baseline {tight:,} > max_vias_increase_pct 2.0")
    (tmp_path / "base.json").write_text(json.dumps(base))
    batch = smoke_variant(tmp_path, smoke_files, baseline=f"  baseline: {tmp_path / 'base.json'}")
    result = make_runner().invoke(app, ["batch", str(batch), "--out", str(out)], env={"CI": "true"})
    assert result.exit_code == 1
    failures = sorted(line for line in result.stderr.splitlines() if line.startswith("gate failed:"))
    assert failures == [f"gate failed: {e}" for e in expected]
    cases = junit_cases(out / "junit.xml")
    failure = cases[f"{S4}__heuristic__defaults"].find("failure")
    assert failure is not None and failure.get("message") == expected[0]
    assert cases[f"{S1}__heuristic__defaults"].find("failure") is None


def test_wirelength_gate_against_a_baseline(smoke, smoke_files, tmp_path: Path) -> None:
    out, first = smoke
    assert first.exit_code == 0
    job = f"{S2}__random__defaults"
    base = json.loads(smoke_files[1].read_text())
    # The job now looks longer: 100 um for ispd18_sample2 (about 104 um), half its length for the stand-in.
    low = 100.0 if CONTEST else round(base["jobs"][job]["wirelength_um"] / 2, 2)
    base["jobs"][job]["wirelength_um"] = low
    (tmp_path / "base.json").write_text(json.dumps(base))
    batch = smoke_variant(tmp_path, smoke_files, baseline=f"  baseline: {tmp_path / 'base.json'}")
    result = make_runner().invoke(app, ["batch", str(batch), "--out", str(out), "--quiet"], env={"CI": "true"})
    assert result.exit_code == 1
    wl = json.loads((out / "summary.json").read_text())
    wl = {r["id"]: r for r in wl["jobs"]}[job]["wirelength_um"]
    assert wl > 1.01 * low
    if CONTEST:
        assert result.stderr == (f"gate failed: job ispd18_sample2__random__defaults: wirelength_um {wl} is +{wl - 100.0:.2f}% "
                                 "over the baseline 100.0 > max_wirelength_increase_pct 1.0\n")
    else:
        assert result.stderr == (f"gate failed: job {job}: wirelength_um {wl:,} is {100.0 * (wl - low) / low:+.2f}% over "
                                 f"the baseline {low:,} > max_wirelength_increase_pct 1.0\n")


def test_failing_job_is_an_error_in_junit(tmp_path: Path, testcase) -> None:
    testcase(S1)
    (tmp_path / "bad.py").write_text("def order(region, features):\n    return [0] * len(features)\n")
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [{S1}]\npolicies: [heuristic, bad.py]\nout_dir: {tmp_path / 'out'}\n")
    result = make_runner().invoke(app, ["batch", str(batch), "--quiet"], env={"CI": "true"})
    assert result.exit_code == 1
    assert result.stderr.startswith(f"job failed: {S1}__bad__default: {tmp_path / 'bad.py'}:1: net-order policy 'bad' "
                                    "returned index 0 twice")
    cases = junit_cases(tmp_path / "out" / "junit.xml")
    assert cases[f"{S1}__bad__default"].find("error") is not None
    assert cases[f"{S1}__heuristic__default"].find("error") is None
    assert sorted(p.name for p in (tmp_path / "out" / "jobs").iterdir()) == [f"{S1}__heuristic__default"]


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
    testcase(S1)
    p = tmp_path / "b.yaml"
    p.write_text(text.replace("ispd18_sample", S1))  # the sample's stand-in without the contest data
    result = make_runner().invoke(app, ["batch", str(p), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {p}:{line}: {message}") and result.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_ray_backend_on_a_local_instance(tmp_path: Path, testcase, smoke_files) -> None:
    pytest.importorskip("ray", reason="ray is an optional extra (pip install 'xroute[ray]')")
    testcase(S1)
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [{S1}]\npolicies: [heuristic, random]\nout_dir: {tmp_path / 'out'}\n")
    result = make_runner().invoke(app, ["batch", str(batch), "--backend", "ray", "--jobs", "2", "--json"],
                                  env={"CI": "true"})
    assert result.exit_code == 0, result.stdout + result.stderr
    doc = json.loads(result.stdout)
    assert doc["backend"] == "ray" and doc["counts"] == {"jobs": 2, "failed": 0, "errors": 0, "resumed": 0}
    stored = json.loads(smoke_files[1].read_text())["jobs"]
    # The figures of the local backend's run of the same policies (the stored baseline).
    assert [r["wirelength_um"] for r in doc["jobs"]] == [stored[f"{S1}__{p}__defaults"]["wirelength_um"]
                                                         for p in ("heuristic", "random")]
