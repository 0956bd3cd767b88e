"""The exceptions xroute raises (the bottom layer: it imports nothing of xroute).

Every error a user can cause derives from :class:`XrouteError`; the command line reports it as
one line and exits with status 2. The compiled engine raises :class:`InputError`,
:class:`RouteArgumentError` and :class:`PolicyError` itself (typed, never recognised by text).
"""

from __future__ import annotations

import difflib
from typing import Iterable


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """``" (did you mean 'x'?)"`` for the closest of ``choices`` to a misspelled ``word``, else ``""``."""
    close = difflib.get_close_matches(word, [c for c in choices if c != word], n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ""


def safe_text(value: object) -> str:
    """``str(value)`` on one line, never raising: an object (a user's exception) whose ``__str__``
    fails or returns something other than text gives ``<TypeName: unprintable>`` instead."""
    try:
        text = str(value)
        if not isinstance(text, str):
            raise TypeError("__str__ returned a non-string")
        text = " ".join(text.split())
    except KeyboardInterrupt:
        raise
    except BaseException:  # noqa: BLE001 - whatever a user's __str__ raises
        try:
            name = type(value).__name__
        except BaseException:  # noqa: BLE001
            name = "object"
        return f"<{name}: unprintable>"
    return text


class XrouteError(Exception):
    """Base class of the errors xroute reports to users as one line (exit code 2)."""


def one_line(text: str) -> str:
    """``text`` with line breaks written as ``\\n`` / ``\\r``: a value quoted from a file (a YAML string
    may hold a newline) must not break an error's one line."""
    return text.replace("\r", "\\r").replace("\n", "\\n")


class InputError(XrouteError, ValueError):
    """A malformed, truncated or inconsistent input file.

    ``path`` names the file and ``line`` the 1-based line (0 when the problem
    concerns the file as a whole, e.g. it is missing).
    """

    def __init__(self, message: str, path: str = "", line: int = 0) -> None:
        message = one_line(message)
        self.message = message
        self.path = path
        self.line = line
        where = f"{path}:{line}" if line > 0 else path
        super().__init__(f"{where}: {message}" if where else message)

    def __reduce__(self):  # keep path/line through pickling (multiprocessing)
        return (type(self), (self.message, self.path, self.line))


class TestcaseNotFound(XrouteError, LookupError):
    """A testcase name that no folder on the search path holds."""


class SettingsError(XrouteError, ValueError):
    """An invalid setting (a value out of range, a setting the design cannot honour)."""


class RouteArgumentError(SettingsError):
    """An invalid detailed-routing setting (region size, iteration count, threads, seed, schedule),
    including a region too large for the engine's grid limit on this design."""


class GlobalRouteArgumentError(SettingsError):
    """An invalid global-routing setting."""


class PolicyError(XrouteError):
    """A policy that cannot be loaded, or that returned something other than a permutation."""
