"""Hostile settings: numbers that are not numbers, and JSON files nested or typed to break the reader.

Every numeric setting is finite and in range (NaN passes every bound check, so it is refused on
its own), a YAML 1.1 base-60 number such as ``1:30`` is not silently read as 90, and a metrics or
baseline JSON nested 200,000 deep or holding the wrong types is one error line naming the file.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from xroute.cli.app import app
from xroute.config import load_config
from xroute.config_schema import ConfigError
from xroute.errors import InputError, RouteArgumentError, safe_text
from xroute.router import check_policy_timeout
from conftest import one_error

DEEP = "[" * 200_000 + "]" * 200_000


def config_problem(tmp_path: Path, text: str) -> ConfigError:
    p = tmp_path / "c.yaml"
    p.write_text(text)
    with pytest.raises(ConfigError) as info:
        load_config(p)
    return info.value


# ----------------------------------------------------------------------------- numbers in YAML
@pytest.mark.parametrize("text, message", [
    ("policy:\n  call_timeout: .nan\n", "policy.call_timeout: must be a finite number, found nan"),
    ("policy:\n  call_timeout: .inf\n", "policy.call_timeout: must be a finite number, found inf"),
    ("cost:\n  via_weight: .nan\n", "cost.via_weight: must be a finite number, found nan"),
    ("cost:\n  drv_weight: .inf\n", "cost.drv_weight: must be a finite number, found inf"),
    ("cost:\n  wirelength_weight: -.inf\n", "cost.wirelength_weight: must be a finite number, found -inf"),
])
def test_nan_and_infinity_are_refused(tmp_path: Path, text: str, message: str) -> None:
    e = config_problem(tmp_path, text)
    assert e.line == 2 and e.message == message


@pytest.mark.parametrize("value", ["1:30", "!!int 1:30", "-2:05:00"])
def test_a_base60_seed_is_not_read_as_a_number(tmp_path: Path, value: str) -> None:
    e = config_problem(tmp_path, f"policy:\n  seed: {value}\n")
    assert e.line == 2 and "policy.seed: expected an integer" in e.message and "base-60" in e.message


def test_plain_numbers_still_read(tmp_path: Path) -> None:
    p = tmp_path / "c.yaml"
    p.write_text("policy:\n  seed: 0x10\n  call_timeout: 1_0.5\ncost:\n  via_weight: 3\n")
    cfg = load_config(p)
    assert (cfg.policy.seed, cfg.policy.call_timeout, cfg.cost.via_weight) == (16, 10.5, 3.0)


def test_the_route_command_names_the_line(runner: CliRunner, tmp_path: Path) -> None:
    p = tmp_path / "c.yaml"
    p.write_text("policy:\n  call_timeout: .nan\n")
    one_error(runner.invoke(app, ["route", "--config", str(p), "--out", str(tmp_path / "o")]), f"{p}:2:", "finite")
    assert not (tmp_path / "o").exists()


def test_library_settings_refuse_nan_time_limits() -> None:
    from xroute import load_design, route_design

    design = load_design("demo")
    for bad in (math.nan, math.inf, -1.0, True):
        with pytest.raises(RouteArgumentError, match="policy_timeout"):
            route_design(design, policy_timeout=bad)
    assert design.engine.metrics()["nets_routed"] == 0  # refused before routing
    assert check_policy_timeout(0) == 0


def test_training_config_refuses_nan(tmp_path: Path) -> None:
    from xroute.policies.rl.train_config import load_config as load_train_config

    p = tmp_path / "t.yaml"
    p.write_text("lr_actor: .nan\n")
    with pytest.raises(InputError, match="finite"):
        load_train_config("ppo", p)


# ----------------------------------------------------------------------------- JSON files
def routed_demo(runner: CliRunner, out: Path) -> Path:
    result = runner.invoke(app, ["route", "--quiet", "--out", str(out)])
    assert result.exit_code == 0, result.output
    return out / "demo.metrics.json"


def test_report_on_deep_json_is_one_line(runner: CliRunner, tmp_path: Path) -> None:
    bad = tmp_path / "deep.metrics.json"
    bad.write_text(DEEP)
    one_error(runner.invoke(app, ["report", str(bad), "--out", str(tmp_path / "r.html")]), str(bad), "nested too deeply")
    assert not (tmp_path / "r.html").exists()


@pytest.mark.parametrize("change", [
    lambda m: {**m, "final": 3},
    lambda m: {**m, "iterations": 4},
    lambda m: {**m, "iterations": [{"violations": "many"}]},
    lambda m: {k: v for k, v in m.items() if k != "final"},
    lambda m: {**m, "final": {**m["final"], "violations_by_type": [1, 2]}},
    lambda m: {**m, "final": {**m["final"], "wirelength_um": None}},
    lambda m: [m],
])
def test_report_on_wrong_types_is_one_line(runner: CliRunner, tmp_path: Path, change) -> None:
    metrics = routed_demo(runner, tmp_path / "run")
    metrics.write_text(json.dumps(change(json.loads(metrics.read_text()))))
    one_error(runner.invoke(app, ["report", str(tmp_path / "run"), "--out", str(tmp_path / "r.html")]),
              str(metrics), "not a metrics JSON written by xroute")
    assert not (tmp_path / "r.html").exists()


def test_batch_on_a_deep_baseline_is_one_line(runner: CliRunner, tmp_path: Path) -> None:
    base = tmp_path / "base.json"
    base.write_text(DEEP)
    batch = tmp_path / "b.yaml"
    batch.write_text(f"testcases: [demo]\npolicies: [heuristic]\ngates:\n  baseline: {base}\n")
    one_error(runner.invoke(app, ["batch", str(batch), "--out", str(tmp_path / "o")]), str(base), "nested too deeply")


def test_safe_text_survives_a_failing_str() -> None:
    class Nasty(Exception):
        def __str__(self) -> str:
            raise RuntimeError("no")

    assert safe_text(Nasty()) == "<Nasty: unprintable>"
    assert safe_text(ValueError("a\nb")) == "a b"


def test_a_value_with_a_line_break_stays_on_the_errors_one_line(tmp_path: Path) -> None:
    """Found by fuzz/fuzz_yaml.py (seed default, 124,424 runs): a policy name holding a newline was
    quoted raw into the message. Line breaks are now written as \\n."""
    from xroute.cli.batch_config import load_batch_config

    f = tmp_path / "b.yaml"
    f.write_text('testcases: [demo]\npolicies: ["heuristic\\n- random"]\n')
    with pytest.raises(InputError) as err:
        load_batch_config(f)
    assert "\n" not in str(err.value) and "heuristic\\n- random" in str(err.value)
    assert all("\n" not in m for _, m in getattr(err.value, "problems", ()))
