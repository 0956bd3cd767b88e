"""Guards around calls into a user's net-order policy: failures named, hangs ended.

* :func:`call_policy` runs ``policy.order`` for the router. A ``SystemExit``, ``GeneratorExit`` or
  any other ``BaseException`` that is not an ``Exception`` raised inside it becomes a
  :class:`PolicyCallError` (a policy cannot end the run with a "success", nor slip past the
  command's error handling); an ``Exception`` propagates unchanged (library callers see their own
  exception) but is tagged with where in the policy it was raised, so the command line prints one
  line ``error: <policy file>:<line>: policy '<name>' raised <Type>: <message>`` (see
  :func:`policy_failure_line`; the traceback only with ``--debug``). A message whose ``__str__``
  fails is shown as ``<Type: unprintable>``. Only ``KeyboardInterrupt`` passes as it is.
* :func:`kept_cwd` puts the working directory back after user code ran: a policy that calls
  ``os.chdir`` cannot move where the run reads and writes. :func:`policy_code` adds the guards of
  :mod:`xroute.policy_process` (prints to stderr, streams put back, forks and ``os._exit`` kept
  from ending the run quietly); every entry into a policy's code goes through it.
* Every failure names the policy's file: :func:`policy_source` is the file that defines it (a
  model file for ONNX and JSON policies), :func:`policy_where` that file and the line of the
  method (for a wrong return value).
* :class:`Watchdog` enforces a per-call time limit (``policy.call_timeout`` in the config,
  :data:`DEFAULT_CALL_TIMEOUT` by default). When a call runs past it, the watchdog raises
  :class:`PolicyTimeout` inside the policy's thread (delivered at the policy's next Python
  instruction); a call still stuck :data:`GRACE_SECONDS` later (blocked in C code, e.g. a long
  ``time.sleep``) ends the process with the same error line and exit status 2. Nothing has been
  written yet at that point: the outputs are written only after routing.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import sys
import threading
import time
import traceback
from pathlib import Path
from typing import Any, Iterator

from xroute.errors import safe_text
from xroute.net_order import PolicyError
from xroute.policy_process import PolicyExit, real_exit, user_code

DEFAULT_CALL_TIMEOUT = 300.0  # seconds per order() call: generous (the built-in policies take milliseconds)
GRACE_SECONDS = 5.0  # after the limit, before a call blocked outside Python ends the process
EXIT_USER_ERROR = 2
_TAG = "_xroute_policy_failure"


class PolicyCallError(PolicyError):
    """A policy's order() failed in a way that must end the run (SystemExit, time limit)."""


class PolicyTimeout(PolicyCallError):
    """A policy's order() call ran past the time limit."""


def stray_threads() -> list[threading.Thread]:
    """Threads still running that are neither the main thread nor daemons (a user's policy may
    start one and leave it running)."""
    main = threading.main_thread()
    return [t for t in threading.enumerate() if t is not main and not t.daemon and t.is_alive()]


def policy_source(policy: Any) -> str | None:
    """The file that defines a policy: its ``source`` (a model file: ONNX, JSON) when it has one,
    else the file of its order (or plan) function; None for built-ins and C++."""
    source = getattr(policy, "source", None)
    if isinstance(source, str) and source:
        return source
    code = _method_code(policy)
    return code.co_filename if code is not None else None


def _method_code(policy: Any) -> Any:
    fn = getattr(policy, "fn", None) or getattr(type(policy), "order", None) or getattr(type(policy), "plan", None)
    return getattr(fn, "__code__", None)


def policy_where(policy: Any) -> str:
    """``<file>:<line>`` of a Python policy's function, ``<file>`` of a model; "" for built-ins."""
    source = policy_source(policy)
    if source is None:
        return ""
    code = _method_code(policy)
    if code is not None and code.co_filename == source:
        return f"{source}:{code.co_firstlineno}"
    return source


@contextlib.contextmanager
def policy_code(policy: Any, method: str) -> Iterator[None]:
    """Runs the block (``policy``'s ``method``, or ``"load"``) under :func:`kept_cwd` and the guards of
    :mod:`xroute.policy_process`."""
    with kept_cwd(), user_code(safe_text(getattr(policy, "name", "policy")), policy_source(policy), method):
        yield


def _where(exc: BaseException, source: str | None) -> tuple[str, int]:
    """(file, line) of the innermost frame of ``exc`` in the policy's file; the file alone when no
    frame is in it (a model file), else the innermost frame."""
    frames = traceback.extract_tb(exc.__traceback__)
    if source is not None:
        try:
            src = str(Path(source).resolve())
            for fr in reversed(frames):
                if str(Path(fr.filename).resolve()) == src:
                    return (fr.filename, fr.lineno or 0)
        except OSError:
            pass
        return (source, 0)
    if not frames:
        return ("policy", 0)
    fr = frames[-1]
    return (fr.filename, fr.lineno or 0)


def tag_failure(exc: BaseException, policy: Any) -> None:
    """Marks ``exc`` as raised by ``policy`` with the file and line where it was raised."""
    file, line = _where(exc, policy_source(policy))
    try:
        setattr(exc, _TAG, (str(getattr(policy, "name", "policy")), file, line))
    except (AttributeError, TypeError):  # exceptions without a __dict__
        pass


