"""The ``xroute`` command: assembles the subcommands (one module each) and turns user errors into one line.

Errors: any :class:`~xroute.errors.XrouteError` (bad input file, unknown testcase)
or ``OSError`` (unreadable file) raised by a command is printed as one line
``error: <file>:<line>: <message>`` on stderr and exits with status 2, without a
traceback. Usage errors keep Typer's status 2. Anything else is a bug and shows its
traceback.
"""

from __future__ import annotations

import os
import sys
import threading
from typing import Annotated, Any

import typer
from typer.core import TyperGroup

from xroute.cli.commands import (
    batch,
    check,
    evaluate,
    export,
    global_route,
    info,
    make_region,
    make_testcase,
    plot,
    plot_region,
    report,
    route,
    testcases,
    train,
    train_schedule,
)
from xroute.cli.console import USER_ERRORS, echo_error, print_error
from xroute.errors import safe_text
from xroute.policy_guard import stray_threads
from xroute.policy_process import install_exit_guard, real_exit

EXIT_USER_ERROR = 2


class XrouteGroup(TyperGroup):
    """The top-level command group: reports user errors from any subcommand as one line."""

    def invoke(self, ctx: Any) -> Any:
        try:
            return super().invoke(ctx)
        except USER_ERRORS as exc:
            _debug_traceback(exc)
            print_error(exc)
            ctx.exit(EXIT_USER_ERROR)
        except MemoryError as exc:  # e.g. std::bad_alloc in the engine on an absurdly large input
            _debug_traceback(exc)
            echo_error(f"error: out of memory ({exc or 'MemoryError'}): the input or the settings ask for too much")
            ctx.exit(EXIT_USER_ERROR)
        except Exception as exc:  # an exception raised inside a user's policy: one line naming it
            from xroute.policy_guard import policy_failure_line

            line = policy_failure_line(exc)
            if line is None:
                if _streams_closed():  # a policy closed stdout or stderr: no traceback could be seen
                    echo_error(f"error: the run failed after stdout or stderr was closed (by a policy?): "
                               f"{type(exc).__name__}: {safe_text(exc)}")
                    ctx.exit(EXIT_USER_ERROR)
                raise  # anything else is a bug: its traceback
            _debug_traceback(exc)
            echo_error("error: " + line)
            ctx.exit(EXIT_USER_ERROR)


DEBUG = {"on": False}  # set by --debug


def _streams_closed() -> bool:
    """Whether stdout or stderr (the Python objects or file descriptors 1 and 2) is closed."""
    for stream, fd in ((sys.stdout, 1), (sys.stderr, 2)):
        if stream is None or getattr(stream, "closed", False):
            return True
        try:
            os.fstat(fd)
        except OSError:
            return True
    return False


def _debug_traceback(exc: BaseException) -> None:
    if DEBUG["on"]:
        import traceback

        traceback.print_exception(exc)


app = typer.Typer(
    cls=XrouteGroup,
    name="xroute",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    help="xroute: a VLSI detailed router whose net order is chosen by a pluggable, learnable policy.",
)


def _print_version(value: bool) -> None:
    if value:
        from xroute import __version__

        typer.echo(f"xroute {__version__}")
        raise typer.Exit()


@app.callback()
def _options(
    version: Annotated[bool, typer.Option("--version", callback=_print_version, is_eager=True,
                                          help="Print the version and exit.")] = False,
    debug: Annotated[bool, typer.Option("--debug", help="Show the traceback of an error (e.g. one raised in a "
                                        "policy).")] = False,
) -> None:
    """xroute: a VLSI detailed router whose net order is chosen by a pluggable, learnable policy."""
    DEBUG["on"] = debug


app.command(name="info")(info.info)
app.command(name="testcases")(testcases.testcases)
app.command(name="route")(route.route)
app.command(name="train")(train.train)
app.command(name="train-schedule")(train_schedule.train_schedule)
app.command(name="export")(export.export)
app.command(name="make-region")(make_region.make_region_command)
app.command(name="make-testcase")(make_testcase.make_testcase)
app.command(name="evaluate")(evaluate.evaluate)
app.command(name="batch")(batch.batch)
app.command(name="report")(report.report)
app.command(name="plot")(plot.plot)
app.command(name="plot-region")(plot_region.plot_region)
app.command(name="global-route")(global_route.global_route)
app.command(name="check")(check.check)


