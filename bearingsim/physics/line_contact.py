"""Line contact of a cylindrical roller on a raceway: Palmgren's load-deflection law, its
sliced form, and the Hertz contact half-width and maximum pressure.

* **Load-deflection** (Palmgren, *Ball and Roller Bearing Engineering*, 3rd ed., 1959; Harris &
  Kotzalas, *Rolling Bearing Analysis*, 5th ed., *Essential Concepts*, chapter "Contact stress
  and deformation", line contact): the approach of one roller-raceway contact of effective
  length ``l`` under the load ``Q`` is ``delta = 3.84e-5 Q^0.9 / l^0.8`` [mm; Q in N, l in mm],
  independent of the radii. Two contacts in series (inner and outer raceway) approach by
  ``7.68e-5 Q^0.9 / l^0.8``, the constant 0.000077 of NSK's tapered-roller displacement
  ``delta_a = 0.000077 Fa^0.9 / ((sin a)^1.9 Z^0.9 Lwe^0.8)`` (NSK *Rolling Bearings*, CAT. No.
  E1102e, Technical Data, section 15.1 (2), p. A 129).
* **Sliced form**: a roller of effective length ``l`` cut into ``n`` slices of width ``w = l/n``;
  slice ``k`` with the approach ``delta_k`` carries the share ``w / l`` of the load the whole
  roller would carry at that approach, ``q_k = (1/n) l^(8/9) (delta_k / c)^(10/9)``. A uniform
  approach gives back Palmgren's law exactly; a tilted roller (misalignment) loads its slices
  unevenly (Harris & Kotzalas, *Advanced Concepts*, chapter "Distribution of internal
  loading", misaligned roller bearings, slice method).
* **Hertz line contact** (Harris & Kotzalas, *Essential Concepts*, chapter "Contact stress and
  deformation"): semi-width ``b = sqrt(8 Q R / (pi l E'))`` with ``E' = 2 / ((1 - nu1^2)/E1 +
  (1 - nu2^2)/E2)`` (:func:`~bearingsim.physics.materials.effective_modulus`), the reduced radius
  ``R = r1 r2 / (r1 + r2)`` of the roller and the raceway (:func:`line_contact_radius`), and
  maximum pressure ``p0 = 2 Q / (pi b l)``.

SI units: loads N, lengths m, pressures Pa. Floats, numpy arrays and CasADi SX alike.
"""

from __future__ import annotations

import math
from typing import Any

from bearingsim import symbolic as op
from bearingsim.errors import ParameterError
from bearingsim.physics.materials import STEEL, Material, effective_modulus
from bearingsim.validation import check_choice, check_count, check_range

__all__ = [
    "PALMGREN_LINE_CONSTANT_MM",
    "PALMGREN_LINE_CONSTANT",
    "MIN_LENGTH",
    "palmgren_deflection",
    "palmgren_load",
    "slice_loads",
    "line_contact_radius",
    "half_width",
    "max_pressure",
]

PALMGREN_LINE_CONSTANT_MM = 3.84e-5
"""Palmgren's constant of one line contact, ``delta = c Q^0.9 / l^0.8`` [mm, N, mm]."""
PALMGREN_LINE_CONSTANT = PALMGREN_LINE_CONSTANT_MM * 1e-3 * 1e3 ** -0.8
"""The same constant in SI, ``delta [m] = c Q^0.9 / l^0.8`` with Q [N], l [m]
(``3.84e-5 * 1e-3 * 1e3^0.8 = 1.5287e-10``)."""
MIN_LENGTH = 1e-6
"""Smallest contact length, radius and roller diameter accepted [m] (1 um: far below any
roller; below it the formulas overflow before they mean anything)."""
_LOAD_EXPONENT = 10.0 / 9.0
_LENGTH_EXPONENT = 8.0 / 9.0


def palmgren_deflection(load, length):
    """Approach of one roller-raceway line contact, ``delta = c Q^0.9 / l^0.8`` [m].

    Parameters
    ----------
    load : float, array or SX
        Contact load Q [N], >= 0.
    length : float
        Effective contact length l [m], >= 1 um.

    Returns
    -------
    float, array or SX
        Approach delta [m].
    """
    check_range(load, "load", "N", 0.0, where="palmgren_deflection")
    check_range(length, "length", "m", MIN_LENGTH, where="palmgren_deflection")
    return PALMGREN_LINE_CONSTANT * op.power(load, 0.9) / length**0.8


def palmgren_load(deflection, length, smooth=None):
    """Load of one line contact at the approach ``delta`` (Palmgren's law inverted) [N].

    ``Q = l^(8/9) (max(delta, 0) / c)^(10/9)``.

    Parameters
    ----------
    deflection : float, array or SX
        Approach delta [m] (negative: a gap, no load).
    length : float or SX
        Effective contact length l [m], >= 1 um.
    smooth : float, optional
        Regularization length [m]: ``max(delta, 0)`` becomes ``(delta + sqrt(delta^2 +
        smooth^2)) / 2`` so that equations stay differentiable (error at most smooth/2 in delta).

    Returns
    -------
    float, array or SX
        Q [N] >= 0.
    """
    check_range(deflection, "deflection", "m", where="palmgren_load")
    check_range(length, "length", "m", MIN_LENGTH, where="palmgren_load")
    if smooth is None:
        compression = op.fmax(deflection, 0.0)
    else:
        check_range(smooth, "smooth", "m", 0.0, low_inclusive=False, where="palmgren_load")
        compression = _smooth_compression(deflection, smooth)
    return op.power(length, _LENGTH_EXPONENT) * op.power(
        compression / PALMGREN_LINE_CONSTANT, _LOAD_EXPONENT)


