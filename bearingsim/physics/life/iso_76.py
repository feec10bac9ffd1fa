"""ISO 76:2006 static load ratings: of ball bearings the factor f0, the basic static radial load
rating C0, the static factors X0, Y0 and the static equivalent load P0; of cylindrical roller
bearings ``C0r = 44 (1 - Dwe cos a / Dpw) i Z Lwe Dwe cos a`` [N, mm].

SI units at the interface (m, N, rad); the ISO formulas are evaluated in their own units (mm, N)
inside. Functions take floats, numpy arrays or CasADi SX; table look-ups are piecewise linear.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from bearingsim import symbolic as op
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.physical_checks import MAX_BALL_DIAMETER, check_diameter
from bearingsim.physics.geometry import pitch_ratio
from bearingsim.physics.life.tables import (
    MM_PER_M,
    check_ball_set,
    check_roller_set,
    interp,
    within_table,
)
from bearingsim.validation import check_choice, check_count, check_range

if TYPE_CHECKING:
    from bearingsim.catalog import BearingGeometry

__all__ = [
    "PAIR_ARRANGEMENTS",
    "pair_static_load_rating",
    "static_factor",
    "static_load_rating",
    "static_load_factors",
    "static_equivalent_load",
    "roller_static_load_rating",
]

# Verification (tests/physics/test_published_examples.py; docs/physics.md, "Verification"):
# * f0: the ISO 76 f0 at the Dw/dm of those four rows equals the f0 NSK prints within 0.05, and
#   f0 Z Dw^2 reproduces NSK's C0r within 0.5 %; elsewhere corroborated by the same public
#   implementations and by the 4 200 MPa Hertz basis of ISO 76 (tests/physics/test_life.py).
# ISO 76:2006, Table 2: f0 for radial contact and angular contact groove ball bearings.
_F0_GAMMA = tuple(round(0.01 * j, 2) for j in range(41))
_F0 = (14.7, 14.9, 15.1, 15.3, 15.5, 15.7, 15.9, 16.1, 16.3, 16.5, 16.4, 16.1, 15.9, 15.6, 15.4,
       15.2, 14.9, 14.7, 14.4, 14.2, 14.0, 13.7, 13.5, 13.2, 13.0, 12.8, 12.5, 12.3, 12.1, 11.8,
       11.6, 11.4, 11.2, 10.9, 10.7, 10.5, 10.3, 10.0, 9.8, 9.6, 9.4)


def static_factor(ball_diameter, pitch_diameter, contact_angle=0.0):
    """ISO 76:2006 factor f0 of radial and angular contact groove ball bearings [N/mm^2].

    Table 2 of ISO 76 (based on 4 200 MPa Hertz pressure at the most heavily loaded contact),
    interpolated linearly in ``gamma = Dw cos(a) / dm`` from 0 to 0.40. It is also the f0 of the
    relative axial load ``f0 Fa / C0`` in :func:`xy_factors`.

    Parameters
    ----------
    ball_diameter : float or array or SX
        Ball diameter Dw [m], in (0, 0.5] (as :func:`dynamic_load_rating`).
    pitch_diameter : float or array or SX
        Pitch diameter dm [m], in (0, 6].
    contact_angle : float or array or SX
        Nominal contact angle [rad] in [0, 45] deg, the range of the ISO 76 / ISO 281 ball
        bearing tables used here.

    Returns
    -------
    f0 [N/mm^2]
    """
    check_diameter(ball_diameter, "ball_diameter", "static_factor", MAX_BALL_DIAMETER)
    check_diameter(pitch_diameter, "pitch_diameter", "static_factor")
    check_range(contact_angle, "contact_angle", "rad", 0.0, np.pi / 4, where="static_factor")
    gamma = pitch_ratio(ball_diameter, pitch_diameter, contact_angle)
    return interp(within_table(gamma, _F0_GAMMA, "static_factor"), _F0_GAMMA, _F0)


def static_load_rating(ball_diameter, pitch_diameter, ball_count, contact_angle=0.0, rows=1):
    """ISO 76:2006 basic static radial load rating ``C0 = f0 i Z Dw^2 cos(a)`` [N] (Dw in mm).

    Parameters
    ----------
    ball_diameter : float or array or SX
        Ball diameter Dw [m], in (0, 0.5] (as :func:`dynamic_load_rating`).
    pitch_diameter : float or array or SX
        Pitch diameter dm [m], in (0, 6].
    ball_count : int or float or SX
        Balls per row Z [-], >= 3.
    contact_angle : float or array or SX
        Nominal contact angle [rad], 0 to 45 deg.
    rows : int
        Number of rows i [-], a whole number >= 1.

    Returns
    -------
    C0 [N]
    """
    check_ball_set(ball_diameter, pitch_diameter, ball_count, contact_angle, rows,
                   "static_load_rating")
    f0 = static_factor(ball_diameter, pitch_diameter, contact_angle)
    dw_mm = ball_diameter * MM_PER_M
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


# Pairs of identical single-row angular contact ball bearings (ISO 76 rates a pair mounted side
# by side as one bearing; the standard's text was not retrievable, the rules are the catalogues'):
# * C0 of the pair = 2 x C0 of one bearing, in every arrangement: SKF General Catalogue 6000
#   (Russian ed., 2006 data), p. 414, "load ratings of paired bearings" ("C0 = 2 x C0 of a single
#   bearing"); NSK CAT. No. E1102e prints the matched pairs' C0 as twice the single one.
# * DB or DF: X0 = 1, Y0 = 2 x the single row's; single and DT (tandem): the single row's X0, Y0
#   and P0 = Fr if larger: NSK Super Precision Bearings (Russian ed.), p. 146, Table 2.1
#   ("single, DT": 0.5/0.46 at 15 deg ... 0.5/0.26 at 40 deg; "DB or DF": 1/0.92 ... 1/0.52;
#   "for single or DT arrangements, when Fr > 0.5 Fr + Y0 Fa, use P0 = Fr"); SKF General
#   Catalogue 6000, p. 415 (72 B, 40 deg: single and tandem P0 = 0.5 Fr + 0.26 Fa, DB/DF
#   P0 = Fr + 0.52 Fa); NSK E1102e pp. B50-B61 ("Single, DT" and "DB or DF" columns).
PAIR_ARRANGEMENTS = ("DB", "DF", "DT")
"""Arrangements of a pair of identical single-row angular contact ball bearings that ISO 76
rates as one bearing: back-to-back, face-to-face, tandem."""
_PAIR_BEARINGS = 2


def _check_arrangement(arrangement: str | None, geometry: BearingGeometry, where: str) -> None:
    """Refuse an arrangement that is not a pair's, or a pair of bearings that are not angular
    contact ball bearings."""
    if arrangement is None:
        return
    check_choice(arrangement, "arrangement", PAIR_ARRANGEMENTS, where)
    if geometry.bearing_type == "deep_groove":
        raise ParameterError(f"{where}: ISO 76 rates {arrangement} pairs of angular contact "
                             f"ball bearings; {geometry.designation} is a deep groove bearing")


def static_load_factors(geometry: BearingGeometry, arrangement: str | None = None
                        ) -> tuple[float, float]:
    """ISO 76:2006 static radial and axial load factors ``(X0, Y0)`` [-] of a single-row bearing
    or of a pair of them.

    Deep groove: ``(0.6, 0.5)``. Angular contact: ``X0 = 0.5`` and ``Y0`` 0.46, 0.42, 0.38,
    0.33, 0.29, 0.26, 0.22 at 15, 20, 25, 30, 35, 40, 45 deg (ISO 76 Table 1), linear in the
    contact angle between these rows. Checked against NSK CAT. No. E1102e pp. B8-B11 and
    B50-B61 and SKF General Catalogue 6000 pp. 415, 440, 455; the 20 deg row is unverified
    (see the comment above :data:`_Y0_ANGULAR` in the source). A DB or DF pair of angular
    contact bearings: ``X0 = 1`` and twice the single row's ``Y0``; a DT (tandem) pair: the
    single row's (NSK Super Precision Bearings p. 146, Table 2.1; SKF General Catalogue 6000
    p. 415; see the comment above :data:`PAIR_ARRANGEMENTS` in the source).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing; its nominal contact angle [rad] selects the row.
    arrangement : {"DB", "DF", "DT"}, optional
        The pair of two such bearings rated as one (None: the single bearing).

    Returns
    -------
    (X0, Y0) : tuple of float [-]

    Raises
    ------
    ParameterError
        For an angular contact bearing whose contact angle lies outside the ISO 76 rows,
        [15, 45] deg, an arrangement other than those above, or a pair of deep groove bearings.
    """
    _check_arrangement(arrangement, geometry, "static_load_factors")
    if geometry.bearing_type == "deep_groove":
        return _X0_DEEP_GROOVE, _Y0_DEEP_GROOVE
    alpha_deg = round(math.degrees(geometry.contact_angle), 9)
    check_range(alpha_deg, "contact_angle", "deg", _Y0_ANGLE_DEG[0], _Y0_ANGLE_DEG[-1],
                where=f"static_load_factors ({geometry.designation}, ISO 76 angular contact)")
    y0 = float(np.interp(alpha_deg, _Y0_ANGLE_DEG, _Y0_ANGULAR))
    if arrangement in ("DB", "DF"):
        return 1.0, _PAIR_BEARINGS * y0
    return _X0_ANGULAR, y0


def pair_static_load_rating(static_load_rating: float) -> float:
    """ISO 76 basic static load rating of a DB, DF or DT pair of identical single-row angular
    contact ball bearings [N]: twice one bearing's (SKF General Catalogue 6000 p. 414).

    Parameters
    ----------
    static_load_rating : float
        C0 of one bearing [N], > 0.

    Returns
    -------
    float
        C0 of the pair [N].
    """
    check_range(static_load_rating, "static_load_rating", "N", 0.0, low_inclusive=False,
                where="pair_static_load_rating")
    return _PAIR_BEARINGS * float(static_load_rating)


def static_equivalent_load(Fr, Fa, geometry: BearingGeometry,  # noqa: N803
                           arrangement: str | None = None):
    """ISO 76 static equivalent load ``P0 = max(Fr, X0 Fr + Y0 Fa)`` [N] (smooth maximum).

    ``X0, Y0`` from :func:`static_load_factors` (deep groove 0.6, 0.5; angular contact 0.5 and
    Y0 from 0.46 at 15 deg to 0.22 at 45 deg, ISO 76:2006 Table 1; a DB/DF pair 1 and twice
    that, a DT pair as one bearing). The maximum is smoothed with a width of 1 N
    (:func:`bearingsim.symbolic.smooth_max0`) so that it can enter equations.

    Parameters
    ----------
    Fr, Fa : float, array or casadi.SX
        Radial and axial load [N], >= 0 (on the whole pair for a pair).
    geometry : BearingGeometry
        The bearing (single row).
    arrangement : {"DB", "DF", "DT"}, optional
        A pair of two such bearings rated as one (None: the single bearing).

    Returns
    -------
    float, array or casadi.SX
        ``P0`` [N].
    """
    check_range(Fr, "Fr", "N", 0.0, where="static_equivalent_load")
    check_range(Fa, "Fa", "N", 0.0, where="static_equivalent_load")
    x0, y0 = static_load_factors(geometry, arrangement)
    return Fr + op.smooth_max0((x0 - 1.0) * Fr + y0 * Fa, 1.0)


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
    check_roller_set(roller_diameter, pitch_diameter, roller_count, length, where)
    check_count(rows, "rows", 1, where=where)
    gamma = roller_diameter / pitch_diameter
    return float(44.0 * (1.0 - gamma) * rows * roller_count * length * 1e3
                 * roller_diameter * 1e3)


# no NaN in or out (bearingsim.checks); an unloaded contact's life is infinite
guard_public_functions(globals(), infinite_results=True)
