"""The order a sweep's points run in: longest first, from an estimate of each point's time.

A sweep ends when its last point does; a worker that draws a long point last keeps the others
idle until it finishes. Handing out the longest points first (longest processing time first,
the classic list-scheduling rule) leaves the short ones for the end, where they fill the
workers evenly. :class:`PointCosts` estimates each point's wall time:

* **a priori**, before any point is back: the rotation the point simulates (the integral of
  the fastest input in rad/s over the time span, :func:`point_features`), else its simulated
  time: a rolling bearing's integration takes steps per ball pass, so a faster or longer run
  costs more. It only ranks the points.
* **learned**, once enough points are back: a linear least-squares fit of the measured wall
  times against the points' features (every numeric swept value, an input expression by its
  mean over the time span, the simulated time and the rotation), in seconds, made again
  without the points it misses by far (:func:`trimmed_least_squares`: a point disturbed by
  another process weighs nothing). A worker's first point also loads the model and its
  compiled kernel, so it is left out of the fit.

The order changes when a point runs, never what it gives: the rows are the same whatever the
order (the table is written in point order).
"""

from __future__ import annotations

import functools
import math
import statistics
from collections.abc import Sequence
from typing import Any

import numpy as np

from bearingsim.scenes.expressions import constant_value
from bearingsim.scenes.scene_types import TableInput
from bearingsim.scenes.sweep_worker import Job

__all__ = ["PointCosts", "point_features", "trimmed_least_squares", "SPAN_SAMPLES",
           "REFIT_GROWTH", "TRIM_KEEP", "TRIM_STARTS", "OUTLIER_SPREADS"]

SPAN_SAMPLES = 201
"""Times at which an input expression is evaluated over a point's time span (its mean)."""
REFIT_GROWTH = 1.25
"""The fit is made again when the points it can use have grown by this factor (a few fits a
sweep, each a few milliseconds of the client's time)."""
TRIM_KEEP = 0.75
"""Share of the measured times each concentration step of :func:`trimmed_least_squares` fits
(a quarter of them may be disturbed)."""
TRIM_STARTS = 30
"""Random starts of :func:`trimmed_least_squares` besides ordinary least squares (with a
fifth of the rows disturbed, none of 30 sets of 4 rows is clean with a chance of 1.4e-7)."""
OUTLIER_SPREADS = 3.0
"""A measured time further from the trimmed fit than this many robust spreads of the residuals
(1.4826 x their median magnitude: the standard deviation of normal noise) is left out of the
last fit."""
ROTATION_UNIT = "rad/s"
"""The unit of the inputs whose integral over the time span is a point's rotation."""


@functools.lru_cache(maxsize=256)
def _mean_abs(text: str, t_start: float, t_end: float) -> float:
    """Mean of the absolute value of the input expression ``text`` over ``[t_start, t_end]``
    (trapezoidal rule on :data:`SPAN_SAMPLES` times); kept per arguments (a sweep's points
    share few expressions)."""
    import casadi as ca

    from bearingsim.scenes.expressions import compile_expression

    t = ca.SX.sym("t")
    grid = np.linspace(t_start, t_end, SPAN_SAMPLES)
    fn = ca.Function("u", [t], [ca.SX(compile_expression(text)(t))])
    return _span_mean(grid, np.asarray(fn.map(grid.size)(grid[None, :]), dtype=float).ravel())


def _span_mean(grid: np.ndarray, values: np.ndarray) -> float:
    """Mean of ``|values|`` over the times ``grid`` (trapezoidal rule, numpy's: the sweep's
    client plans without importing scipy.integrate, 0.3 s; a span of no length: the first
    value)."""
    level = np.abs(values)
    span = grid[-1] - grid[0]
    return float(np.trapezoid(level, grid) / span) if span > 0 else float(level[0])


def _input_level(value: Any, t_start: float, t_end: float) -> float | None:
    """The mean absolute value of an input over the time span (None: not a number, an
    expression of time or a table)."""
    if isinstance(value, TableInput):
        times, values = value.as_tuple()
        grid = np.linspace(t_start, t_end, SPAN_SAMPLES)
        return _span_mean(grid, np.interp(grid, times, values))
    try:
        constant = constant_value(value)
    except Exception:  # noqa: BLE001 - not an input value this estimate can read
        return None
    if constant is not None:
        return abs(constant)
    return _mean_abs(value, t_start, t_end) if isinstance(value, str) else None


