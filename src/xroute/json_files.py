"""JSON files read by name (metrics, baselines, records): one clear error, never a traceback.

:func:`read_json` reads a regular file (a FIFO or a device is refused without blocking, see
:mod:`xroute.regular_files`) and parses it; text that is not UTF-8, not JSON, or nested so deep
that the parser gives up (``[[[[...`` 200,000 levels: RecursionError) becomes an
:class:`~xroute.errors.InputError` naming the file (and the line where the parser says).
"""

from __future__ import annotations

import json
import os
from typing import Any

from xroute.errors import InputError
from xroute.regular_files import read_regular_bytes


def parse_json(text: str | bytes, path: str, what: str = "JSON file") -> Any:
    """The value of JSON ``text`` read from ``path``; InputError (naming ``path``) when it is not JSON."""
    try:
        if isinstance(text, bytes):
            text = text.decode("utf-8")
        return json.loads(text)
    except UnicodeDecodeError:
        raise InputError(f"{what} is not UTF-8 text", path, 0) from None
    except json.JSONDecodeError as exc:
        raise InputError(f"{what} is not valid JSON: {exc.msg} (column {exc.colno})", path, exc.lineno) from None
    except RecursionError:
        raise InputError(f"{what} is nested too deeply to be read", path, 0) from None
    except ValueError as exc:  # e.g. an integer with too many digits
        raise InputError(f"{what} is not valid JSON: {exc}", path, 0) from None


def read_json(path: str | os.PathLike[str], what: str = "JSON file") -> Any:
    """The parsed content of the JSON file ``path`` (see the module doc). Raises InputError."""
    data = read_regular_bytes(path, what=what)
    return parse_json(data, os.fspath(path), what)
