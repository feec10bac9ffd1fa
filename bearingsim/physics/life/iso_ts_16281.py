"""ISO/TS 16281:2008 basic reference rating life of ball bearings from the internal load
distribution: the raceway ratings consistent with C of ISO 281 and the life from the ball loads.

The load distribution in the standard's own kinematics is :mod:`bearingsim.physics.iso_ts_16281`.
Lives are in millions of revolutions. Functions take floats, numpy arrays or CasADi SX.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physics.life.lundberg_palmgren import (
    bearing_life,
    contact_life,
    raceway_equivalent_load,
)
from bearingsim.physics.life.tables import ball_entries
from bearingsim.validation import check_count, check_range

__all__ = [
    "raceway_dynamic_ratings",
    "reference_rating_life",
]


def raceway_dynamic_ratings(c, fi, fo, gamma, ball_count, contact_angle=0.0, rows=1):
    """ISO/TS 16281:2008 basic dynamic load ratings of the raceway contacts, (Q_ci, Q_ce) [N].

    ``Q_ci = C / (0.407 Z i^0.7 cos a) (1 + x^(10/3))^0.3``,
    ``Q_ce = C / (0.389 Z i^0.7 cos a) (1 + x^(-10/3))^0.3`` with
    ``x = 1.044 ((1 - g)/(1 + g))^1.72 (fi (2 fo - 1) / (fo (2 fi - 1)))^0.41``: the ball loads for
    which the inner and outer raceways reach 10^6 revolutions, consistent with C of ISO 281.

    Checked: the constants 0.407, 0.389, 1.044, 1.72, 0.41, 10/3 and 0.3 agree with an independent
    public implementation of ISO/TS 16281 (GitHub ``minzhun/ISO16281``, ``BallBearing.py``,
    "Equation 19-24"); the standard's text itself was not retrievable. That implementation divides
    by ``(i cos a)^0.7`` where this function divides by ``i^0.7 cos a``. This function's form is
    the one consistent with ISO 281 and Lundberg-Palmgren: ISO 281's ``(i cos a)^0.7`` multiplies
    an ``fc(gamma)`` that contains ``gamma^0.3 = (Dw/dm)^0.3 cos(a)^0.3``, while the
    Lundberg-Palmgren capacity (:func:`raceway_contact_capacity`, ``(Dw/dm)^0.3``) enters C as
    ``0.407 Z Q_c i^0.7 cos a``; so ``Q_ci`` here is the same multiple (1.244) of the
    Lundberg-Palmgren capacity at every contact angle, whereas ``(i cos a)^0.7`` would change it
    by ``cos(a)^0.3`` (1 % at 15 deg, 2.9 % at 25 deg; test_published_examples.py). Whether the
    printed ISO/TS 16281 eq. (19)/(20) reads ``i^0.7 cos a`` remains unchecked.

    Parameters
    ----------
    c : float or array or SX
        Basic dynamic radial load rating C [N].
    fi, fo : float or array or SX
        Groove curvature factors [-].
    gamma : float or array or SX
        Dw cos(a) / dm [-].
    ball_count : int or float
        Balls per row Z [-].
    contact_angle : float or array or SX
        Nominal contact angle [rad].
    rows : int
        Number of rows i [-], a whole number >= 1.
    """
    where = "raceway_dynamic_ratings"
    check_range(c, "c", "N", 0.0, low_inclusive=False, where=where)
    check_range(fi, "fi", "-", 0.5, 1.0, low_inclusive=False, where=where)
    check_range(fo, "fo", "-", 0.5, 1.0, low_inclusive=False, where=where)
    check_range(gamma, "gamma", "-", 0.0, 1.0, high_inclusive=False, where=where)
    check_range(ball_count, "ball_count", "-", 3, where=where)
    check_range(contact_angle, "contact_angle", "rad", 0.0, np.pi / 4, where=where)
    check_count(rows, "rows", 1, where=where)
    x = 1.044 * op.power((1.0 - gamma) / (1.0 + gamma), 1.72) * op.power(
        fi * (2.0 * fo - 1.0) / (fo * (2.0 * fi - 1.0)), 0.41)
    base = c / (ball_count * op.power(rows, 0.7) * op.cos(contact_angle))
    return (base / 0.407 * op.power(1.0 + op.power(x, 10.0 / 3.0), 0.3),
            base / 0.389 * op.power(1.0 + op.power(x, -10.0 / 3.0), 0.3))


def reference_rating_life(loads_inner, loads_outer, c, fi, fo, gamma, contact_angle=0.0,
                          rows=1, inner_rotating: bool = True) -> Any:
    """Basic reference rating life L10r from the internal load distribution [10^6 rev].

    In the manner of ISO/TS 16281:2008 for ball bearings: raceway ratings Q_ci, Q_ce from C
    (:func:`raceway_dynamic_ratings`), equivalent raceway loads from the ball loads
    (:func:`raceway_equivalent_load`, cubic mean on the rotating ring, 10/3 mean on the
    stationary one), raceway lives ``(Q_c/Q_e)^3`` combined by :func:`bearing_life`.

    Included: whatever the given contact loads contain (clearance, combined radial, axial and
    moment load, misalignment, centrifugal ball loads, which make inner and outer loads differ).
    Not included: the life modification factor a_ISO (lubrication, contamination, fatigue load
    limit), the reliability factor a1, ISO/TS 16281's treatment of roller bearings and of
    truncated contact ellipses, and the variation of the operating contact angle in Q_c (the
    nominal angle is used).

    Parameters
    ----------
    loads_inner, loads_outer : sequence or array or SX column
        Contact loads of every ball (including unloaded balls) on the inner and outer raceway
        [N], the same number of entries (one per ball) in both.
    c : float or array or SX
        Basic dynamic radial load rating C [N] (:func:`dynamic_load_rating` or catalogue).
    fi, fo, gamma, contact_angle, rows
        As in :func:`raceway_dynamic_ratings`.
    inner_rotating : bool
        Whether the inner ring rotates relative to the load (else the outer ring does).

    Returns
    -------
    L10r [10^6 revolutions]

    Raises
    ------
    ParameterError
        If ``loads_inner`` and ``loads_outer`` differ in length (Z is taken from them).
    """
    z = len(ball_entries(loads_inner))
    z_outer = len(ball_entries(loads_outer))
    if z != z_outer:
        raise ParameterError(
            f"reference_rating_life: loads_inner and loads_outer [N] need one entry per ball "
            f"each, got {z} and {z_outer}")
    qci, qce = raceway_dynamic_ratings(c, fi, fo, gamma, z, contact_angle, rows)
    qei = raceway_equivalent_load(loads_inner, rotating=inner_rotating)
    qee = raceway_equivalent_load(loads_outer, rotating=not inner_rotating)
    return bearing_life(contact_life(qci, qei), contact_life(qce, qee))


# no NaN in or out (bearingsim.checks); an unloaded contact's life is infinite
guard_public_functions(globals(), infinite_results=True)
