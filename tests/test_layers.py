"""The package's layers only import downward, and no module imports itself back (ARCHITECTURE.md).

Every module of the package is found through the import system (each package's ``__path__``,
so the walk sees the files where an editable or a regular install keeps them) and counted
against the modules of pyproject.toml's package map read from the folders: a walk that stops
seeing a folder fails. Every ``import`` / ``from ... import`` of an ``xroute`` module, at module
level or inside a function, is read from the source with ``ast``:

* an import of a higher layer fails the test, naming the file and line;
* so does any cycle of imports between modules, inside one layer too (a function-local import
  hides a cycle from Python until the day someone moves it to the top).

Imports inside ``if TYPE_CHECKING:`` blocks are type hints only and are allowed. A package's own
``__init__`` being run before its submodules is not an import edge.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import pkgutil
from functools import cache
from pathlib import Path

import pytest

from pyproject_meta import REPO_ROOT, package_map, source_modules

ROOT = "xroute"

# Layer of each module prefix, lowest first; the longest matching prefix wins.
LAYERS: dict[str, int] = {
    "xroute.errors": 0,
    "xroute._engine": 0,
    # The search path and the table of known testcases: plain data, needed by load_design.
    "xroute.testcases.known": 1,
    "xroute.testcases.registry": 1,
    # The library: design, global and detailed router, the net-order seam, outputs, config, pipeline.
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


def _walk(package: str, found: dict[str, Path]) -> None:
    """Adds every Python module under ``package`` (imported to read its ``__path__``) to ``found``."""
    pkg = importlib.import_module(package)
    found[package] = Path(pkg.__file__)
    # An editable install made by scikit-build-core 1.x also lists the repository root in
    # ``xroute.__path__`` (the parent of the mapped folders): its own packages (experiments/) are
    # no part of the package map, so that entry is not walked.
    paths = [p for p in pkg.__path__ if Path(p).resolve() != REPO_ROOT]
    for info in pkgutil.iter_modules(paths, prefix=package + "."):
        if info.name in found:
            continue  # a name on two entries of __path__: the first wins, as for import
        if info.ispkg:
            _walk(info.name, found)
            continue
        spec = importlib.util.find_spec(info.name)  # the parent is imported; the module is not run
        if spec is not None and spec.origin is not None and spec.origin.endswith(".py"):
            found[info.name] = Path(spec.origin)


@cache
def package_modules() -> dict[str, Path]:
    """Every Python module of the package, dotted name -> the file the import system would run.

    The walk starts at ``xroute`` and at each subpackage of the package map: an editable install
    made by scikit-build-core before 1.0 imports ``xroute.cli`` from ``cli/`` without listing
    that folder in ``xroute.__path__``."""
    found: dict[str, Path] = {}
    for root in (ROOT, *package_map()):
        if root not in found:
            _walk(root, found)
    return dict(sorted(found.items()))


def _type_checking_lines(tree: ast.AST) -> set[int]:
    lines: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            for child in node.body:
                lines.update(range(child.lineno, (child.end_lineno or child.lineno) + 1))
    return lines


def imported_modules(path: Path, module: str, modules: set[str]) -> list[tuple[int, str]]:
    """(line, module) for every xroute import in the file, resolved to absolute names; ``from a
    import b`` names the module ``a.b`` when that is one of ``modules``, else ``a``."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    hints = _type_checking_lines(tree)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, (ast.Import, ast.ImportFrom)) or node.lineno in hints:
            continue
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names if a.name.split(".")[0] == ROOT]
            continue
        if node.level:
            base = package.split(".")[: len(package.split(".")) - node.level + 1]
            target = ".".join(base + ([node.module] if node.module else []))
        else:
            target = node.module or ""
        if target.split(".")[0] != ROOT:
            continue
        for alias in node.names:
            sub = f"{target}.{alias.name}"
            found.append((node.lineno, sub if sub in modules else target))
    return found


@cache
def import_graph() -> dict[str, list[tuple[int, str]]]:
    """module -> (line, imported module) for every xroute import in its source."""
    mods = package_modules()
    names = set(mods) | {"xroute._engine"}
    return {m: imported_modules(p, m, names) for m, p in mods.items()}


def import_cycles(graph: dict[str, list[tuple[int, str]]]) -> list[list[str]]:
    """The strongly connected components of more than one module (or a module importing itself),
    each sorted: Tarjan's algorithm, iterative."""
    edges = {m: sorted({t for _, t in targets if t in graph}) for m, targets in graph.items()}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, i = work.pop()
            if i == 0:
                index[node] = low[node] = len(index)
                stack.append(node)
                on_stack.add(node)
            if i < len(edges[node]):
                work.append((node, i + 1))
                nxt = edges[node][i]
                if nxt not in index:
                    work.append((nxt, 0))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    top = stack.pop()
                    on_stack.discard(top)
                    component.append(top)
                    if top == node:
                        break
                if len(component) > 1 or node in edges[node]:
                    cycles.append(sorted(component))
    return sorted(cycles)


def test_the_walk_sees_every_module_of_the_package_map() -> None:
    """The import system's view and the folders' agree module for module (92 when this was
    written; the old test's rglob, which did not enter the linked folders, saw 19 of 91)."""
    walked = sorted(package_modules())
    assert walked == source_modules()
    assert len(walked) >= 90


def test_every_import_looks_down_or_sideways_within_its_package() -> None:
    upward = []
    for module, targets in import_graph().items():
        path = package_modules()[module]
        for line, target in targets:
            if layer(target) > layer(module):
                upward.append(f"{path}:{line}: {module} (layer {layer(module)}) "
                              f"imports {target} (layer {layer(target)})")
    assert upward == []


def test_no_import_cycles() -> None:
    assert import_cycles(import_graph()) == []


def test_the_cycle_check_finds_a_cycle_inside_a_layer_and_a_self_import() -> None:
    graph = {
        "xroute.a": [(3, "xroute.b")], "xroute.b": [(7, "xroute.c")], "xroute.c": [(1, "xroute.a")],
        "xroute.d": [(2, "xroute.a")], "xroute.e": [(5, "xroute.e")], "xroute.f": [(1, "xroute.errors")],
    }
    assert import_cycles(graph) == [["xroute.a", "xroute.b", "xroute.c"], ["xroute.e"]]


def test_the_layer_test_sees_an_upward_import(tmp_path: Path) -> None:
    """The checker itself: a library module importing the CLI is caught."""
    path = tmp_path / "router.py"
    path.write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from xroute.envs import core\n"
                    "def f():\n    from xroute.cli.console import print_error\n")
    found = imported_modules(path, "xroute.router", set(package_modules()))
    assert found == [(5, "xroute.cli.console")]  # the TYPE_CHECKING import is a hint, not a dependency
    assert layer("xroute.cli.console") > layer("xroute.router")


@pytest.mark.parametrize("module, expected", [
    ("xroute.errors", 0), ("xroute.testcases.registry", 1), ("xroute.design", 2), ("xroute.pipeline", 2),
    ("xroute.policies.rl.models", 3), ("xroute.testcases.regions", 3), ("xroute.envs.core", 4),
    ("xroute.cli.commands.route", 5),
])
def test_layers_of_known_modules(module: str, expected: int) -> None:
    assert layer(module) == expected


def test_no_generic_top_level_packages_importable() -> None:
    """One import root, xroute: the folders it is built from are not importable by their own
    names from the installed (or editable) package's location."""
    site = Path(importlib.import_module(ROOT).__file__).resolve().parent.parent
    assert not any((site / name / "__init__.py").exists() for name in ("policies", "testcases", "cli", "envs"))
