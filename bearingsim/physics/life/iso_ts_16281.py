"""ISO/TS 16281:2008 basic reference rating life from the internal load distribution: the
raceway ratings consistent with C of ISO 281 and the life from the ball loads, or from the slice
loads of the rollers.

**Roller bearings** (Lundberg-Palmgren line contact with the slice method): each roller is cut
into ``ns`` slices; slice ``k`` of the inner and outer raceway has the dynamic rating
``q_c,k = Q_c ns^(-7/9)`` (a contact's capacity goes with its length to the power 7/9), the
equivalent load ``q_e,k = (1/Z sum_j q_jk^4)^(1/4)`` on the rotating ring and ``(1/Z sum_j
q_jk^(9/2))^(2/9)`` on the stationary one, and the life is
``L10r = (sum_k (q_ci,k/q_ei,k)^(-9/2) + (q_ce,k/q_ee,k)^(-9/2))^(-8/9)`` [10^6 rev].
The raceway ratings ``Q_ci``, ``Q_ce`` are those consistent with C, as
:func:`raceway_dynamic_ratings` does for balls: at zero clearance and a pure radial load (load
zone ``epsilon = 0.5``) the life is ``(C/Fr)^(10/3)``. The constants of that consistency are the
line-contact load integrals (Sjovall; Harris & Kotzalas, *Essential Concepts*, chapter
"Distribution of internal loading"): ``Jr(0.5) = 0.2448`` (so ``Q_max = Fr / (Z Jr) = 4.08 Fr /
Z``, NSK CAT. No. E728g, section 5.1, eq. (5)), ``J1 = 0.6504``, ``J2 = 0.6743``;
``552 Jr/J1 = 207.8`` and ``J2/J1 = 1.037`` are ISO 281's 207.9 and 1.04
(:func:`~bearingsim.physics.life.lundberg_palmgren.line_load_integrals`). The standard's text
itself was not retrievable; the slice exponents are the Lundberg-Palmgren line-contact ones
(load-life exponent 4 per contact, Weibull slope 9/8). Not included: the life modification
factor a_ISO and the reliability factor a1.

The load distribution in the standard's own kinematics is :mod:`bearingsim.physics.iso_ts_16281`.
Lives are in millions of revolutions. Functions take floats, numpy arrays or CasADi SX.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physics.life.lundberg_palmgren import (
    bearing_life,
    contact_life,
    line_load_integrals,
    raceway_equivalent_load,
)
from bearingsim.physics.life.tables import (
    LINE_CAPACITY_RATIO_EXPONENT,
    ball_entries,
    check_roller_gamma,
)
from bearingsim.validation import check_count, check_range

__all__ = [
    "raceway_dynamic_ratings",
    "reference_rating_life",
    "roller_raceway_ratings",
    "slice_equivalent_load",
    "roller_reference_rating_life",
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

    Returns
    -------
    (Q_ci, Q_ce) : tuple [N]
        Inner and outer raceway contact ratings.
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


def roller_raceway_ratings(c: float, gamma: float, roller_count: int) -> tuple[float, float]:
    """Basic dynamic ratings ``(Q_ci, Q_ce)`` of a whole roller's inner and outer raceway
    contact [N], consistent with C (contact angle 0, one row).

    ``Q_ci = C J1 / (Z Jr) [1 + (J2/J1 x)^(9/2)]^(2/9)``, ``Q_ce = Q_ci / x`` with
    ``x = ((1 - gamma)/(1 + gamma))^(143/108)`` (the Lundberg-Palmgren ratio of the two contacts'
    capacities) and the integrals of :func:`line_load_integrals` at ``epsilon = 0.5``.

    Parameters
    ----------
    c : float
        Basic dynamic radial load rating C [N], > 0.
    gamma : float
        ``Dwe / Dpw`` [-].
    roller_count : int
        Z.

    Returns
    -------
    (Q_ci, Q_ce) [N]
    """
    where = "roller_raceway_ratings"
    check_range(c, "c", "N", 0.0, low_inclusive=False, where=where)
    check_roller_gamma(gamma, where)
    check_count(roller_count, "roller_count", 3, where=where)
    jr, j1, j2 = line_load_integrals(0.5)
    x = ((1.0 - gamma) / (1.0 + gamma)) ** LINE_CAPACITY_RATIO_EXPONENT
    q_ci = c * j1 / (roller_count * jr) * (1.0 + (j2 / j1 * x) ** 4.5) ** (2.0 / 9.0)
    return q_ci, q_ci / x


def slice_equivalent_load(loads: Sequence[Any], rotating: bool) -> Any:
    """Equivalent load of one slice position of a raceway from the rollers' slice loads [N].

    Rotating ring: ``(1/Z sum q_j^4)^(1/4)``; stationary ring: ``(1/Z sum q_j^(9/2))^(2/9)``.

    Parameters
    ----------
    loads : sequence of float or SX
        The slice load of every roller at this slice position [N], >= 0.
    rotating : bool
        Whether the raceway rotates relative to the load.

    Returns
    -------
    float or SX
        q_e [N].
    """
    if isinstance(loads, (str, bytes)) or not hasattr(loads, "__iter__"):
        raise ParameterError(f"slice_equivalent_load: loads [N] must be a sequence with one "
                             f"entry per roller, got {loads!r:.60}")
    q = list(loads)
    if not q:
        raise ParameterError("slice_equivalent_load: loads [N] needs one entry per roller")
    for value in q:
        check_range(value, "loads", "N", 0.0, where="slice_equivalent_load")
    w = 4.0 if rotating else 4.5
    return op.power(sum(op.power(v, w) for v in q) / len(q), 1.0 / w)


def _rollers(value: Any, name: str) -> list[list]:
    """The slice loads of every roller as lists (a clear error for anything else)."""
    def sequence(v):
        return not isinstance(v, (str, bytes)) and hasattr(v, "__len__") and \
            hasattr(v, "__getitem__")

    if not sequence(value) or not all(sequence(r) for r in value):
        raise ParameterError(f"roller_reference_rating_life: {name} [N] must hold one sequence "
                             f"of slice loads per roller, got {value!r:.60}")
    return [list(r) for r in value]


def roller_reference_rating_life(slice_loads_inner: Sequence[Sequence[Any]],
                                 slice_loads_outer: Sequence[Sequence[Any]], c: float,
                                 gamma: float, inner_rotating: bool = True) -> Any:
    """ISO/TS 16281 (roller form) basic reference rating life L10r [10^6 rev].

    Parameters
    ----------
    slice_loads_inner, slice_loads_outer : Z sequences of ns loads
        Slice loads of every roller on the inner and outer raceway [N], roller by roller
        (including unloaded rollers), the same shape on both raceways.
    c : float
        Basic dynamic radial load rating C [N].
    gamma : float
        ``Dwe / Dpw`` [-].
    inner_rotating : bool
        Whether the inner ring rotates relative to the load.

    Returns
    -------
    float or SX
        L10r [10^6 revolutions] (infinite without load).

    Raises
    ------
    ParameterError
        For loads of different shapes, or fewer than 3 rollers.
    """
    inner, outer = (_rollers(v, name) for v, name in ((slice_loads_inner, "slice_loads_inner"),
                                                      (slice_loads_outer, "slice_loads_outer")))
    shape = (len(inner), len(inner[0]) if inner else 0)
    if shape != (len(outer), len(outer[0]) if outer else 0) or any(
            len(r) != shape[1] for r in inner + outer) or shape[1] == 0:
        raise ParameterError(
            "roller_reference_rating_life: slice_loads_inner and slice_loads_outer [N] need "
            "the same number of rollers, each with the same number (>= 1) of slices")
    z, ns = shape
    q_ci, q_ce = roller_raceway_ratings(c, gamma, z)
    q_ci_k, q_ce_k = q_ci * ns ** (-7.0 / 9.0), q_ce * ns ** (-7.0 / 9.0)
    total = 0.0
    for k in range(ns):
        q_ei = slice_equivalent_load([inner[j][k] for j in range(z)], inner_rotating)
        q_ee = slice_equivalent_load([outer[j][k] for j in range(z)], not inner_rotating)
        total = total + op.power(q_ei / q_ci_k, 4.5) + op.power(q_ee / q_ce_k, 4.5)
    if not op.is_symbolic(total) and float(total) == 0.0:
        return math.inf
    return op.power(total, -8.0 / 9.0)


# no NaN in or out (bearingsim.checks); an unloaded contact's life is infinite
guard_public_functions(globals(), infinite_results=True)
