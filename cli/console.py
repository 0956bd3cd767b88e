"""Terminal output for the ``xroute`` command: Rich consoles, JSON output and one-line errors.

Only the command layer uses this module; the library never prints.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Callable, Iterator

import typer
from rich.console import Console

from xroute.errors import InputError, XrouteError

if TYPE_CHECKING:
    from xroute.design import Design

# Width of tables when stdout is not a terminal (pipes, CliRunner) and COLUMNS is unset.
PIPE_WIDTH = 160


MORE_PROBLEMS = 9  # a config file's problems after the first that its error line names


def counted(n: int, noun: str) -> str:
    """``n`` and the noun in the right number: "1 violation", "2 violations", "1,024 vias"."""
    return f"{n:,} {noun}" + ("" if n == 1 else "s")


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
        problems = list(getattr(exc, "problems", ()))  # a config file's problems: all named on the one line
        message = problems[0][1] if len(problems) > 1 else exc.message
        text = f"{where}: {message}" if where else message
        if len(problems) > 1:
            shown = [f"line {line}: {msg}" for line, msg in problems[1:1 + MORE_PROBLEMS]]
            left = len(problems) - 1 - len(shown)
            text += "; also " + "; ".join(shown) + (f"; and {left} more" if left else "")
    elif isinstance(exc, OSError) and exc.filename is not None:
        text = f"{exc.filename}: {exc.strerror or exc}"
    elif isinstance(exc, OSError) and exc.errno == errno.EBADF:
        text = f"standard output or error closed during the run (by a policy?): {exc.strerror or exc}"
    else:
        text = str(exc)
    return "error: " + " ".join(text.split())  # one line, whatever the message held


def print_error(exc: BaseException) -> None:
    """Prints :func:`error_line` on stderr (plain text: no wrapping, no colour codes); when stderr
    cannot be written (a policy closed it), on the copy of it kept at start
    (:func:`xroute.policy_process.write_error`)."""
    echo_error(error_line(exc))


def echo_error(line: str) -> None:
    """Writes one ``error: ...`` line on stderr, or where :func:`xroute.policy_process.write_error` can."""
    try:
        typer.echo(line, err=True)
    except (OSError, ValueError):  # a closed stderr (its fd, or the Python object)
        from xroute.policy_process import write_error

        write_error(line)


MAX_WARNINGS_SHOWN = 5  # warnings read from the input files that check and route print (info prints all)


def print_read_warnings(design: Design) -> None:
    """The warnings of reading ``design``'s files, on stderr as ``warning: <file>:<line>: ...`` lines:
    the first :data:`MAX_WARNINGS_SHOWN`, then how many more (``xroute info`` lists them all)."""
    messages = design.warnings()
    for message in messages[:MAX_WARNINGS_SHOWN]:
        typer.echo("warning: " + " ".join(message.split()), err=True)
    if len(messages) > MAX_WARNINGS_SHOWN:
        typer.echo(f"warning: ... and {len(messages) - MAX_WARNINGS_SHOWN} more warnings reading the inputs "
                   "(xroute info lists them all)", err=True)


def print_unmodelled_rules(design: Design) -> None:
    """One ``warning:`` line on stderr for each rule the LEF states that neither the router nor the
    checker models (:meth:`Design.unmodelled_rules`), with its layers: the route is made and checked
    without it."""
    for r in design.unmodelled_rules():
        typer.echo(f"warning: {r['rule']} on {', '.join(r['layers'])}: not modelled (routed and checked "
                   "without it; see xroute check's not-checked list)", err=True)


@contextlib.contextmanager
def json_output(active: bool) -> Iterator[Callable[[Any], None]]:
    """A context for a command's work that yields the function printing its JSON document. When
    ``active`` (``--json``) stdout is the document's alone: anything else written there from now
    on (a policy's prints, by C code too, a thread it left running) goes to stderr. On the real
    stdout (file descriptor 1) that holds for the rest of the process: descriptor 1 is pointed at
    stderr and the document is written to a copy of the original."""
    if not active:
        yield print_json
        return
    out = sys.stdout
    try:
        fd = out.fileno()
    except (AttributeError, ValueError, OSError):  # not a file (an in-process runner's stream)
        fd = None
    if fd != 1:
        sys.stdout = sys.stderr
        try:
            yield lambda data: _write_json(out, data)
        finally:
            sys.stdout = out
        return
    out.flush()
    stream = os.fdopen(os.dup(1), "w", encoding=getattr(out, "encoding", None) or "utf-8", errors="backslashreplace")
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    yield lambda data: _write_json(stream, data)


def _write_json(stream: Any, data: Any) -> None:
    stream.write(json.dumps(data, indent=2, sort_keys=False) + "\n")
    stream.flush()


USER_ERRORS: tuple[type[BaseException], ...] = (XrouteError, OSError)


# The design inputs shared by commands that read one design: a testcase name, or LEF/DEF (+ guide) files.
TestcaseArg = Annotated[
    str | None,
    typer.Argument(help="Testcase name, looked up on the search path (see `xroute testcases`).", show_default=False),
]
LefOption = Annotated[
    list[Path] | None,
    typer.Option("--lef", help="LEF file to read instead of a testcase (repeatable, in order).", show_default=False),
]
DefOption = Annotated[Path | None, typer.Option("--def", help="DEF file to read (with --lef).", show_default=False)]
GuideOption = Annotated[
    Path | None, typer.Option("--guide", help="Route guide file (optional, with --lef/--def).", show_default=False)
]


def check_design_args(testcase: str | None, lef: list[Path] | None, def_: Path | None, guide: Path | None) -> None:
    """Raises typer.BadParameter unless exactly one of a testcase name or --lef and --def is given."""
    if testcase is not None and (lef or def_ is not None or guide is not None):
        raise typer.BadParameter("give a testcase name or --lef/--def files, not both", param_hint="TESTCASE")
    if testcase is None and (not lef or def_ is None):
        raise typer.BadParameter("give a testcase name, or both --lef and --def", param_hint="TESTCASE")


def load_design_args(testcase: str | None, lef: list[Path] | None, def_: Path | None, guide: Path | None,
                     prepare: bool = False) -> Design:
    """Loads the design the (checked) arguments name: as it is, or with ``prepare`` ready to route
    (:func:`xroute.pipeline.prepare_design`: global-routed when it has no guide). The compiled
    engine loads only now."""
    from xroute.design import load_design
    from xroute.pipeline import prepare_design

    load = prepare_design if prepare else load_design
    if testcase is not None:
        return load(testcase)
    return load(lef=[str(p) for p in lef or []], def_=str(def_), guide=str(guide) if guide else None)
