"""Shared test helpers: testcase lookup and loaded designs.

The tests import the installed package ``xroute`` (``pip install .`` then the test group, or an
editable install for development, see the README): the repository has no top-level ``xroute``
folder that could shadow it.

Fixtures (nothing here is autouse; nothing changes the working directory):

* ``testcase(name)`` -> :class:`xroute.testcases.FoundTestcase`, or skips the test naming the
  search path when the testcase is not there;
* ``loaded_design(name, use_guide=True)`` -> a :class:`xroute.Design` loaded once per
  session and shared: tests must not modify it;
* ``imitation_sample`` -> the name of a generated design of 800 cells for the set scorer's tests.

Stand-ins: tests whose assertions are invariants (0 opens, determinism, round trips, error
messages, CLI behaviour) run on a contest testcase when it is on the search path and otherwise on
a small generated design that takes its place (:data:`STANDIN_FOR`). ``pick(name)`` gives the
contest name when it is found, else its stand-in's name; ``available(*names)`` does that for a
list (for ``parametrize``: the contest ids are unchanged when the data is there). Stand-ins are
generated with ``xroute.testcases.generator`` on first use into one temporary folder per session,
which ``pytest_configure`` appends to ``$XROUTE_TESTCASES`` so that everything that looks a
testcase up by name (the CLI, batch jobs in child processes, the envs) finds them; the folders the
test process itself finds go before it, so a child started in another working directory (an
installed package looks beside the working directory) finds the contest data too.
``load_file(path)`` imports a repository file that is not part of the package (``fuzz/``,
``examples/``) as a module of its own, without putting its folder on ``sys.path``.
``sample_lef()`` is ispd18_sample's LEF, or tests/data/lef/sample_names.lef (our own LEF with the
names the tests' hand-written DEFs use) when the contest data is missing.
"""

from __future__ import annotations

import importlib.util
import os
import shutil
import sys
import tempfile
from pathlib import Path
from types import ModuleType
from typing import Any, Callable

import pytest
from typer.testing import CliRunner

REPO_ROOT = Path(__file__).resolve().parent.parent
SAMPLE_NAMES_LEF = Path(__file__).resolve().parent / "data" / "lef" / "sample_names.lef"

# Generated stand-ins: name -> (cells, seed, with a guide file). All are small (seconds to route).
STANDINS: dict[str, tuple[int, int, bool]] = {
    "standin_sample": (18, 1, True),  # 10 nets on a die of 3 x 3 GCells (one region), like ispd18_sample
    "standin_sample2": (40, 2, True),
    # standin_sample4: 4 regions at region size 5 (1 in the first pass at the default 10), IO pins, power rails
    "standin_sample4": (120, 3, True),
    "standin_noguide": (60, 4, False),  # no guide file, like ispd19_test3
    # standin_marked: at region size 2 its violations go 15 -> 21 -> 0 (two-net markers after the
    # second iteration); the smaller stand-ins route clean in their first pass
    "standin_marked": (800, 3, True),
}
# The stand-in that takes a contest testcase's place in tests of invariants.
STANDIN_FOR: dict[str, str] = {
    "ispd18_sample": "standin_sample",
    "ispd18_sample2": "standin_sample2",
    "ispd18_sample3": "standin_sample2",
    "ispd19_sample4": "standin_sample4",
    "ispd18_test1": "standin_sample4",
    "ispd19_test1": "standin_sample4",
    "ispd19_test3": "standin_noguide",
}
_standin_root: Path | None = None


def pytest_configure(config: pytest.Config) -> None:
    """One folder for this session's stand-ins, appended to $XROUTE_TESTCASES (files made on first use)."""
    global _standin_root
    from xroute.testcases import ENV_VAR, search_path

    _standin_root = Path(tempfile.mkdtemp(prefix="xroute-standins-"))
    # The folders this process finds (../shared/testcases beside the working directory among them)
    # go first, so that a child process started in another directory finds the same testcases.
    found = [str(p) for p in search_path() if p.is_dir()]
    os.environ[ENV_VAR] = os.pathsep.join(dict.fromkeys([*found, str(_standin_root)]))


def pytest_unconfigure(config: pytest.Config) -> None:
    if _standin_root is not None:
        shutil.rmtree(_standin_root, ignore_errors=True)


def standin_root() -> Path:
    assert _standin_root is not None, "pytest_configure has not run"
    return _standin_root


def make_standin(name: str) -> Path:
    """The stand-in's folder, generated on first use."""
    cells, seed, guide = STANDINS[name]
    folder = standin_root() / name
    if not (folder / f"{name}.def").is_file():
        from xroute.testcases.generator import make_testcase

        make_testcase(cells, seed, folder)
        if not guide:
            (folder / f"{name}.guide").unlink()
    return folder


def is_standin(name: str) -> bool:
    return name in STANDINS


