"""The compiled module's typed stub (src/xroute/_engine.pyi) is current, and every
bound function and property carries a docstring of its own.

Regenerate the stub after changing the bindings (after reinstalling):

    python -m nanobind.stubgen -m xroute._engine -o src/xroute/_engine.pyi
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from xroute import _engine

STUB = Path(__file__).resolve().parent.parent / "src" / "xroute" / "_engine.pyi"
REGENERATE = "python -m nanobind.stubgen -m xroute._engine -o src/xroute/_engine.pyi"


def test_stub_matches_compiled_module(tmp_path: Path) -> None:
    try:
        import nanobind  # noqa: F401  (stubgen ships with nanobind)
    except ImportError:
        pytest.skip("nanobind is not importable: install the 'test' extra (pip install '.[test]') to check the stub")
    out = tmp_path / "_engine.pyi"
    # Run stubgen on the package the tests import, from a folder where nothing shadows it.
    env = dict(os.environ)
    subprocess.run(
        [sys.executable, "-m", "nanobind.stubgen", "-q", "-m", "xroute._engine", "-o", str(out)],
        check=True, cwd=tmp_path, env=env, capture_output=True, text=True,
    )
    assert out.read_text() == STUB.read_text(), f"src/xroute/_engine.pyi is stale; regenerate it: {REGENERATE}"


def _own_docs(fn) -> list[str]:
    """The docstring of each overload of a nanobind function, without the signature line."""
    return [doc or "" for _sig, doc, *_ in fn.__nb_signature__]


def _public(cls_or_module) -> dict[str, object]:
    return {name: value for name, value in vars(cls_or_module).items() if not name.startswith("_")}


def test_every_database_member_has_a_docstring() -> None:
    members = _public(_engine.Database)
    assert {"counts", "design_name", "net_routing", "warning_count"} <= members.keys()
    undocumented = []
    for name, member in members.items():
        if isinstance(member, property):
            docs = [member.__doc__ or ""]
        else:
            docs = _own_docs(member)
        if not all(d.strip() for d in docs):
            undocumented.append(name)
    assert undocumented == []
    assert (_engine.Database.__doc__ or "").strip()


def test_every_module_function_has_a_docstring() -> None:
    functions = {name: f for name, f in _public(_engine).items() if hasattr(f, "__nb_signature__")}
    assert {"load", "load_lef", "route", "check_shapes"} <= set(functions)
    assert [name for name, f in functions.items() if not all(d.strip() for d in _own_docs(f))] == []
    assert (_engine.__doc__ or "").strip()