def _smooth_compression(deflection, smooth):
    """``(d + sqrt(d^2 + e^2)) / 2``, written for a gap (``d < 0``) as ``e^2 / (2 (sqrt(d^2 +
    e^2) - d))``: the same value without the cancellation that makes the first form 0 or
    negative (and its power NaN) for ``|d| >> e``; both branches stay finite."""
    gap = op.fmin(deflection, 0.0)
    closed = op.fmax(deflection, 0.0)
    return op.if_else(deflection > 0.0,
                      0.5 * (closed + op.sqrt(closed * closed + smooth * smooth)),
                      0.5 * smooth * smooth / (op.sqrt(gap * gap + smooth * smooth) - gap))


def slice_loads(deflections, length, smooth=None) -> list:
    """Loads of the slices of one line contact (sliced Palmgren law) [N].

    Slice ``k`` of ``n`` carries ``q_k = Q(delta_k) / n`` with ``Q`` the whole contact's load at
    that approach (:func:`palmgren_load`), so a uniform approach gives Palmgren's load.

    Parameters
    ----------
    deflections : sequence of float or SX
        Approach of each slice [m] (n >= 1 slices of equal width).
    length : float or SX
        Effective length of the whole contact [m], > 0.
    smooth : float, optional
        Regularization length [m] (:func:`palmgren_load`).

    Returns
    -------
    list
        Slice loads [N].
    """
    if isinstance(deflections, (str, bytes)) or not hasattr(deflections, "__len__"):
        raise ParameterError(f"slice_loads: deflections [m] must be a sequence with one "
                             f"approach per slice, got {deflections!r:.60}")
    n = len(deflections)
    check_count(n, "number of slices", 1, where="slice_loads")
    return [palmgren_load(d, length, smooth) / n for d in deflections]


def line_contact_radius(roller_diameter: float, pitch_diameter: float, race: str) -> float:
    """Reduced radius ``R`` of a roller on its raceway [m].

    Inner raceway (convex-convex): ``R = Dw (dm - Dw) / (2 dm)``; outer raceway
    (convex-concave): ``R = Dw (dm + Dw) / (2 dm)``.

    Parameters
    ----------
    roller_diameter, pitch_diameter : float
        Dw and dm [m], ``0 < Dw < dm``.
    race : {"inner", "outer"}

    Returns
    -------
    float
        R [m].
    """
    where = "line_contact_radius"
    check_range(roller_diameter, "roller_diameter", "m", MIN_LENGTH, where=where)
    check_range(pitch_diameter, "pitch_diameter", "m", roller_diameter, low_inclusive=False,
                where=where)
    check_choice(race, "race", ("inner", "outer"), where)
    sign = -1.0 if race == "inner" else 1.0
    return roller_diameter * (pitch_diameter + sign * roller_diameter) / (2.0 * pitch_diameter)


def half_width(load, length: float, radius: float, roller: Material = STEEL,
               ring: Material = STEEL) -> Any:
    """Hertz semi-width of a line contact, ``b = sqrt(8 Q R / (pi l E'))`` [m].

    Parameters
    ----------
    load : float, array or SX
        Contact load Q [N], >= 0.
    length : float
        Contact length l [m], >= 1 um.
    radius : float
        Reduced radius R [m], >= 1 um (:func:`line_contact_radius`).
    roller, ring : Material

    Returns
    -------
    float, array or SX
        b [m].
    """
    _check_hertz(load, length, radius, "half_width")
    e_eff = effective_modulus(roller, ring)
    return op.sqrt(8.0 * load * radius / (math.pi * length * e_eff))


def max_pressure(load, length: float, radius: float, roller: Material = STEEL,
                 ring: Material = STEEL) -> Any:
    """Hertz maximum pressure of a line contact, ``p0 = 2 Q / (pi b l) = sqrt(Q E' / (2 pi l
    R))`` [Pa].

    Parameters
    ----------
    load : float, array or SX
        Contact load Q [N], >= 0 (of the whole length, or of one slice with its width).
    length : float
        Contact length l [m], >= 1 um (the slice width for a slice load).
    radius : float
        Reduced radius R [m], >= 1 um.
    roller, ring : Material

    Returns
    -------
    float, array or SX
        p0 [Pa].
    """
    _check_hertz(load, length, radius, "max_pressure")
    e_eff = effective_modulus(roller, ring)
    return op.sqrt(load * e_eff / (2.0 * math.pi * length * radius))


def _check_hertz(load, length: float, radius: float, where: str) -> None:
    """The arguments of a Hertz line contact: load >= 0 N, length and radius >= 1 um."""
    check_range(load, "load", "N", 0.0, where=where)
    check_range(length, "length", "m", MIN_LENGTH, where=where)
    check_range(radius, "radius", "m", MIN_LENGTH, where=where)
