"""Where testcases are found: the search path and the lookup by name.

A testcase folder ``<root>/<name>/`` holds ``<name>.input.lef`` and ``<name>.input.def``
and, optionally, ``<name>.input.guide`` (the contest's naming), or the plain
``<name>.lef`` / ``<name>.def`` / ``<name>.guide``. Files are read as they are: no
compressed (.gz) variants. The roots, in order, are given by :func:`search_path`; after
them, the testcases shipped inside the package (:data:`EMBEDDED_ROOT`: ``demo``, made by
``xroute.testcases.generator``), so a folder named ``demo`` on the search path wins over the shipped one.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from xroute.testcases.known import KNOWN_TESTCASES, KnownTestcase
from xroute.errors import TestcaseNotFound, did_you_mean

ENV_VAR = "XROUTE_TESTCASES"
SHARED_RELATIVE = Path("..") / "shared" / "testcases"  # relative to the project root
EMBEDDED_ROOT = Path(__file__).resolve().parent / "data"  # testcases shipped in the package
DEMO = "demo"  # the shipped testcase routed by `xroute route` without arguments

# File name patterns, tried in this order: (lef, def, guide).
_PATTERNS = (
    ("{n}.input.lef", "{n}.input.def", "{n}.input.guide"),
    ("{n}.lef", "{n}.def", "{n}.guide"),
)


@dataclass(frozen=True)
class FoundTestcase:
    """A testcase located on disk."""

    name: str
    folder: Path
    lef: Path
    def_: Path
    guide: Path | None  # None when the folder has no guide file


def _checkout_root() -> Path | None:
    """The repository root when this package runs from a source checkout, else None.

    The root is the folder that holds the ``testcases`` package and ``pyproject.toml``;
    an installed copy (in site-packages) has no such folder.
    """
    root = Path(__file__).resolve().parent.parent
    return root if (root / "pyproject.toml").is_file() else None


def _cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base).expanduser() / "xroute" / "testcases"


def search_path() -> list[Path]:
    """The folders searched for testcases, in order, without duplicates.

    1. each entry of ``$XROUTE_TESTCASES`` (``os.pathsep``-separated);
    2. ``../shared/testcases`` relative to the repository root (when running from a
       source checkout), then relative to the current directory (for an installed
       package run from the project root);
    3. the user cache ``$XDG_CACHE_HOME/xroute/testcases`` (default ``~/.cache/xroute/testcases``).
    """
    candidates = [Path(p).expanduser() for p in os.environ.get(ENV_VAR, "").split(os.pathsep) if p.strip()]
    checkout = _checkout_root()
    if checkout is not None:
        candidates.append(checkout / SHARED_RELATIVE)
    candidates.append(Path.cwd() / SHARED_RELATIVE)
    candidates.append(_cache_dir())
    out: list[Path] = []
    for path in candidates:
        resolved = path.resolve()
        if resolved not in out:
            out.append(resolved)
    return out


def _match(folder: Path, name: str) -> FoundTestcase | None:
    for lef_pat, def_pat, guide_pat in _PATTERNS:
        lef, def_ = folder / lef_pat.format(n=name), folder / def_pat.format(n=name)
        if lef.is_file() and def_.is_file():
            guide = folder / guide_pat.format(n=name)
            return FoundTestcase(name, folder, lef, def_, guide if guide.is_file() else None)
    return None


def not_found_message(name: str, roots: list[Path]) -> str:
    """One line: what was searched and how to add the testcase."""
    searched = ", ".join(str(r) for r in roots) or "(nothing)"
    names = {k.name for k in KNOWN_TESTCASES}
    for root in roots:
        try:
            names.update(p.name for p in root.iterdir() if p.is_dir())
        except OSError:
            pass
    return (
        f"testcase '{name}' not found{did_you_mean(name, names)}; searched {searched}; to add it, put "
        f"{name}/{name}.input.{{lef,def,guide}} under {SHARED_RELATIVE.as_posix()} (beside the project) "
        f"or under a folder listed in {ENV_VAR}; 'xroute testcases' lists the known ones"
    )


def find_testcase(name: str) -> FoundTestcase:
    """The first folder ``<root>/<name>`` on the search path that holds the testcase's LEF and DEF.

    Names the registry does not list are found the same way; the testcases shipped in the
    package (``demo``) come last. Raises :class:`~xroute.errors.TestcaseNotFound` naming
    the folders searched.
    """
    roots = search_path()
    if name and "/" not in name and os.sep not in name and name not in (".", ".."):
        for root in [*roots, EMBEDDED_ROOT]:
            found = _match(root / name, name)
            if found is not None:
                return found
    raise TestcaseNotFound(not_found_message(name, roots))


def locate_all() -> list[tuple[KnownTestcase, FoundTestcase | None]]:
    """Every known testcase with where it was found (None when not on the search path)."""
    out: list[tuple[KnownTestcase, FoundTestcase | None]] = []
    for known in KNOWN_TESTCASES:
        try:
            out.append((known, find_testcase(known.name)))
        except TestcaseNotFound:
            out.append((known, None))
    return out
