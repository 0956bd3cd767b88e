"""The router in a background thread, asking a Gymnasium environment for its decisions.

An environment whose episode is one routing run (:mod:`xroute.envs.ordering_evaluation`,
:mod:`xroute.envs.schedule_iteration`) cannot call the router step by step: the router calls *it*,
through a policy. :class:`EngineBridge` turns this around. :meth:`~EngineBridge.start` runs the
route in a thread; the policy's callback, in that thread, calls :meth:`~EngineBridge.ask` with what
the environment must decide on and blocks until the environment answers; the environment's
``reset`` and ``step`` call :meth:`~EngineBridge.next_event` for the next question (or the run's
end) and :meth:`~EngineBridge.answer` to let the router go on. :meth:`~EngineBridge.stop` drops an
unfinished run: every question after it is answered by :class:`Aborted`, raised in the router's
thread, and the thread is waited for.
"""

from __future__ import annotations

import queue
import threading
from typing import Any, Callable

_ABORT = object()  # the answer that ends an unfinished run


class Aborted(Exception):
    """Raised inside the router's policy call when the environment drops an unfinished run."""


class EngineBridge:
    """One routing run in a background thread and the questions it asks (see the module doc)."""

    def __init__(self, name: str) -> None:
        self.name = name  # the thread's name
        self._thread: threading.Thread | None = None
        self._events: queue.Queue = queue.Queue()
        self._answers: queue.Queue = queue.Queue()

    @property
    def running(self) -> bool:
        """Whether a run was started and has not ended (nor been dropped)."""
        return self._thread is not None

    def start(self, route: Callable[[], Any]) -> None:
        """Runs ``route()`` in a new thread (after dropping any unfinished run); its result, or the
        exception it raised, is the run's end (:meth:`next_event`)."""
        self.stop()
        events, self._answers = queue.Queue(), queue.Queue()
        self._events = events

        def run() -> None:
            try:
                events.put(("done", route()))
            except BaseException as exc:  # noqa: BLE001 - handed to the environment's thread
                events.put(("error", exc))

        self._thread = threading.Thread(target=run, name=self.name, daemon=True)
        self._thread.start()

    # -- the router's thread ---------------------------------------------------
    def ask(self, question: Any) -> Any:
        """Hands ``question`` to the environment and returns its answer; raises :class:`Aborted`
        when the environment drops the run instead."""
        self._events.put(("ask", question))
        answer = self._answers.get()
        if answer is _ABORT:
            raise Aborted()
        return answer

    # -- the environment's thread ----------------------------------------------
    def next_event(self) -> tuple[bool, Any]:
        """Waits for the router: ``(True, question)`` when it asks, ``(False, result)`` when the run
        ended (the thread is then joined); the exception the run raised is raised here."""
        kind, payload = self._events.get()
        if kind == "ask":
            return True, payload
        self._join()
        if kind == "error":
            raise payload
        return False, payload

    def answer(self, value: Any) -> None:
        """Lets the router go on with ``value`` as the answer to its question."""
        self._answers.put(value)

    def stop(self) -> None:
        """Drops an unfinished run (see the module doc) and waits for its thread to end."""
        if self._thread is None:
            return
        self._answers.put(_ABORT)
        while self._events.get()[0] == "ask":
            self._answers.put(_ABORT)
        self._join()

    def _join(self) -> None:
        assert self._thread is not None
        self._thread.join()
        self._thread = None
