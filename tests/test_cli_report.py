"""``xroute report``: a self-contained HTML page, checked in headless Chromium (screenshot and DOM)."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import pick
from png import colour_pixels, distinct_colours
from xroute.cli.app import app
from xroute.cli.svg_chart import line_chart

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
    typed = sum(any(any(it["violations_by_type"].values()) for it in json.loads(p.read_text())["iterations"])
                for p in two_runs.rglob("*.metrics.json"))  # runs with a violations-by-type chart
    assert html.count("<svg") == 4 + typed  # WL, vias, DRVs, time for the one design; by type per run
    assert f"{SAMPLE4}: trends over iterations" in html
    # the DRV columns by type that are non-zero in a run, and the paper's cost (ispd19_sample4's runs
    # end with 0 violations since the PRL-aware footprint: no column by type; they had CutShort before)
    assert "<th>paper cost</th>" in html and "<th>CutShort</th>" not in html
    assert "paper cost = 0.5·WL(µm) + 4·vias + 500·violations" in html and "contest score = 0.5·WL + 2·vias" in html
    assert re.search(r"made \d{4}-\d\d-\d\d \d\d:\d\d UTC by xroute \S+", html)
    from xroute import __version__

    written = re.findall(r"<td>\d{4}-\d\d-\d\d \d\d:\d\d UTC; xroute ([^<]+)</td>", html)
    assert written == [__version__] * 2  # each run: when and by which xroute it was written
    # relative links to each run's files, which resolve from the report's folder
    links = re.findall(r'<a href="([^"]+)">(DEF|metrics|DRC)</a>', html)
    assert len(links) == 6 and all(not h.startswith("/") and (out.parent / h).is_file() for h, _ in links)
    assert "violations by iteration (exact counts)" in html and html.count('<tr class="drv">') == 2


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
    assert dom.count("<polyline") >= 8  # WL, vias, DRVs, time x 2 runs (and the by-type charts)


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
    typed = sum(any(any(it["violations_by_type"].values()) for it in json.loads(p.read_text())["iterations"])
                for p in two_runs.rglob("*.metrics.json"))
    assert html.count("<svg") == 4 + typed + 3  # routing trends, by type, and 3 training charts


def test_report_bad_training_log_is_one_line(runner: CliRunner, tmp_path: Path) -> None:
    log = tmp_path / "t" / "metrics.jsonl"
    _training_log(log, 3)
    with open(log, "a") as f:
        f.write("{not json\n")
    result = runner.invoke(app, ["report", str(tmp_path / "t"), "--out", str(tmp_path / "r.html")])
    assert result.exit_code == 2
    assert result.stderr.startswith(f"error: {log}:4: not a training log line written by xroute train")
    assert result.stderr.count("\n") == 1


MARKED = "standin_marked"  # a generated design whose violations go 15 -> 21 -> 0 at region size 2
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1400,2400"]


@pytest.fixture
def twin_runs(runner: CliRunner, testcase, tmp_path: Path) -> Path:
    """Two runs of the same settings (same seed): every series of the one equals the other's."""
    testcase(MARKED)
    for name in ("first", "second"):
        result = runner.invoke(app, ["route", MARKED, "--iterations", "4", "--region-size", "2", "--quiet",
                                     "--out", str(tmp_path / "twins" / name)])
        assert result.exit_code == 0, result.stderr
    return tmp_path / "twins"


def _chart(dom: str, title: str) -> str:
    found = re.search(rf'<svg[^>]*aria-label="{re.escape(title)}".*?</svg>', dom, flags=re.S)
    assert found, title
    return found.group(0)


