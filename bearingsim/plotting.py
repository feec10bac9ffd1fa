"""Plot helpers shared by :meth:`bearingsim.simulation.Result.plot` and the scene runner."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["WIDE_RANGE", "is_wide_positive", "set_value_scale"]

WIDE_RANGE = 1e3
"""Ratio of the largest to the smallest value above which a positive series is drawn on a
logarithmic axis (e.g. a rating life that falls from millions of hours at rest to a few
thousand at speed)."""


def is_wide_positive(values: Sequence[np.ndarray]) -> bool:
    """Whether the finite values of all series are positive and span at least
    :data:`WIDE_RANGE`.

    Parameters
    ----------
    values : sequence of numpy.ndarray
        The series drawn on one axis.

    Returns
    -------
    bool
    """
    finite = np.concatenate([np.asarray(v, dtype=float).ravel() for v in values])
    finite = finite[np.isfinite(finite)]
    if finite.size == 0 or np.min(finite) <= 0.0:
        return False
    return bool(np.max(finite) / np.min(finite) >= WIDE_RANGE)


def set_value_scale(ax, values: Sequence[np.ndarray]) -> None:
    """Use a logarithmic value axis for positive series spanning :data:`WIDE_RANGE` or more,
    a linear one otherwise.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axis the series are drawn on.
    values : sequence of numpy.ndarray
        Those series.
    """
    if is_wide_positive(values):
        ax.set_yscale("log")
