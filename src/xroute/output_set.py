"""One run, one consistent set of output files.

A run writes its files (routed DEF, DRC report, metrics JSON) into a fresh staging folder
inside the output folder, ``.xroute-stage.<pid>.<hex>`` (created exclusively), checks them
there, and only then publishes them (:func:`publish`):

1. a note ``publishing.json`` in the staging folder names the final files and the SHA-256 of
   each new one;
2. each staged file is renamed over its final name (``os.replace``: each file whole), the
   metrics JSON last; the metrics JSON is the run's manifest: it holds the run id and the
   SHA-256 of the DEF and DRC report it describes (``"run"``);
3. the staging folder is removed.

A run killed before step 1 leaves only its staging folder. One killed during step 2 leaves the
staging folder with its note; :func:`clean_leftovers`, called at the start of every run in that
folder, removes staging folders of dead processes and, when their note shows that some but not
all files had been replaced (a mix of two runs), removes those files too: a set is whole (old or
new) or absent.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import uuid
from pathlib import Path
from typing import Iterable

from xroute.atomic_files import atomic_write_text, pid_alive
from xroute.safe_paths import inside

STAGE_PREFIX = ".xroute-stage."
NOTE = "publishing.json"


def make_stage(out_dir: Path) -> Path:
    """A new, empty staging folder inside ``out_dir`` (never an existing one, never a link)."""
    for _ in range(100):
        stage = out_dir / f"{STAGE_PREFIX}{os.getpid()}.{uuid.uuid4().hex[:8]}"
        try:
            stage.mkdir(mode=0o755)
        except FileExistsError:
            continue
        return stage
    raise FileExistsError(f"cannot create a staging folder in {out_dir}")


def file_sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def publish(out_dir: Path, stage: Path, files: Iterable[tuple[Path, Path]]) -> None:
    """Moves each staged ``(source, final)`` file into place, in order (the manifest last), as
    described in the module doc; every final path must lie inside ``out_dir``."""
    from xroute.regular_files import check_output

    pairs = [(Path(src), check_output(inside(out_dir, dst))) for src, dst in files]  # all checked before the first rename
    note = {"files": [dst.name for _, dst in pairs], "sha256": {dst.name: file_sha256(src) for src, dst in pairs}}
    atomic_write_text(stage / NOTE, json.dumps(note, indent=2) + "\n")
    for src, dst in pairs:
        os.replace(src, dst)


def _clean_partial_publish(out_dir: Path, stage: Path) -> list[Path]:
    """The files of an interrupted publish, removed when only some of them had been replaced."""
    try:
        note = json.loads((stage / NOTE).read_text(encoding="utf-8"))
        names = [n for n in note["files"] if isinstance(n, str)]
        hashes = dict(note["sha256"])
    except (OSError, ValueError, KeyError, TypeError):
        return []
    targets = []
    for n in names:
        try:
            targets.append(inside(out_dir, out_dir / n))
        except ValueError:
            continue
    new = 0
    for t in targets:
        try:
            new += bool(t.is_file() and not t.is_symlink() and file_sha256(t) == hashes.get(t.name))
        except OSError:
            pass
    if new == 0 or new == len(targets):
        return []  # the old set untouched, or the new set complete
    removed = []
    for t in targets:
        if t.is_file() or t.is_symlink():
            t.unlink()
            removed.append(t)
    return removed


def clean_leftovers(out_dir: Path) -> list[Path]:
    """Removes what killed runs left in ``out_dir``: staging folders of dead processes, and the
    files of a publish that was cut between its renames. Returns the removed paths."""
    removed: list[Path] = []
    if not out_dir.is_dir():
        return removed
    for p in list(out_dir.iterdir()):
        if p.name.startswith(STAGE_PREFIX) and p.is_dir() and not p.is_symlink():
            pid_text = p.name[len(STAGE_PREFIX):].partition(".")[0]
            if pid_text.isdigit() and int(pid_text) != os.getpid() and not pid_alive(int(pid_text)):
                removed += _clean_partial_publish(out_dir, p)
                shutil.rmtree(p, ignore_errors=True)
                removed.append(p)
    return removed


def new_run_id() -> str:
    return uuid.uuid4().hex
