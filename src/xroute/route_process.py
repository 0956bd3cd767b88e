"""One command in a child process, measured by the kernel: the runner of the benches, the schedule
experiments and ``xroute train-schedule``.

:func:`run_process` starts a command (usually ``xroute route ...``, see :func:`xroute_command`),
waits for it with ``os.wait4`` and returns a :class:`ProcessRun`: its exit status, its standard
output and error, its wall seconds, the CPU seconds of the child (user + system, all its threads:
less sensitive to a shared machine's load than the wall time), its peak resident memory and, when
given the output folder of a route, the metrics JSON the route wrote there. A run may be given a
time limit, in wall seconds or in the child's CPU seconds (which a shared machine's load moves far
less): the child is killed when it passes it.

The child's output goes to anonymous temporary files, not pipes, so a child that writes much to
both streams never waits for the parent to read one of them. The library never prints.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping, Sequence

POLL_SECONDS = 0.05  # how often a run with a time limit looks whether its child has ended


@dataclass(frozen=True)
class ProcessRun:
    """What one child process did."""

    command: tuple[str, ...]
    returncode: int  # the exit status; -N when signal N ended it (-9 when stopped at a time limit)
    stdout: str
    stderr: str
    wall_s: float  # from the start to the end of the child
    cpu_s: float  # user + system seconds of the child, all its threads (ru_utime + ru_stime)
    peak_rss_mb: float  # the child's peak resident memory, MB (ru_maxrss, KiB on Linux, / 1024)
    stopped: bool = False  # killed at its time limit (wall or CPU seconds)
    metrics: Any = None  # the metrics JSON of the route (its ``metrics_dir``), when it wrote one

    @property
    def last_line(self) -> str:
        """The last non-empty line of the standard error, else of the standard output, else the
        exit status: what a failed run said last (an ``xroute`` error is one line)."""
        for text in (self.stderr, self.stdout):
            lines = [line for line in text.splitlines() if line.strip()]
            if lines:
                return lines[-1]
        return "stopped at its time limit" if self.stopped else f"exit {self.returncode}"


def xroute_command(*args: str) -> list[str]:
    """``python -m xroute ARGS``: the installed command, run by this Python."""
    return [sys.executable, "-m", "xroute", *args]


def run_process(command: Sequence[str], *, env: Mapping[str, str] | None = None, timeout: float | None = None,
                cpu_limit: float | None = None, metrics_dir: str | os.PathLike[str] | None = None) -> ProcessRun:
    """Runs ``command`` in a child process and waits for it (see the module doc).

    ``env``: variables added to this process's environment for the child. ``timeout``: wall seconds,
    ``cpu_limit``: CPU seconds of the child, after which it is killed (SIGKILL; ``stopped`` is then
    true). ``metrics_dir``: the output folder of a route; the one ``*.metrics.json`` in it, when there
    is one, is read into ``metrics`` (an :class:`~xroute.errors.InputError` when it is not JSON)."""
    command = tuple(str(part) for part in command)
    child_env = None if env is None else {**os.environ, **env}
    with tempfile.TemporaryFile("w+b") as out, tempfile.TemporaryFile("w+b") as err:
        start = time.perf_counter()
        proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=out, stderr=err, env=child_env)
        returncode, usage, stopped = _wait(proc, None if timeout is None else start + timeout, cpu_limit)
        wall = time.perf_counter() - start
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode("utf-8", "replace")
        stderr = err.read().decode("utf-8", "replace")
    return ProcessRun(command, returncode, stdout, stderr, wall,
                      usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, stopped,
                      _metrics(Path(metrics_dir)) if metrics_dir is not None else None)


def _wait(proc: subprocess.Popen, deadline: float | None, cpu_limit: float | None) -> tuple[int, Any, bool]:
    """(exit status, resource usage, killed at a limit) of ``proc``, reaped with ``os.wait4``."""
    stopped = False
    if deadline is None and cpu_limit is None:
        _, status, usage = os.wait4(proc.pid, 0)
    else:
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if ((deadline is not None and time.perf_counter() > deadline)
                    or (cpu_limit is not None and cpu_seconds(proc.pid) > cpu_limit)):
                proc.kill()  # not reaped yet: the id is still the child's
                _, status, usage = os.wait4(proc.pid, 0)
                stopped = True
                break
            time.sleep(POLL_SECONDS)
    proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait for it again
    return proc.returncode, usage, stopped


def cpu_seconds(pid: int) -> float:
    """User + system CPU seconds of the running process ``pid``, all its threads (/proc; 0 where unreadable)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _metrics(folder: Path) -> Any:
    from xroute.json_files import read_json

    found = sorted(folder.glob("*.metrics.json")) if folder.is_dir() else []
    return read_json(found[0], what="metrics JSON") if len(found) == 1 else None