def contest_found(name: str) -> bool:
    """Whether the contest testcase ``name`` is on the search path (the stand-ins never are)."""
    from xroute.errors import TestcaseNotFound
    from xroute.testcases import find_testcase

    try:
        find_testcase(name)
        return True
    except TestcaseNotFound:
        return False


def pick(name: str) -> str:
    """``name`` when that contest testcase is on the search path, else the name of its stand-in."""
    return name if contest_found(name) else STANDIN_FOR[name]


def available(*names: str) -> list[str]:
    """:func:`pick` of each name, without repeats: the designs a parametrized test runs on."""
    out: list[str] = []
    for name in names:
        got = pick(name)
        if got not in out:
            out.append(got)
    return out


# Net counts of the contest samples (their DEF's NETS statement), as the tests assert them.
CONTEST_NETS = {"ispd18_sample": 11, "ispd18_sample2": 16, "ispd19_sample4": 22}


def nets_of(name: str) -> int:
    """How many nets the design has: the contest figure, or a stand-in's NETS count read from its DEF text."""
    if name in CONTEST_NETS:
        return CONTEST_NETS[name]
    import re

    text = require_testcase(name).def_.read_text()
    return int(re.search(r"^NETS (\d+) ;", text, re.M).group(1))


def load_file(relative: str) -> ModuleType:
    """The repository file ``relative`` (``fuzz/fuzz_yaml.py``, ``examples/maskable_ppo.py``) imported
    from its path as the module ``xroute_file_<stem>``; its folder does not go on ``sys.path``."""
    path = REPO_ROOT / relative
    name = f"xroute_file_{path.stem}"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None, path
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module  # dataclasses look their module up there
        spec.loader.exec_module(module)
    return sys.modules[name]


def sample_lef() -> Path:
    """ispd18_sample's LEF, or our LEF with the same names (tests/data/lef/sample_names.lef)."""
    from xroute.errors import TestcaseNotFound
    from xroute.testcases import find_testcase

    try:
        return find_testcase("ispd18_sample").lef
    except TestcaseNotFound:
        return SAMPLE_NAMES_LEF


def require_testcase(name: str) -> Any:
    """The testcase's :class:`~xroute.testcases.FoundTestcase`, or skip the calling test."""
    from xroute.testcases import ENV_VAR, find_testcase, search_path
    from xroute.errors import TestcaseNotFound

    if is_standin(name):
        make_standin(name)
    try:
        return find_testcase(name)
    except TestcaseNotFound:
        roots = ", ".join(str(p) for p in search_path())
        pytest.skip(f"testcase {name} not found on the search path ({roots}); set {ENV_VAR} or add ../shared/testcases/{name}/")


@pytest.fixture
def testcase() -> Callable[[str], Any]:
    """``testcase(name)`` -> FoundTestcase, or skips the test when it is not on the search path."""
    return require_testcase


@pytest.fixture(scope="session")
def loaded_design() -> Callable[..., Any]:
    """``loaded_design(name, use_guide=True)`` -> Design, loaded once per session (read-only: shared)."""
    cache: dict[tuple[str, bool], Any] = {}

    def load(name: str, use_guide: bool = True) -> Any:
        key = (name, use_guide)
        if key not in cache:
            require_testcase(name)
            from xroute.design import load_design

            cache[key] = load_design(name, use_guide=use_guide)
        return cache[key]

    return load


IMITATION_SAMPLE = "imitation_sample"  # generated: 800 cells, 64 regions of 2x2 GCells


@pytest.fixture(scope="session")
def imitation_sample() -> str:
    """The name of the set scorer's tests' design (:data:`IMITATION_SAMPLE`), generated among the stand-ins
    on first use."""
    from xroute.testcases.generator import make_testcase

    folder = standin_root() / IMITATION_SAMPLE
    if not (folder / f"{IMITATION_SAMPLE}.def").is_file():
        make_testcase(800, 5, folder)
    return IMITATION_SAMPLE


def make_runner() -> CliRunner:
    """A CliRunner whose ``result.stderr`` is separate from ``result.stdout`` on every Click version."""
    try:
        return CliRunner(mix_stderr=False)  # Click < 8.2 mixes stderr into stdout by default
    except TypeError:
        return CliRunner()  # Click >= 8.2: result.stderr is always separate


@pytest.fixture
def runner() -> CliRunner:
    """See :func:`make_runner`."""
    return make_runner()


def one_error(result: Any, *needles: str) -> str:
    """The one ``error:`` line of a CliRunner result that failed with exit 2 and no traceback, holding
    every needle (asserted)."""
    text = result.output + (result.stderr or "")
    assert "Traceback" not in text, text
    assert result.exit_code == 2, text
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    for needle in needles:
        assert needle in lines[0], (lines[0], needle)
    return lines[0]
