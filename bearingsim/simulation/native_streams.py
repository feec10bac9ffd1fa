"""What native code writes and Ctrl-C during a native call: standard output sent to the null
device (the MUMPS banner), standard error held aside while a run may be stopped on purpose,
CasADi's dump of a failed function's inputs dropped, and SIGINT recorded while CVODES or IDAS
run.
"""

from __future__ import annotations

import _signal
import contextlib
import io
import os
import re
import signal
import sys
import tempfile
import threading
from collections.abc import Iterator
from typing import Any

__all__ = ["Interrupted", "casadi_dumps_dropped", "held_stderr", "interrupts", "quiet_stdout"]


@contextlib.contextmanager
def quiet_stdout() -> Iterator[None]:
    """Send the process's standard output (file descriptor 1) to the null device: MUMPS prints
    a banner on standard output when CasADi destroys one of its solvers, and has no option
    against it (CasADi's MUMPS interface sets none)."""
    try:
        sys.stdout.flush()
        saved = os.dup(1)
    except (OSError, ValueError, AttributeError):  # no standard output to protect
        yield
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


_DUMP_LINE = re.compile(r"Function \S+ \(0x[0-9a-fA-F]+\)\n|Input \d+ \(\S*\): .*\n")
"""A line of CasADi's dump of a failed function's inputs (``Function::operator()`` writes it to
``sys.stderr`` before it raises, whatever the function's options)."""
_DUMP_STARTS = ("Function ", "Input ")


class _DumpFilter:
    """``sys.stderr`` less CasADi's input dumps: a line that may be one is held until its end,
    every other text passes at once (a progress bar's ``\r`` lines stay live)."""

    def __init__(self, stream: Any) -> None:
        self.stream = stream
        self.line = ""

    def write(self, text: str) -> int:
        for piece in text.splitlines(keepends=True):
            self.line += piece
            if self.line.endswith("\n"):
                if not _DUMP_LINE.fullmatch(self.line):
                    self.stream.write(self.line)
                self.line = ""
            elif not any(self.line.startswith(s) or s.startswith(self.line)
                         for s in _DUMP_STARTS):
                self.stream.write(self.line)
                self.line = ""
        return len(text)

    def flush(self) -> None:
        if self.line:
            self.stream.write(self.line)
            self.line = ""
        self.stream.flush()

    def __getattr__(self, name: str) -> Any:
        return getattr(self.stream, name)


_DUMP_LOCK = threading.Lock()
_DUMP_USERS = [0, None]  # contexts open, the stream the first one replaced


@contextlib.contextmanager
def casadi_dumps_dropped() -> Iterator[None]:
    """While the context lasts, drop from ``sys.stderr`` the inputs CasADi prints of every
    function in the chain of a failed evaluation (a Newton block that did not converge prints
    its own, the right-hand side's and the caller's inputs, hundreds of numbers); the error it
    raises says what failed. Everything else written to standard error passes. Contexts in
    several threads share one filter, removed when the last one ends."""
    with _DUMP_LOCK:
        if _DUMP_USERS[0] == 0:
            _DUMP_USERS[1] = sys.stderr
            sys.stderr = _DumpFilter(sys.stderr)
        _DUMP_USERS[0] += 1
    try:
        yield
    finally:
        with _DUMP_LOCK:
            _DUMP_USERS[0] -= 1
            if _DUMP_USERS[0] == 0:
                sys.stderr.flush()
                sys.stderr = _DUMP_USERS[1]
                _DUMP_USERS[1] = None


@contextlib.contextmanager
def held_stderr(hold: bool) -> Iterator[None]:
    """With ``hold``, send the process's standard error (file descriptor 2, and Python's
    ``sys.stderr``) aside while the context lasts, then copy it to standard error unless the
    context ends in an error: a run its budget stopped ends in a failed evaluation, which the
    Python layer, CasADi and SUNDIALS each report on standard error; the budget's own error
    says what happened, as a failed run's error says why it failed (IDAS prints its failure
    whatever its options).

    Parameters
    ----------
    hold : bool
        Whether to hold standard error at all.
    """
    if not hold:
        yield
        return
    try:
        sys.stderr.flush()
        saved = os.dup(2)
    except (OSError, ValueError, AttributeError):  # no standard error to hold
        yield
        return
    python_level = io.StringIO()  # Python's own reports go to sys.stderr, not always fd 2
    raised = False
    with tempfile.TemporaryFile() as held, contextlib.redirect_stderr(python_level):
        os.dup2(held.fileno(), 2)
        try:
            yield
        except BaseException:
            raised = True
            raise
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            if not raised:
                held.seek(0)
                text = held.read()
                if text:
                    os.write(2, text)
    if not raised and python_level.getvalue():
        sys.stderr.write(python_level.getvalue())


class Interrupted:
    """Whether Ctrl-C came during a run (set from the SIGINT handler, in the main thread)."""

    __slots__ = ("value",)

    def __init__(self) -> None:
        self.value = False

    def is_set(self) -> bool:
        return self.value


@contextlib.contextmanager
def interrupts() -> Iterator[Interrupted]:
    """Record Ctrl-C (SIGINT) during a SUNDIALS run: CasADi checks for it between evaluations
    and turns it into a failed evaluation (a RuntimeError); the flag tells the two apart, so
    an interrupted run raises KeyboardInterrupt instead of being diagnosed as a failure.
    Outside the main thread (where Python delivers signals) the flag stays clear.

    The handler is swapped with ``_signal.signal``, the C function under ``signal.signal``:
    the latter's conversion of the previous handler to an enum costs tens of microseconds per
    call (a failed enum lookup for a function), a tenth of a short run's fixed cost. The
    values are the same (SIG_DFL and SIG_IGN as plain ints, which are not callable either).
    """
    flag = Interrupted()
    if threading.current_thread() is not threading.main_thread():
        yield flag
        return

    def handler(signum, frame):
        flag.value = True
        if callable(previous):
            previous(signum, frame)
        raise KeyboardInterrupt

    previous = _signal.signal(signal.SIGINT, handler)
    try:
        yield flag
    finally:
        _signal.signal(signal.SIGINT, previous)
