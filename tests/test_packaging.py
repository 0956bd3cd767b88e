"""The packaging facts the README relies on: the test dependency group and the test extra name
the same packages, the version has one definition, and pyproject.toml's package map puts the
repository's folders under one import root without links."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

import xroute
from pyproject_meta import REPO_ROOT, package_map, pyproject

# The package map ARCHITECTURE.md describes: each subpackage and the folder it is built from.
EXPECTED_MAP = {
    "xroute": "src/xroute",
    "xroute.cli": "cli",
    "xroute.policies": "policies",
    "xroute.envs": "envs",
    "xroute.testcases": "testcases",
}


def _name(requirement: str) -> str:
    return re.split(r"[<>=!~\[; ]", requirement, maxsplit=1)[0].lower()


def test_test_group_installs_what_the_test_extra_does() -> None:
    meta = pyproject()
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
    assert "tomli" in group  # tests/pyproject_meta.py reads pyproject.toml with it on Python 3.10


def test_version_comes_from_the_package_metadata() -> None:
    assert xroute.__version__ == pyproject()["project"]["version"]


def test_package_map_names_each_folder_once_by_its_subpackage() -> None:
    table = pyproject()["tool"]["scikit-build"]["wheel"]["packages"]
    assert {k.replace("/", "."): v for k, v in table.items()} == EXPECTED_MAP
    for key, folder in table.items():
        # scikit-build-core's rule for the table form: a key and its folder end in the same name.
        assert Path(key).name == Path(folder).name
        assert (REPO_ROOT / folder / "__init__.py").is_file()


def test_the_source_tree_has_no_links() -> None:
    """The package is the folders themselves: no symlink anywhere in them (grep finds each file once)."""
    links = [p for folder in package_map().values() for p in [folder, *folder.rglob("*")] if p.is_symlink()]
    assert links == []


@pytest.mark.parametrize("package", sorted(EXPECTED_MAP))
def test_each_subpackage_is_imported_from_its_folder(package: str) -> None:
    """An editable install imports the mapped folder's files; an installed one its copy of them,
    at the same place under xroute/ in site-packages."""
    module = importlib.import_module(package)
    where = Path(module.__file__).resolve().parent
    folder = package_map()[package].resolve()
    installed = Path(xroute.__file__).resolve().parent.joinpath(*package.split(".")[1:])
    assert where in (folder, installed)
    assert sorted(p.name for p in where.glob("*.py")) == sorted(p.name for p in folder.glob("*.py"))


def test_package_data_is_in_the_package() -> None:
    """The shipped demo and models are found through the imported packages."""
    import xroute.policies
    import xroute.testcases

    demo = Path(xroute.testcases.__file__).parent / "data" / "demo"
    assert sorted(p.suffix for p in demo.iterdir() if p.suffix) == [".def", ".guide", ".lef"]
    assert len(list((Path(xroute.policies.__file__).parent / "models").glob("*.onnx"))) >= 1
