"""Output modes: Rich progress on a terminal, plain lines when piped or CI=true, --quiet and --json."""

from __future__ import annotations

import io
import re

import pytest
from rich.console import Console

from xroute.cli.progress import ProgressDisplay, output_mode
from xroute.router import IterationReport, RouteProgress


def console(terminal: bool) -> Console:
    return Console(file=io.StringIO(), force_terminal=terminal, width=120)


@pytest.mark.parametrize("terminal, ci, flags, expected", [
    (True, "", {}, "rich"),
    (True, "true", {}, "lines"),
    (True, "1", {}, "lines"),
    (False, "", {}, "lines"),
    (True, "", {"quiet": True}, "quiet"),
    (True, "true", {"as_json": True, "quiet": True}, "json"),
    (False, "", {"configured": "rich"}, "rich"),
    (True, "false", {}, "rich"),
])
def test_output_mode(monkeypatch, terminal: bool, ci: str, flags: dict, expected: str) -> None:
    monkeypatch.setenv("CI", ci)
    assert output_mode(console(terminal), **flags) == expected


def event(done: bool) -> RouteProgress:
    report = IterationReport(iteration=0, region_size=5, offset=0, regions=4, net_routes=9, unreached=0, wirelength_dbu=2000,
                             wirelength_um=1.0, vias=3, violations_by_type={"Short": 2}, violations=2,
                             seconds=0.5 if done else 0.0)
    return RouteProgress(report, 4 if done else 2, 4, done, 10)


def test_rich_progress_shows_iteration_regions_and_violations() -> None:
    c = console(True)
    with ProgressDisplay(c, "rich", 10, label="job") as display:
        display(event(False))
        display(event(True))
    text = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", "", c.file.getvalue())  # without colours and cursor moves
    assert "job: iteration 0: region size 5, 4 regions, 9 net routes, WL 1.0 um, 3 vias, 2 violations (Short 2), 0.50 s" in text
    assert "regions 4/4" in text and "violations 2" in text


def test_lines_and_off(capsys) -> None:
    with ProgressDisplay(console(False), "lines", 10) as display:
        display(event(False))  # a batch of regions: no line
        display(event(True))
    assert capsys.readouterr().out == "iteration 0: region size 5, 4 regions, 9 net routes, WL 1.0 um, 3 vias, 2 violations (Short 2), 0.50 s\n"
    with ProgressDisplay(console(False), "quiet", 10) as display:
        display(event(True))
    assert capsys.readouterr().out == ""


def test_progress_counts_the_regions_each_iteration_routes() -> None:
    """Within an iteration every event has the same total, the regions with work (known before the
    first is routed), the count rises to it and the iteration's last event reaches it; at region size 1
    the later iterations route far fewer regions than the partition has (the bar once never filled)."""
    from conftest import pick, require_testcase
    from xroute.design import load_design
    from xroute.router import route_design

    name = pick("ispd19_sample4")
    require_testcase(name)
    events: list[RouteProgress] = []
    result = route_design(load_design(name), region_size=1, progress=events.append)
    for it in result.iterations:
        mine = [e for e in events if e.report.iteration == it.iteration]
        assert {e.regions_total for e in mine} == {it.regions}
        assert [e.regions_done for e in mine] == sorted(e.regions_done for e in mine)
        assert mine[-1].iteration_done and mine[-1].regions_done == it.regions
    assert len(result.iterations) >= 2 and result.iterations[1].regions < result.iterations[0].regions


def test_lines_say_one_violation_and_two_vias() -> None:
    from xroute.cli.progress import iteration_line

    report = IterationReport(iteration=1, region_size=5, offset=0, regions=1, net_routes=1, unreached=0,
                             wirelength_dbu=2000, wirelength_um=1.0, vias=2, violations_by_type={"Short": 1},
                             violations=1, seconds=0.5)
    line = iteration_line(RouteProgress(report, 1, 1, True, 10))
    assert "1 region, 1 net route," in line and "2 vias, 1 violation (" in line