def tolerant_streams() -> None:
    """Makes stdout and stderr write what their encoding cannot hold as escapes (``\\xb5``) instead
    of raising UnicodeEncodeError (``PYTHONIOENCODING=ascii``, a C locale, a file name with bytes
    that are not UTF-8)."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None:
            try:
                reconfigure(errors="backslashreplace")
            except (ValueError, OSError):  # a closed or detached stream: nothing to protect
                pass


def _thread_failure(args: threading.ExceptHookArgs) -> None:
    """One line for an exception that ends a thread (one a user's policy started): no traceback."""
    if args.exc_type is SystemExit:
        return
    name = args.thread.name if args.thread is not None else "a thread"
    sys.stderr.write(f"warning: thread {name} (started by a policy?) ended with {args.exc_type.__name__}: "
                     f"{safe_text(args.exc_value)}\n")


def finish(code: object) -> None:
    """Ends the process with ``code`` (a ``SystemExit`` code) once the command is done. Python waits
    for every non-daemon thread before it exits, so a thread left running by a user's policy
    would keep the process alive after the outputs are written: then the exit handlers are run
    and the streams flushed here, and the process ends at once (``os._exit``)."""
    if not stray_threads():
        sys.exit(code)
    if code is None:
        status = 0
    elif isinstance(code, int):
        status = code & 0xFF
    else:
        sys.stderr.write(f"{code}\n")
        status = 1
    import atexit

    atexit._run_exitfuncs()  # what a normal exit runs after the threads (multiprocessing, logging)
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (ValueError, OSError):
            pass
    real_exit(status)


def _click_exceptions() -> tuple[tuple[type[BaseException], ...], tuple[type[BaseException], ...]]:
    """The usage-error and abort classes of click and of the copy of click that newer typer
    releases carry (``typer._click``), whichever are installed."""
    import importlib

    errors: list[type[BaseException]] = []
    aborts: list[type[BaseException]] = [typer.Abort]
    for name in ("click.exceptions", "typer._click.exceptions"):
        try:
            module = importlib.import_module(name)
        except ImportError:
            continue
        for kind, found in (("ClickException", errors), ("Abort", aborts)):
            cls = getattr(module, kind, None)
            if isinstance(cls, type) and issubclass(cls, BaseException) and cls not in found:
                found.append(cls)
    return tuple(errors), tuple(aborts)


def main() -> None:
    """Console-script entry point (``xroute``): text that the terminal's encoding cannot show is
    escaped, and threads a policy left running do not outlive the command (:func:`finish`)."""
    tolerant_streams()
    install_exit_guard()  # os._exit from a policy: one error line and status 2 (xroute.policy_process)
    threading.excepthook = _thread_failure
    usage_errors, aborts = _click_exceptions()
    code: object = 0
    try:
        # standalone_mode=False: a usage error comes here as an exception and is printed as one
        # line, instead of the usage text and a boxed message over several lines.
        returned = app(prog_name="xroute", standalone_mode=False)
        if isinstance(returned, int) and not isinstance(returned, bool):
            code = returned  # typer.Exit(code) comes back as its code
    except usage_errors as exc:
        code = exc.exit_code
        if type(exc).__name__ != "NoArgsIsHelpError":  # that one's help text is printed already
            ctx = getattr(exc, "ctx", None)
            command = ctx.command_path if ctx is not None else "xroute"
            hint = f" (see '{command} --help')" if ctx is not None else ""
            message = " ".join(safe_text(exc.format_message()).split())
            sys.stderr.write(f"error: {command}: {message}{hint}\n")
    except aborts:
        sys.stderr.write("Aborted!\n")
        code = 1
    except SystemExit as exc:
        code = exc.code
    finish(code)
