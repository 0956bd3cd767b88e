"""The package's layers only import downward (ARCHITECTURE.md).

Every ``import`` / ``from ... import`` of an ``xroute`` module, at module level or inside a
function, is read from the source with ``ast`` and the importer's layer compared with the
imported module's: an import of a higher layer fails the test, naming the file and line.
Imports inside ``if TYPE_CHECKING:`` blocks are type hints only and are allowed.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import xroute

PACKAGE = Path(xroute.__file__).resolve().parent

# Layer of each module prefix, lowest first; the longest matching prefix wins.
LAYERS: dict[str, int] = {
    "xroute.errors": 0,
    "xroute._engine": 0,
    # The search path and the table of known testcases: plain data, needed by load_design.
    "xroute.testcases.known": 1,
    "xroute.testcases.registry": 1,
    # The library: design, global and detailed router, the policy seam, outputs, config, pipeline.
    "xroute": 2,
    # Above the library, beside each other.
    "xroute.policies": 3,
    "xroute.testcases": 3,
    # The environments use policies' observations and testcases' static regions.
    "xroute.envs": 4,
    # The command line is the top.
    "xroute.cli": 5,
    "xroute.__main__": 5,
}


def layer(module: str) -> int:
    best = max((p for p in LAYERS if module == p or module.startswith(p + ".")), key=len)
    return LAYERS[best]


def module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _type_checking_lines(tree: ast.AST) -> set[int]:
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            for child in node.body:
                lines.update(range(child.lineno, (child.end_lineno or child.lineno) + 1))
    return lines


def imported_modules(path: Path, module: str) -> list[tuple[int, str]]:
    """(line, module) for every xroute import in the file, resolved to absolute names."""
    tree = ast.parse(path.read_text(), filename=str(path))
    hints = _type_checking_lines(tree)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, (ast.Import, ast.ImportFrom)) or node.lineno in hints:
            continue
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names if a.name.split(".")[0] == "xroute"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "xroute":
                continue
            # `from xroute import errors` imports the module xroute.errors, not the package.
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                found.append((node.lineno, sub if (PACKAGE.parent / sub.replace(".", "/")).exists()
                              or (PACKAGE.parent / (sub.replace(".", "/") + ".py")).exists() else target))
    return found


def python_files() -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def test_every_import_looks_down_or_sideways_within_its_package() -> None:
    upward = []
    for path in python_files():
        module = module_name(path)
        for line, target in imported_modules(path, module):
            if layer(target) > layer(module):
                upward.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {module} (layer {layer(module)}) "
                              f"imports {target} (layer {layer(target)})")
    assert upward == []


def test_the_layer_test_sees_an_upward_import(tmp_path: Path) -> None:
    """The checker itself: a library module importing the CLI is caught."""
    path = tmp_path / "router.py"
    path.write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from xroute.envs import core\n"
                    "def f():\n    from xroute.cli.console import print_error\n")
    found = imported_modules(path, "xroute.router")
    assert found == [(5, "xroute.cli.console")]  # the TYPE_CHECKING import is a hint, not a dependency
    assert layer("xroute.cli.console") > layer("xroute.router")


@pytest.mark.parametrize("module, expected", [
    ("xroute.errors", 0), ("xroute.testcases.registry", 1), ("xroute.design", 2), ("xroute.pipeline", 2),
    ("xroute.policies.rl.models", 3), ("xroute.testcases.regions", 3), ("xroute.envs.core", 4),
    ("xroute.cli.commands.route", 5),
])
def test_layers_of_known_modules(module: str, expected: int) -> None:
    assert layer(module) == expected


def test_no_generic_top_level_packages_installed() -> None:
    """pip install puts one import root, xroute, into site-packages (no policies/testcases/xroute_cli)."""
    site = PACKAGE.parent
    assert not any((site / name / "__init__.py").exists() for name in ("policies", "testcases", "xroute_cli", "envs"))
