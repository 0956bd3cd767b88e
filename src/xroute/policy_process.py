"""What a policy's code may do to the process it runs in, and how the run stays whole.

Policies (``.py`` files, ONNX models, schedule files) run inside the xroute process. Around every
piece of their code - loading a file, each ``order()``, ``next_net()`` or ``plan()`` call
(:func:`user_code`, entered by :mod:`xroute.policy_guard`):

* their output goes to stderr: ``print`` and writes to file descriptor 1 (by C code too) land on
  the standard error stream while the policy runs, so stdout holds only what the command prints
  (``--json`` stays JSON);
* streams they close or replace are put back: file descriptors 1 and 2, ``sys.stdout`` and
  ``sys.stderr`` are what they were before, whatever the policy closed;
* a fork does not continue the run: a child the policy forked that returns into xroute (instead
  of ending itself) is ended there, quietly, with status 2. It would otherwise route on beside
  its parent and write the same outputs, and, forked from one of the engine's worker threads,
  die in Python's thread-state setup ("Fatal Python error: init_threadstate") the next time the
  engine called back;
* ``os._exit`` ends nothing quietly (:func:`install_exit_guard`, installed by the command line and
  in a batch's workers): inside a policy call it raises :class:`PolicyExit` (reported as one line
  naming the file and line, status 2); from elsewhere in the process (a thread the policy started,
  an exit handler) it prints one ``error:`` line naming the caller's file and line and ends the
  process with status 2 - never 0, since the outputs were not written.

Why a guard and not a supervising parent process: a parent would also see a policy that reaches
libc's ``exit`` through ctypes, but every command would run as two processes, the parent would
have to forward signals, and a parent killed with SIGKILL would leave the child routing on. The
guard covers what Python code can call (``os._exit``, ``posix._exit``, ``sys.exit``); a policy
that calls into libc directly is outside it.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
import threading
from dataclasses import dataclass
from types import FrameType
from typing import Any, Iterator, NoReturn

EXIT_POLICY_FAILURE = 2
_REAL_EXIT = os._exit  # captured before install_exit_guard replaces it


class PolicyExit(BaseException):
    """Raised by ``os._exit(code)`` called inside a policy call (see the module doc)."""

    def __init__(self, code: object) -> None:
        super().__init__(code)
        self.code = code


@dataclass
class _Call:
    name: str  # the policy's name
    source: str  # its file ("" when unknown)
    method: str  # "order", "next_net", "plan", "load"
    pid: int
    thread: int


_calls: list[_Call] = []  # policy code running now (one at a time: the engine serialises the calls)
_sources: list[str] = []  # every policy file whose code has run in this process, in order
_guard: dict[str, int | None] = {"pid": None, "stderr": None}  # where the exit guard was installed


def real_exit(status: int) -> NoReturn:
    """The process's own ``os._exit``, whatever the guard did to ``os._exit``."""
    _REAL_EXIT(status)


def _flush(stream: Any) -> None:
    try:
        stream.flush()
    except (OSError, ValueError, AttributeError):
        pass


_LIBC: list[Any] = []  # the C library, loaded once: its stdio buffers are flushed like Python's


def _flush_c_stdio() -> None:
    """``fflush(NULL)``: what C code (``printf``, ``puts``) left in stdio's buffers goes out now,
    while descriptor 1 still points where the policy's output belongs (not at the process's end)."""
    try:
        if not _LIBC:
            import ctypes

            _LIBC.append(ctypes.CDLL(None))
        _LIBC[0].fflush(None)
    except (OSError, AttributeError):  # no C library to reach: nothing buffered there either
        pass


def _dup(fd: int) -> int | None:
    try:
        return os.dup(fd)
    except OSError:
        return None


def _reopened(fd: int, old: Any, line_buffering: bool) -> Any:
    """A text stream on ``fd`` like ``old`` (which was closed)."""
    encoding = getattr(old, "encoding", None) or "utf-8"
    errors = getattr(old, "errors", None) or "backslashreplace"
    try:
        raw = io.FileIO(fd, "w", closefd=False)
    except (OSError, ValueError):
        return old
    return io.TextIOWrapper(io.BufferedWriter(raw), encoding=encoding, errors=errors, line_buffering=line_buffering)


