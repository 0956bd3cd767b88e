"""The README stays true: its install commands are what CI runs, every `xroute` command and flag
it shows exists, every name its Python examples import exists, and the figures of its status
table for the small designs are what routing them gives now (routing is deterministic)."""

from __future__ import annotations

import importlib
import re
import shlex

import pytest

from conftest import REPO_ROOT, make_runner
from xroute.cli.app import app

README = (REPO_ROOT / "README.md").read_text()
CI_SCRIPT = (REPO_ROOT / ".ci" / "run").read_text()


def code_blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", README, flags=re.S)


def _logical_lines(block: str) -> list[str]:
    """Lines with backslash continuations joined and comments dropped."""
    joined = re.sub(r"\\\n\s*", " ", block)
    return [line.split(" #")[0].strip() for line in joined.splitlines() if line.strip() and not line.startswith("#")]


def xroute_invocations() -> list[list[str]]:
    calls = []
    for block in code_blocks("bash"):
        for line in _logical_lines(block):
            for part in re.split(r"&&|\|", line):
                words = part.strip().split()
                while words and ("=" in words[0] and not words[0].startswith("-")):  # CI=true xroute ...
                    words = words[1:]
                if len(words) >= 2 and words[0] == "xroute" and not words[1].startswith("-"):
                    calls.append(words)
    return calls


def test_the_two_readme_commands_are_what_ci_runs() -> None:
    first = _logical_lines(code_blocks("bash")[0])
    assert first[0] == "pip install . && xroute route"
    assert first[1].endswith("pip install --group test && python -m pytest -q")
    assert "python -m pip install .\n" in CI_SCRIPT
    assert "python -m pip install --group test\n" in CI_SCRIPT
    assert "python -m pytest -q" in CI_SCRIPT


def test_every_xroute_command_and_flag_in_the_readme_exists() -> None:
    runner = make_runner()
    helps: dict[str, str] = {}
    problems = []
    calls = xroute_invocations()
    assert len(calls) > 20  # the README shows the commands
    for words in calls:
        command = words[1]
        if command not in helps:
            result = runner.invoke(app, [command, "--help"], terminal_width=200)
            helps[command] = result.output if result.exit_code == 0 else ""
        if not helps[command]:
            problems.append(f"unknown command: {' '.join(words)}")
            continue
        for flag in (w.split("=")[0] for w in words[2:] if w.startswith("--")):
            if flag not in helps[command]:
                problems.append(f"xroute {command} has no {flag}")
    assert problems == []


def test_every_name_the_python_examples_import_exists() -> None:
    missing = []
    for block in code_blocks("python"):
        for module, names in re.findall(r"^from ([\w.]+) import ([\w, ]+)$", block, flags=re.M):
            mod = importlib.import_module(module)
            missing += [f"{module}.{n.strip()}" for n in names.split(",") if not hasattr(mod, n.strip())]
    assert missing == []


def status_rows() -> dict[str, tuple[float, int, int]]:
    """testcase -> (WL µm, vias, violations) from the status table's xroute rows (bench/quality.py)."""
    rows = {}
    for m in re.finditer(r"^\| (demo|ispd\w+) \| xroute \| ([\d,.]+) \| ([\d,]+) \| ([\d,]+)", README, flags=re.M):
        name = m.group(1)
        rows[name] = (float(m.group(2).replace(",", "")), int(m.group(3).replace(",", "")),
                      int(m.group(4).replace(",", "")))
    return rows


# ispd18_sample3 routes for about 15 s: slow.
SMALL = ["demo", "ispd18_sample", "ispd18_sample2", pytest.param("ispd18_sample3", marks=pytest.mark.slow),
         "ispd19_sample4"]


@pytest.mark.parametrize("name", SMALL)
def test_status_table_figures_of_the_small_designs_are_current(name: str, testcase) -> None:
    rows = status_rows()
    assert name in rows, f"the README's status table has no row for {name}"
    if name != "demo":
        testcase(name)  # skips when the contest data is absent
    from xroute import prepare_design, route_design

    result = route_design(prepare_design(name))  # the defaults, as bench/quality.py routes
    wl, vias, violations = rows[name]
    assert (round(result.wirelength_um, 1), result.vias, result.violations) == (wl, vias, violations)


def test_readme_mentions_no_removed_module_paths() -> None:
    stale = [p for p in ("xroute_cli", "from policies", "import policies",
                         "learned policies come later") if p in README]
    assert stale == []


def test_every_script_path_the_docs_name_exists() -> None:
    """Paths under bench/, fuzz/, examples/ and experiments/ (and `python -m experiments.…` modules)
    named by the README and ARCHITECTURE.md point at files that exist."""
    docs = README + (REPO_ROOT / "ARCHITECTURE.md").read_text()
    paths = set(re.findall(r"\b((?:bench|fuzz|examples|experiments)/[\w/.-]*\w\.(?:py|sh|md))", docs))
    paths |= {m.replace(".", "/") + ".py" for m in re.findall(r"python -m (experiments(?:\.\w+)+)", docs)}
    assert len(paths) > 10
    assert sorted(p for p in paths if not (REPO_ROOT / p).is_file()) == []


def test_shlex_can_split_every_bash_line() -> None:
    """A quoting mistake in a shown command would make it fail when pasted."""
    for block in code_blocks("bash"):
        for line in _logical_lines(block):
            shlex.split(line)


def test_the_gymnasium_quick_start_runs(capsys) -> None:
    """policies/rl/README.md's quick start, run as written (on the shipped demo)."""
    text = (REPO_ROOT / "policies" / "rl" / "README.md").read_text()
    block = re.search(r"## Quick start\n\n```python\n(.*?)```", text, re.S)
    assert block is not None and len(block.group(1).splitlines()) <= 12
    exec(compile(block.group(1), "policies/rl/README.md quick start", "exec"), {})
    assert re.fullmatch(r"region cost \d+\.\d\n", capsys.readouterr().out)
