"""Shared test helpers: testcase lookup and loaded designs.

The tests import the installed package ``xroute`` (``pip install .`` then the test group, or an
editable install for development, see the README): the repository has no top-level ``xroute``
folder that could shadow it.

Fixtures (nothing here is autouse; nothing changes the working directory):

* ``testcase(name)`` -> :class:`xroute.testcases.FoundTestcase`, or skips the test naming the
  search path when the testcase is not there;
* ``loaded_design(name, use_guide=True)`` -> a :class:`xroute.Design` loaded once per
  session and shared: tests must not modify it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable

import pytest
from typer.testing import CliRunner

REPO_ROOT = Path(__file__).resolve().parent.parent


def require_testcase(name: str) -> Any:
    """The testcase's :class:`~xroute.testcases.FoundTestcase`, or skip the calling test."""
    from xroute.testcases import ENV_VAR, find_testcase, search_path
    from xroute.errors import TestcaseNotFound

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
