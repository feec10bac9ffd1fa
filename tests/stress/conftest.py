"""Stress tests: each test runs under a wall-clock limit, so a hang fails instead of blocking."""

from __future__ import annotations

import signal
from contextlib import contextmanager

import pytest

LIMIT_S = 60


class Hang(Exception):
    """The code under test exceeded its wall-clock budget."""


@contextmanager
def time_limit(seconds: float):
    """Raise :class:`Hang` in the main thread after ``seconds`` (SIGALRM)."""

    def handler(signum, frame):
        raise Hang(f"exceeded {seconds} s")

    old = signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


@pytest.fixture(autouse=True)
def _no_hang():
    with time_limit(LIMIT_S):
        yield
