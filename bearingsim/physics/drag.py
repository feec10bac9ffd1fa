"""Viscous drag of the lubricant: on the balls (orbital drag and spin drag moment) and on a ring
turning in an oil-filled annular gap (laminar Couette torque).

Both are written so that the Stokes (creeping-flow) part is explicit and linear in the speed: they
are finite and smooth through zero speed. Forces and moments returned act on the ball and oppose
its motion relative to the oil.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.checks import guard_public_functions
from bearingsim.physical_checks import MIN_LENGTH
from bearingsim.physics.lubricant import check_kinematic_viscosity
from bearingsim.symbolic import smooth_abs, sqrt
from bearingsim.validation import check_range

__all__ = [
    "sphere_drag_coefficient",
    "ball_drag_force",
    "orbital_drag_force",
    "rotating_sphere_moment_coefficient",
    "spin_drag_moment",
    "TAYLOR_ONSET",
    "couette_damping",
    "taylor_number",
]

TAYLOR_ONSET = 41.3
"""Taylor number ``Ta = (omega R1 d / nu) sqrt(d / R1)`` at which Taylor vortices appear between
concentric cylinders with the inner one turning and a narrow gap d (Taylor 1923; the classical
narrow-gap value, e.g. Schlichting, *Boundary-Layer Theory*). Below it the flow is the laminar
Couette flow of :func:`couette_damping`; above it the torque is larger."""

_ROTATING_SPHERE_BL = 5.32
"""Laminar boundary-layer coefficient of the rotating-sphere moment, ``C_m = 5.32 / sqrt(Re)``
(Sawatzki 1970, as quoted in Schlichting, *Boundary-Layer Theory*, rotating sphere).