@contextlib.contextmanager
def output_to_stderr() -> Iterator[None]:
    """Runs the block with file descriptor 1 and ``sys.stdout`` writing to stderr; afterwards both
    standard streams (descriptors and objects) are as they were, even if the block closed them."""
    out, err = sys.stdout, sys.stderr
    _flush(out)
    _flush(err)
    saved_out, saved_err = _dup(1), _dup(2)
    redirected = saved_out is not None and saved_err is not None
    if redirected:
        os.dup2(saved_err, 1)  # type: ignore[arg-type]
        if err is not None:
            sys.stdout = err
    try:
        yield
    finally:
        _flush(sys.stdout)
        _flush(sys.stderr)
        _flush_c_stdio()
        sys.stdout, sys.stderr = out, err
        for fd, saved in ((1, saved_out), (2, saved_err)):
            if saved is not None:
                os.dup2(saved, fd)
                os.close(saved)
        if getattr(sys.stdout, "closed", False):
            sys.stdout = _reopened(1, out, line_buffering=False)
        if getattr(sys.stderr, "closed", False):
            sys.stderr = _reopened(2, err, line_buffering=True)


@contextlib.contextmanager
def user_code(name: str, source: str | None, method: str) -> Iterator[None]:
    """Runs the block (a policy's code: loading it, or one call of ``method``) under the guards of
    the module doc."""
    pid = os.getpid()
    _calls.append(_Call(name, source or "", method, pid, threading.get_ident()))
    if source and source not in _sources:
        _sources.append(source)
    try:
        with output_to_stderr():
            try:
                yield
            finally:
                if os.getpid() != pid:  # a child the policy forked came back here: it ends now
                    _flush(sys.stdout)
                    _flush(sys.stderr)
                    _REAL_EXIT(EXIT_POLICY_FAILURE)
    finally:
        _calls.pop()


def write_error(line: str) -> None:
    """Writes ``line`` (one ``error: ...`` line) on stderr; when stderr is closed, on the copy of
    it the exit guard kept, if any."""
    data = (line.rstrip("\n") + "\n").encode("utf-8", "backslashreplace")
    for fd in (2, _guard["stderr"]):
        if fd is None:
            continue
        try:
            _flush(sys.stderr)
            os.write(fd, data)
            return
        except OSError:
            continue


def _exit_message(status: object, frame: FrameType | None) -> str:
    """The error line for ``os._exit(status)`` called outside a policy call, from ``frame``: the
    innermost frame in a policy file that ran here if there is one, else the caller with the
    policy files named."""
    caller, wanted = frame, {os.path.realpath(s) for s in _sources}
    while frame is not None and os.path.realpath(frame.f_code.co_filename) not in wanted:
        frame = frame.f_back
    at = f"{caller.f_code.co_filename}:{caller.f_lineno}" if caller is not None else "?"
    if frame is not None:
        where, how = f"{frame.f_code.co_filename}:{frame.f_lineno}", "by a policy's thread or exit handler?"
    elif _sources:
        where, how = _sources[-1], f"by a thread or exit handler of this policy?, at {at}"
    else:
        where, how = at, "by a policy's thread or exit handler?"
    return (f"error: {where}: os._exit({status!r}) called before xroute finished ({how}): the run did not finish "
            "and its outputs were not written")


def install_exit_guard() -> None:
    """Replaces ``os._exit`` (and ``posix._exit``) in this process as the module doc says; keeps a
    copy of stderr for :func:`write_error`. Idempotent."""
    if _guard["pid"] == os.getpid():
        return
    _guard["pid"] = os.getpid()
    try:
        _guard["stderr"] = os.dup(2)  # not inherited by children (os.dup's default)
    except OSError:
        _guard["stderr"] = None

    def guarded_exit(status: object = 0) -> NoReturn:
        here, tid = os.getpid(), threading.get_ident()
        call = _calls[-1] if _calls else None
        if call is not None and call.pid == here and call.thread == tid:
            raise PolicyExit(status)
        if here != _guard["pid"]:
            _REAL_EXIT(status if isinstance(status, int) else EXIT_POLICY_FAILURE)  # a child's own end
        write_error(_exit_message(status, sys._getframe(1)))
        _REAL_EXIT(EXIT_POLICY_FAILURE)

    os._exit = guarded_exit  # type: ignore[assignment]
    posix = sys.modules.get("posix")
    if posix is not None:
        posix._exit = guarded_exit  # type: ignore[attr-defined]
