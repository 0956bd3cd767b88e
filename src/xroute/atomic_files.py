"""Files written whole or not at all, and how a later run tells a killed run's temporaries.

Every file the package writes goes through :func:`atomic_write_bytes` (or
:func:`atomic_write_text`): the data goes to a temporary file ``.NAME.PID.XXXXXXXX.tmp`` in the
same folder, is flushed to disk, then renamed over ``NAME`` (:func:`replace`), so an interrupted
run leaves the old file or the new one, never a part.

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

import itertools
import os
import signal
import time
import uuid
from pathlib import Path
from typing import Iterator

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
