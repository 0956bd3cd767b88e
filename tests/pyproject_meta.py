"""pyproject.toml as the tests read it: the metadata and the package map.

``tomllib`` is in the standard library from Python 3.11; on 3.10 the test group and the test
extra install ``tomli``, the same parser under another name.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

REPO_ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = REPO_ROOT / "pyproject.toml"


def pyproject() -> dict[str, Any]:
    return tomllib.loads(PYPROJECT.read_text(encoding="utf-8"))


def package_map() -> dict[str, Path]:
    """``[tool.scikit-build.wheel.packages]``: each package's dotted name -> its source folder."""
    table = pyproject()["tool"]["scikit-build"]["wheel"]["packages"]
    return {key.replace("/", "."): REPO_ROOT / folder for key, folder in table.items()}


def source_modules() -> list[str]:
    """Every module of the package by its dotted name, read from the folders of the package map
    (the files where they are, not through the import system)."""
    folders = package_map()
    names = set()
    for package, folder in folders.items():
        for path in folder.rglob("*.py"):
            rel = path.relative_to(folder).with_suffix("")
            parts = [*package.split("."), *rel.parts]
            if parts[-1] == "__init__":
                parts.pop()
            names.add(".".join(parts))
    return sorted(names)