def test_report_identical_runs_both_visible_in_chromium(runner: CliRunner, twin_runs: Path, tmp_path: Path) -> None:
    browser = chromium()
    out = tmp_path / "twins.html"
    assert runner.invoke(app, ["report", str(twin_runs), "--out", str(out)]).exit_code == 0
    dom = subprocess.run([browser, *FLAGS, "--dump-dom", out.as_uri()], check=True, capture_output=True, text=True,
                         timeout=120).stdout
    drvs = _chart(dom, "Violations by iteration")
    first = [json.loads(p.read_text())["iterations"] for p in sorted(twin_runs.rglob("*.metrics.json"))]
    counts = [it["violations"] for it in first[0]]
    assert counts == [it["violations"] for it in first[1]] and counts[-1] == 0 and max(counts) >= 10
    # the log axis: the ticks 0, 1 and 10 at three different heights
    ticks = {label: float(y) for y, label in re.findall(r'y="([\d.]+)" text-anchor="end" class="tick">(\d+)<', drvs)}
    assert {"0", "1", "10"} <= ticks.keys() and ticks["0"] > ticks["1"] > ticks["10"]
    # both series drawn, the second with its marks shifted and named identical in the legend
    groups = re.findall(r'<g class="series" data-series="(\d)">(.*?)</g>', drvs, flags=re.S)
    assert [g for g, _ in groups] == ["0", "1"]
    marks = [re.findall(r"<title>([^<]*)</title>", body) for _, body in groups]
    assert len(marks[0]) == len(marks[1]) == len(counts)
    assert "identical to first (heuristic): marks shifted 5 px" in drvs
    shot = tmp_path / "twins.png"
    subprocess.run([browser, *FLAGS, f"--screenshot={shot}", out.as_uri()], check=True, capture_output=True, timeout=120)
    assert distinct_colours(shot) > 20
    # both colours are on the page in the browser: the first series' blue and the second's red
    assert colour_pixels(shot, (0x1F, 0x77, 0xB4)) > 50 and colour_pixels(shot, (0xD6, 0x27, 0x28)) > 50


def test_single_iteration_runs_get_a_table_not_a_trend(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(MARKED)
    result = runner.invoke(app, ["route", MARKED, "--iterations", "1", "--quiet", "--out", str(tmp_path / "one" / "a")])
    assert result.exit_code == 0, result.stderr
    out = tmp_path / "one.html"
    assert runner.invoke(app, ["report", str(tmp_path / "one"), "--out", str(out)]).exit_code == 0
    html = out.read_text()
    assert f"{MARKED}: one iteration" in html and "trends over iterations" not in html
    assert "<svg" not in html and html.count('<tr class="single">') == 1


def test_line_chart_axes() -> None:
    # symlog: 10, 1 and 0 are each drawn at their own height, with those tick labels
    svg = line_chart("drvs", [("a", [10.0, 1.0, 0.0])], "count", scale="symlog")
    ys = [float(v) for v in re.findall(r'<circle cx="[\d.]+" cy="([\d.]+)"', svg)][:3]  # the legend mark comes last
    assert ys[0] < ys[1] < ys[2]
    assert all(f'class="tick">{t}<' in svg for t in ("0", "1", "10"))
    # a 0.4% change on a linear axis of at least 10% of the top: it is not drawn as the whole height
    svg = line_chart("wl", [("a", [1000.0, 1004.0])], "µm", min_span=100.4, unit="µm")
    ticks = [float(t.replace(",", "")) for t in re.findall(r'text-anchor="end" class="tick">([\d,.]+)<', svg)]
    assert max(ticks) - min(ticks) >= 100
    assert "values 1,000 to 1,004 µm (spread 0.398% of the largest)" in svg
    # different dash patterns and marker shapes, not colour alone
    svg = line_chart("x", [("a", [1.0, 2.0]), ("b", [2.0, 1.0])], "n")
    assert 'stroke-dasharray="7 3"' in svg and "<rect x=" in svg and "<circle" in svg


def test_report_says_when_it_replaces_a_file(runner: CliRunner, two_runs: Path, tmp_path: Path) -> None:
    out = tmp_path / "r.html"
    first = runner.invoke(app, ["report", str(two_runs), "--out", str(out)])
    second = runner.invoke(app, ["report", str(two_runs), "--out", str(out)])
    assert first.exit_code == second.exit_code == 0
    assert "replaced" not in first.output and "(replaced the file that was there)" in second.output
