"""The documents stay true.

* The README's two commands are the documented ones (and what CI runs); every `xroute` command
  the README and the manual pages show names a command and options that exist.
* The status table between the README's markers is the rendering of the committed results file
  (bench/results/quality.json), byte for byte: it is generated, never edited by hand.
* That file's deterministic figures for the small designs are what routing them gives now.
* Every relative link and every script path the documents name points at a file that exists, and
  the Python examples import names that exist.
"""

from __future__ import annotations

import importlib
import json
import re
import shlex
from pathlib import Path
from typing import Any

import pytest
import typer

from conftest import REPO_ROOT, load_file, make_runner
from xroute.cli.app import app

README = (REPO_ROOT / "README.md").read_text()
CI_SCRIPT = (REPO_ROOT / ".ci" / "run").read_text()
RESULTS = REPO_ROOT / "bench" / "results" / "quality.json"
MANUALS = sorted((REPO_ROOT / "docs").glob("*.md"))
# The documents whose commands, links and paths are checked (the experiments' logs are records).
DOCUMENTS = [REPO_ROOT / p for p in ("README.md", "ARCHITECTURE.md", "CONTRIBUTING.md", "CHANGELOG.md",
                                     "bench/README.md", "fuzz/README.md", "examples/README.md",
                                     "experiments/README.md", "policies/rl/README.md")]
DOCUMENTS += MANUALS + sorted((REPO_ROOT / "engine_cpp").glob("*/README.md"))
DOCUMENTS += sorted((REPO_ROOT / "policies" / "models").glob("*.card.md"))

quality = load_file("bench/quality.py")


def rel(path: Path) -> str:
    return str(path.relative_to(REPO_ROOT))