Verification status: unverified; no source text printing the value could be retrieved, so treat
it as a representative value. The Stokes part ``16 pi / Re``
(``M = 8 pi eta R^3 omega``) is the exact creeping-flow result and does not depend on it."""


def _check_fluid(rho: Any, eta: Any, where: str) -> None:
    check_range(rho, "rho", "kg/m^3", 0.0, None, low_inclusive=False, where=where)
    check_range(eta, "eta", "Pa s", 0.0, None, low_inclusive=False, where=where)


def sphere_drag_coefficient(Re: Any) -> Any:  # noqa: N803 - published symbol
    """Drag coefficient of a sphere, White's fit ``C_D = 24/Re + 6/(1 + sqrt(Re)) + 0.4``.

    Smooth and within about 10 % of the measured standard drag curve for ``0 < Re <= 2e5``
    (F. M. White, *Viscous Fluid Flow*, 2nd ed., 1991, eq. 3-225; the standard curve is the one in
    Schlichting, *Boundary-Layer Theory*, fig. 1.21). Tends to Stokes' ``24/Re`` as ``Re -> 0``.

    Parameters
    ----------
    Re : float, array or casadi.SX
        Reynolds number ``rho v D / eta`` [-], ``0 < Re <= 2e5``.

    Returns
    -------
    float, array or casadi.SX
        Drag coefficient [-].
    """
    check_range(Re, "Re", "-", 0.0, 2e5, low_inclusive=False, where="sphere_drag_coefficient")
    return 24.0 / Re + 6.0 / (1.0 + sqrt(Re)) + 0.4


def ball_drag_force(
    v: Any,
    Dw: float,  # noqa: N803 - published symbol
    rho: Any,
    eta: Any,
    area_fraction: float = 1.0,
    v_reg: float = 1e-9,
) -> Any:
    """Drag force of the oil on a ball moving at speed ``v`` through it.

    ``F_D = 1/2 C_D rho v^2 A`` with ``A = area_fraction * pi Dw^2 / 4`` the frontal area in the
    oil (Schlichting, *Boundary-Layer Theory*; the ball drag of Harris & Kotzalas, 5th ed.,
    Advanced Concepts, ch. 5, and docs/studies.md, section C) and ``C_D`` from
    :func:`sphere_drag_coefficient`. The ``24/Re`` part is written out as Stokes' ``3 pi eta Dw v``
    (times the area fraction), so the force is smooth and finite at ``v = 0``.

    Parameters
    ----------
    v : float, array or casadi.SX
        Speed of the ball centre relative to the oil [m/s].
    Dw : float
        Ball diameter [m], > 0.
    rho : float or casadi.SX
        Oil (or oil-air mixture) density [kg/m^3], > 0.
    eta : float or casadi.SX
        Dynamic viscosity [Pa s], > 0.
    area_fraction : float
        Immersed fraction of the frontal area [-], in (0, 1].
    v_reg : float
        Regularization of ``|v|`` [m/s], > 0.

    Returns
    -------
    float, array or casadi.SX
        Drag force on the ball [N], opposite in sign to ``v``.
    """
    where = "ball_drag_force"
    check_range(Dw, "Dw", "m", 0.0, None, low_inclusive=False, where=where)
    _check_fluid(rho, eta, where)
    check_range(area_fraction, "area_fraction", "-", 0.0, 1.0, low_inclusive=False, where=where)
    check_range(v, "v", "m/s", where=where)
    speed = smooth_abs(v, v_reg)
    area = area_fraction * np.pi * Dw * Dw / 4.0
    reynolds = rho * speed * Dw / eta
    inertial = 0.5 * rho * speed * v * area * (6.0 / (1.0 + sqrt(reynolds)) + 0.4)
    return -(3.0 * np.pi * eta * Dw * area_fraction * v + inertial)


def orbital_drag_force(
    omega_orbit: Any,
    dm: float,
    Dw: float,  # noqa: N803
    rho: Any,
    eta: Any,
    area_fraction: float = 1.0,
) -> Any:
    """Drag on a ball orbiting at ``omega_orbit`` on the pitch circle: ``v = omega_orbit dm / 2``.

    docs/studies.md, section C, ``F_D = 1/2 C_D rho (w dm/2)^2 A``; see :func:`ball_drag_force`.

    Parameters
    ----------
    omega_orbit : float, array or casadi.SX
        Orbital (cage) angular speed relative to the oil [rad/s].
    dm : float
        Pitch diameter [m], > 0.
    Dw : float
        Ball diameter [m], > 0.
    rho : float or casadi.SX
        Density [kg/m^3].
    eta : float or casadi.SX
        Dynamic viscosity [Pa s].
    area_fraction : float
        Immersed fraction of the frontal area [-].

    Returns
    -------
    float, array or casadi.SX
        Tangential drag force on the ball [N], opposite in sign to ``omega_orbit``.
    """
    check_range(dm, "dm", "m", 0.0, None, low_inclusive=False, where="orbital_drag_force")
    return ball_drag_force(0.5 * omega_orbit * dm, Dw, rho, eta, area_fraction)


def rotating_sphere_moment_coefficient(Re: Any) -> Any:  # noqa: N803
    """Moment coefficient ``C_m`` of a sphere spinning in still fluid, ``Re = omega R^2 / nu``.

    ``C_m = 16 pi / Re + 5.32 / sqrt(Re)``: the exact Stokes limit ``M = 8 pi eta R^3 omega``
    (Lamb, *Hydrodynamics*, art. 334) plus the laminar boundary-layer law quoted by Schlichting
    (*Boundary-Layer Theory*, rotating sphere, after Sawatzki 1970). The sum is an additive blend
    of the two asymptotes (the same construction as White's sphere drag fit).

    Parameters
    ----------
    Re : float, array or casadi.SX
        Rotational Reynolds number [-], > 0.

    Returns
    -------
    float, array or casadi.SX
        Moment coefficient [-], defined by ``M = 1/2 rho omega^2 R^5 C_m``.
    """
    check_range(Re, "Re", "-", 0.0, None, low_inclusive=False,
                where="rotating_sphere_moment_coefficient")
    return 16.0 * np.pi / Re + _ROTATING_SPHERE_BL / sqrt(Re)


def spin_drag_moment(
    omega: Any,
    Dw: float,  # noqa: N803
    rho: Any,
    eta: Any,
    omega_reg: float = 1e-6,
) -> Any:
    """Viscous moment on a ball spinning in oil, ``M_e = 1/2 rho omega^2 (Dw/2)^5 C_m``.

    The study (docs/studies.md, section C) writes ``1/2 rho w (Dw/2)^5 C_m``; the dimensionally
    consistent form has ``omega^2`` (Schlichting, *Boundary-Layer Theory*, rotating bodies), used
    here with ``C_m`` from :func:`rotating_sphere_moment_coefficient`. Expanded,
    ``M = 8 pi eta R^3 omega + 2.66 sqrt(rho eta) R^4 |omega|^0.5 omega``, which is smooth and
    zero at zero spin.

    Parameters
    ----------
    omega : float, array or casadi.SX
        Spin speed of the ball relative to the oil [rad/s].
    Dw : float
        Ball diameter [m], > 0.
    rho : float or casadi.SX
        Density [kg/m^3], > 0.
    eta : float or casadi.SX
        Dynamic viscosity [Pa s], > 0.
    omega_reg : float
        Regularization of ``|omega|`` [rad/s], > 0.

    Returns
    -------
    float, array or casadi.SX
        Drag moment on the ball about its spin axis [N m], opposite in sign to ``omega``.
    """
    where = "spin_drag_moment"
    check_range(Dw, "Dw", "m", 0.0, None, low_inclusive=False, where=where)
    _check_fluid(rho, eta, where)
    check_range(omega, "omega", "rad/s", where=where)
    r = 0.5 * Dw
    boundary_layer = 0.5 * _ROTATING_SPHERE_BL * sqrt(rho * eta) * r**4
    return -(8.0 * np.pi * eta * r**3 * omega
             + boundary_layer * sqrt(smooth_abs(omega, omega_reg)) * omega)


def couette_damping(radius: float, gap: float, length: float, eta: float,
                    wetted: float = 1.0) -> float:
    """Torque per unit speed [N m s/rad] of a cylinder turning inside a fixed coaxial bore
    filled with oil (exact laminar Couette solution of the Navier-Stokes equations):

        ``M = -4 pi eta L R1^2 R2^2 / (R2^2 - R1^2) omega``, ``R2 = R1 + gap``,

    times the wetted fraction of the circumference. Valid while the Taylor number stays below
    :data:`TAYLOR_ONSET` (:func:`taylor_number`); in the narrow-gap limit it is
    ``2 pi eta L R1^3 / gap``.

    Parameters
    ----------
    radius : float
        Radius R1 of the turning cylinder [m], at least 1 nm.
    gap : float
        Radial gap to the fixed bore [m], at least 1 nm.
    length : float
        Wetted axial length [m], at least 1 nm.
    eta : float
        Dynamic viscosity of the oil [Pa s], > 0.
    wetted : float
        Wetted fraction of the circumference, in (0, 1] (e.g. a ring dipping into a bath).

    Returns
    -------
    float
        The damping coefficient c with ``M = -c omega`` [N m s/rad].
    """
    where = "couette_damping"
    for value, name in ((radius, "radius"), (gap, "gap"), (length, "length")):
        check_range(value, name, "m", MIN_LENGTH, 6.0, where=where)
    check_range(eta, "eta", "Pa s", 0.0, None, low_inclusive=False, where=where)
    check_range(wetted, "wetted", "1", 0.0, 1.0, low_inclusive=False, where=where)
    r1, r2 = radius, radius + gap
    return 4.0 * np.pi * eta * length * r1**2 * r2**2 / (r2**2 - r1**2) * wetted


def taylor_number(omega: Any, radius: float, gap: float, nu: float) -> Any:
    """Taylor number ``Ta = (|omega| R1 d / nu) sqrt(d / R1)`` [-] of the annular gap of
    :func:`couette_damping` (laminar below :data:`TAYLOR_ONSET`).

    Parameters
    ----------
    omega : float, array or casadi.SX
        Speed of the inner cylinder [rad/s].
    radius, gap : float
        R1 and the gap d [m], > 0.
    nu : float
        Kinematic viscosity [m^2/s], > 0.

    Returns
    -------
    float, array or casadi.SX
        Ta [-].
    """
    where = "taylor_number"
    check_range(omega, "omega", "rad/s", where=where)
    check_range(radius, "radius", "m", MIN_LENGTH, 6.0, where=where)
    check_range(gap, "gap", "m", MIN_LENGTH, 6.0, where=where)
    check_range(nu, "nu", "m^2/s", 0.0, None, low_inclusive=False, where=where)
    check_kinematic_viscosity(nu, "nu", where)
    return smooth_abs(omega, 1e-12) * radius * gap / nu * np.sqrt(gap / radius)


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
