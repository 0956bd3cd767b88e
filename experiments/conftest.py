"""The experiments' tests: the ``experiment`` marker and the generated designs they run on.

A test module here sets ``pytestmark = pytest.mark.experiment``. Such a test is collected by every
run (``testpaths`` holds ``experiments``) but skips, with its reason in the summary, unless the
``-m`` expression names ``experiment`` without ``not`` before it::

    python -m pytest -q                                  # skipped: "experiment: ..."
    python -m pytest -q -m experiment experiments/       # run
    python -m pytest -q -m "experiment and not slow" experiments/

(``addopts = -m "not experiment"`` would deselect them silently and keep them out of explicit runs
that do not repeat the marker.) The designs are generated with ``xroute.testcases.generator`` into
one temporary folder per session, put in front of ``$XROUTE_TESTCASES`` for the session only (the
experiments look testcases up by name, in worker processes too); nothing here uses ``tests/``.
"""

from __future__ import annotations

import os
import re
from typing import Callable, Iterator

import pytest

# name -> (cells, seed): the same designs as tests/conftest.py's imitation_sample and standin_sample4.
DESIGNS = {"imitation_sample": (800, 5), "standin_sample4": (120, 3)}
SKIP_REASON = "experiment: outside the default run; python -m pytest -m experiment experiments/ runs it"


def selects_experiments(markexpr: str) -> bool:
    """Whether a ``-m`` expression names the marker ``experiment`` other than as ``not experiment``."""
    tokens = re.findall(r"[()]|[\w.]+", markexpr or "")
    return any(t == "experiment" and (i == 0 or tokens[i - 1] != "not") for i, t in enumerate(tokens))


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if selects_experiments(config.getoption("markexpr", "")):
        return
    skip = pytest.mark.skip(reason=SKIP_REASON)
    for item in items:
        if item.get_closest_marker("experiment") is not None:
            item.add_marker(skip)


@pytest.fixture(scope="session")
def generated(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Callable[[str], str]]:
    """``generated(name)`` -> ``name``, a design of :data:`DESIGNS` generated on first use into this
    session's folder, which is on the testcase search path until the session ends."""
    from xroute.testcases import ENV_VAR
    from xroute.testcases.generator import make_testcase

    root = tmp_path_factory.mktemp("experiment-designs")
    old = os.environ.get(ENV_VAR)
    os.environ[ENV_VAR] = os.pathsep.join(p for p in (str(root), old) if p)

    def make(name: str) -> str:
        folder = root / name
        if not (folder / f"{name}.def").is_file():
            cells, seed = DESIGNS[name]
            make_testcase(cells, seed, folder)
        return name

    yield make
    if old is None:
        os.environ.pop(ENV_VAR, None)
    else:
        os.environ[ENV_VAR] = old


@pytest.fixture(scope="session")
def imitation_sample(generated: Callable[[str], str]) -> str:
    """A generated design of 800 cells: 64 regions of 2x2 GCells."""
    return generated("imitation_sample")
