"""Pure-rolling kinematics of a ball bearing (no slip, balls at a common contact angle).

Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., *Essential Concepts of Bearing Technology*,
chapter "Rolling bearing kinematics", with the ball's rolling axis inclined at the contact angle.
Speeds are angular speeds about the bearing axis [rad/s]; floats, arrays and CasADi SX alike.
"""

from __future__ import annotations

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.validation import check_choice, check_finite, check_range

__all__ = [
    "pitch_ratio",
    "cage_speed",
    "ball_rotation_speed",
    "ball_revolutions_per_revolution",
    "ball_pass_ratio",
]


_RIGHT_ANGLE = 0.5 * np.pi


def pitch_ratio(ball_diameter, pitch_diameter, contact_angle=0.0):
    """Dimensionless ball size ``gamma = Dw cos(alpha) / dm`` [-].

    Parameters
    ----------
    ball_diameter : float or array or SX
        Ball diameter Dw [m], > 0.
    pitch_diameter : float or array or SX
        Pitch diameter dm [m], > Dw.
    contact_angle : float or array or SX
        Contact angle [rad], in [0, pi/2) (0 to below 90 deg: the radial-bearing kinematics of
        this module).

    Returns
    -------
    float or array or SX
        ``gamma`` [-], in (0, 1).

    Raises
    ------
    ParameterError
        For a diameter <= 0, ``Dw >= dm`` or a contact angle outside [0, 90) deg.
    """
    where = "pitch_ratio"
    check_range(contact_angle, "contact_angle", "rad", 0.0, _RIGHT_ANGLE, high_inclusive=False,
                where=where)
    check_range(ball_diameter, "ball_diameter", "m", 0.0, low_inclusive=False, where=where)
    check_range(pitch_diameter, "pitch_diameter", "m", 0.0, low_inclusive=False, where=where)
    check_range(ball_diameter / pitch_diameter, "ball_diameter/pitch_diameter", "-", 0.0, 1.0,
                high_inclusive=False, where=where)
    return ball_diameter * op.cos(contact_angle) / pitch_diameter


def cage_speed(omega_inner, omega_outer, gamma):
    """Cage (ball orbital) speed of pure rolling ``((1 - g) w_i + (1 + g) w_o) / 2`` [rad/s].

    Parameters
    ----------
    omega_inner, omega_outer : float or array or SX
        Inner- and outer-ring speeds [rad/s].
    gamma : float or array or SX
        Pitch ratio Dw cos(alpha) / dm [-], see :func:`pitch_ratio`.

    Returns
    -------
    float or array or SX
        Cage speed [rad/s].
    """
    check_range(gamma, "gamma", "-", 0.0, 1.0, high_inclusive=False, where="cage_speed")
    check_finite("cage_speed", "rad/s", omega_inner=omega_inner, omega_outer=omega_outer)
    return 0.5 * ((1.0 - gamma) * omega_inner + (1.0 + gamma) * omega_outer)


def ball_revolutions_per_revolution(ball_diameter, pitch_diameter, contact_angle=0.0):
    """Ball revolutions about its own axis, relative to the cage, per relative ring revolution.

    ``N = dm cos(alpha) (1 - gamma^2) / (2 Dw)`` [-] (the ``N_j`` of the ball life terms in
    docs/studies.md, section C).

    Parameters are those of :func:`pitch_ratio`.

    Parameters
    ----------
    ball_diameter : float
        Dw [m].
    pitch_diameter : float
        dm [m].
    contact_angle : float
        alpha [rad].

    Returns
    -------
    float
        N [-].
    """
    gamma = pitch_ratio(ball_diameter, pitch_diameter, contact_angle)
    return pitch_diameter * op.cos(contact_angle) * (1.0 - gamma * gamma) / (2.0 * ball_diameter)


def ball_rotation_speed(omega_inner, omega_outer, ball_diameter, pitch_diameter,
                        contact_angle=0.0):
    """Ball speed about its own axis relative to the cage, ``N (w_i - w_o)`` [rad/s].

    Parameters
    ----------
    omega_inner, omega_outer : float or array or SX
        Ring speeds [rad/s].
    ball_diameter, pitch_diameter, contact_angle
        As in :func:`pitch_ratio`.

    Returns
    -------
    float or array or SX
        Ball spin speed relative to the cage [rad/s].
    """
    n = ball_revolutions_per_revolution(ball_diameter, pitch_diameter, contact_angle)
    return n * (omega_inner - omega_outer)


def ball_pass_ratio(ball_count, gamma, race: str):
    """Balls passing a point of a raceway per relative ring revolution [-].

    ``Z (1 + gamma) / 2`` for the inner and ``Z (1 - gamma) / 2`` for the outer raceway: the
    ball pass frequencies BPFI, BPFO over the relative shaft frequency, and the stress cycles per
    revolution of a raceway point in Lundberg-Palmgren theory.

    Parameters
    ----------
    ball_count : int or float
        Number of balls Z [-].
    gamma : float or array or SX
        Pitch ratio [-].
    race : {"inner", "outer"}

    Returns
    -------
    float or array or SX
        Ball passes per relative revolution [-].
    """
    check_range(ball_count, "ball_count", "-", 3, where="ball_pass_ratio")
    check_range(gamma, "gamma", "-", 0.0, 1.0, high_inclusive=False, where="ball_pass_ratio")
    check_choice(race, "race", ("inner", "outer"), "ball_pass_ratio")
    sign = 1.0 if race == "inner" else -1.0
    return 0.5 * ball_count * (1.0 + sign * gamma)


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
