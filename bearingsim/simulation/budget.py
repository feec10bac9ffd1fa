"""Step and wall-time budgets of a run: every integration ends, in a named error that says the
time it reached, instead of running on.

A :class:`RunBudget` is checked by the integrators once per step (scipy's methods) or once per
batch of steps (the compiled BDF, SUNDIALS between output chunks). Exceeding it raises
:class:`~bearingsim.errors.BudgetExceededError` with the simulated time reached, the steps
taken and the wall time used.
"""

from __future__ import annotations

import math
import time

from bearingsim.errors import BudgetExceededError
from bearingsim.validation import check_count, check_range

__all__ = ["DEFAULT_MAX_STEPS", "MAX_TIMEOUT", "RunBudget"]

DEFAULT_MAX_STEPS = 100_000
"""Step budget of a run unless the caller gives one (CVODES' ``max_num_steps`` default of
bearingsim: a run of 10^5 accepted steps at a typical 10^-4 relative step size is far beyond
what any shipped scene needs)."""
MAX_TIMEOUT = 7 * 24 * 3600.0
"""Largest wall-time budget [s] (a week); above it the value is taken for a unit slip."""


class RunBudget:
    """Steps and wall time a run may use.

    Parameters
    ----------
    max_steps : int
        Most integrator steps (accepted or rejected) [-], >= 1.
    timeout : float, optional
        Most wall time [s] from the budget's creation, in (0, :data:`MAX_TIMEOUT`]; ``None``:
        no limit.
    method : str
        The integrator's name, used in the message.
    t_end : float
        End time of the run [s], used in the message.
    """

    def __init__(self, max_steps: int = DEFAULT_MAX_STEPS, timeout: float | None = None,
                 method: str = "", t_end: float = math.nan):
        check_count(max_steps, "max_steps", 1, "simulate")
        if timeout is not None:
            check_range(timeout, "timeout", "s", 0.0, MAX_TIMEOUT, low_inclusive=False,
                        where="simulate")
        self.max_steps = int(max_steps)
        self.timeout = None if timeout is None else float(timeout)
        self.method = method
        self.t_end = t_end
        self.steps = 0
        self.started = time.perf_counter()

    def start(self) -> None:
        """Start the wall-time clock (at the integration's start, after the set-up)."""
        self.started = time.perf_counter()

    def step(self, t_reached: float, n: int = 1) -> None:
        """Count ``n`` steps taken up to ``t_reached`` [s]; raise when the budget is spent.

        Parameters
        ----------
        t_reached : float
            Simulation time reached by these steps [s].
        n : int, default 1
            Steps taken (>= 0).

        Raises
        ------
        BudgetExceededError
            Naming the method, the time reached, the steps and the wall time.
        """
        self.steps += n
        used = time.perf_counter() - self.started
        if self.steps > self.max_steps:
            why = (f"its step budget of {self.max_steps} steps (max_steps); a step size "
                   f"collapsing to a tiny value points to a discontinuity or a tolerance "
                   f"below the model's round-off (give a larger atol), else raise the budget")
        elif self.timeout is not None and used > self.timeout:
            why = (f"its wall-time budget of {self.timeout:g} s (timeout); raise it, or "
                   f"shorten the run")
        else:
            return
        taken = f"{self.steps} steps and " if self.steps else ""
        raise BudgetExceededError(
            f"{self.method or 'the integrator'} stopped at t = {t_reached:.6g} s of "
            f"{self.t_end:g} s after {taken}{used:.3g} s: the run used up {why}",
            t_reached=t_reached, steps=self.steps, wall_time=used)
