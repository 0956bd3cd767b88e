"""Files of the right kind: inputs that are regular files, outputs that replace only regular files.

A FIFO given where a file is read would block the run forever, and a device, FIFO, socket or
folder at an output path must never be replaced by the file the run writes (as root that would
remove a device node). Every path the package reads by name or writes goes through these checks:

* :func:`check_input` (and :func:`read_regular_bytes`, which opens without blocking and checks the
  opened file itself) refuses anything but a regular file (a link to one is fine);
* :func:`check_output` refuses an existing output path that is neither a regular file nor a link
  (a link is replaced, never what it points to);
* :func:`path_text` refuses a name that is not valid UTF-8 (bytes the terminal passed through as
  surrogates): the engine and the JSON outputs take text.

Each raises :class:`~xroute.errors.InputError` naming the path, shown printable.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from xroute.errors import InputError

PathLike = str | os.PathLike[str]

_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"), (stat.S_ISLNK, "a link"))


def kind(mode: int) -> str:
    """What a file of ``mode`` is, in words ("a FIFO", "a folder", ...)."""
    for test, words in _KINDS:
        if test(mode):
            return words
    return "a regular file" if stat.S_ISREG(mode) else "a special file"


def shown(path: PathLike) -> str:
    """``path`` as printable text: bytes that are not UTF-8 appear as ``\\xNN``."""
    raw = os.fsencode(path)
    return raw.decode("utf-8", "backslashreplace")


def path_text(path: PathLike, what: str = "file") -> str:
    """``path`` as text; InputError when its name is not valid UTF-8."""
    text = os.fspath(path)
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise InputError(f"{what} name is not valid UTF-8 text: rename it", shown(path), 0) from None
    return text


def check_input(path: PathLike, what: str = "input file") -> str:
    """``path`` (as text) if it names a regular file (or a link to one); InputError otherwise."""
    text = path_text(path, what)
    try:
        mode = os.stat(text).st_mode
    except FileNotFoundError:
        raise InputError(f"{what} not found", text, 0) from None
    except OSError as exc:
        raise InputError(f"{what} cannot be read: {exc.strerror or exc}", text, 0) from None
    if not stat.S_ISREG(mode):
        raise InputError(f"{what} is {kind(mode)}, not a regular file", text, 0)
    return text


def read_regular_bytes(path: PathLike, limit: int | None = None, what: str = "input file") -> bytes:
    """The bytes of a regular file (at most ``limit + 1`` when ``limit`` is given: the caller tells
    "too large"). The file is opened without blocking and checked after opening, so a FIFO
    swapped in at the last moment is refused too. Raises InputError."""
    text = check_input(path, what)
    try:
        fd = os.open(text, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise InputError(f"{what} cannot be read: {exc.strerror or exc}", text, 0) from None
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            raise InputError(f"{what} is {kind(mode)}, not a regular file", text, 0)
        os.set_blocking(fd, True)
        with os.fdopen(fd, "rb", closefd=False) as f:
            return f.read() if limit is None else f.read(limit + 1)
    except OSError as exc:
        raise InputError(f"{what} cannot be read: {exc.strerror or exc}", text, 0) from None
    finally:
        os.close(fd)


def check_output(path: PathLike, what: str = "output file") -> Path:
    """``path`` if writing a file there replaces nothing but a regular file or a link (or nothing);
    InputError when a folder, FIFO, device or socket is there."""
    text = path_text(path, what)
    try:
        mode = os.lstat(text).st_mode
    except FileNotFoundError:
        return Path(text)
    except OSError as exc:
        raise InputError(f"{what} cannot be written: {exc.strerror or exc}", text, 0) from None
    if not (stat.S_ISREG(mode) or stat.S_ISLNK(mode)):
        raise InputError(f"{what} exists and is {kind(mode)}: refusing to replace it", text, 0)
    return Path(text)


def make_output_folder(path: PathLike, what: str = "output folder") -> Path:
    """Creates the folder ``path`` (and its parents) unless it exists; InputError when something
    other than a folder (or a link to one) is there."""
    text = path_text(path, what)
    try:
        mode = os.stat(text).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as exc:
        raise InputError(f"{what} cannot be used: {exc.strerror or exc}", text, 0) from None
    if mode is not None and not stat.S_ISDIR(mode):
        raise InputError(f"{what} exists and is {kind(mode)}, not a folder", text, 0)
    Path(text).mkdir(parents=True, exist_ok=True)
    return Path(text)
