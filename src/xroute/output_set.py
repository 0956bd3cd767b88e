"""One run, one consistent set of output files.

A run (``route``: routed DEF, DRC report, metrics JSON; ``check``: DRC report, marker database,
check JSON; ``batch``: summary.csv, summary.md, junit.xml, summary.json) writes its files into a
fresh staging folder inside the output folder,
``.xroute-stage.<pid>.<hex>`` (created exclusively and locked while in use, :func:`staging`),
checks them there, and only then publishes them (:func:`publish`):

1. a note ``publishing.json`` in the staging folder names the final files and the SHA-256 of
   each new one;
2. each staged file is renamed over its final name (each file whole), the manifest last: the
   metrics JSON (check JSON, batch summary.json) holds the run id and the SHA-256 of the other files of its set
   (``"run"``), so a reader can tell a set whose files come from different runs
   (:func:`set_problems`, used by ``report``);
3. the staging folder is removed.

A run killed before step 1 leaves only its staging folder. One killed during step 2 leaves the
staging folder with its note, the files not yet moved still in it. :func:`clean_leftovers`,
called at the start of every run in that folder, finds the staging folders whose run has ended
(their lock is free: :func:`xroute.atomic_files.owner_gone`, whatever the process id in the
name) and finishes an interrupted publish: the files still staged are moved into place, so the
folder holds the new set whole; when that cannot be done (a staged file missing or changed) the
files of the mixed set are removed. Either way a set is whole (old or new) or absent.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import uuid
from pathlib import Path
from typing import Any, Iterable, Iterator

from xroute.atomic_files import atomic_write_text, open_locked_folder, owner_gone, replace
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


@contextlib.contextmanager
def staging(out_dir: Path) -> Iterator[Path]:
    """A new staging folder in ``out_dir``, locked as in use while the block runs, removed after it.
    An error naming a file in it (a full disk while writing it) names the file's final place
    instead: the staging folder is gone by the time the error is read."""
    from xroute.errors import InputError

    stage = make_stage(out_dir)
    fd = None
    try:
        fd = open_locked_folder(stage)
        yield stage
    except InputError as exc:
        final = _final_name(exc.path, stage, out_dir)
        if final is None:
            raise
        raise InputError(exc.message, final, exc.line) from exc
    except OSError as exc:
        final = _final_name(exc.filename, stage, out_dir)
        if final is None:
            raise
        raise OSError(exc.errno, exc.strerror or str(exc), final) from exc
    finally:
        shutil.rmtree(stage, ignore_errors=True)
        if fd is not None:
            os.close(fd)


def _final_name(path: Any, stage: Path, out_dir: Path) -> str | None:
    """Where a file named by ``path`` inside ``stage`` is published (in ``out_dir``; the folder itself
    for the publishing note); None for a path elsewhere."""
    if not isinstance(path, (str, os.PathLike)) or not str(path):
        return None
    p = Path(path)
    if p.parent != stage:
        return None
    return str(out_dir) if p.name == NOTE else str(out_dir / p.name)


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
        replace(src, dst)


def _matches(path: Path, digest: Any) -> bool:
    try:
        return path.is_file() and not path.is_symlink() and file_sha256(path) == digest
    except OSError:
        return False


def _finish_partial_publish(out_dir: Path, stage: Path) -> list[Path]:
    """Completes the publish a killed run began (files still staged moved into place), or, when it
    cannot, removes the files of the mixed set. Returns the removed paths."""
    try:
        note = json.loads((stage / NOTE).read_text(encoding="utf-8"))
        names = [n for n in note["files"] if isinstance(n, str)]
        hashes = dict(note["sha256"])
    except (OSError, ValueError, KeyError, TypeError, RecursionError):
        return []
    targets = []
    for n in names:
        try:
            targets.append(inside(out_dir, out_dir / n))
        except ValueError:
            continue
    placed = [_matches(t, hashes.get(t.name)) for t in targets]
    if not any(placed) or all(placed):
        return []  # the old set untouched, or the new set complete
    staged = [_matches(stage / t.name, hashes.get(t.name)) for t in targets]
    if all(p or s for p, s in zip(placed, staged)):
        for t, p in zip(targets, placed):  # in the note's order: the manifest last
            if not p:
                replace(stage / t.name, t)
        return []
    removed = []
    for t in targets:
        if t.is_file() or t.is_symlink():
            t.unlink()
            removed.append(t)
    return removed


def clean_leftovers(out_dir: Path) -> list[Path]:
    """Removes what killed runs left in ``out_dir``: staging folders whose run has ended (after
    finishing or undoing a publish that was cut between its renames). Returns the removed paths."""
    removed: list[Path] = []
    if not out_dir.is_dir():
        return removed
    for p in list(out_dir.iterdir()):
        if p.name.startswith(STAGE_PREFIX) and p.is_dir() and not p.is_symlink():
            pid_text = p.name[len(STAGE_PREFIX):].partition(".")[0]
            if owner_gone(p, int(pid_text) if pid_text.isdigit() else None):
                removed += _finish_partial_publish(out_dir, p)
                shutil.rmtree(p, ignore_errors=True)
                removed.append(p)
    return removed


def run_record(manifest_of: dict[str, Path]) -> dict[str, Any]:
    """The ``"run"`` entry of a manifest: a new run id and the SHA-256 of each file of the set
    (``{role: staged path}``)."""
    return {"id": new_run_id(), "sha256": {role: file_sha256(p) for role, p in manifest_of.items()}}


def set_mismatches(manifest: dict[str, Any], files: dict[str, Path]) -> list[Path]:
    """The files of a manifest's set (``{role: path}``, beside it) whose SHA-256 differs from the
    one its ``"run"`` records: files of another run (absent files are not counted)."""
    run = manifest.get("run")
    if not isinstance(run, dict) or not isinstance(run.get("sha256"), dict):
        return []  # written before manifests: nothing to compare
    mismatched = []
    for role, path in files.items():
        digest = run["sha256"].get(role)
        if digest is None or not path.is_file():
            continue
        try:
            same = file_sha256(path) == digest
        except OSError:
            continue
        if not same:
            mismatched.append(path)
    return mismatched


def new_run_id() -> str:
    return uuid.uuid4().hex
