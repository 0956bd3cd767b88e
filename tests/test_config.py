"""YAML configs: the loader's one validation pass (file, line, key), the shipped configs, and
``xroute route --config`` with flags overriding the file."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from conftest import pick
from xroute.cli.app import app
from xroute.config import CostSection, RouterSection, XrouteConfig, load_config, run_settings
from xroute.config_schema import ConfigError

REPO = Path(__file__).resolve().parent.parent
CONFIGS = REPO / "configs"



def write(tmp_path: Path, text: str, name: str = "c.yaml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def problem(path: Path) -> ConfigError:
    with pytest.raises(ConfigError) as info:
        load_config(path)
    return info.value


def test_unknown_key_named_with_file_and_line(tmp_path: Path) -> None:
    p = write(tmp_path, "region:\n  region_size: 3\n  region_sise: 4\n")
    e = problem(p)
    assert (e.path, e.line) == (str(p), 3)
    assert e.message.startswith("region.region_sise: unknown key (did you mean 'region_size'?) "
                                "(known keys here: region_location, region_loop, region_size)")


def test_wrong_type_out_of_range_and_all_problems_collected(tmp_path: Path) -> None:
    p = write(tmp_path, "router:\n  iteration_count: ten\n  thread_count: 0\ncost:\n  via_weight: -1\nbogus: 1\n")
    e = problem(p)
    assert e.problems == (
        (2, "router.iteration_count: expected an integer, found 'ten'"),
        (3, "router.thread_count: must be between 1 and 1024, found 0"),
        (5, "cost.via_weight: must be at least 0.0, found -1.0"),
        (6, "bogus: unknown key (known keys here: cost, output, policy, region, router, testcase)"),
    )
    assert e.line == 2 and "(and 3 more problems in this file)" in e.message


def test_bool_is_not_an_integer_and_int_is_a_float(tmp_path: Path) -> None:
    assert problem(write(tmp_path, "router: {thread_count: true}\n")).problems == (
        (1, "router.thread_count: expected an integer, found True"),)
    assert load_config(write(tmp_path, "cost: {drv_weight: 100}\n", "d.yaml")).cost.drv_weight == 100.0


def test_missing_testcase_and_policy_file(tmp_path: Path) -> None:
    p = write(tmp_path, "testcase:\n  testcase_name: ispd18_nope\npolicy:\n  policy: missing.py\n")
    lines = problem(p).problems
    assert lines[0] == (2, "testcase.testcase_name: testcase 'ispd18_nope' not found on the search path (see `xroute testcases`)")
    assert lines[1] == (4, f"policy.policy: policy file not found: {tmp_path / 'missing.py'}")
    (tmp_path / "adir.py").mkdir()
    e = problem(write(tmp_path, "policy: {policy: adir.py}\n", "e.yaml"))
    assert e.problems == ((1, f"policy.policy: policy file {tmp_path / 'adir.py'} is not a file"),)
    e = problem(write(tmp_path, "policy: {policy: greedy}\n", "f.yaml"))
    assert e.message.startswith("policy.policy: unknown policy 'greedy': use heuristic, random")


def test_policy_file_resolved_relative_to_the_config(tmp_path: Path) -> None:
    (tmp_path / "sub").mkdir()
    (tmp_path / "pol.py").write_text("def order(region, features):\n    return list(range(len(features)))\n")
    cfg = load_config(write(tmp_path / "sub", "policy: {policy: ../pol.py, seed: 7}\n"))
    assert Path(cfg.policy.policy).resolve() == (tmp_path / "pol.py").resolve()
    assert cfg.policy.seed == 7


def test_duplicate_key_bad_yaml_and_unreadable_file(tmp_path: Path) -> None:
    assert problem(write(tmp_path, "router:\n  thread_count: 1\n  thread_count: 2\n")).problems == (
        (3, "router.thread_count: duplicate key"),)
    e = problem(write(tmp_path, "router: [1, 2\n", "b.yaml"))
    assert e.message.startswith("invalid YAML") and e.line == 2
    e = problem(tmp_path / "absent.yaml")
    assert e.message.startswith("cannot read config file") and e.line == 0


def test_schedule_entries_checked_one_by_one(tmp_path: Path) -> None:
    p = write(tmp_path, "router:\n  iteration_schedule:\n    - {region_size: 5, offset: 2}\n"
                        "    - {region_size: 3, offset: 3}\n    - {offset: 1}\n")
    assert problem(p).problems == (
        (4, "router.iteration_schedule[1]: offset 3 must be smaller than region_size 3"),
        (5, "router.iteration_schedule[2].region_size: required key is missing"),
    )
    ok = load_config(write(tmp_path, "router:\n  iteration_schedule: [{region_size: 5, offset: 2}, {region_size: 3}]\n",
                           "ok.yaml"))
    assert run_settings(ok).router.schedule == [(5, 2), (3, 0)]


def test_default_yaml_is_the_defaults_and_documents_every_key() -> None:
    assert load_config(CONFIGS / "default.yaml") == XrouteConfig()
    text = (CONFIGS / "default.yaml").read_text()
    data = yaml.safe_load(text)
    lines = text.splitlines()
    for section, keys in data.items():
        fields = getattr(XrouteConfig(), section).__dataclass_fields__
        assert set(keys) == set(fields), section
        for key in keys:  # the comment block above each key names its default
            at = next(i for i, line in enumerate(lines) if re.match(rf"\s+{key}:", line))
            block = []
            for line in reversed(lines[:at]):
                if not line.strip().startswith("#"):
                    break
                block.append(line)
            assert any("Default:" in line for line in block), key


@pytest.mark.parametrize("name", sorted(p.name for p in CONFIGS.glob("*.yaml")
                                         if p.name not in ("batch.yaml", "ci-smoke.yaml")
                                         and not p.name.startswith("train-")))  # training settings: test_rl_models
def test_shipped_configs_load(name: str, testcase) -> None:
    data = yaml.safe_load((CONFIGS / name).read_text()) or {}
    tc = (data.get("testcase") or {}).get("testcase_name")
    if tc:
        testcase(tc)
    load_config(CONFIGS / name)


def test_paper_parameters_and_cost() -> None:
    cfg = XrouteConfig()
    names = {f for s in (cfg.testcase, cfg.region, cfg.router) for f in s.__dataclass_fields__}
    assert {"testcase_name", "testcase_loop", "region_size", "region_location", "region_loop",
            "iteration_count", "thread_count", "net_loop"} <= names
    assert CostSection().cost(100.0, 10, 2) == 0.5 * 100 + 4 * 10 + 500 * 2
    assert RouterSection().iteration_count == 16


# The contest samples, or their generated stand-ins when the contest data is missing.
SAMPLE, SAMPLE4 = pick("ispd18_sample"), pick("ispd19_sample4")


def test_route_bad_config_is_one_line_exit_2(runner: CliRunner, tmp_path: Path) -> None:
    p = write(tmp_path, "router:\n  iteration_count: 99\n")
    result = runner.invoke(app, ["route", "ispd18_sample", "--config", str(p), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert result.stderr == f"error: {p}:2: router.iteration_count: must be between 1 and 64, found 99\n"
    assert "Traceback" not in result.stdout + result.stderr
    assert not (tmp_path / "o").exists()


def test_route_config_values_and_flag_overrides(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE)
    p = write(tmp_path, f"testcase: {{testcase_name: {SAMPLE}}}\nregion: {{region_size: 3}}\n"
                        "router: {iteration_count: 2}\npolicy: {policy: random, seed: 5}\n"
                        f"output: {{out_dir: {tmp_path / 'out'}}}\n")
    result = runner.invoke(app, ["route", "--config", str(p), "--seed", "9", "--json"])
    assert result.exit_code == 0, result.stdout + result.stderr
    settings = json.loads(result.stdout)["settings"]
    assert settings == {"region_size": 3, "iterations": 2, "threads": 1, "seed": 9, "schedule": None, "repair_rounds": 0,
                        "policy": "random", "schedule_policy": "rule", "sole_landing_penalty": 0}
    assert (tmp_path / "out" / f"{SAMPLE}.metrics.json").is_file()


def test_net_loop_above_one_is_refused_by_route(runner: CliRunner, tmp_path: Path) -> None:
    p = write(tmp_path, "router: {net_loop: 2}\n")
    result = runner.invoke(app, ["route", "ispd18_sample", "--config", str(p), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert result.stderr.startswith("error: net_loop 2: the full-design router orders each region's nets once per visit")


def test_iteration_schedule_from_the_config_reaches_the_router(runner: CliRunner, testcase, tmp_path: Path) -> None:
    testcase(SAMPLE4)
    p = write(tmp_path, "router:\n  iteration_count: 3\n  iteration_schedule:\n    - {region_size: 2, offset: 0}\n"
                        "    - {region_size: 3, offset: 1}\n")
    result = runner.invoke(app, ["route", SAMPLE4, "--config", str(p), "--json", "--out", str(tmp_path / "o")])
    assert result.exit_code == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["settings"]["schedule"] == [[2, 0], [3, 1]]
    steps = [(it["region_size"], it["offset"]) for it in data["iterations"]]
    assert steps == [(2, 0), (3, 1), (2, 0)][: len(steps)]
    # a --schedule flag overrides the config's schedule
    result = runner.invoke(app, ["route", SAMPLE4, "--config", str(p), "--json", "--schedule", "4:1",
                                 "--out", str(tmp_path / "o")])
    assert json.loads(result.stdout)["settings"]["schedule"] == [[4, 1]]
