"""Exceptions raised by xroute for bad user input."""

from __future__ import annotations


class XrouteError(Exception):
    """Base class of the errors xroute reports to users as one line (exit code 2)."""


class InputError(XrouteError, ValueError):
    """A malformed, truncated or inconsistent input file.

    ``path`` names the file and ``line`` the 1-based line (0 when the problem
    concerns the file as a whole, e.g. it is missing).
    """

    def __init__(self, message: str, path: str = "", line: int = 0) -> None:
        self.message = message
        self.path = path
        self.line = line
        where = f"{path}:{line}" if line > 0 else path
        super().__init__(f"{where}: {message}" if where else message)

    def __reduce__(self):  # keep path/line through pickling (multiprocessing)
        return (type(self), (self.message, self.path, self.line))


class TestcaseNotFound(XrouteError, LookupError):
    """A testcase name that no folder on the search path holds."""
