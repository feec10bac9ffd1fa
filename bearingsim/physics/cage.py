"""Cage forces: ball-pocket contact (dry or lubricated) and outer-ring land guidance.

Both use the short ("Ocvirk") journal-bearing solution of Reynolds' equation with the pi-film
(half-Sommerfeld) boundary condition, as in the cage models of Gupta (*Advanced Dynamics of Rolling
Elements*, ch. 5) and Harris & Kotzalas (5th ed., Advanced Concepts, cage dynamics). Everything is
smooth (no events): eccentricity ratios are saturated smoothly below 1, and the switch between
asperity contact and film uses a tanh weight. Forces returned act on the ball or cage.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.checks import guard_public_functions
from bearingsim.physical_checks import check_regularization
from bearingsim.physics.traction import regularized_coulomb
from bearingsim.symbolic import (
    fmax,
    fmin,
    if_else,
    smooth_abs,
    smooth_max0,
    sqrt,
    sqrt_power,
    tanh,
)
from bearingsim.validation import check_finite, check_range

__all__ = [
    "SIGMA_BALL",
    "SIGMA_CAGE",
    "FilmForce",
    "journal_film_force",
    "PocketGap",
    "pocket_gap",
    "PocketForce",
    "ball_pocket_force",
    "CageGuidance",
    "cage_guidance_force",
]

SIGMA_BALL = 0.02e-6
"""RMS roughness of a ball [m] (docs/studies.md, section C)."""
SIGMA_CAGE = 0.4e-6
"""RMS roughness of a cage pocket or land [m] (docs/studies.md, section C)."""

_EPS_MAX = 0.98  # smooth saturation of the eccentricity ratio
_EPS_WIDTH = 0.01


_EPS_OFFSET = float(0.5 * (-_EPS_MAX + np.hypot(_EPS_MAX, _EPS_WIDTH)))


def _saturate(eps: Any) -> Any:
    """Smooth ``min(eps, 0.98)``: 0 at 0, below 0.9801 always, within 1e-3 of ``eps`` up to 0.95.

    Ratios beyond 10 (a journal far outside its clearance, which the land contact prevents)
    are first clipped to 10, where the smooth minimum is exact to 1e-6; without the clip its
    cancellation at ratios of 1e14 and more returned values above 1 (and NaN forces)."""
    eps = fmin(eps, 10.0)
    return eps - (smooth_max0(eps - _EPS_MAX, _EPS_WIDTH) - _EPS_OFFSET)


@dataclass(frozen=True)
class FilmForce:
    """Short-bearing film force on the journal in the plane, and its polar parts.

    Attributes
    ----------
    fx, fy : float or casadi.SX
        Force on the journal [N].
    radial, tangential : float or casadi.SX
        Components along ``e_r`` (bearing centre to journal centre) and ``e_t`` (``e_r`` turned
        by +90 degrees) [N]; ``radial < 0`` is restoring.
    eps : float or casadi.SX
        Eccentricity ratio used (saturated) [-].
    """

    fx: Any
    fy: Any
    radial: Any
    tangential: Any
    eps: Any


def journal_film_force(
    ex: Any,
    ey: Any,
    vx: Any,
    vy: Any,
    omega_sum: Any,
    eta: Any,
    R: float,  # noqa: N803
    L: float,  # noqa: N803
    c: float,
    e_reg: float = 1e-12,
) -> FilmForce:
    """Short journal bearing (pi-film) force on the journal from its position and velocity.

    With ``eps = e/c`` and the line-of-centres rotation rate ``phi_dot`` (Ocvirk's short-bearing
    solution; Childs, *Turbomachinery Rotordynamics*, 1993, ch. 3; Hamrock, *Fundamentals of Fluid
    Film Lubrication*, short-width journal bearings):

        F_r = -(eta R L^3 / c^2) [eps^2 |w| / (1 - eps^2)^2
                                  + pi (1 + 2 eps^2) eps_dot / (2 (1 - eps^2)^2.5)]
        F_t =  (eta R L^3 / c^2) [pi eps w / (4 (1 - eps^2)^1.5)
                                  + 2 eps eps_dot / (1 - eps^2)^2]

    where ``w = omega_sum - 2 phi_dot`` and ``omega_sum`` is the sum of the journal and bearing
    angular speeds. ``|w|`` keeps the radial force restoring for either direction of rotation.

    Parameters
    ----------
    ex, ey : float or casadi.SX
        Journal centre relative to the bearing centre [m].
    vx, vy : float or casadi.SX
        Journal centre velocity relative to the bearing [m/s].
    omega_sum : float or casadi.SX
        Journal plus bearing angular speed [rad/s].
    eta : float or casadi.SX
        Dynamic viscosity [Pa s], >= 0.
    R : float
        Journal radius [m], > 0.
    L : float
        Bearing width [m], > 0.
    c : float
        Radial clearance [m], > 0.
    e_reg : float
        Regularization of the eccentricity magnitude [m].

    Returns
    -------
    FilmForce
        Force on the journal.
    """
    where = "journal_film_force"
    check_finite(where, "m", ex=ex, ey=ey)
    check_finite(where, "m/s", vx=vx, vy=vy)
    check_range(omega_sum, "omega_sum", "rad/s", where=where)
    check_regularization(e_reg, "e_reg", "m", where)
    check_range(eta, "eta", "Pa s", 0.0, None, where=where)
    for name, value in (("R", R), ("L", L), ("c", c)):
        check_range(value, name, "m", 0.0, None, low_inclusive=False, where=where)
    e = sqrt(ex * ex + ey * ey + e_reg * e_reg)
    erx, ery = ex / e, ey / e
    eps = _saturate(e / c)
    eps_dot = (ex * vx + ey * vy) / (e * c)
    phi_dot = (ex * vy - ey * vx) / (e * e)
    w = omega_sum - 2.0 * phi_dot
    one = 1.0 - eps * eps
    scale = eta * R * L**3 / c**2
    radial = -scale * (eps * eps * smooth_abs(w, 1e-9) / one**2
                       + np.pi * (1.0 + 2.0 * eps * eps) * eps_dot / (2.0 * sqrt_power(one, 2)))
    tangential = scale * (np.pi * eps * w / (4.0 * sqrt_power(one, 1))
                          + 2.0 * eps * eps_dot / one**2)
    return FilmForce(
        fx=radial * erx - tangential * ery,
        fy=radial * ery + tangential * erx,
        radial=radial,
        tangential=tangential,
        eps=eps,
    )


@dataclass(frozen=True)
class PocketGap:
    """Gap between a ball and a stadium-shaped cage pocket.

    Attributes
    ----------
    gap : float or casadi.SX
        Clearance between ball surface and pocket wall along the normal [m] (< 0: overlap).
    nx, ny : float or casadi.SX
        Unit normal from the pocket centre line towards the wall touched (pocket plane).
    on_end : float or casadi.SX
        1 where the ball faces a half-circle end, 0 where it faces a straight side.
    dx : float or casadi.SX
        Offset of the ball centre from the nearest point of the pocket centre segment along x [m].
    """

    gap: Any
    nx: Any
    ny: Any
    on_end: Any
    dx: Any


def pocket_gap(
    x: Any,
    y: Any,
    Rb: float,  # noqa: N803
    Rp: float,  # noqa: N803
    Sp: float,  # noqa: N803
    d_reg: float = 1e-12,
) -> PocketGap:
    """Gap and contact normal of a ball in a pocket made of a rectangle and two half circles.

    The pocket (docs/studies.md, section C) is the set of points within ``Rp`` of the segment
    ``-Sp/2 <= x <= Sp/2, y = 0``: straight sides of length ``Sp`` at ``y = +-Rp`` and half circles
    of radius ``Rp`` at the ends. For a ball of radius ``Rb`` centred at ``(x, y)`` the gap is
    ``Rp - Rb - dist((x, y), segment)``; the normal points from the nearest segment point to the
    ball centre (the wall the ball moves towards).

    Parameters
    ----------
    x, y : float or casadi.SX
        Ball centre relative to the pocket centre: along the straight sides and across [m].
    Rb : float
        Ball radius [m], > 0.
    Rp : float
        Pocket half-width = end radius [m], >= Rb.
    Sp : float
        Length of the straight part [m], >= 0.
    d_reg : float
        Regularization of the distance at the centre line [m].

    Returns
    -------
    PocketGap
        Gap, normal and which part is faced.
    """
    where = "pocket_gap"
    check_finite(where, "m", x=x, y=y)
    check_regularization(d_reg, "d_reg", "m", where)
    check_range(Rb, "Rb", "m", 0.0, None, low_inclusive=False, where=where)
    check_range(Rp, "Rp", "m", Rb, None, where=where)
    check_range(Sp, "Sp", "m", 0.0, None, where=where)
    half = 0.5 * Sp
    dx = x - fmin(fmax(x, -half), half)
    dist = sqrt(dx * dx + y * y + d_reg * d_reg)
    return PocketGap(
        gap=Rp - Rb - dist,
        nx=dx / dist,
        ny=y / dist,
        on_end=if_else(fmax(x, -x) > half, 1.0, 0.0),
        dx=dx,
    )


@dataclass(frozen=True)
class PocketForce:
    """Force of the pocket on the ball (pocket plane x, y and pocket axis z).

    Attributes
    ----------
    fx, fy, fz : float or casadi.SX
        Force on the ball [N].
    normal : float or casadi.SX
        Normal force magnitude pushing the ball away from the wall [N].
    contact_weight : float or casadi.SX
        Weight of the asperity-contact model [-] (1: dry Hertz contact, 0: full film).
    gap : PocketGap
        Geometry.
    """

    fx: Any
    fy: Any
    fz: Any
    normal: Any
    contact_weight: Any
    gap: PocketGap


def ball_pocket_force(
    x: Any,
    y: Any,
    vx: Any,
    vy: Any,
    slide_t: Any,
    slide_z: Any,
    omega_z: Any,
    *,
    Rb: float,  # noqa: N803
    Rp: float,  # noqa: N803
    Sp: float,  # noqa: N803
    width: float,
    K: float,  # noqa: N803
    mu: float,
    eta: Any,
    sigma_ball: float = SIGMA_BALL,
    sigma_cage: float = SIGMA_CAGE,
    v_reg: float = 1e-3,
) -> PocketForce:
    """Ball-pocket force: Hertz contact with Coulomb friction or short-bearing film, blended.

    docs/studies.md, section C. With the gap ``h`` (:func:`pocket_gap`) and the composite roughness
    ``sigma = sqrt(sigma_ball^2 + sigma_cage^2)`` (Hamrock; Harris & Kotzalas):

    * contact: normal force ``K max(-h, 0)^1.5`` (Hertz, ``K`` from the ball-pocket geometry) and
      regularized Coulomb friction ``-mu Fn`` along the sliding velocity
      (:func:`regularized_coulomb`);
    * film: :func:`journal_film_force` of the ball (journal, radius ``Rb``) in the pocket end
      (bearing, clearance ``Rp - Rb``, width ``width``), with the ball centre measured from the
      nearest point of the pocket centre segment (so the straight sides behave like a wide end);
    * blend: contact weight ``w = (1 + tanh((sigma - h)/sigma)) / 2``, total ``w F_contact +
      (1 - w) F_film`` (1/2 at ``h = sigma``; ``w < 0.02`` for ``h > 3 sigma``).

    Parameters
    ----------
    x, y : float or casadi.SX
        Ball centre relative to the pocket centre [m].
    vx, vy : float or casadi.SX
        Ball centre velocity relative to the pocket [m/s].
    slide_t, slide_z : float or casadi.SX
        Sliding velocity of the ball surface relative to the pocket at the contact, along the
        in-plane tangent ``(-ny, nx)`` and along the pocket axis z [m/s].
    omega_z : float or casadi.SX
        Ball spin about the pocket axis relative to the cage [rad/s] (entrains the film).
    Rb, Rp, Sp : float
        Ball radius, pocket end radius, straight length [m].
    width : float
        Pocket width along z (cage web thickness) [m], > 0.
    K : float
        Hertz constant of the ball-pocket contact [N/m^1.5], >= 0.
    mu : float
        Coulomb coefficient of the ball-pocket contact [-].
    eta : float or casadi.SX
        Dynamic viscosity [Pa s], >= 0.
    sigma_ball, sigma_cage : float
        RMS roughness [m] (defaults 0.02 um, 0.4 um).
    v_reg : float
        Regularization speed of the Coulomb friction [m/s].

    Returns
    -------
    PocketForce
        Force on the ball.
    """
    where = "ball_pocket_force"
    check_range(width, "width", "m", 0.0, None, low_inclusive=False, where=where)
    check_range(K, "K", "N/m^1.5", 0.0, None, where=where)
    check_range(sigma_ball, "sigma_ball", "m", 0.0, None, where=where)
    check_range(sigma_cage, "sigma_cage", "m", 0.0, None, where=where)
    sigma = float(np.hypot(sigma_ball, sigma_cage))
    check_range(sigma, "composite roughness", "m", 0.0, None, low_inclusive=False, where=where)
    geo = pocket_gap(x, y, Rb, Rp, Sp)
    clearance = Rp - Rb
    check_range(clearance, "Rp - Rb", "m", 0.0, None, low_inclusive=False, where=where)
    weight = 0.5 * (1.0 + tanh((sigma - geo.gap) / sigma))
    overlap = smooth_max0(-geo.gap, 1e-3 * sigma)
    f_hertz = K * overlap * sqrt(overlap)
    slide = sqrt(slide_t * slide_t + slide_z * slide_z + v_reg * v_reg)
    friction = -regularized_coulomb(slide, mu, v_reg) * f_hertz / slide
    tx, ty = -geo.ny, geo.nx
    film = journal_film_force(geo.dx, y, vx, vy, omega_z, eta, Rb, width, clearance)
    fx_c = -f_hertz * geo.nx + friction * slide_t * tx
    fy_c = -f_hertz * geo.ny + friction * slide_t * ty
    return PocketForce(
        fx=weight * fx_c + (1.0 - weight) * film.fx,
        fy=weight * fy_c + (1.0 - weight) * film.fy,
        fz=weight * friction * slide_z,
        normal=weight * f_hertz - (1.0 - weight) * film.radial,
        contact_weight=weight,
        gap=geo,
    )


@dataclass(frozen=True)
class CageGuidance(FilmForce):
    """Land-guidance forces and drag moment on the cage: the guiding film's force and the
    drag moment of its shear.

    Attributes
    ----------
    fx, fy : float or casadi.SX
        Film force on the cage [N].
    radial, tangential : float or casadi.SX
        Its components along and across the eccentricity [N].
    eps : float or casadi.SX
        Eccentricity ratio [-].
    moment : float or casadi.SX
        Viscous drag moment on the cage about its axis [N m], opposite to the relative speed.
    """

    moment: Any


def cage_guidance_force(
    ex: Any,
    ey: Any,
    vx: Any,
    vy: Any,
    omega_cage: Any,
    omega_ring: Any = 0.0,
    *,
    Rg: float,  # noqa: N803
    Bg: float,  # noqa: N803
    Cg: float,  # noqa: N803
    eta: Any,
) -> CageGuidance:
    """Outer-ring guided cage: short journal bearing between cage rail and ring land.

    The cage is the journal (radius ``Rg``, width ``Bg``, radial clearance ``Cg``), the guiding
    land the bearing; forces from :func:`journal_film_force` with eccentricity ratio
    ``eps = e / Cg`` (docs/studies.md, section C; Gupta, ch. 5; Harris & Kotzalas, cage dynamics).
    The drag moment is the Couette shear of an eccentric full film,
    ``M = -2 pi eta Rg^3 Bg (omega_cage - omega_ring) / (Cg sqrt(1 - eps^2))`` (Hamrock, journal
    bearing friction; Petroff at ``eps = 0``). All are proportional to the speeds.

    Parameters
    ----------
    ex, ey : float or casadi.SX
        Cage centre relative to the ring centre [m].
    vx, vy : float or casadi.SX
        Cage centre velocity [m/s].
    omega_cage, omega_ring : float or casadi.SX
        Cage and guiding ring angular speeds [rad/s].
    Rg : float
        Guide land radius [m].
    Bg : float
        Guide land width [m].
    Cg : float
        Radial guide clearance [m].
    eta : float or casadi.SX
        Dynamic viscosity [Pa s].

    Returns
    -------
    CageGuidance
        Forces and moment on the cage.
    """
    check_finite("cage_guidance_force", "rad/s", omega_cage=omega_cage, omega_ring=omega_ring)
    film = journal_film_force(ex, ey, vx, vy, omega_cage + omega_ring, eta, Rg, Bg, Cg)
    moment = (-2.0 * np.pi * eta * Rg**3 * Bg * (omega_cage - omega_ring)
              / (Cg * sqrt(1.0 - film.eps * film.eps)))
    return CageGuidance(fx=film.fx, fy=film.fy, radial=film.radial,
                        tangential=film.tangential, moment=moment, eps=film.eps)


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
