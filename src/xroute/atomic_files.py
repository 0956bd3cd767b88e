"""Files written whole or not at all, and the process ids in temporary names.

Every file the package writes goes through :func:`atomic_write_bytes` (or
:func:`atomic_write_text`): the data goes to a temporary file ``.NAME.PID.XXXXXXXX.tmp`` in the
same folder, is flushed to disk, then renamed over ``NAME`` (``os.replace``), so an interrupted
run leaves the old file or the new one, never a part. A killed run's temporaries carry its
process id; :func:`pid_alive` tells whether that process is gone
(:func:`xroute.outputs.clean_stale_temporaries` removes them then).
"""

from __future__ import annotations

import os
import uuid
from pathlib import Path


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
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        check_output(path)  # again: something may have appeared there meanwhile
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
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
