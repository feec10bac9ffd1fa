"""Lundberg-Palmgren lives of each ball-raceway contact (Harris & Kotzalas, *Rolling Bearing
Analysis*, 5th ed., *Essential Concepts of Bearing Technology*, chapter "Fatigue life: basic
theory and rating standards"), combined as docs/studies.md, section C prescribes, and the
raceway equivalent loads and bearing life they give; Sjovall's load integrals of a line contact
row (:func:`line_load_integrals`), which relate a roller bearing's C to its raceway ratings.

SI units at the interface (m, N, rad); the capacity formula is evaluated in mm and N inside.
Lives are in millions of revolutions. Functions take floats, numpy arrays or CasADi SX.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physics.geometry import ball_pass_ratio, pitch_ratio
from bearingsim.physics.life.tables import (
    DW_LARGE_MM,
    MM_PER_M,
    ball_entries,
    check_ball_set,
    check_life,
)
from bearingsim.validation import check_choice, check_range

__all__ = [
    "raceway_contact_capacity",
    "ball_contact_capacity",
    "contact_life",
    "combined_contact_life",
    "raceway_equivalent_load",
    "bearing_life",
    "line_load_integrals",
]

# Harris & Kotzalas: Lundberg-Palmgren constant of the raceway contact capacity, N and mm.
_LP_CONSTANT = 98.1


def _check_race(race: str, where: str) -> None:
    check_choice(race, "race", ("inner", "outer"), where)


def raceway_contact_capacity(ball_diameter, pitch_diameter, groove_factor, ball_count,
                             contact_angle, race: str):
    """Lundberg-Palmgren basic dynamic capacity Qc of a raceway contact [N] (Harris & Kotzalas).

    ``Qc = 98.1 (2f/(2f - 1))^0.41 (1 -+ g)^1.39 / (1 +- g)^(1/3) (Dw/dm)^0.3 Dw^1.8 Z^(-1/3)``
    (upper signs inner, lower outer raceway, Dw in mm; ``3.647 Dw^1.4`` for Dw > 25.4 mm): the
    ball load the raceway carries for 10^6 revolutions with 90 % reliability. The raceway life at a
    ball load Q is ``(Qc/Q)^3`` (:func:`contact_life`).

    Parameters
    ----------
    ball_diameter, pitch_diameter : float or array or SX
        Dw in (0, 0.5], dm in (0, 6] [m] (larger values are taken for millimetres).
    groove_factor : float or array or SX
        Groove curvature factor f of this raceway [-], > 0.5.
    ball_count : int or float
        Number of balls Z [-].
    contact_angle : float or array or SX
        Contact angle [rad].
    race : {"inner", "outer"}

    Returns
    -------
    Qc [N]
    """
    where = "raceway_contact_capacity"
    _check_race(race, where)
    gamma = check_ball_set(ball_diameter, pitch_diameter, ball_count, contact_angle, 1, where)
    check_range(groove_factor, "groove_factor", "-", 0.5, 1.0, low_inclusive=False, where=where)
    sign = -1.0 if race == "inner" else 1.0
    dw_mm = ball_diameter * MM_PER_M
    size = op.if_else(dw_mm <= DW_LARGE_MM, op.power(dw_mm, 1.8),
                      3.647 * op.power(dw_mm, 1.4))
    conformity = op.power(2.0 * groove_factor / (2.0 * groove_factor - 1.0), 0.41)
    return (_LP_CONSTANT * conformity * op.power(1.0 + sign * gamma, 1.39)
            / op.power(1.0 - sign * gamma, 1.0 / 3.0)
            * op.power(ball_diameter / pitch_diameter, 0.3) * size
            * op.power(ball_count, -1.0 / 3.0))


def ball_contact_capacity(ball_diameter, pitch_diameter, groove_factor, ball_count,
                          contact_angle, race: str):
    """Capacity of the ball surface at a raceway contact, for lives in ball revolutions [N].

    Lundberg-Palmgren theory gives the same stress field in the ball and in the raceway at a
    contact; the two differ in the length of the stressed track, ``pi dm (1 -+ g)`` on the raceway
    and ``pi Dw`` on the ball, and in the stress cycles per revolution, ``u`` (balls passing a
    raceway point per ring revolution, :func:`~bearingsim.physics.geometry.ball_pass_ratio`) and
    one per ball revolution. With the life in stress cycles proportional to
    ``track length^(-1/e)``, e = 10/9, this gives
    ``Qcb^3 = u Qc^3 (dm (1 -+ g) / Dw)^0.9``, and the ball life at load Q is ``(Qcb/Q)^3`` millions
    of ball revolutions. This is our derivation from the theory in Harris & Kotzalas (chapter
    "Fatigue life: basic theory and rating standards"); the formula of docs/studies.md, section C
    needs such ball lives but does not define them.

    Parameters
    ----------
    ball_diameter, pitch_diameter : float or array or SX
        Dw in (0, 0.5], dm in (0, 6] [m] (as :func:`raceway_contact_capacity`).
    groove_factor : float or array or SX
        Groove curvature factor f of this raceway [-], > 0.5.
    ball_count : int or float
        Number of balls Z [-].
    contact_angle : float or array or SX
        Contact angle [rad].
    race : {"inner", "outer"}
        The raceway of the contact.

    Returns
    -------
    Qcb [N]
    """
    qc = raceway_contact_capacity(ball_diameter, pitch_diameter, groove_factor, ball_count,
                                  contact_angle, race)
    gamma = pitch_ratio(ball_diameter, pitch_diameter, contact_angle)
    sign = -1.0 if race == "inner" else 1.0
    track_ratio = pitch_diameter * (1.0 + sign * gamma) / ball_diameter
    cycles = ball_pass_ratio(ball_count, gamma, race)
    return qc * op.power(cycles * op.power(track_ratio, 0.9), 1.0 / 3.0)


def contact_life(capacity, load):
    """Life of one contact ``L = (Qc/Q)^3`` [10^6 revolutions]; infinite at zero load.

    Parameters
    ----------
    capacity : float or array or SX
        Contact capacity Qc [N], > 0.
    load : float or array or SX
        Contact load Q [N], >= 0.

    Returns
    -------
    float or array or SX
        Life [10^6 revolutions], inf at zero load.
    """
    check_range(capacity, "capacity", "N", 0.0, low_inclusive=False, where="contact_life")
    check_range(load, "load", "N", 0.0, where="contact_life")
    with np.errstate(divide="ignore"):
        return op.power(load / capacity, -3.0)


def _per_ball(value, z: int, name: str, where: str) -> list:
    """One entry per ball: a sequence, array or SX column of length z, or one shared value."""
    if isinstance(value, (list, tuple)) or (
        hasattr(value, "shape") and int(np.prod(value.shape)) > 1
    ):
        items = ball_entries(value)
        if len(items) != z:
            raise ParameterError(
                f"{where}: {name} needs one entry per ball ({z}), got {len(items)}"
            )
        return items
    return [value] * z


def _inverse_life_power(life):
    """``L^(-10/9)``; zero for an infinite life."""
    return op.power(life, -10.0 / 9.0)


def _life_from_inverse_power(total):
    with np.errstate(divide="ignore"):
        return op.power(total, -0.9)


def combined_contact_life(life_outer, life_inner, life_ball_outer, life_ball_inner,
                          ball_revolutions):
    """Bearing life from the per-contact lives, as docs/studies.md, section C states it
    [10^6 rev].

    ``L10^(-10/9) = (1/Z) (sum_j L_1j^(-10/9) + sum_j L_2j^(-10/9))
    + sum_j (L_b1j / N_j)^(-10/9) + sum_j (L_b2j / N_j)^(-10/9)``.
    Note that both raceway terms average ``L^(-10/9)``, the rule of Harris & Kotzalas for a
    stationary ring; :func:`bearing_life` with :func:`raceway_equivalent_load` distinguishes the
    rotating ring.

    Parameters
    ----------
    life_outer, life_inner : sequence or array or SX column
        Lives L_1j, L_2j of the outer and inner raceway contacts of each ball j [10^6 rev]
        (:func:`contact_life` with :func:`raceway_contact_capacity`).
    life_ball_outer, life_ball_inner : sequence or array or SX column
        Lives L_b1j, L_b2j of ball j at its outer and inner contact [10^6 ball revolutions]
        (:func:`contact_life` with :func:`ball_contact_capacity`).
    ball_revolutions : float or sequence or array or SX
        Ball revolutions per ring revolution N_j [-] (one value for all balls or one per ball),
        see :func:`~bearingsim.physics.geometry.ball_revolutions_per_revolution`.

    Returns
    -------
    L10 [10^6 revolutions]
    """
    where = "combined_contact_life"
    outer = ball_entries(life_outer)
    z = len(outer)
    inner = _per_ball(life_inner, z, "life_inner", where)
    ball_outer = _per_ball(life_ball_outer, z, "life_ball_outer", where)
    ball_inner = _per_ball(life_ball_inner, z, "life_ball_inner", where)
    n = _per_ball(ball_revolutions, z, "ball_revolutions", where)
    for name, values in (("life_outer", outer), ("life_inner", inner),
                         ("life_ball_outer", ball_outer), ("life_ball_inner", ball_inner)):
        for value in values:
            check_life(value, name, where)
    for value in n:
        check_range(value, "ball_revolutions", "-", 0.0, low_inclusive=False, where=where)
    total = sum(_inverse_life_power(lo) + _inverse_life_power(li)
                for lo, li in zip(outer, inner, strict=True)) / z
    for lbo, lbi, nj in zip(ball_outer, ball_inner, n, strict=True):
        total = total + _inverse_life_power(lbo / nj) + _inverse_life_power(lbi / nj)
    return _life_from_inverse_power(total)


def raceway_equivalent_load(loads, rotating: bool):
    """Equivalent ball load of a raceway from the ball loads (Lundberg-Palmgren).

    Rotating ring (each point meets every ball load): ``Qe = (1/Z sum Q_j^3)^(1/3)``; stationary
    ring (each point always under the same ball position): ``Qe = (1/Z sum Q_j^(10/3))^0.3``
    (Harris & Kotzalas; ISO/TS 16281).

    Parameters
    ----------
    loads : sequence or array or SX column
        Contact load of every ball on this raceway, including unloaded balls [N], >= 0; at
        least one ball.
    rotating : bool
        Whether the raceway rotates relative to the load.

    Returns
    -------
    Qe [N]

    Raises
    ------
    ParameterError
        For an empty ``loads`` or a negative or non-finite load.
    """
    q = ball_entries(loads)
    if not q:
        raise ParameterError(
            "raceway_equivalent_load: loads [N] needs one entry per ball (at least one), got none")
    for value in q:
        check_range(value, "loads", "N", 0.0, where="raceway_equivalent_load")
    w = 3.0 if rotating else 10.0 / 3.0
    return op.power(sum(op.power(qj, w) for qj in q) / len(q), 1.0 / w)


def bearing_life(life_inner, life_outer):
    """Bearing life from the raceway lives, ``L = (L_i^(-10/9) + L_o^(-10/9))^(-9/10)`` [10^6 rev].

    Lundberg-Palmgren (Harris & Kotzalas); ISO/TS 16281. Infinite raceway lives are allowed.

    Parameters
    ----------
    life_inner, life_outer : float or array or SX
        Raceway lives [10^6 revolutions], > 0.

    Returns
    -------
    float or array or SX
        Bearing life [10^6 revolutions].
    """
    check_life(life_inner, "life_inner", "bearing_life")
    check_life(life_outer, "life_outer", "bearing_life")
    return _life_from_inverse_power(_inverse_life_power(life_inner)
                                    + _inverse_life_power(life_outer))


@lru_cache(maxsize=16)
def line_load_integrals(epsilon: float = 0.5) -> tuple[float, float, float]:
    """Sjovall's load integrals of a line contact row, ``(Jr, J1, J2)`` [-].

    With ``Q(psi) = Q_max (1 - (1 - cos psi) / (2 epsilon))^(10/9)`` (0 outside the load zone):
    ``Jr = 1/(2 pi) int (Q/Q_max) cos psi``, ``J1 = (1/(2 pi) int (Q/Q_max)^4)^(1/4)`` (rotating
    ring), ``J2 = (1/(2 pi) int (Q/Q_max)^(9/2))^(2/9)`` (stationary ring); ``Fr = Z Jr Q_max``.

    Parameters
    ----------
    epsilon : float
        Load zone parameter, in (0, 1] (0.5: zero clearance).

    Returns
    -------
    (Jr, J1, J2) : tuple of float
    """
    check_range(epsilon, "epsilon", "-", 0.0, 1.0, low_inclusive=False,
                where="line_load_integrals")
    from scipy.integrate import quad  # on use: scipy.integrate takes ~0.6 s to import

    edge = math.acos(max(1.0 - 2.0 * epsilon, -1.0))

    def share(psi):
        return max(1.0 - (1.0 - math.cos(psi)) / (2.0 * epsilon), 0.0) ** (10.0 / 9.0)

    def mean(fn):
        return quad(fn, -edge, edge, limit=200)[0] / (2.0 * math.pi)

    jr = mean(lambda s: share(s) * math.cos(s))
    j1 = mean(lambda s: share(s) ** 4) ** 0.25
    j2 = mean(lambda s: share(s) ** 4.5) ** (2.0 / 9.0)
    return jr, j1, j2


# no NaN in or out (bearingsim.checks); an unloaded contact's life is infinite
guard_public_functions(globals(), infinite_results=True)