def point_features(job: Job, values: dict[str, Any], input_units: dict[str, str]
                   ) -> dict[str, float]:
    """The numbers a point's wall time is estimated from.

    Parameters
    ----------
    job : Job
        The point (its scene holds the point's inputs and time span).
    values : dict
        The point's swept values by key (the sweep's table values).
    input_units : dict of str to str
        SI unit of each input of the point's model.

    Returns
    -------
    dict of str to float
        ``span`` (simulated time [s]), ``rotation`` (integral over the span of the fastest
        input in rad/s [rad]; 0 without one) and each swept key with a numeric value (an
        input by its mean absolute value over the span).
    """
    sim = job.scene.simulation
    t_start, t_end = float(sim.t_start), float(sim.t_end)
    span = max(t_end - t_start, 0.0)
    speeds = [_input_level(v, t_start, t_end) for name, v in job.scene.inputs.items()
              if input_units.get(name) == ROTATION_UNIT]
    out = {"span": span, "rotation": span * max((s for s in speeds if s is not None),
                                                default=0.0)}
    for key, value in values.items():
        head, _, name = key.partition(".")
        if head == "inputs":
            value = _input_level(job.scene.inputs.get(name), t_start, t_end)
        elif not isinstance(value, (int, float)) or isinstance(value, bool):
            continue
        if value is not None and math.isfinite(value):
            out[key] = float(value)
    return out


def trimmed_least_squares(a: np.ndarray, y: np.ndarray, rounds: int = 10) -> np.ndarray:
    """Least-squares coefficients of ``a @ c ~ y`` without the rows it misses by far.

    Least trimmed squares by concentration steps (FAST-LTS: Rousseeuw and Van Driessen,
    "Computing LTS regression for large data sets", Data Min. Knowl. Disc. 12, 2006,
    p. 29-45): from ordinary least squares and from the fits through :data:`TRIM_STARTS`
    random sets of as many rows as coefficients (seeded: the same rows give the same fit),
    each step fits the :data:`TRIM_KEEP` share of the rows the previous fit missed least
    (two steps from each start, then the three best until the rows stop changing); the fit
    whose kept rows are missed least wins. Then one fit of every row within
    :data:`OUTLIER_SPREADS` robust spreads of its residuals (at least 1 % of the median
    magnitude of ``y``). Each fit is :func:`numpy.linalg.lstsq`: a robust loss from
    :func:`scipy.optimize.least_squares` would import scipy.optimize, about 0.8 s of a sweep
    client's CPU, taken from the workers on a machine with as many cores as workers.

    Parameters
    ----------
    a : numpy.ndarray
        Design matrix, one row per measurement.
    y : numpy.ndarray
        The measurements (here wall times [s]).
    rounds : int
        Most concentration steps from each start.

    Returns
    -------
    numpy.ndarray
        The coefficients, one per column of ``a``.
    """
    def fit(rows: np.ndarray) -> np.ndarray:
        return np.linalg.lstsq(a[rows], y[rows], rcond=None)[0]

    n, width = a.shape
    size = min(n, max(width, math.ceil(TRIM_KEEP * n)))

    def concentrate(coef: np.ndarray, steps: int) -> tuple[float, np.ndarray]:
        rows = None
        for _ in range(steps):
            closest = np.sort(np.argsort(np.abs(a @ coef - y), kind="stable")[:size])
            if rows is not None and np.array_equal(closest, rows):
                break
            rows, coef = closest, fit(closest)
        return float(np.sum(np.sort((a @ coef - y) ** 2)[:size])), coef

    draw = np.random.default_rng(0)
    starts = [fit(np.arange(n))] + [fit(draw.choice(n, width, replace=False))
                                    for _ in range(TRIM_STARTS if size < n else 0)]
    # two steps from each start, then the three best to the end (as FAST-LTS does)
    trials = sorted((concentrate(c, 2) for c in starts), key=lambda t: t[0])[:3]
    best = min((concentrate(c, rounds) for _, c in trials), key=lambda t: t[0])[1]
    miss = np.abs(a @ best - y)
    near = miss <= max(OUTLIER_SPREADS * 1.4826 * float(np.median(miss)),
                       0.01 * abs(float(np.median(y))))
    return fit(near) if near.sum() >= width else best


