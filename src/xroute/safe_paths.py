"""Output names that cannot escape the output folder.

A DEF's ``DESIGN`` name is text from the input file: ``DESIGN ../escaped ;`` or
``DESIGN /tmp/x ;`` must not choose where files go. :func:`safe_stem` turns any name into a
plain file stem (letters, digits, ``-``, ``_``, ``.``; no leading dot; bounded length), and
:func:`inside` checks that a path lies inside the output folder (after resolving ``..`` and
symlinks of the folders on the way) before anything is written there.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from xroute.errors import XrouteError

MAX_STEM = 100  # characters kept of a name (a hash of the whole name follows when cut)


class OutputPathError(XrouteError, ValueError):
    """An output path that would lie outside the output folder."""


def safe_stem(name: str | None, fallback: str = "design") -> str:
    """A file stem made from ``name``: every character other than a letter, digit, ``-``, ``_``
    or ``.`` becomes ``_``; leading dots and ``_`` are dropped (no hidden files, no ``..``); a name
    that was changed or cut gets a short hash of the original, so two different names keep
    different stems. Empty results give ``fallback``."""
    text = name or ""
    kept = "".join(c if (c.isascii() and (c.isalnum() or c in "-_.")) else "_" for c in text)
    kept = kept.lstrip("._")
    while ".." in kept:
        kept = kept.replace("..", "._")
    changed = kept != text
    if len(kept) > MAX_STEM:
        kept, changed = kept[:MAX_STEM], True
    if not kept:
        kept, changed = fallback, bool(text)
    if changed and text:
        kept += "_" + hashlib.sha1(text.encode("utf-8", "surrogateescape")).hexdigest()[:8]
    return kept


def inside(folder: str | os.PathLike[str], path: str | os.PathLike[str]) -> Path:
    """``path`` if it lies inside ``folder`` (both resolved; the file itself need not exist and is
    not followed if it is a link); raises :class:`OutputPathError` otherwise."""
    root = Path(folder).resolve()
    p = Path(path)
    parent = p.parent.resolve()
    target = parent / p.name
    if p.name in ("", ".", "..") or (parent != root and root not in parent.parents):
        raise OutputPathError(f"output path {path} lies outside the output folder {folder}")
    return target


def output_file(folder: str | os.PathLike[str], stem: str, suffix: str) -> Path:
    """``folder/<safe stem><suffix>``, checked to lie inside ``folder``."""
    return inside(folder, Path(folder) / f"{safe_stem(stem)}{suffix}")
