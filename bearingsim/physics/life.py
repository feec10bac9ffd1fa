"""Fatigue life of ball bearings: ISO 281, Lundberg-Palmgren per contact, ISO/TS 16281.

* ISO 281:2007 basic dynamic load rating C, equivalent dynamic load P (X, Y factors) and basic
  rating life ``L10 = (C/P)^3``; ISO 76:2006 basic static load rating C0, static factors
  X0, Y0 and the static equivalent load P0.
* Lundberg-Palmgren lives of each ball-raceway contact (Harris & Kotzalas, *Rolling Bearing
  Analysis*, 5th ed., *Essential Concepts of Bearing Technology*, chapter "Fatigue life: basic
  theory and rating standards"), combined as docs/studies.md, section C prescribes.
* A basic reference rating life from the internal load distribution in the manner of
  ISO/TS 16281:2008.

SI units at the interface (m, N, rad, rad/s); the ISO formulas are evaluated in their own units
(mm, N) inside. Lives are in millions of revolutions of the rotating ring relative to the other.
Functions take floats, numpy arrays or CasADi SX; table look-ups are piecewise linear.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from bearingsim import symbolic as op
from bearingsim.errors import ParameterError
from bearingsim.physics.geometry import ball_pass_ratio, pitch_ratio

if TYPE_CHECKING:
    from bearingsim.catalog import BearingGeometry

from bearingsim.checks import guard_public_functions
from bearingsim.validation import (
    MAX_BALL_DIAMETER,
    check_choice,
    check_count,
    check_diameter,
    check_range,
)

__all__ = [
    "dynamic_load_rating",
    "static_load_rating",
    "static_factor",
    "static_load_factors",
    "static_equivalent_load",
    "xy_factors",
    "equivalent_dynamic_load",
    "rating_life",
    "life_hours",
    "basic_rating_life_hours",
    "raceway_contact_capacity",
    "ball_contact_capacity",
    "contact_life",
    "combined_contact_life",
    "raceway_equivalent_load",
    "bearing_life",
    "raceway_dynamic_ratings",
    "reference_rating_life",
]

_MM = 1e3  # metres to millimetres for the ISO formulas
_DW_LARGE_MM = 25.4

# Verification (tests/physics/test_published_examples.py; docs/physics.md, "Verification").
# The standards' own text was not retrievable; what was checked against published values:
# * X/Y/e, radial contact groove ball bearings (all 9 rows) and single-row angular contact 15 deg
#   (rows 0.178 to 5.35), 25, 30 and 40 deg: identical to the tables NSK prints with its bearing
#   tables (NSK CAT. No. E1102e, pp. B8-B11 and B50-B61), which reproduce ISO 281 Table 3; NSK's
#   worked Example 3 (p. A34) is reproduced. All nine 15 deg (e, Y) rows, including the last
#   (7.14, which NSK omits), and the 30/40 deg rows also equal Koyo CAT. NO. 203E-1, p. B20 (Koyo
#   prints them over the older abscissa Fa/C0r, 0.015 to 0.58). e = 1.34 at 45 deg equals the e
#   of SKF's 45 deg double-row series 33 D (SKF General Catalogue 6000, 2006 data, p. 440, Table 3;
#   ISO 281 has one e column for single and double row from 20 deg up). By the same argument
#   e = 0.95 at 35 deg equals the limit of SKF's 35 deg four-point contact bearings QJ 2/QJ 3
#   (same catalogue, p. 455: P = Fr + 0.66 Fa for Fa/Fr <= 0.95, else 0.6 Fr + 1.07 Fa, i.e. the
#   ISO double-row factors). The single-row X, Y at 20, 35 and 45 deg and e at 20 deg: GOST
#   18855-2013 (ISO 281:2007, MOD), Table 3, p. 9 (scanned standard, read from the page image);
#   the 20 deg row also in NSK's super precision catalogue, Table 1.1 p. 139, labelled 18 deg
#   (NSK applies the 20 deg factors to its 18 deg BNR series; bearingsim interpolates between
#   15 and 20 deg at 18 deg, so enter 20 deg to compare with NSK's BNR figures).
#   (tests/physics/test_published_tables.py)
# * Double-row X, Y (rows=2; also two single-row bearings back-to-back DB or face-to-face DF):
#   15 deg (e, Y1 for Fa/Fr <= e, X2 and Y2 for Fa/Fr > e; rows 0.178 to 5.35), 25, 30 and
#   40 deg: identical to the "DB or DF" columns NSK prints beside "Single, DT" (E1102e,
#   pp. B50-B61; the 25 deg factors also with its double-row 52/53 series, p. B67); 15 deg (all
#   nine rows), 30 and 40 deg also to Koyo's "back-to-back and face-to-face" columns (203E-1,
#   p. B20; Koyo adds the 7.14 row and prints
#   Y2 2.21 for the 0.714 row, a misprint: NSK 2.11 = 2^0.7 x 1.30 keeps P continuous at e).
#   30, 40, 45 deg: SKF GC 6000, p. 440, Table 3 (32 A/33 A, 33 DNRCBM, 33 D); 35 deg: SKF,
#   p. 455 (QJ four-point contact). The 20 deg double-row factors (Y1 1.09, X2 0.70, Y2 1.63):
#   GOST 18855-2013, Table 3, p. 9, and NSK's "DB or DF" columns of its 18 deg row (Table 1.1).
#   Corroborated only loosely: Koyo p. B21 prints its 24 deg (52/53 series) and 32 deg (32/33
#   series) double-row factors, and its 32 deg row is exactly our linear interpolation between
#   30 and 35 deg; its 24 deg row (0.66, 0.95, 0.68, 1.45) is too if the 20 deg row is ours
#   (the 24 deg print bounds each 20 deg value to +-0.025 only). Interpolating 15 to 25 deg
#   directly would miss Koyo's 24 deg Y2 (1.45) by 0.018 or more.
#   Deep-groove (0 deg) double row: SKF GC 6000, p. 393 (42/43 series): P = Fr for Fa/Fr <= e,
#   else 0.56 Fr + Y Fa, e and Y over f0 Fa/C0 in the single-row table (Table 1 there prints all
#   nine rows), i.e. rows=2 changes nothing for deep-groove bearings.
# * fc: ISO 281 C from our geometry reproduces NSK's ISO 281-based Cr of 6204, 6205, 6206 and 6304
#   within 0.3 % (Dw cos a/dm 0.20 to 0.26), and at 15/25 deg GMN's C of S 6014 C/E from GMN's
#   printed ball set within 0.3 % (Dw cos a/dm 0.128, 0.120; GMN 4000 0813 EN, pp. 38-39).
#   Every tabulated value below also agrees with two independent public implementations (GitHub
#   code index), which in addition list the odd hundredths above 0.10 (e.g. 0.11: 56.6, 0.19:
#   60.0); our linear interpolation between the even rows stays within 0.1 (0.17 %) of those.
#   Values outside 0.12-0.13 and 0.20-0.26 are corroborated only.
# * f0: the ISO 76 f0 at the Dw/dm of those four rows equals the f0 NSK prints within 0.05, and
#   f0 Z Dw^2 reproduces NSK's C0r within 0.5 %; elsewhere corroborated by the same public
#   implementations and by the 4 200 MPa Hertz basis of ISO 76 (tests/physics/test_life.py).
# ISO 281:2007, Table 2: fc for single-row radial contact and angular contact groove ball bearings.
# Every hundredth of gamma as GOST 18855-2013 (ISO 281:2007, MOD), Table 2, pp. 5-6, prints it
# (the odd hundredths above 0.10 were interpolated before; they differed by at most 0.1).
_FC_GAMMA = tuple(round(0.01 * j, 2) for j in range(1, 41))
_FC = (29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 56.6, 57.5, 58.2, 58.8,
       59.3, 59.6, 59.8, 59.9, 60.0, 59.9, 59.8, 59.6, 59.3, 59.0, 58.6, 58.2, 57.7, 57.1,
       56.6, 56.0, 55.3, 54.6, 53.9, 53.2, 52.4, 51.7, 50.9, 50.0, 49.2, 48.4)

# ISO 76:2006, Table 2: f0 for radial contact and angular contact groove ball bearings.
_F0_GAMMA = tuple(round(0.01 * j, 2) for j in range(41))
_F0 = (14.7, 14.9, 15.1, 15.3, 15.5, 15.7, 15.9, 16.1, 16.3, 16.5, 16.4, 16.1, 15.9, 15.6, 15.4,
       15.2, 14.9, 14.7, 14.4, 14.2, 14.0, 13.7, 13.5, 13.2, 13.0, 12.8, 12.5, 12.3, 12.1, 11.8,
       11.6, 11.4, 11.2, 10.9, 10.7, 10.5, 10.3, 10.0, 9.8, 9.6, 9.4)

# ISO 281:2007, Table 3: radial contact groove ball bearings (relative axial load f0 Fa / C0r).
_DG_LOAD = (0.172, 0.345, 0.689, 1.03, 1.38, 2.07, 3.45, 5.17, 6.89)
_DG_E = (0.19, 0.22, 0.26, 0.28, 0.30, 0.34, 0.38, 0.42, 0.44)
_DG_Y = (2.30, 1.99, 1.71, 1.55, 1.45, 1.31, 1.15, 1.04, 1.00)
_DG_X = 0.56
# ISO 281:2007, Table 3: single-row angular contact ball bearings, 15 deg (i f0 Fa / C0r).
_AC15_LOAD = (0.178, 0.357, 0.714, 1.07, 1.43, 2.14, 3.57, 5.35, 7.14)
_AC15_E = (0.38, 0.40, 0.43, 0.46, 0.47, 0.50, 0.55, 0.56, 0.56)
_AC15_Y = (1.47, 1.40, 1.30, 1.23, 1.19, 1.12, 1.02, 1.00, 1.00)
_AC15_X = 0.44
# ISO 281:2007, Table 3: single-row angular contact ball bearings, 20 to 45 deg: (alpha, e, X, Y).
_AC_FIXED = ((20.0, 0.57, 0.43, 1.00), (25.0, 0.68, 0.41, 0.87), (30.0, 0.80, 0.39, 0.76),
             (35.0, 0.95, 0.37, 0.66), (40.0, 1.14, 0.35, 0.57), (45.0, 1.34, 0.33, 0.50))
# ISO 281:2007, Table 3: double-row angular contact ball bearings (i = 2; also DB and DF pairs of
# single-row bearings, whose e is the single-row one): Y1 (X = 1) for Fa/Fr <= e, X2 and Y2 for
# Fa/Fr > e. 15 deg over i f0 Fa / C0r (_AC15_LOAD):
_AC15_Y1 = (1.65, 1.57, 1.46, 1.38, 1.34, 1.26, 1.14, 1.12, 1.12)
_AC15_X2 = 0.72
_AC15_Y2 = (2.39, 2.28, 2.11, 2.00, 1.93, 1.82, 1.66, 1.63, 1.63)
# 20 to 45 deg: (alpha, Y1, X2, Y2); GOST 18855-2013, Table 3 (see the comment above).
_AC2_FIXED = ((20.0, 1.09, 0.70, 1.63), (25.0, 0.92, 0.67, 1.41), (30.0, 0.78, 0.63, 1.24),
              (35.0, 0.66, 0.60, 1.07), (40.0, 0.55, 0.57, 0.93), (45.0, 0.47, 0.54, 0.81))

# Harris & Kotzalas: Lundberg-Palmgren constant of the raceway contact capacity, N and mm.
_LP_CONSTANT = 98.1


def _interp(x, xs: Sequence[float], ys: Sequence[float]):
    """Piecewise-linear interpolation, constant beyond the ends; symbolic-safe (sum of ramps)."""
    x = op.fmin(op.fmax(x, xs[0]), xs[-1])
    result = ys[0]
    previous_slope = 0.0
    for j in range(len(xs) - 1):
        slope = (ys[j + 1] - ys[j]) / (xs[j + 1] - xs[j])
        result = result + (slope - previous_slope) * op.fmax(x - xs[j], 0.0)
        previous_slope = slope
    return result


def _within_table(gamma, table: Sequence[float], where: str):
    """Check ``gamma = Dw cos(a)/dm`` against a table's range and clip round-off at its ends.

    Values within a relative 1e-9 of an end (e.g. ``dm`` computed from a ratio) count as the end.
    """
    lo, hi = table[0], table[-1]
    check_range(gamma, "Dw cos(alpha)/dm", "-", lo * (1.0 - 1e-9), hi * (1.0 + 1e-9), where=where)
    return op.fmin(op.fmax(gamma, lo), hi)


def _check_bearing(ball_diameter, pitch_diameter, ball_count, contact_angle, rows, where):
    check_diameter(ball_diameter, "ball_diameter", where, MAX_BALL_DIAMETER)
    check_diameter(pitch_diameter, "pitch_diameter", where)
    check_range(ball_count, "ball_count", "-", 3, where=where)
    check_range(contact_angle, "contact_angle", "rad", 0.0, np.pi / 4, where=where)
    check_count(rows, "rows", 1, where=where)
    return pitch_ratio(ball_diameter, pitch_diameter, contact_angle)


def dynamic_load_rating(ball_diameter, pitch_diameter, ball_count, contact_angle=0.0, rows=1,
                        bm=1.3):
    """ISO 281:2007 basic dynamic radial load rating C of a radial ball bearing [N].

    ``C = bm fc (i cos a)^0.7 Z^(2/3) Dw^1.8`` for Dw <= 25.4 mm and
    ``C = 3.647 bm fc (i cos a)^0.7 Z^(2/3) Dw^1.4`` above (Dw in mm), with fc from ISO 281
    Table 2 (single-row radial and angular contact groove ball bearings), interpolated linearly in
    ``gamma = Dw cos(a) / dm``.

    Parameters
    ----------
    ball_diameter : float or array or SX
        Ball diameter Dw [m], in (0, 0.5] (a larger value is taken for millimetres, see
        :func:`~bearingsim.validation.check_diameter`).
    pitch_diameter : float or array or SX
        Pitch diameter dm [m], in (0, 6].
    ball_count : int or float or SX
        Balls per row Z [-].
    contact_angle : float or array or SX
        Nominal contact angle [rad], 0 to 45 deg.
    rows : int
        Number of rows i [-], a whole number >= 1.
    bm : float
        Rating factor for contemporary material and manufacturing quality [-]: 1.3 for radial
        ball bearings (1.1 for filling-slot and insert bearings).

    Returns
    -------
    C [N]

    Raises
    ------
    ParameterError
        If gamma lies outside the table, 0.01 to 0.40, the contact angle outside [0, 45] deg or
        ``rows`` is not a whole number >= 1.
    """
    where = "dynamic_load_rating"
    gamma = _check_bearing(ball_diameter, pitch_diameter, ball_count, contact_angle, rows, where)
    gamma = _within_table(gamma, _FC_GAMMA, where)
    check_range(bm, "bm", "-", 0.0, low_inclusive=False, where=where)
    dw_mm = ball_diameter * _MM
    size = op.if_else(dw_mm <= _DW_LARGE_MM, op.power(dw_mm, 1.8),
                      3.647 * op.power(dw_mm, 1.4))
    return (bm * _interp(gamma, _FC_GAMMA, _FC) * op.power(rows * op.cos(contact_angle), 0.7)
            * op.power(ball_count, 2.0 / 3.0) * size)


def static_factor(ball_diameter, pitch_diameter, contact_angle=0.0):
    """ISO 76:2006 factor f0 of radial and angular contact groove ball bearings [N/mm^2].

    Table 2 of ISO 76 (based on 4 200 MPa Hertz pressure at the most heavily loaded contact),
    interpolated linearly in ``gamma = Dw cos(a) / dm`` from 0 to 0.40. It is also the f0 of the
    relative axial load ``f0 Fa / C0`` in :func:`xy_factors`.

    Parameters are those of :func:`dynamic_load_rating` (contact angle [rad] in [0, 45] deg,
    the range of the ISO 76 / ISO 281 ball bearing tables used here). Returns f0 [N/mm^2].
    """
    check_diameter(ball_diameter, "ball_diameter", "static_factor", MAX_BALL_DIAMETER)
    check_diameter(pitch_diameter, "pitch_diameter", "static_factor")
    check_range(contact_angle, "contact_angle", "rad", 0.0, np.pi / 4, where="static_factor")
    gamma = pitch_ratio(ball_diameter, pitch_diameter, contact_angle)
    return _interp(_within_table(gamma, _F0_GAMMA, "static_factor"), _F0_GAMMA, _F0)


def static_load_rating(ball_diameter, pitch_diameter, ball_count, contact_angle=0.0, rows=1):
    """ISO 76:2006 basic static radial load rating ``C0 = f0 i Z Dw^2 cos(a)`` [N] (Dw in mm).

    Parameters are those of :func:`dynamic_load_rating`. Returns C0 [N].
    """
    _check_bearing(ball_diameter, pitch_diameter, ball_count, contact_angle, rows,
                   "static_load_rating")
    f0 = static_factor(ball_diameter, pitch_diameter, contact_angle)
    dw_mm = ball_diameter * _MM
    return f0 * rows * ball_count * dw_mm * dw_mm * op.cos(contact_angle)


# ISO 76:2006, Table 1: static factors of single-row radial ball bearings. Deep groove:
# X0 = 0.6, Y0 = 0.5. Single-row angular contact: X0 = 0.5 and Y0 by nominal contact angle below,
# interpolated linearly in the angle between the rows (our choice; ISO 76 lists the rows only).
# The standard's text was not retrievable; checked against published catalogue values
# (tests/physics/test_published_tables.py, test_static_factors_*):
# * Deep groove 0.6, 0.5: NSK CAT. No. E1102e, deep-groove tables pp. B8-B11 (e.g. B9: "P0 =
#   0.6 Fr + 0.5 Fa" for Fa/Fr > 0.8, "P0 = Fr" for Fa/Fr <= 0.8, i.e. the maximum).
# * 15, 25, 30, 40 deg (0.46, 0.38, 0.33, 0.26; X0 0.5): NSK E1102e prints them ("Single, DT")
#   with every angular contact table, pp. B50-B61 (e.g. B55, B57), and "DB or DF" X0 1, Y0 0.92,
#   0.76, 0.66, 0.52 beside them: exactly twice the single-row Y0 at every angle.
# * 40 deg also: SKF General Catalogue 6000 (Russian ed., 2006 data), p. 415, series 72 B/73 B
#   (40 deg, p. 410): single and tandem P0 = 0.5 Fr + 0.26 Fa (P0 = Fr if larger); DB/DF
#   P0 = Fr + 0.52 Fa.
# * 30, 45 deg through double-row bearings (Y0 twice the single-row one, as NSK shows): SKF
#   p. 440, Table 3, P0 = Fr + Y0 Fa with Y0 0.66 (32 A/33 A, 30 deg), 0.52 (33 DNRCBM, 40 deg),
#   0.44 (33 D, 45 deg), so 45 deg single row = 0.22.
# * 35 deg: SKF p. 455, four-point contact QJ 2/QJ 3 (35 deg, p. 452; rated as a double row):
#   P0 = Fr + 0.58 Fa, so single row 0.29.
# * 20 deg (0.42), and every single-row (0.46 ... 0.22 at 15 ... 45 deg) and double-row (0.92
#   ... 0.44) Y0: GOST 18854-94 (ISO 76-87), Table 2, p. 5; the 20 deg row also in NSK's super
#   precision catalogue, Table 2.1 p. 146, labelled 18 deg (X0 0.5, Y0 0.42; DB/DF 1, 0.84).
_Y0_ANGLE_DEG = (15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0)
_Y0_ANGULAR = (0.46, 0.42, 0.38, 0.33, 0.29, 0.26, 0.22)
_X0_ANGULAR = 0.5
_X0_DEEP_GROOVE, _Y0_DEEP_GROOVE = 0.6, 0.5


def static_load_factors(geometry: BearingGeometry) -> tuple[float, float]:
    """ISO 76:2006 static radial and axial load factors ``(X0, Y0)`` [-] of a single-row bearing.

    Deep groove: ``(0.6, 0.5)``. Angular contact: ``X0 = 0.5`` and ``Y0`` 0.46, 0.42, 0.38,
    0.33, 0.29, 0.26, 0.22 at 15, 20, 25, 30, 35, 40, 45 deg (ISO 76 Table 1), linear in the
    contact angle between these rows. Checked against NSK CAT. No. E1102e pp. B8-B11 and
    B50-B61 and SKF General Catalogue 6000 pp. 415, 440, 455; the 20 deg row is unverified
    (see the comment above :data:`_Y0_ANGULAR` in the source).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing; its nominal contact angle [rad] selects the row.

    Returns
    -------
    (X0, Y0) : tuple of float [-]

    Raises
    ------
    ParameterError
        For an angular contact bearing whose contact angle lies outside the ISO 76 rows,
        [15, 45] deg.
    """
    if geometry.bearing_type == "deep_groove":
        return _X0_DEEP_GROOVE, _Y0_DEEP_GROOVE
    alpha_deg = round(math.degrees(geometry.contact_angle), 9)
    check_range(alpha_deg, "contact_angle", "deg", _Y0_ANGLE_DEG[0], _Y0_ANGLE_DEG[-1],
                where=f"static_load_factors ({geometry.designation}, ISO 76 angular contact)")
    return _X0_ANGULAR, float(np.interp(alpha_deg, _Y0_ANGLE_DEG, _Y0_ANGULAR))


def static_equivalent_load(Fr, Fa, geometry: BearingGeometry):  # noqa: N803
    """ISO 76 static equivalent load ``P0 = max(Fr, X0 Fr + Y0 Fa)`` [N] (smooth maximum).

    ``X0, Y0`` from :func:`static_load_factors` (deep groove 0.6, 0.5; angular contact 0.5 and
    Y0 from 0.46 at 15 deg to 0.22 at 45 deg, ISO 76:2006 Table 1). The maximum is smoothed
    with a width of 1 N (:func:`bearingsim.symbolic.smooth_max0`) so that it can enter equations.

    Parameters
    ----------
    Fr, Fa : float, array or casadi.SX
        Radial and axial load [N], >= 0.
    geometry : BearingGeometry
        The bearing (single row).

    Returns
    -------
    float, array or casadi.SX
        ``P0`` [N].
    """
    check_range(Fr, "Fr", "N", 0.0, where="static_equivalent_load")
    check_range(Fa, "Fa", "N", 0.0, where="static_equivalent_load")
    x0, y0 = static_load_factors(geometry)
    return Fr + op.smooth_max0((x0 - 1.0) * Fr + y0 * Fa, 1.0)


def _interp_angle(alpha_deg: float, table: Sequence[tuple]):
    """Entries of the table row at ``alpha_deg``, linear between the tabulated angles (our choice;
    Koyo's 32 deg double-row factors, 203E-1 p. B21, are this interpolation between 30 and 35)."""
    for row0, row1 in zip(table[:-1], table[1:], strict=True):
        a0, a1 = row0[0], row1[0]
        if a0 <= alpha_deg <= a1:
            w = (alpha_deg - a0) / (a1 - a0)
            return tuple(v0 + w * (v1 - v0) for v0, v1 in zip(row0[1:], row1[1:], strict=True))
    raise AssertionError("contact angle checked before")  # pragma: no cover


def _angular_contact_factors(relative_load, alpha_deg: float, rows: int):
    """(e, X, Y for Fa/Fr <= e, X, Y for Fa/Fr > e) of angular contact ball bearings, ISO 281
    Table 3, single row (rows=1) or double row (rows=2).

    15 deg depends on the relative axial load ``i f0 Fa / C0``; 20 to 45 deg are constants. Between
    tabulated angles the factors are interpolated linearly in the contact angle (our choice).
    """
    e15 = _interp(relative_load, _AC15_LOAD, _AC15_E)
    e = _interp_angle(alpha_deg, [(15.0, e15)] + [(a, e_) for a, e_, _, _ in _AC_FIXED])[0]
    if rows == 1:
        single = [(15.0, _AC15_X, _interp(relative_load, _AC15_LOAD, _AC15_Y))]
        x, y = _interp_angle(alpha_deg, single + [(a, x_, y_) for a, _, x_, y_ in _AC_FIXED])
        return e, 1.0, 0.0, x, y
    double = [(15.0, _interp(relative_load, _AC15_LOAD, _AC15_Y1), _AC15_X2,
               _interp(relative_load, _AC15_LOAD, _AC15_Y2))]
    y1, x2, y2 = _interp_angle(alpha_deg, double + list(_AC2_FIXED))
    return e, 1.0, y1, x2, y2


def _check_rows(rows, where: str) -> int:
    """``rows`` as 1 or 2; anything else (including symbolic values) is a ParameterError."""
    ok = (not op.is_symbolic(rows) and np.ndim(rows) == 0 and not isinstance(rows, bool)
          and isinstance(rows, (int, float, np.integer, np.floating)) and float(rows) in (1.0, 2.0))
    if not ok:
        raise ParameterError(
            f"{where}: rows = {rows!r} is not supported: ISO 281 Table 3 has factors for "
            f"rows = 1 (single row, or bearings in tandem DT) and rows = 2 (double row, or two "
            f"single-row bearings back-to-back DB or face-to-face DF)"
        )
    return int(rows)


def xy_factors(radial_load, axial_load, c0, f0, contact_angle: float = 0.0, rows: int = 1):
    """ISO 281:2007 factors X, Y and the limit e of a radial ball bearing (Table 3).

    ``P = X Fr + Y Fa`` with, for ``Fa/Fr <= e``, X = 1 and Y = 0 (single row) or Y = Y1 (double
    row), and for ``Fa/Fr > e`` the heavy-axial factors X, Y (X2, Y2 for a double row).

    * Deep-groove (contact_angle = 0): e and Y from the table over ``f0 Fa / C0``, X = 0.56;
      rows = 2 gives the same factors (ISO 281; SKF General Catalogue 6000, p. 393, double-row
      deep groove ball bearings: P = Fr for Fa/Fr <= e, else 0.56 Fr + Y Fa from the same table).
    * Angular contact (15 to 45 deg): at 15 deg e, Y (and Y1, X2, Y2) depend on ``i f0 Fa / C0``
      with i = rows; from 20 deg up they are constants, interpolated linearly in the contact angle
      between the tabulated 15, 20, 25, 30, 35, 40 and 45 deg. e is the same for one and two rows.
      Use rows = 2 for double-row bearings and for two single-row bearings mounted back-to-back
      (DB) or face-to-face (DF); rows = 1 for a single bearing and for bearings in tandem (DT).

    Values between the rows of the 15 deg and deep-groove tables are interpolated linearly;
    relative axial loads beyond a table take its end rows.

    Parameters
    ----------
    radial_load, axial_load : float or array or SX
        Radial and axial load Fr, Fa [N], >= 0, on the whole bearing (pair).
    c0 : float or array or SX
        Basic static radial load rating C0 [N] of the whole bearing, as
        :func:`static_load_rating` with the same ``rows`` gives it (for a DB/DF pair that of the
        pair, twice one bearing's, as NSK prints it under "matched"). ``i f0 Fa / C0`` is then
        f0 Fa over the C0 of one row (our reading of the ISO 281 abscissa).
    f0 : float or array or SX
        Factor f0 [-] of :func:`static_factor` (of one row).
    contact_angle : float
        Nominal contact angle [rad]: 0, or 15 to 45 deg. A number (it selects the table).
    rows : int
        Number of rows i [-]: 1 or 2 (see above).

    Returns
    -------
    (X, Y, e) : tuple [-]

    Raises
    ------
    ParameterError
        For a contact angle outside 0 and [15, 45] deg, a symbolic contact angle, or rows other
        than 1 or 2.
    """
    where = "xy_factors"
    check_range(radial_load, "radial_load", "N", 0.0, where=where)
    check_range(axial_load, "axial_load", "N", 0.0, where=where)
    check_range(c0, "c0", "N", 0.0, low_inclusive=False, where=where)
    check_range(f0, "f0", "-", 0.0, low_inclusive=False, where=where)
    rows = _check_rows(rows, where)
    if op.is_symbolic(contact_angle):
        raise ParameterError(f"{where}: contact_angle must be a number [rad], not symbolic")
    alpha_deg = round(float(np.degrees(contact_angle)), 9)
    relative = f0 * axial_load / c0
    if alpha_deg == 0.0:
        e = _interp(relative, _DG_LOAD, _DG_E)
        x_light, y_light = 1.0, 0.0
        x_heavy, y_heavy = _DG_X, _interp(relative, _DG_LOAD, _DG_Y)
    elif 15.0 <= alpha_deg <= 45.0:
        e, x_light, y_light, x_heavy, y_heavy = _angular_contact_factors(rows * relative,
                                                                         alpha_deg, rows)
    else:
        raise ParameterError(
            f"{where}: contact_angle = {alpha_deg:g} deg is outside the tables: use 0 deg "
            f"(deep-groove) or [15, 45] deg (angular contact)"
        )
    heavy_axial = axial_load > e * radial_load
    return (op.if_else(heavy_axial, x_heavy, x_light), op.if_else(heavy_axial, y_heavy, y_light),
            e)


def equivalent_dynamic_load(radial_load, axial_load, c0, f0, contact_angle: float = 0.0,
                            rows: int = 1):
    """ISO 281:2007 equivalent dynamic radial load ``P = X Fr + Y Fa`` [N].

    Parameters are those of :func:`xy_factors`. Returns P [N].
    """
    x, y, _ = xy_factors(radial_load, axial_load, c0, f0, contact_angle, rows)
    return x * radial_load + y * axial_load


def rating_life(c, p, exponent=3.0):
    """Basic rating life ``L10 = (C/P)^p`` [10^6 revolutions] (ISO 281; p = 3 for ball bearings).

    Parameters
    ----------
    c : float or array or SX
        Basic dynamic load rating C [N], > 0.
    p : float or array or SX
        Equivalent dynamic load P [N], > 0.
    exponent : float
        Life exponent [-], finite and > 0 (3 for ball bearings).
    """
    check_range(c, "c", "N", 0.0, low_inclusive=False, where="rating_life")
    check_range(p, "p", "N", 0.0, low_inclusive=False, where="rating_life")
    check_range(exponent, "exponent", "-", 0.0, low_inclusive=False, where="rating_life")
    return op.power(c / p, exponent)


def life_hours(life, speed):
    """Life in operating hours at a constant speed [h].

    Parameters
    ----------
    life : float or array or SX
        Life [10^6 revolutions], >= 0.
    speed : float or array or SX
        Relative ring speed [rad/s], > 0.
    """
    check_range(life, "life", "1e6 rev", 0.0, where="life_hours")
    check_range(speed, "speed", "rad/s", 0.0, low_inclusive=False, where="life_hours")
    return life * 1e6 * 2.0 * np.pi / (3600.0 * speed)


def basic_rating_life_hours(geometry: BearingGeometry, radial_load, axial_load,
                            speed) -> np.ndarray:
    """ISO 281 basic rating life [h] of a single-row bearing over a series of operating points.

    At each point ``L10h = (C / P)^3 10^6 / (60 n)`` with the equivalent dynamic load ``P`` of
    :func:`equivalent_dynamic_load` (f0 of :func:`static_factor`) and ``n`` the relative ring
    speed in r/min. The magnitudes of the loads and the speed are used. A point without load
    (``Fr = Fa = 0``) or at rest (speed 0) has an infinite life.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing: ball diameter, pitch diameter, contact angle and its ratings C and C0 [N].
    radial_load, axial_load : float or array_like
        Radial and axial load Fr, Fa [N], finite.
    speed : float or array_like
        Speed of the rotating ring relative to the other [rad/s], finite.

    Returns
    -------
    numpy.ndarray
        L10h [h] at each point (the broadcast shape of the inputs), ``inf`` where unloaded or
        at rest.

    Raises
    ------
    ParameterError
        When the geometry has no dynamic or static load rating, or for non-finite loads or
        speeds.
    """
    where = "basic_rating_life_hours"
    c, c0 = geometry.dynamic_load_rating, geometry.static_load_rating
    if c is None or c0 is None:
        raise ParameterError(f"{where}: {geometry.designation} has no load ratings C and C0 "
                             f"[N]; give dynamic_load_rating and static_load_rating")
    fr, fa, w = np.broadcast_arrays(*(np.abs(np.asarray(check_range(v, n, u, where=where),
                                                        dtype=float))
                                      for v, n, u in ((radial_load, "radial_load", "N"),
                                                      (axial_load, "axial_load", "N"),
                                                      (speed, "speed", "rad/s"))))
    hours = np.full(fr.shape, np.inf)
    running = (fr + fa > 0.0) & (w > 0.0)
    if np.any(running):
        f0 = static_factor(geometry.ball_diameter, geometry.pitch_diameter,
                           geometry.contact_angle)
        p = equivalent_dynamic_load(fr[running], fa[running], c0, f0, geometry.contact_angle)
        hours[running] = life_hours(rating_life(c, p), w[running])
    return hours


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
    gamma = _check_bearing(ball_diameter, pitch_diameter, ball_count, contact_angle, 1, where)
    check_range(groove_factor, "groove_factor", "-", 0.5, 1.0, low_inclusive=False, where=where)
    sign = -1.0 if race == "inner" else 1.0
    dw_mm = ball_diameter * _MM
    size = op.if_else(dw_mm <= _DW_LARGE_MM, op.power(dw_mm, 1.8),
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

    Parameters are those of :func:`raceway_contact_capacity`. Returns Qcb [N].
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
    """
    check_range(capacity, "capacity", "N", 0.0, low_inclusive=False, where="contact_life")
    check_range(load, "load", "N", 0.0, where="contact_life")
    with np.errstate(divide="ignore"):
        return op.power(load / capacity, -3.0)


def _balls(values) -> list:
    """Per-ball entries of a list, a numpy array (balls along axis 0) or an SX column."""
    if hasattr(values, "shape"):
        return [values[j] for j in range(values.shape[0])]
    return list(values)


def _per_ball(value, z: int, name: str, where: str) -> list:
    """One entry per ball: a sequence, array or SX column of length z, or one shared value."""
    if isinstance(value, (list, tuple)) or (
        hasattr(value, "shape") and int(np.prod(value.shape)) > 1
    ):
        items = _balls(value)
        if len(items) != z:
            raise ParameterError(
                f"{where}: {name} needs one entry per ball ({z}), got {len(items)}"
            )
        return items
    return [value] * z


def _check_life(value, name: str, where: str) -> None:
    """Lives must be > 0; unlike check_range, an infinite life (an unloaded contact) is allowed."""
    if op.is_symbolic(value):
        return
    arr = np.asarray(value, dtype=float)
    if np.any(np.isnan(arr)) or np.any(arr <= 0.0):
        raise ParameterError(f"{where}: {name} must be > 0 (inf allowed) [1e6 rev], got {value}")


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
    outer = _balls(life_outer)
    z = len(outer)
    inner = _per_ball(life_inner, z, "life_inner", where)
    ball_outer = _per_ball(life_ball_outer, z, "life_ball_outer", where)
    ball_inner = _per_ball(life_ball_inner, z, "life_ball_inner", where)
    n = _per_ball(ball_revolutions, z, "ball_revolutions", where)
    for name, values in (("life_outer", outer), ("life_inner", inner),
                         ("life_ball_outer", ball_outer), ("life_ball_inner", ball_inner)):
        for value in values:
            _check_life(value, name, where)
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
    q = _balls(loads)
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
    """
    _check_life(life_inner, "life_inner", "bearing_life")
    _check_life(life_outer, "life_outer", "bearing_life")
    return _life_from_inverse_power(_inverse_life_power(life_inner)
                                    + _inverse_life_power(life_outer))


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
    z = len(_balls(loads_inner))
    z_outer = len(_balls(loads_outer))
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
