"""Terminal output for the ``xroute`` command: Rich consoles, JSON output and one-line errors.

Only the command layer uses this module; the library never prints.
"""

from __future__ import annotations

import json
import os
from typing import Any

import typer
from rich.console import Console

from xroute_cli.errors import InputError, XrouteError

# Width of tables when stdout is not a terminal (pipes, CliRunner) and COLUMNS is unset.
PIPE_WIDTH = 160


def stdout_console() -> Console:
    """A Rich console on stdout; wider than Rich's default of 80 when piped."""
    console = Console()
    if not console.is_terminal and "COLUMNS" not in os.environ:
        console = Console(width=PIPE_WIDTH)
    return console


def print_json(data: Any) -> None:
    """Writes ``data`` as indented JSON on stdout, nothing else."""
    typer.echo(json.dumps(data, indent=2, sort_keys=False))


def error_line(exc: BaseException) -> str:
    """The one line shown for a user error: ``error: <file>:<line>: <message>``."""
    if isinstance(exc, InputError):
        where = f"{exc.path}:{exc.line}" if exc.line > 0 else exc.path
        text = f"{where}: {exc.message}" if where else exc.message
    elif isinstance(exc, OSError) and exc.filename is not None:
        text = f"{exc.filename}: {exc.strerror or exc}"
    else:
        text = str(exc)
    return "error: " + " ".join(text.split())  # one line, whatever the message held


def print_error(exc: BaseException) -> None:
    """Prints :func:`error_line` on stderr (plain text: no wrapping, no colour codes)."""
    typer.echo(error_line(exc), err=True)


USER_ERRORS: tuple[type[BaseException], ...] = (XrouteError, OSError)
