"""What the bearing formulas of ISO 281, ISO 76, Lundberg-Palmgren and ISO/TS 16281 share: the
piecewise-linear table look-up, the checks of a ball or roller set's dimensions and the
millimetre scale the standards' formulas are written in.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from bearingsim import symbolic as op
from bearingsim.errors import ParameterError
from bearingsim.physical_checks import MAX_BALL_DIAMETER, check_diameter
from bearingsim.physics.geometry import pitch_ratio
from bearingsim.validation import check_count, check_range

MM_PER_M = 1e3
"""Metres to millimetres, the unit of the ISO formulas [mm/m]."""
DW_LARGE_MM = 25.4
"""Ball diameter [mm] above which ISO 281 and Lundberg-Palmgren use ``3.647 Dw^1.4`` for
``Dw^1.8``."""
LINE_CAPACITY_RATIO_EXPONENT = 143.0 / 108.0
"""Exponent of ``(1 - gamma)/(1 + gamma)`` in the ratio of the inner to the outer line-contact
capacity (Lundberg-Palmgren; ISO 281's roller fc) [-]."""


def interp(x, xs: Sequence[float], ys: Sequence[float]):
    """Piecewise-linear interpolation, constant beyond the ends; symbolic-safe (sum of ramps).

    Parameters
    ----------
    x : float or SX
        Abscissa.
    xs : sequence of float
        Table abscissae, increasing.
    ys : sequence of float
        Table values at ``xs``.

    Returns
    -------
    float or SX
        The interpolated value.
    """
    x = op.fmin(op.fmax(x, xs[0]), xs[-1])
    result = ys[0]
    previous_slope = 0.0
    for j in range(len(xs) - 1):
        slope = (ys[j + 1] - ys[j]) / (xs[j + 1] - xs[j])
        result = result + (slope - previous_slope) * op.fmax(x - xs[j], 0.0)
        previous_slope = slope
    return result


def within_table(gamma, table: Sequence[float], where: str):
    """Check ``gamma = Dw cos(a)/dm`` against a table's range and clip round-off at its ends.

    Values within a relative 1e-9 of an end (e.g. ``dm`` computed from a ratio) count as the end.

    Parameters
    ----------
    gamma : float or array or SX
        Dw cos(a)/dm [-].
    table : sequence of float
        The table's gamma values, increasing.
    where : str
        The model or function, for error messages.

    Returns
    -------
    float or array or SX
        gamma [-], clipped to the table's range.
    """
    lo, hi = table[0], table[-1]
    check_range(gamma, "Dw cos(alpha)/dm", "-", lo * (1.0 - 1e-9), hi * (1.0 + 1e-9), where=where)
    return op.fmin(op.fmax(gamma, lo), hi)


def check_ball_set(ball_diameter, pitch_diameter, ball_count, contact_angle, rows, where):
    """Check a ball set (Dw, dm, Z, contact angle, rows i) and return ``gamma = Dw cos(a)/dm``.

    Parameters
    ----------
    ball_diameter : float or array or SX
        Ball diameter Dw [m], in (0, 0.5].
    pitch_diameter : float or array or SX
        Pitch diameter dm [m], in (0, 6].
    ball_count : int or float or SX
        Balls per row Z [-], >= 3.
    contact_angle : float or array or SX
        Contact angle [rad], in [0, pi/4].
    rows : int
        Number of rows i [-], a whole number >= 1.
    where : str
        The function, for error messages.

    Returns
    -------
    float or array or SX
        gamma [-].
    """
    check_diameter(ball_diameter, "ball_diameter", where, MAX_BALL_DIAMETER)
    check_diameter(pitch_diameter, "pitch_diameter", where)
    check_range(ball_count, "ball_count", "-", 3, where=where)
    check_range(contact_angle, "contact_angle", "rad", 0.0, np.pi / 4, where=where)
    check_count(rows, "rows", 1, where=where)
    return pitch_ratio(ball_diameter, pitch_diameter, contact_angle)


def ball_entries(values) -> list:
    """Per-ball entries of a list, a numpy array (balls along axis 0) or an SX column.

    Parameters
    ----------
    values : list or ndarray or SX
        One entry per ball.

    Returns
    -------
    list
        The entries, one per ball.
    """
    if hasattr(values, "shape"):
        return [values[j] for j in range(values.shape[0])]
    return list(values)


def check_roller_gamma(gamma, where: str):
    """Check a roller set's ``gamma = Dwe cos(a)/Dpw`` [-], in (0, 1).

    Parameters
    ----------
    gamma : float or array or SX
        Dwe cos(a)/Dpw [-].
    where : str
        The function, for error messages.

    Returns
    -------
    float or array or SX
        gamma [-], checked.
    """
    return check_range(gamma, "gamma", "-", 0.0, 1.0, low_inclusive=False, high_inclusive=False,
                       where=where)


def check_roller_set(roller_diameter, pitch_diameter, roller_count, length, where):
    """Check a roller set: Dwe, Dpw > Dwe, Lwe [m] and Z >= 3.

    Parameters
    ----------
    roller_diameter : float or array or SX
        Roller diameter Dwe [m], > 0.
    pitch_diameter : float or array or SX
        Pitch diameter Dpw [m], > Dwe.
    roller_count : int or float
        Rollers per row Z [-], >= 3.
    length : float or array or SX
        Effective roller length Lwe [m], > 0.
    where : str
        The function, for error messages.
    """
    check_range(roller_diameter, "roller_diameter", "m", 0.0, low_inclusive=False, where=where)
    check_range(pitch_diameter, "pitch_diameter", "m", roller_diameter, low_inclusive=False,
                where=where)
    check_count(roller_count, "roller_count", 3, where=where)
    check_range(length, "length", "m", 0.0, low_inclusive=False, where=where)


def check_life(value, name: str, where: str) -> None:
    """Lives must be > 0; unlike check_range, an infinite life (an unloaded contact) is allowed.

    Parameters
    ----------
    value : float or array or SX
        Life [10^6 revolutions], > 0 (inf allowed); symbols pass unchecked.
    name : str
        Parameter name, for the message.
    where : str
        The function, for the message.
    """
    if op.is_symbolic(value):
        return
    arr = np.asarray(value, dtype=float)
    if np.any(np.isnan(arr)) or np.any(arr <= 0.0):
        raise ParameterError(f"{where}: {name} must be > 0 (inf allowed) [1e6 rev], got {value}")