def policy_failure_line(exc: BaseException) -> str | None:
    """``<file>:<line>: policy '<name>' raised <Type>: <message>`` for an exception tagged by
    :func:`call_policy`; None for any other exception."""
    tag = getattr(exc, _TAG, None)
    if tag is None:
        return None
    name, file, line = tag
    return _raised_line(exc, name, file, line)


def _raised_line(exc: BaseException, name: str, file: str, line: int) -> str:
    where = f"{file}:{line}" if line else file
    message = safe_text(exc)
    return f"{where}: policy '{name}' raised {type(exc).__name__}" + (f": {message}" if message else "")


def user_failure(exc: BaseException, policy: Any, method: str) -> BaseException:
    """What to raise for ``exc``, raised by ``policy``'s ``method`` (user code): KeyboardInterrupt
    and PolicyError as they are; SystemExit and any other BaseException that is not an Exception
    (GeneratorExit, a user's subclass) as a PolicyCallError naming the file and line; an Exception
    as it is, tagged for :func:`policy_failure_line`."""
    if isinstance(exc, (KeyboardInterrupt, PolicyError)):
        return exc
    name = safe_text(getattr(policy, "name", "policy"))
    if isinstance(exc, Exception):
        tag_failure(exc, policy)
        return exc
    file, line = _where(exc, policy_source(policy))
    if isinstance(exc, (SystemExit, PolicyExit)):
        where = f"{file}:{line}" if line else file
        call = "os._exit" if isinstance(exc, PolicyExit) else "sys.exit"
        return PolicyCallError(f"{where}: policy '{name}' called {call}({safe_text(exc.code)}) inside {method}(): "
                               "a policy cannot end the run")
    return PolicyCallError(_raised_line(exc, name, file, line) + f" inside {method}()")


@contextlib.contextmanager
def kept_cwd() -> Iterator[None]:
    """Runs the block (user code) and puts the working directory back as it was, even if the block
    called ``os.chdir``: relative paths of the run keep meaning what the command printed."""
    try:
        fd: int | None = os.open(".", os.O_RDONLY | getattr(os, "O_DIRECTORY", 0) | getattr(os, "O_CLOEXEC", 0))
        saved = None
    except OSError:  # a folder we may not read: go back by name
        fd, saved = None, os.getcwd()
    try:
        yield
    finally:
        try:
            if fd is not None:
                os.fchdir(fd)
            else:
                os.chdir(saved)  # type: ignore[arg-type]
        finally:
            if fd is not None:
                os.close(fd)


class Watchdog:
    """Ends policy calls that run longer than ``limit`` seconds (one watchdog per routing run)."""

    def __init__(self, limit: float, policy: Any) -> None:
        self.limit = float(limit)
        if not 0 < self.limit < float("inf"):  # NaN or infinity would never fire
            raise ValueError(f"policy call time limit must be a finite number of seconds > 0, got {limit!r}")
        self.policy = policy
        self.name = str(getattr(policy, "name", "policy"))
        self._lock = threading.Lock()
        self._calls: dict[int, float] = {}  # thread id -> start (monotonic)
        self._fired: dict[int, float] = {}  # thread id -> when the timeout was raised there
        self._thread: threading.Thread | None = None
        self._stop = threading.Event()
        message = (f"policy '{self.name}' ({policy_source(policy) or 'built-in'}): an order() call ran longer than "
                   f"{self.limit:g} s (policy.call_timeout)")
        self.message = message

        class _Timeout(PolicyTimeout):
            def __init__(self, *args: Any) -> None:
                super().__init__(message)

        self._timeout_class = _Timeout

    def begin(self) -> None:
        with self._lock:
            self._calls[threading.get_ident()] = time.monotonic()
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name="xroute-policy-watchdog", daemon=True)
                self._thread.start()

    def end(self) -> None:
        tid = threading.get_ident()
        with self._lock:
            self._calls.pop(tid, None)
            fired = self._fired.pop(tid, None)
        if fired is not None:
            ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(tid), None)  # not delivered yet: cancel
            raise self._timeout_class()

    def close(self) -> None:
        self._stop.set()

    def _run(self) -> None:
        tick = min(0.1, max(self.limit / 10, 0.005))
        while not self._stop.wait(tick):
            now = time.monotonic()
            with self._lock:
                for tid, start in list(self._calls.items()):
                    if tid in self._fired:
                        if now - self._fired[tid] > GRACE_SECONDS:
                            sys.stderr.write(f"error: {self.message}; it did not stop, ending the run\n")
                            sys.stderr.flush()
                            real_exit(EXIT_USER_ERROR)
                    elif now - start > self.limit:
                        self._fired[tid] = now
                        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(tid),
                                                                   ctypes.py_object(self._timeout_class))


def call_policy(policy: Any, region: Any, features: Any, watchdog: Watchdog | None, method: str = "order") -> Any:
    """``policy.order(region, features)`` (or ``policy.next_net`` with ``method="next_net"``) under the
    guards described in the module doc."""
    if watchdog is not None:
        watchdog.begin()
    try:
        try:
            with policy_code(policy, method):
                return getattr(policy, method)(region, features)
        finally:
            if watchdog is not None:
                watchdog.end()
    except PolicyTimeout:
        raise
    except BaseException as exc:  # noqa: BLE001 - the user's code: named, see user_failure
        failure = user_failure(exc, policy, method)
        if failure is exc:
            raise
        raise failure from None
