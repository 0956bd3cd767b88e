"""Files written whole or not at all, and how a later run tells a killed run's temporaries.

Every file the package writes goes through :func:`atomic_write_bytes`: the data goes to a
temporary file ``.NAME.PID.XXXXXXXX.tmp`` in the same folder, is flushed to disk, then renamed
over ``NAME`` (:func:`replace`), so an interrupted run leaves the old file or the new one, never a
part. The other writers feed it: :func:`atomic_write_text` (UTF-8 text), :func:`atomic_write_from`
(whatever a serialiser such as ``torch.save`` or ``np.savez_compressed`` writes into a file
object), :func:`atomic_copy` (a copy of another file) and :class:`AtomicLog` (a log of lines that
grows while a run works, rewritten whole). The compiled engine's writers (DEF, DRC report, guide
file: ``engine_cpp/io/atomic_file.cpp``) publish their files the same way.

Whose temporary is it? The writer holds an exclusive ``flock`` on each temporary (file or staging
folder, :func:`hold_lock`) for as long as it works on it; the kernel drops the lock when the
process ends, however it ends (SIGKILL included). :func:`owner_gone` therefore asks the lock, not
the process id in the name, which may belong to another process by now (ids are reused, and a
container sees other ids); the id only spares a temporary created an instant ago, before its
lock was taken (:data:`LOCK_GRACE_SECONDS`). :func:`xroute.outputs.clean_stale_temporaries`
removes what :func:`owner_gone` says is left over.

Test hook: with ``XROUTE_TEST_KILL_AT=N`` in the environment, the process kills itself with
SIGKILL just before its N-th :func:`replace` (1-based): the kill tests stop a run at every rename.
"""

from __future__ import annotations

import io
import itertools
import os
import signal
import time
import uuid
from pathlib import Path
from typing import IO, Any, Callable, Iterator

try:
    import fcntl
except ImportError:  # not POSIX: only the process ids tell
    fcntl = None  # type: ignore[assignment]

KILL_AT_VARIABLE = "XROUTE_TEST_KILL_AT"
LOCK_GRACE_SECONDS = 10.0  # a temporary younger than this, of a live process id, may not be locked yet
_renames: Iterator[int] = itertools.count(1)  # renames of this process, for the test hook only


def replace(src: str | os.PathLike[str], dst: str | os.PathLike[str]) -> None:
    """``os.replace(src, dst)``: every rename that publishes an output goes through here (see the
    test hook in the module doc)."""
    at = os.environ.get(KILL_AT_VARIABLE)
    if at is not None and next(_renames) == int(at):
        os.kill(os.getpid(), signal.SIGKILL)
    os.replace(src, dst)


def hold_lock(fd: int) -> None:
    """Takes the exclusive lock that marks a temporary (file or folder, opened as ``fd``) as in use
    by this process; it lasts until ``fd`` is closed or the process ends."""
    if fcntl is not None:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)


def open_locked_folder(path: str | os.PathLike[str]) -> int:
    """A descriptor of the folder ``path`` holding its lock (:func:`hold_lock`); close it when done."""
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        hold_lock(fd)
    except BaseException:
        os.close(fd)
        raise
    return fd


def owner_gone(path: str | os.PathLike[str], pid: int | None) -> bool:
    """Whether the run that made the temporary ``path`` (a file or a staging folder; ``pid`` the
    process id in its name) has ended: no process holds its lock, and it is not one created an
    instant ago by a live process (see the module doc)."""
    if pid == os.getpid():
        return False
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError:
        return False
    try:
        if fcntl is not None:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                return False  # its writer is at work
            except OSError:
                return pid is not None and not pid_alive(pid)
            if pid is None or not pid_alive(pid):
                return True
            return time.time() - os.fstat(fd).st_mtime > LOCK_GRACE_SECONDS
        return pid is not None and not pid_alive(pid)
    finally:
        os.close(fd)


def atomic_write_text(path: str | os.PathLike[str], text: str) -> None:
    """Writes ``text`` (UTF-8) to ``path`` atomically (see :func:`atomic_write_bytes`)."""
    atomic_write_bytes(path, text.encode("utf-8"))


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Writes ``data`` to ``path`` through a temporary file in the same folder and ``os.replace``
    (the file gets the usual permissions: 0666 less the umask); the temporary file is created
    exclusively (never an existing file or link) and removed if anything fails. Only a regular
    file or a link is ever replaced: a folder, FIFO, device or socket at ``path`` is an InputError
    (:func:`xroute.regular_files.check_output`)."""
    from xroute.regular_files import check_output

    path = check_output(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")
    try:
        with open(tmp, "xb") as f:
            hold_lock(f.fileno())  # in use until renamed (owner_gone)
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
            check_output(path)  # again: something may have appeared there meanwhile
            replace(tmp, path)
    except BaseException as exc:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError) and exc.filename is None:  # a write or flush (ENOSPC): name the file
            raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from exc
        raise


def atomic_write_from(path: str | os.PathLike[str], write: Callable[[IO[bytes]], Any]) -> None:
    """Writes to ``path`` atomically what ``write(file)`` writes into a binary file object (e.g.
    ``lambda f: torch.save(state, f)``): it is serialised in memory first, then published by
    :func:`atomic_write_bytes`."""
    buffer = io.BytesIO()
    write(buffer)
    atomic_write_bytes(path, buffer.getvalue())


def atomic_copy(src: str | os.PathLike[str], dst: str | os.PathLike[str]) -> None:
    """Copies the file ``src`` to ``dst`` atomically (:func:`atomic_write_bytes`)."""
    atomic_write_bytes(dst, Path(src).read_bytes())


class AtomicLog:
    """A text file of lines that grows while a run works (a training run's ``metrics.jsonl``) and is
    whole at every moment: each publication rewrites the whole file through :func:`atomic_write_text`.
    It is published when opened (empty), after a line when ``interval`` seconds have passed since the
    last publication, and on :meth:`close` (which a ``with`` block calls, also when it raises). So a
    reader, or a run killed at any instant, finds every line of some moment whole, at most
    ``interval`` seconds behind, and the rewriting costs one file a second however fast lines come."""

    def __init__(self, path: str | os.PathLike[str], interval: float = 1.0) -> None:
        self.path = Path(path)
        self.interval = interval  # seconds between publications at most, while lines come
        self._lines: list[str] = []
        self._published = 0  # lines in the file
        self._at = time.monotonic()
        self.flush()

    def write_line(self, line: str) -> None:
        """Appends ``line`` (without its line break); published now or within ``interval`` seconds."""
        self._lines.append(line + "\n")
        if time.monotonic() - self._at >= self.interval:
            self.flush()

    def flush(self) -> None:
        """Publishes every line written so far."""
        atomic_write_text(self.path, "".join(self._lines))
        self._published = len(self._lines)
        self._at = time.monotonic()

    def close(self) -> None:
        if self._published != len(self._lines):
            self.flush()

    def __enter__(self) -> AtomicLog:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def pid_alive(pid: int) -> bool:
    """Whether process ``pid`` exists (one of another user counts; an impossible id does not
    count as gone)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True
