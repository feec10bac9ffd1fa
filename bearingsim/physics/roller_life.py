"""Ratings and life of radial cylindrical roller bearings: ISO 281, ISO 76 and the roller (line
contact, sliced) form of ISO/TS 16281.

* **Basic rating life**: ``L10 = (C/P)^(10/3)`` (:func:`~bearingsim.physics.life.rating_life`
  with :data:`LINE_LIFE_EXPONENT`).
* **Basic dynamic radial load rating** (ISO 281:2007, eq. for radial roller bearings):
  ``Cr = bm fc (i Lwe cos a)^(7/9) Z^(3/4) Dwe^(29/27)`` [N, mm], ``bm = 1.1`` for cylindrical
  roller bearings (ISO 281:2007, Table 8) and ``fc`` of Table 7, the closed form
  ``fc = 207.9 lambda nu gamma^(2/9) (1 - gamma)^(29/27) (1 + gamma)^(-1/4)
  [1 + (1.04 ((1 - gamma)/(1 + gamma))^(143/108))^(9/2)]^(-2/9)`` with ``lambda nu = 0.83`` and
  ``gamma = Dwe cos a / Dpw`` (:func:`roller_fc`, which reproduces Table 7 to 0.05).
* **Basic static radial load rating** (ISO 76:2006, radial roller bearings):
  ``C0r = 44 (1 - Dwe cos a / Dpw) i Z Lwe Dwe cos a`` [N, mm].
* **Reference rating life from the load distribution** (ISO/TS 16281:2008, roller bearings;
  Lundberg-Palmgren line contact with the slice method): each roller is cut into ``ns`` slices;
  slice ``k`` of the inner and outer raceway has the dynamic rating ``q_c,k = Q_c ns^(-7/9)``
  (a contact's capacity goes with its length to the power 7/9), the equivalent load
  ``q_e,k = (1/Z sum_j q_jk^4)^(1/4)`` on the rotating ring and ``(1/Z sum_j
  q_jk^(9/2))^(2/9)`` on the stationary one, and the life is
  ``L10r = (sum_k (q_ci,k/q_ei,k)^(-9/2) + (q_ce,k/q_ee,k)^(-9/2))^(-8/9)`` [10^6 rev].
  The raceway ratings ``Q_ci``, ``Q_ce`` are those consistent with C, as
  :func:`~bearingsim.physics.life.raceway_dynamic_ratings` does for balls: at zero clearance
  and a pure radial load (load zone ``epsilon = 0.5``) the life is ``(C/Fr)^(10/3)``.
  The constants of that consistency are the line-contact load integrals (Sjovall; Harris &
  Kotzalas, *Essential Concepts*, chapter "Distribution of internal loading"):
  ``Jr(0.5) = 0.2448`` (so ``Q_max = Fr / (Z Jr) = 4.08 Fr / Z``, NSK CAT. No. E728g,
  section 5.1, eq. (5)), ``J1 = 0.6504``, ``J2 = 0.6743``; ``552 Jr/J1 = 207.8`` and
  ``J2/J1 = 1.037`` are ISO 281's 207.9 and 1.04 (:func:`line_load_integrals`).

The standard's text itself was not retrievable; the slice exponents are the Lundberg-Palmgren
line-contact ones (load-life exponent 4 per contact, Weibull slope 9/8). Not included: the
life modification factor a_ISO and the reliability factor a1.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from typing import Any

import numpy as np
from scipy.integrate import quad

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.validation import check_count, check_range

__all__ = [
    "CYLINDRICAL_BM",
    "LINE_LIFE_EXPONENT",
    "roller_fc",
    "roller_dynamic_load_rating",
    "roller_static_load_rating",
    "line_load_integrals",
    "roller_raceway_ratings",
    "slice_equivalent_load",
    "roller_reference_rating_life",
]

CYLINDRICAL_BM = 1.1
"""Rating factor bm of cylindrical roller bearings (ISO 281:2007, Table 8)."""
LINE_LIFE_EXPONENT = 10.0 / 3.0
"""Load-life exponent p of roller bearings, ``L10 = (C/P)^p``."""
_LAMBDA_NU = 0.83
_RATIO_EXPONENT = 143.0 / 108.0


def _check_gamma(gamma, where: str):
    return check_range(gamma, "gamma", "-", 0.0, 1.0, low_inclusive=False, high_inclusive=False,
                       where=where)


def roller_fc(gamma):
    """ISO 281 factor fc of radial roller bearings [N/mm^2-ish, ISO 281 units].

    Parameters
    ----------
    gamma : float or array
        ``Dwe cos(a) / Dpw`` [-], in (0, 1).

    Returns
    -------
    float or array
        fc (ISO 281:2007, Table 7, as its closed form).
    """
    _check_gamma(gamma, "roller_fc")
    g = np.asarray(gamma, dtype=float)
    ratio = (1.0 - g) / (1.0 + g)
    out = (207.9 * _LAMBDA_NU * g ** (2.0 / 9.0) * (1.0 - g) ** (29.0 / 27.0) * (1.0 + g) ** -0.25
           * (1.0 + (1.04 * ratio**_RATIO_EXPONENT) ** 4.5) ** (-2.0 / 9.0))
    return out[()]


def _check_roller_set(roller_diameter, pitch_diameter, roller_count, length, where):
    check_range(roller_diameter, "roller_diameter", "m", 0.0, low_inclusive=False, where=where)
    check_range(pitch_diameter, "pitch_diameter", "m", roller_diameter, low_inclusive=False,
                where=where)
    check_count(roller_count, "roller_count", 3, where=where)
    check_range(length, "length", "m", 0.0, low_inclusive=False, where=where)


def roller_dynamic_load_rating(roller_diameter: float, pitch_diameter: float, roller_count: int,
                               length: float, rows: int = 1, bm: float = CYLINDRICAL_BM) -> float:
    """ISO 281 basic dynamic radial load rating of a cylindrical roller bearing [N].

    ``Cr = bm fc (i Lwe)^(7/9) Z^(3/4) Dwe^(29/27)`` (contact angle 0), evaluated in mm and N.

    Parameters
    ----------
    roller_diameter, pitch_diameter : float
        Dwe and Dpw [m].
    roller_count : int
        Rollers per row Z.
    length : float
        Effective roller length Lwe [m].
    rows : int
        Number of rows i.
    bm : float
        Rating factor (default :data:`CYLINDRICAL_BM`).

    Returns
    -------
    float
        Cr [N].
    """
    where = "roller_dynamic_load_rating"
    _check_roller_set(roller_diameter, pitch_diameter, roller_count, length, where)
    check_count(rows, "rows", 1, where=where)
    check_range(bm, "bm", "-", 0.0, low_inclusive=False, where=where)
    fc = roller_fc(roller_diameter / pitch_diameter)
    return float(bm * fc * (rows * length * 1e3) ** (7.0 / 9.0) * roller_count**0.75
                 * (roller_diameter * 1e3) ** (29.0 / 27.0))


def roller_static_load_rating(roller_diameter: float, pitch_diameter: float, roller_count: int,
                              length: float, rows: int = 1) -> float:
    """ISO 76 basic static radial load rating of a cylindrical roller bearing [N].

    ``C0r = 44 (1 - Dwe/Dpw) i Z Lwe Dwe`` (contact angle 0), in mm and N.

    Parameters
    ----------
    roller_diameter, pitch_diameter : float
        Dwe and Dpw [m].
    roller_count : int
        Z.
    length : float
        Lwe [m].
    rows : int
        i.

    Returns
    -------
    float
        C0r [N].
    """
    where = "roller_static_load_rating"
    _check_roller_set(roller_diameter, pitch_diameter, roller_count, length, where)
    check_count(rows, "rows", 1, where=where)
    gamma = roller_diameter / pitch_diameter
    return float(44.0 * (1.0 - gamma) * rows * roller_count * length * 1e3
                 * roller_diameter * 1e3)


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
    edge = math.acos(max(1.0 - 2.0 * epsilon, -1.0))

    def share(psi):
        return max(1.0 - (1.0 - math.cos(psi)) / (2.0 * epsilon), 0.0) ** (10.0 / 9.0)

    def mean(fn):
        return quad(fn, -edge, edge, limit=200)[0] / (2.0 * math.pi)

    jr = mean(lambda s: share(s) * math.cos(s))
    j1 = mean(lambda s: share(s) ** 4) ** 0.25
    j2 = mean(lambda s: share(s) ** 4.5) ** (2.0 / 9.0)
    return jr, j1, j2


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
    _check_gamma(gamma, where)
    check_count(roller_count, "roller_count", 3, where=where)
    jr, j1, j2 = line_load_integrals(0.5)
    x = ((1.0 - gamma) / (1.0 + gamma)) ** _RATIO_EXPONENT
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


# no NaN in or out (bearingsim.checks); an unloaded bearing's life is infinite
guard_public_functions(globals(), infinite_results=True)
