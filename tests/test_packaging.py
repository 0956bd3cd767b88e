"""The packaging facts the README relies on: the test dependency group and the test extra name
the same packages, and the version has one definition."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import xroute

PYPROJECT = Path(__file__).resolve().parent.parent / "pyproject.toml"


def _name(requirement: str) -> str:
    return re.split(r"[<>=!~\[; ]", requirement, maxsplit=1)[0].lower()


def test_test_group_installs_what_the_test_extra_does() -> None:
    meta = tomllib.loads(PYPROJECT.read_text())
    extras = meta["project"]["optional-dependencies"]
    from_extra: dict[str, str] = {}
    for req in extras["test"]:
        if req.startswith("xroute["):
            for sub in req[len("xroute["):-1].split(","):
                from_extra.update({_name(r): r for r in extras[sub]})
        else:
            from_extra[_name(req)] = req
    group = {_name(r): r for r in meta["dependency-groups"]["test"]}
    assert group == from_extra


def test_version_comes_from_the_package_metadata() -> None:
    meta = tomllib.loads(PYPROJECT.read_text())
    assert xroute.__version__ == meta["project"]["version"]
