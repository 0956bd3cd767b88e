"""Shared test helpers: which ``xroute_cli`` the tests import, testcase lookup, and loaded designs.

Which package is imported. ``python -m pytest`` puts the repository root first on
``sys.path``, so ``import xroute_cli`` would pick the source folder even when the
package was installed with ``pip install '.[test]'``. The source folder only holds the
compiled engine after an in-place build (``ninja -C build/dev``). So:

* source folder has ``xroute_cli/_engine*.so`` for this Python -> test the source tree
  (developer flow);
* otherwise -> drop the repository root from ``sys.path`` and test the installed
  package (CI flow, clean clone).

Fixtures (nothing here is autouse; nothing changes the working directory):

* ``testcase(name)`` -> :class:`testcases.FoundTestcase`, or skips the test naming the
  search path when the testcase is not there;
* ``loaded_design(name, use_guide=True)`` -> a :class:`xroute_cli.Design` loaded once per
  session and shared: tests must not modify it.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import sys
from pathlib import Path
from typing import Any, Callable

import pytest
from typer.testing import CliRunner

REPO_ROOT = Path(__file__).resolve().parent.parent


def _source_has_engine() -> bool:
    package = REPO_ROOT / "xroute_cli"
    return any((package / f"_engine{suffix}").is_file() for suffix in importlib.machinery.EXTENSION_SUFFIXES)


def _is_repo_root(entry: str) -> bool:
    try:
        return Path(entry or ".").resolve() == REPO_ROOT
    except OSError:
        return False


def _choose_package() -> None:
    if _source_has_engine():
        return
    kept = [entry for entry in sys.path if not _is_repo_root(entry)]
    removed = [entry for entry in sys.path if _is_repo_root(entry)]
    sys.path[:] = kept
    spec = importlib.util.find_spec("xroute_cli._engine") if importlib.util.find_spec("xroute_cli") else None
    if spec is None:  # nothing usable installed either: keep the source tree (pure-Python tests still run)
        sys.modules.pop("xroute_cli", None)
        sys.path[:0] = removed


_choose_package()


def require_testcase(name: str) -> Any:
    """The testcase's :class:`~testcases.FoundTestcase`, or skip the calling test."""
    from testcases import ENV_VAR, find_testcase, search_path
    from xroute_cli.errors import TestcaseNotFound

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
            from xroute_cli.design import load_design

            cache[key] = load_design(name, use_guide=use_guide)
        return cache[key]

    return load


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
