"""Stress tests: time limits and the two case counts.

Every test runs under :data:`LIMIT_S` of wall-clock time, and each generated case inside it
under its own limit (:func:`time_limit` nests: a case's limit ends at the test's limit at the
latest, and the test's clock keeps running through its cases), so a hang fails instead of
blocking.

Cases are counted in two kinds (:data:`STRESS`, printed by ``tests/conftest.py`` at the end of
the run): *valid* operating points, which must simulate or solve and pass their invariants (any
error fails the test), and *invalid* inputs, which must be refused with a named
:class:`~bearingsim.errors.BearingsimError`.
"""

from __future__ import annotations

import signal
import time
from contextlib import contextmanager

import pytest

LIMIT_S = 60.0
"""Wall-clock limit of one stress test [s]."""
CASE_LIMIT_S = 20.0
"""Wall-clock limit of one generated case [s]."""

STRESS = {"cases": 0, "seconds": 0.0, "valid": 0, "valid_seconds": 0.0, "invalid": 0,
          "invalid_seconds": 0.0, "invalid_accepted": 0}
"""This process's case counts and times [s]: ``valid`` operating points run and checked,
``invalid`` inputs refused with a named error, ``invalid_accepted`` generated bad-input cases
that turned out valid and gave finite numbers; ``cases``/``seconds`` are the totals."""


class Hang(Exception):
    """The code under test exceeded its wall-clock budget."""


@contextmanager
def time_limit(seconds: float):
    """Raise :class:`Hang` in the main thread after ``seconds`` (SIGALRM), or at an enclosing
    limit if that comes first; the enclosing limit is re-armed with its remaining time."""
    outer_handler = signal.getsignal(signal.SIGALRM)
    outer_left, _ = signal.getitimer(signal.ITIMER_REAL)
    start = time.monotonic()
    limit = seconds if outer_left <= 0 else min(seconds, outer_left)
    which = f"{seconds} s" if limit == seconds else f"the enclosing limit ({outer_left:.3g} s)"

    def handler(signum, frame):
        raise Hang(f"exceeded {which}")

    signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, limit)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, outer_handler)
        if outer_left > 0:  # the enclosing clock ran on meanwhile
            signal.setitimer(signal.ITIMER_REAL,
                             max(outer_left - (time.monotonic() - start), 1e-6))


def _count(kind: str, start: float, n: int = 1) -> None:
    elapsed = time.perf_counter() - start
    STRESS[kind] += n
    STRESS["cases"] += n
    STRESS["seconds"] += elapsed
    if kind != "invalid_accepted":
        STRESS[f"{kind}_seconds"] += elapsed


@contextmanager
def valid_case(n: int = 1):
    """One valid operating point (or a batch of ``n`` evaluated together as arrays): bounded in
    time, counted when it passes. Any exception, named or not, propagates and fails the
    test."""
    start = time.perf_counter()
    with time_limit(CASE_LIMIT_S):
        yield
    _count("valid", start, n)


@pytest.fixture(autouse=True)
def _no_hang():
    with time_limit(LIMIT_S):
        yield
