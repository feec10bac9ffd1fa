"""The load distribution of a radial ball bearing as ISO/TS 16281:2008 writes it.

bearingsim's own quasi-static row (:mod:`bearingsim.components.ball_row`) moves the groove
curvature centres with exact rigid-ring kinematics and takes moments with the exact lever of
every contact. ISO/TS 16281 writes the same problem in a simpler form, and tools that implement
the standard follow it; this module is that form, so that results can be compared with them:

* **Contact spring constant** (the standard's eq. for ``c_p``):
  ``c_p = 1.48 E' [K(chi_i) (Sum rho_i / (chi_i^2 E(chi_i)))^(1/3)
  + K(chi_e) (Sum rho_e / (chi_e^2 E(chi_e)))^(1/3)]^(-3/2)``, one constant for both contacts in
  series, evaluated at the nominal contact angle; ``E' = E / (1 - nu^2)`` (for unlike ball and
  ring materials the effective modulus of :func:`~bearingsim.physics.materials.effective_modulus`),
  ``chi`` the ellipticity from the curvature difference (eq. 2), ``K``, ``E`` the complete
  elliptic integrals (eqs. 3, 4).
* **Deflection of ball j** (eq. 12), in small-rotation kinematics with the inner groove-centre
  radius ``R_i = Dpw/2 + (r_i - Dw/2) cos(alpha0)`` as the lever of the misalignment:
  ``delta_j = sqrt((A cos a0 + d_r,j)^2 + (A sin a0 + d_a + R_i s_j)^2) - A``,
  ``tan(alpha_j) = (A sin a0 + d_a + R_i s_j) / (A cos a0 + d_r,j)``; here with the rings
  centred (``A sin a0 + d_a = z``), ``d_r,j = x cos psi_j + y sin psi_j`` and the misalignment
  ``s_j = sin(tx) sin psi_j - sin(ty) cos psi_j`` (the standard writes one tilt in the plane of
  the radial load; two tilts are the same form about two axes).
* **Equilibrium** (eqs. 16-18): ``F = c_p sum delta_j^1.5 (cos alpha_j cos psi_j,
  cos alpha_j sin psi_j, sin alpha_j)`` and the moment with the **pitch radius** ``Dpw/2`` as the
  lever of the axial ball forces, ``M = (Dpw/2) c_p sum delta_j^1.5 sin alpha_j (sin psi_j,
  -cos psi_j)``, although the kinematics above uses ``R_i``: the form is not the derivative of
  an elastic energy, and its moments differ from bearingsim's exact ones by about
  ``R_i / (Dpw/2) - 1`` (1 to 2 % for deep-groove bearings).
* **Ratings, equivalent loads and life** (eqs. 19-29): the raceway ratings of
  :func:`~bearingsim.physics.life.raceway_dynamic_ratings` with ``(i cos a)^0.7`` in the
  denominator where bearingsim writes ``i^0.7 cos a`` (identical for deep-groove bearings,
  ``a = 0``; see that function), the equivalent loads and the life of
  :func:`~bearingsim.physics.life.reference_rating_life`.

The standard's own text was not retrievable here; the equations are those of the public
implementation ``minzhun/ISO16281`` (``BallBearing.py``), which numbers them as the standard
does (eqs. 2-4, 10, 12, 16-29). Floats, numpy arrays and CasADi SX alike.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from bearingsim import symbolic as op
from bearingsim.catalog import BearingGeometry
from bearingsim.checks import guard_public_functions
from bearingsim.physics.contact_curvature import curvature_sum, raceway_radii
from bearingsim.physics.hertz import elliptic_parameters
from bearingsim.physics.life import raceway_dynamic_ratings
from bearingsim.physics.materials import STEEL, Material, effective_modulus
from bearingsim.validation import check_range

__all__ = [
    "contact_spring_constant",
    "deflections",
    "inner_groove_centre_radius",
    "raceway_ratings",
    "ring_loads",
]


def contact_spring_constant(geometry: BearingGeometry, ball: Material = STEEL,
                            ring: Material = STEEL) -> float:
    """The standard's spring constant ``c_p`` of a ball between both raceways [N/m^1.5].

    Parameters
    ----------
    geometry : BearingGeometry
        Dw, Dpw, fi, fo and the nominal contact angle.
    ball, ring : Material
        Materials (the standard has one; unlike materials enter through ``E'``).

    Returns
    -------
    float
        ``c_p`` in ``Q = c_p delta^1.5`` [N/m^1.5].
    """
    e_eff = effective_modulus(ball, ring)
    total = 0.0
    for race, f in (("inner", geometry.fi), ("outer", geometry.fo)):
        rx, ry = raceway_radii(geometry.ball_diameter, geometry.pitch_diameter, f,
                               geometry.contact_angle, race)
        chi, k_int, e_int = elliptic_parameters(rx, ry, "exact")
        total += float(k_int) * float(curvature_sum(rx, ry) / (chi * chi * e_int)) ** (1 / 3)
    return 1.48 * e_eff * total ** -1.5


def inner_groove_centre_radius(geometry: BearingGeometry) -> float:
    """``R_i = Dpw/2 + (r_i - Dw/2) cos(alpha0)`` [m], the standard's lever of the
    misalignment (``alpha0`` the free contact angle of the clearance).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing (Dpw, Dw, fi and its clearance).

    Returns
    -------
    float
        R_i [m], > 0.
    """
    return (0.5 * geometry.pitch_diameter
            + (geometry.fi - 0.5) * geometry.ball_diameter * np.cos(geometry.free_contact_angle))


def _azimuths(geometry: BearingGeometry, ball_position_angle: float) -> np.ndarray:
    check_range(ball_position_angle, "ball_position_angle", "rad", where="iso_ts_16281")
    z = geometry.ball_count
    return ball_position_angle + 2.0 * np.pi * np.arange(z) / z


def deflections(geometry: BearingGeometry, displacement: Sequence[Any],
                ball_position_angle: float = 0.0) -> tuple[list, list]:
    """Ball deflections and contact angles of eq. (12) for a ring displacement.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing; its diametral clearance gives ``alpha0`` and the centred reference.
    displacement : sequence of 5
        Inner ring against outer ring ``(x, y, z, tx, ty)`` [m, m, m, rad, rad], measured from
        the rings centred (z along the axis; floats or CasADi SX).
    ball_position_angle : float
        Azimuth of ball 0 [rad].

    Returns
    -------
    (delta, alpha) : lists of length Z
        Elastic deflection [m] (negative: a gap) and contact angle [rad] of every ball.
    """
    x, y, z, tx, ty = displacement
    a = geometry.groove_centre_distance
    # A cos(alpha0) = A - Pd/2 for a clearance; the same form holds for a preload (Pd < 0)
    radial0 = a - 0.5 * geometry.diametral_clearance
    lever = inner_groove_centre_radius(geometry)
    delta, alpha = [], []
    for psi in _azimuths(geometry, ball_position_angle):
        c, s = float(np.cos(psi)), float(np.sin(psi))
        radial = radial0 + x * c + y * s
        axial = z + lever * (op.sin(tx) * s - op.sin(ty) * c)
        delta.append(op.sqrt(radial * radial + axial * axial) - a)
        alpha.append(op.atan2(axial, radial))
    return delta, alpha


def ring_loads(geometry: BearingGeometry, loads: Sequence[Any], alpha: Sequence[Any],
               ball_position_angle: float = 0.0) -> list:
    """Loads the balls put on the inner ring, eqs. (16)-(18) generalised to two tilt axes.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing.
    loads, alpha : sequences of length Z
        Ball loads [N] and contact angles [rad] (:func:`deflections`).
    ball_position_angle : float
        Azimuth of ball 0 [rad].

    Returns
    -------
    list of 5
        ``(Fx, Fy, Fz, Mx, My)`` on the inner ring [N, N m]: minus the resultant of the ball
        loads, its moments taken with the pitch radius ``Dpw/2`` as the standard does.
    """
    half = 0.5 * geometry.pitch_diameter
    out = [0.0] * 5
    for q, a, psi in zip(loads, alpha, _azimuths(geometry, ball_position_angle), strict=True):
        c, s = float(np.cos(psi)), float(np.sin(psi))
        radial, axial = q * op.cos(a), q * op.sin(a)
        for k, value in enumerate((radial * c, radial * s, axial, half * axial * s,
                                   -half * axial * c)):
            out[k] = out[k] - value
    return out


def raceway_ratings(c: float, geometry: BearingGeometry, rows: int = 1) -> tuple[float, float]:
    """The standard's raceway ratings ``(Q_ci, Q_ce)`` [N] (eqs. 19-24), with ``(i cos a)^0.7``.

    Parameters
    ----------
    c : float
        Basic dynamic load rating C [N], > 0.
    geometry : BearingGeometry
        fi, fo, Z, nominal contact angle, gamma.
    rows : int
        Number of rows i.

    Returns
    -------
    (Q_ci, Q_ce) [N]
    """
    check_range(c, "c", "N", 0.0, low_inclusive=False, where="raceway_ratings")
    qci, qce = raceway_dynamic_ratings(c, geometry.fi, geometry.fo, geometry.gamma,
                                       geometry.ball_count, geometry.contact_angle, rows)
    # bearingsim divides by i^0.7 cos(a); the standard by (i cos(a))^0.7
    factor = float(np.cos(geometry.contact_angle)) ** 0.3
    return float(qci) * factor, float(qce) * factor


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