def code_blocks(text: str, lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", text, flags=re.S)


def _logical_lines(block: str) -> list[str]:
    """Lines with backslash continuations joined and comments dropped."""
    joined = re.sub(r"\\\n\s*", " ", block)
    return [line.split(" #")[0].strip() for line in joined.splitlines() if line.strip() and not line.startswith("#")]


def xroute_invocations(text: str) -> list[list[str]]:
    """The words of every `xroute COMMAND ...` shown: in bash blocks and in inline code."""
    lines = [line for block in code_blocks(text, "bash") for line in _logical_lines(block)]
    lines += re.findall(r"`(xroute [^`]+)`", text)
    calls = []
    for line in lines:
        for part in re.split(r"&&|;|\s\|\s(?!-)", line):  # not `a|b` or `[--json | --quiet]`
            words = part.strip().split()
            while words and "=" in words[0] and not words[0].startswith("-"):  # CI=true xroute ...
                words = words[1:]
            if len(words) >= 2 and words[0] == "xroute" and re.fullmatch(r"[a-z][a-z-]*", words[1]):
                calls.append(words)
    return calls


def test_the_two_readme_commands_are_the_documented_ones() -> None:
    first = _logical_lines(code_blocks(README, "bash")[0])
    assert first == ["pip install . && xroute route",
                     "pip install -U 'pip>=25.1' && pip install --group test && python -m pytest -q"]
    assert "python -m pytest -q -m slow" in README
    assert "python -m pytest -q -m experiment experiments/" in README
    assert "python -m pip install .\n" in CI_SCRIPT
    assert "python -m pip install --group test\n" in CI_SCRIPT
    assert "python -m pytest -q" in CI_SCRIPT


def _options(command: Any) -> set[str]:
    return {opt for param in command.params for opt in (*param.opts, *param.secondary_opts)}


@pytest.mark.parametrize("doc", DOCUMENTS, ids=rel)
def test_every_xroute_command_shown_exists_with_its_options(doc: Path) -> None:
    group = typer.main.get_command(app)  # a click group (typer may bring its own copy of click)
    problems = []
    for words in xroute_invocations(doc.read_text()):
        command = group.commands.get(words[1])
        if command is None:
            problems.append(f"unknown command: {' '.join(words)}")
            continue
        known = _options(command) | {"--help"}
        for flag in re.findall(r"(?<![\w-])(--?[a-z][\w-]*)", " ".join(words[2:])):
            if flag not in known:
                problems.append(f"xroute {words[1]} has no {flag}")
    assert problems == []


def test_the_readme_and_the_manuals_show_commands() -> None:
    """The check above cannot pass by finding nothing."""
    assert len(xroute_invocations(README)) >= 10
    assert len(MANUALS) >= 8
    commands = {words[1] for doc in MANUALS for words in xroute_invocations(doc.read_text())}
    assert commands >= set(typer.main.get_command(app).commands)  # every command has its manual entry


def test_a_command_with_a_wrong_option_is_caught() -> None:
    """The option check itself: an option no command has is reported."""
    calls = xroute_invocations("```bash\nxroute route demo --no-such-flag 3\n```\n")
    group = typer.main.get_command(app)
    assert calls == [["xroute", "route", "demo", "--no-such-flag", "3"]]
    assert "--no-such-flag" not in _options(group.commands["route"])


def test_the_status_table_is_the_rendering_of_the_committed_results() -> None:
    block = quality.generated_block(README)
    assert block is not None, "the README has no status-table markers"
    results = json.loads(RESULTS.read_text())
    assert block == quality.render_markdown(results), (
        "the README's status table differs from bench/results/quality.json; regenerate it with "
        "python bench/quality.py --from-json bench/results/quality.json --readme README.md")


def test_the_results_say_how_they_were_measured() -> None:
    results = json.loads(RESULTS.read_text())
    assert re.fullmatch(r"\d{4}-\d{2}-\d{2}", results["date"])
    assert results["machine"]["cores"] >= 1 and results["machine"]["cpu"]
    assert re.fullmatch(r"[0-9a-f]{7,40}(-dirty)?", results["commit"])
    assert results["settings"]["threads"] >= 1
    assert {r["testcase"] for r in results["rows"]} >= {"demo"}


# ispd18_sample3 routes for about 40 s on the 2-core machine: slow.
SMALL = ["demo", "ispd18_sample", "ispd18_sample2", pytest.param("ispd18_sample3", marks=pytest.mark.slow),
         "ispd19_sample4"]


@pytest.mark.parametrize("name", SMALL)
def test_the_results_of_the_small_designs_are_current(name: str, testcase, tmp_path: Path) -> None:
    """Routing is deterministic: a fresh route with the file's settings, judged by `xroute check` as
    bench/quality.py judges it, gives the file's wirelength, vias, violations and opens."""
    if name != "demo":
        testcase(name)  # skips, naming the search path, when the contest data is absent
    results = json.loads(RESULTS.read_text())
    rows = [r for r in results["rows"] if r["testcase"] == name and r["router"] == "xroute"]
    assert len(rows) == 1, f"{rel(RESULTS)} has no xroute row for {name}: re-run bench/quality.py"
    settings = results["settings"]
    args = ["route", name, "--threads", str(settings["threads"]), "--out", str(tmp_path / "r"), "--quiet"]
    if settings["iterations"]:
        args += ["--iterations", str(settings["iterations"])]
    runner = make_runner()
    routed = runner.invoke(app, args)
    assert routed.exit_code in (0, 1), routed.output
    (def_path,) = (tmp_path / "r").glob("*.routed.def")
    checked = runner.invoke(app, ["check", name, "--def", str(def_path), "--out", str(tmp_path / "c"), "--json"])
    assert checked.exit_code in (0, 1), checked.output
    doc = json.loads(checked.stdout)
    got = (doc["wirelength_um"], doc["vias"], doc["violations"], doc["opens"])
    row = rows[0]
    assert got == (row["wl_um"], row["vias"], row["violations"], row["opens"])


def _slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def _anchors(path: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", path.read_text(), flags=re.S)
    return {_slug(h) for h in re.findall(r"^#+ (.+)$", text, flags=re.M)}


@pytest.mark.parametrize("doc", DOCUMENTS, ids=rel)
def test_every_relative_link_points_at_a_file_that_exists(doc: Path) -> None:
    text = re.sub(r"```.*?```", "", doc.read_text(), flags=re.S)
    broken = []
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target):  # http:, https:, mailto:
            continue
        file, _, anchor = target.partition("#")
        path = (doc.parent / file).resolve() if file else doc
        if not path.exists():
            broken.append(target)
        elif anchor and path.suffix == ".md" and anchor not in _anchors(path):
            broken.append(target)
    assert broken == []


def test_the_link_check_finds_links() -> None:
    assert len(re.findall(r"\]\((?!https?:)[^)\s]+\)", README)) >= 8


def test_every_script_path_the_docs_name_exists() -> None:
    """Paths under bench/, fuzz/, examples/, experiments/ and docs/ (and `python -m experiments.…`
    modules) named by the documents point at files that exist."""
    docs = "".join(p.read_text() for p in DOCUMENTS)
    paths = set(re.findall(r"\b((?:bench|fuzz|examples|experiments|docs)/[\w/.-]*\w\.(?:py|sh|md|json))", docs))
    paths |= {m.replace(".", "/") + ".py" for m in re.findall(r"python -m (experiments(?:\.\w+)+)", docs)}
    assert len(paths) > 10
    assert sorted(p for p in paths if not (REPO_ROOT / p).is_file()) == []


def test_every_name_the_python_examples_import_exists() -> None:
    missing = []
    for doc in [REPO_ROOT / "README.md", *MANUALS]:
        for block in code_blocks(doc.read_text(), "python"):
            for module, names in re.findall(r"^from ([\w.]+) import ([\w, ]+)$", block, flags=re.M):
                mod = importlib.import_module(module)
                missing += [f"{module}.{n.strip()}" for n in names.split(",") if not hasattr(mod, n.strip())]
    assert missing == []


def test_shlex_can_split_every_bash_line() -> None:
    """A quoting mistake in a shown command would make it fail when pasted."""
    for doc in DOCUMENTS:
        for block in code_blocks(doc.read_text(), "bash"):
            for line in _logical_lines(block):
                shlex.split(line)


def test_the_documents_mention_no_removed_module_paths() -> None:
    stale = [(rel(d), p) for d in DOCUMENTS for p in ("xroute_cli", "from policies", "import policies")
             if p in d.read_text()]
    assert stale == []


def test_the_gymnasium_quick_start_runs(capsys) -> None:
    """policies/rl/README.md's quick start, run as written (on the shipped demo)."""
    text = (REPO_ROOT / "policies" / "rl" / "README.md").read_text()
    block = re.search(r"## Quick start\n\n```python\n(.*?)```", text, re.S)
    assert block is not None and len(block.group(1).splitlines()) <= 12
    exec(compile(block.group(1), "policies/rl/README.md quick start", "exec"), {})
    assert re.fullmatch(r"region cost \d+\.\d\n", capsys.readouterr().out)
