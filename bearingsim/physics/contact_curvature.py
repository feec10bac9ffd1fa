"""Curvature of a ball-raceway contact: the effective radii along and across the rolling
direction (:func:`raceway_radii`), their curvature sum and curvature difference (Hamrock; Harris
& Kotzalas, *Essential Concepts*, chapter "Contact stress and deformation"), the geometric input
of the Hertz solution in :mod:`bearingsim.physics.hertz`.

Every function works on floats, numpy arrays and CasADi SX alike.
"""

from __future__ import annotations

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.physical_checks import MAX_BALL_DIAMETER, check_diameter, check_radii
from bearingsim.validation import check_choice, check_range

__all__ = [
    "raceway_radii",
    "curvature_sum",
    "curvature_difference",
]


def raceway_radii(ball_diameter, pitch_diameter, groove_factor, contact_angle, race: str):
    """Effective radii of a ball-raceway contact (Hamrock; Harris & Kotzalas).

    ``Rx = Dw (1 -+ gamma) / 2`` (inner -, outer +), ``Ry = f Dw / (2 f - 1)``,
    ``gamma = Dw cos(alpha) / dm``.

    Parameters
    ----------
    ball_diameter : float or array or SX
        Ball diameter Dw [m], in (0, 0.5] (:data:`MAX_BALL_DIAMETER`).
    pitch_diameter : float or array or SX
        Pitch diameter dm [m], in (0, 6] (:data:`MAX_BEARING_DIAMETER`).
    groove_factor : float or array or SX
        Groove curvature factor f = groove radius / Dw [-], > 0.5.
    contact_angle : float or array or SX
        Contact angle [rad].
    race : {"inner", "outer"}
        Which raceway.

    Returns
    -------
    (Rx, Ry) : tuple
        Effective radii along and across the rolling direction [m].
    """
    where = "raceway_radii"
    check_diameter(ball_diameter, "ball_diameter", where, MAX_BALL_DIAMETER)
    check_diameter(pitch_diameter, "pitch_diameter", where)
    check_range(groove_factor, "groove_factor", "-", 0.5, 1.0, low_inclusive=False, where=where)
    check_range(contact_angle, "contact_angle", "rad", -np.pi / 2, np.pi / 2, where=where)
    check_choice(race, "race", ("inner", "outer"), where)
    gamma = ball_diameter * op.cos(contact_angle) / pitch_diameter
    check_range(gamma, "Dw cos(alpha)/dm", "-", 0.0, 1.0, high_inclusive=False, where=where)
    sign = -1.0 if race == "inner" else 1.0
    rx = 0.5 * ball_diameter * (1.0 + sign * gamma)
    ry = groove_factor * ball_diameter / (2.0 * groove_factor - 1.0)
    return rx, ry


def curvature_sum(rx, ry):
    """Curvature sum ``1/Rx + 1/Ry`` [1/m] (Harris's sum rho).

    Parameters
    ----------
    rx, ry : float or array
        Effective radii of curvature in the rolling and transverse directions [m], > 0.

    Returns
    -------
    float or array
        Curvature sum [1/m].
    """
    check_radii(rx, ry, "curvature_sum")
    return 1.0 / rx + 1.0 / ry


def curvature_difference(rx, ry):
    """Curvature difference ``F(rho) = (1/Rx - 1/Ry) / (1/Rx + 1/Ry)`` [-] (Harris).

    Parameters
    ----------
    rx, ry : float or array
        Effective radii of curvature in the rolling and transverse directions [m], > 0.

    Returns
    -------
    float or array
        Curvature difference [-].
    """
    check_radii(rx, ry, "curvature_difference")
    return (ry - rx) / (ry + rx)


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