class PointCosts:
    """Estimated wall time of each point of a sweep, learned as points finish.

    Parameters
    ----------
    features : dict of int to dict of str to float
        Point number -> :func:`point_features` of every point still to run.

    Attributes
    ----------
    version : int
        Increases whenever the estimates change (a new fit or a first measured time).
    """

    def __init__(self, features: dict[int, dict[str, float]]):
        names = sorted({n for f in features.values() for n in f})
        matrix = np.array([[f.get(n, math.nan) for n in names] for f in features.values()],
                          dtype=float).reshape(len(features), len(names))
        # a constant and the columns known at every point, standardized (scaled to their
        # largest magnitude first: a swept value may be as large as 1e308), each kept only
        # when it is not a combination of those before it (the rotation of a sweep over
        # speed alone follows the speed)
        x = np.ones((len(features), 1))
        for column in matrix.T:
            if not np.all(np.isfinite(column)) or np.all(column == column[0]):
                continue
            column = column / np.max(np.abs(column))
            wider = np.column_stack([x, (column - column.mean()) / column.std()])
            if np.all(np.isfinite(wider)) and np.linalg.matrix_rank(wider) == wider.shape[1]:
                x = wider
        self._rows = {k: x[i] for i, k in enumerate(features)}
        self._prior = {k: f["rotation"] if f.get("rotation", 0.0) > 0 else f.get("span", 0.0)
                       for k, f in features.items()}
        self._measured: dict[int, float] = {}
        self._times: list[float] = []
        self._coef: np.ndarray | None = None
        self._fitted_on = 0
        self.version = 0

    @property
    def n_coefficients(self) -> int:
        """Coefficients of the fit: one per varying feature and a constant.

        Returns
        -------
        int
            The number of coefficients.
        """
        return len(next(iter(self._rows.values()), [1.0]))

    def add(self, index: int, wall_s: float, first_on_worker: bool = False) -> None:
        """Record the measured wall time of a finished point.

        Parameters
        ----------
        index : int
            The point number.
        wall_s : float
            Its wall time on the worker [s].
        first_on_worker : bool
            The first point its worker ran (which loaded the model and its kernel): kept for
            the typical time, left out of the fit.
        """
        if not math.isfinite(wall_s):
            return
        self._times.append(wall_s)
        if index in self._rows and not first_on_worker:
            self._measured[index] = wall_s
        if len(self._times) == 1:
            self.version += 1
        if len(self._measured) >= max(self.n_coefficients + 2,
                                      REFIT_GROWTH * max(self._fitted_on, 1)):
            self._fit()

    def _fit(self) -> None:
        done = list(self._measured)
        a = np.array([self._rows[k] for k in done])
        y = np.array([self._measured[k] for k in done])
        self._coef = trimmed_least_squares(a, y)
        self._fitted_on = len(done)
        self.version += 1

    @property
    def typical_s(self) -> float:
        """Median measured wall time of a point [s] (NaN: none yet).

        Returns
        -------
        float
            The median [s] or NaN.
        """
        return statistics.median(self._times) if self._times else math.nan

    def estimate(self, index: int) -> float:
        """Estimated wall time of a point [s]: the fit, else the typical time (NaN before any
        point is back).

        Parameters
        ----------
        index : int
            The point number.

        Returns
        -------
        float
            The estimate [s], > 0, or NaN.
        """
        if self._coef is None or index not in self._rows:
            return self.typical_s
        return max(float(self._rows[index] @ self._coef), 0.1 * min(self._measured.values()))

    def longest_first(self, indices: Sequence[int]) -> list[int]:
        """The points in the order to run them: longest estimated first (by the fit once
        there is one, else by the a-priori rank); equal estimates keep their order.

        Parameters
        ----------
        indices : sequence of int
            Point numbers.

        Returns
        -------
        list of int
            The same point numbers, reordered.
        """
        if self._coef is not None:
            return sorted(indices, key=lambda k: -self.estimate(k))
        return sorted(indices, key=lambda k: -self._prior.get(k, 0.0))
