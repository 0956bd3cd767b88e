"""``xroute report``: a self-contained HTML page, checked in headless Chromium (screenshot and DOM)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import pick
from png import distinct_colours
from xroute.cli.app import app

CHROMIUM_NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")


def chromium() -> str:
    """The headless browser; skips when absent, except in CI (CI=true), where .ci/run installs it."""
    for name in CHROMIUM_NAMES:
        path = shutil.which(name)
        if path:
            return path
    if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
        pytest.fail("chromium is missing in CI (.ci/run installs the Debian package 'chromium')")
    pytest.skip("chromium not installed (apt-get install chromium)")



SAMPLE4 = pick("ispd19_sample4")  # or its generated stand-in without the contest data


@pytest.fixture
def two_runs(runner: CliRunner, testcase, tmp_path: Path) -> Path:
    testcase(SAMPLE4)
    # Region size 5: each run has a second iteration, so each chart draws a line (at the default 10
    # ispd19_sample4 ends its first pass with 0 violations and the flow stops there).
    for policy in ("heuristic", "random"):
        result = runner.invoke(app, ["route", SAMPLE4, "--iterations", "3", "--region-size", "5",
                                     "--policy", policy, "--quiet", "--out", str(tmp_path / "runs" / policy)])
        assert result.exit_code == 0, result.stderr
    return tmp_path / "runs"


def test_report_html_is_self_contained(runner: CliRunner, two_runs: Path, tmp_path: Path) -> None:
    out = tmp_path / "report.html"
    result = runner.invoke(app, ["report", str(two_runs), "--out", str(out)])
    assert result.exit_code == 0, result.stderr
    assert result.stdout == f"report: 2 run(s) -> {out}\n"
    html = out.read_text()
    assert html.count('<tr class="run">') == 2
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", html)  # nothing fetched
    assert "<link" not in html and "<script src" not in html and "@import" not in html
    assert html.count("<svg") == 3  # WL, vias, DRVs for the one design
    assert f"{SAMPLE4}: trends over iterations" in html
    # the DRV columns by type that are non-zero in a run, and the paper's cost (ispd19_sample4's runs
    # end with 0 violations since the PRL-aware footprint: no column by type; they had CutShort before)
    assert "<th>cost</th>" in html and "<th>CutShort</th>" not in html


def test_report_renders_in_headless_chromium(runner: CliRunner, two_runs: Path, tmp_path: Path) -> None:
    browser = chromium()
    out = tmp_path / "report.html"
    assert runner.invoke(app, ["report", str(two_runs), "--out", str(out)]).exit_code == 0
    flags = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1280,1000"]
    shot = tmp_path / "shot.png"
    subprocess.run([browser, *flags, f"--screenshot={shot}", out.as_uri()], check=True, capture_output=True, timeout=120)
    assert distinct_colours(shot) > 20  # text, table and coloured lines: not a blank page
    dom = subprocess.run([browser, *flags, "--dump-dom", out.as_uri()], check=True, capture_output=True, text=True,
                         timeout=120).stdout
    rows = re.findall(r'<tr class="run">(.*?)</tr>', dom, flags=re.S)
    assert len(rows) == 2
    assert sorted(re.findall(r"<td>(heuristic|random)</td>", dom)) == ["heuristic"] * 2 + ["random"] * 2  # run, policy
    assert dom.count("<polyline") == 6  # 3 charts x 2 runs


def test_report_of_a_folder_without_runs_is_one_line(runner: CliRunner, tmp_path: Path) -> None:
    result = runner.invoke(app, ["report", str(tmp_path), "--out", str(tmp_path / "r.html")])
    assert result.exit_code == 2
    assert result.stderr == (f"error: {tmp_path}: no *.metrics.json (route, evaluate or batch output) or "
                             "metrics.jsonl (xroute train) found\n")
    assert not (tmp_path / "r.html").exists()


def _training_log(path: Path, episodes: int) -> None:
    """A metrics.jsonl as xroute train writes it: reward rising, cost and violations falling."""
    import json

    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w") as f:
        for e in range(1, episodes + 1):
            f.write(json.dumps({"episode": e, "steps": 4, "total_steps": 4 * e, "reward": -200.0 + 2 * e,
                                "cost": 900.0 - 5 * e, "wirelength_dbu": 4000, "vias": 12, "drvs": 3 if e <= 20 else 1,
                                "seconds": 0.5, "policy_loss": 0.1}) + "\n")


def test_report_training_dashboard(runner: CliRunner, tmp_path: Path) -> None:
    _training_log(tmp_path / "runs" / "train-ppo" / "metrics.jsonl", 40)
    out = tmp_path / "train.html"
    result = runner.invoke(app, ["report", str(tmp_path / "runs"), "--out", str(out)])
    assert result.exit_code == 0, result.stderr
    assert result.stdout == f"report: 0 run(s), 1 training run(s) -> {out}\n"
    html = out.read_text()
    assert html.count('<tr class="training">') == 1 and '<tr class="run">' not in html
    assert html.count("<svg") == 3  # reward, cost and violations by episode
    for title in ("Reward by episode", "Cost by episode", "Violations by episode"):
        assert title in html
    assert html.count('class="legend">mean of 2 episodes<') == 3  # the moving mean beside each raw series
    row = re.search(r'<tr class="training">(.*?)</tr>', html).group(1)
    cells = re.findall(r"<td[^>]*>([^<]*)</td>", row)
    # run, episodes, steps, time; reward / cost / violations over the first and the last 4 episodes
    assert cells[:4] == ["train-ppo", "40", "160", "20.0"]
    assert [float(c.replace(",", "")) for c in cells[4:]] == [-195.0, -123.0, 887.5, 707.5, 3.0, 1.0]
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", html)  # nothing fetched


def test_report_mixes_routing_and_training_runs(runner: CliRunner, two_runs: Path, tmp_path: Path) -> None:
    _training_log(two_runs / "train" / "metrics.jsonl", 5)
    out = tmp_path / "both.html"
    result = runner.invoke(app, ["report", str(two_runs), "--out", str(out)])
    assert result.exit_code == 0, result.stderr
    html = out.read_text()
    assert html.count('<tr class="run">') == 2 and html.count('<tr class="training">') == 1
    assert html.count("<svg") == 6  # 3 routing trends + 3 training charts


def test_report_bad_training_log_is_one_line(runner: CliRunner, tmp_path: Path) -> None:
    log = tmp_path / "t" / "metrics.jsonl"
    _training_log(log, 3)
    with open(log, "a") as f:
        f.write("{not json\n")
    result = runner.invoke(app, ["report", str(tmp_path / "t"), "--out", str(tmp_path / "r.html")])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {log}:4: not a training log line written by xroute train")
    assert result.stderr.count("\n") == 1
