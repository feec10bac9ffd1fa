"""Quasi-static equilibrium of the balls and the inner ring (start values and reference).

The same contact geometry as the dynamic components
(:func:`~bearingsim.physics.groove_contact.groove_contact`) and the same smooth Hertz law,
solved in numbers by Newton (scipy ``root``): for every ball the radial and axial force balance
with the centrifugal force ``m r w_c^2``, for the inner ring the balance with the external load
(Jones 1960; Harris & Kotzalas, *Advanced Concepts*, ch. "High-speed operation"). Traction,
cage and drag forces are neglected, as in the classical quasi-static analysis; the balls carry
the same weak regularizing spring as the quasi-static
:class:`~bearingsim.components.dynamic.ball.Ball`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bearingsim.errors import ParameterError, SimulationError
from bearingsim.physics.bearing_design import POSITION_REGULARIZATION, BearingDesign
from bearingsim.physics.contact_law import contact_load
from bearingsim.physics.groove_contact import groove_contact

__all__ = ["StaticState", "static_state"]


_UNIT = np.array([1e-6, 1e-6, 1e-6, 1e-4, 1e-4])
"""Scale of the ring unknowns in the iteration [m, m, m, rad, rad]."""


@dataclass(frozen=True)
class StaticState:
    """Quasi-static solution.

    Attributes
    ----------
    ring : numpy.ndarray
        Inner-ring displacement (x, y, z, tx, ty) [m, m, m, rad, rad].
    r, z : numpy.ndarray
        Ball centre radial and axial positions [m].
    q_inner, q_outer : numpy.ndarray
        Contact loads [N].
    alpha_inner, alpha_outer : numpy.ndarray
        Contact angles [rad].
    """

    ring: np.ndarray
    r: np.ndarray
    z: np.ndarray
    q_inner: np.ndarray
    q_outer: np.ndarray
    alpha_inner: np.ndarray
    alpha_outer: np.ndarray


def _contacts(design: BearingDesign, ring, r, z, theta, smooth):
    g = design.geometry
    p = (r * np.cos(theta), r * np.sin(theta), z)
    zero = np.zeros(5)
    out = {}
    for race, disp, rho, f, k in (("inner", ring, design.rho_inner, g.fi, design.k_inner),
                                  ("outer", zero, design.rho_outer, g.fo, design.k_outer)):
        delta, n, ep = groove_contact(p, disp, rho, f, g.ball_diameter)
        q = contact_load(k, delta, smooth=smooth)
        alpha = np.arctan2(n[2], np.abs(n[0] * ep[0] + n[1] * ep[1]))
        out[race] = (q, np.array(n), alpha, p)
    return out


def static_state(design: BearingDesign, loads: dict[str, float], w_cage: float = 0.0,
                 theta0: float = 0.0, smooth: float = 2e-8,
                 free_tilt: bool = False, guess: StaticState | None = None) -> StaticState:
    """Solve the quasi-static equilibrium for a load and cage speed.

    Parameters
    ----------
    design : BearingDesign
    loads : dict
        External load on the inner ring: ``Fx, Fy, Fz`` [N], ``Mx, My`` [N m] (missing: 0).
    w_cage : float
        Orbital speed of the balls [rad/s] (centrifugal force).
    theta0 : float
        Azimuth of ball 0 [rad]; ball j sits at ``theta0 + 2 pi j / Z``.
    smooth : float
        Smooth ramp of the Hertz law [m] (as in the components).
    free_tilt : bool
        Whether the ring tilts under the moments; else the shaft holds it straight, takes the
        moments as a reaction and ``Mx, My`` must be absent or 0.
    guess : StaticState, optional
        Start of the iteration (e.g. the solution of a nearby load). Default: the *seated*
        start: each loaded direction of the ring alone brought to balance by a
        one-dimensional root of the two-force ball model (balls on the line of their groove
        centres, no centrifugal force), which also holds for zero clearance, where the centred
        position has no stiffness.

    Returns
    -------
    StaticState

    Raises
    ------
    ParameterError
        For a nonzero ``Mx`` or ``My`` with ``free_tilt=False`` (it would not be applied).
    SimulationError
        If Newton does not converge (e.g. a zero load with clearance: the ring floats).
    """
    if not free_tilt:
        for key in ("Mx", "My"):
            if float(loads.get(key, 0.0)) != 0.0:
                raise ParameterError(f"static_state: loads[{key!r}] = {loads[key]!r} [N.m] is "
                                     f"not applied with free_tilt=False (the shaft holds the "
                                     f"ring straight and takes the moments); give "
                                     f"free_tilt=True or {key} = 0")
    g = design.geometry
    nz = g.ball_count
    theta = theta0 + 2.0 * np.pi * np.arange(nz) / nz
    f_ext = np.array([float(loads.get(k, 0.0)) for k in ("Fx", "Fy", "Fz", "Mx", "My")])
    m_b = design.ball_mass
    scale_r = 1e-6

    def unpack(v):
        return v[:5] * _UNIT, v[5:5 + nz] * scale_r, v[5 + nz:] * scale_r

    def residual(v):
        ring, dr, z = unpack(v)
        r = 0.5 * g.pitch_diameter + dr
        c = _contacts(design, ring, r, z, theta, smooth)
        qi, ni, _, p = c["inner"]
        qo, no, _, _ = c["outer"]
        e_r = np.array([np.cos(theta), np.sin(theta), 0.0 * theta])
        f_ball = -qi * ni - qo * no + m_b * r * w_cage**2 * e_r
        res_ball_r = np.sum(f_ball * e_r, axis=0) - POSITION_REGULARIZATION * dr
        res_ball_z = f_ball[2] - POSITION_REGULARIZATION * z
        f_ring = qi * ni
        arm = np.array(p) - ring[:3, None] + 0.5 * g.ball_diameter * ni
        m_ring = np.cross(arm.T, f_ring.T).T
        res_ring = np.concatenate([f_ring.sum(axis=1), m_ring[:2].sum(axis=1)]) + f_ext
        if not free_tilt:
            res_ring[3:] = v[3:5]
        return np.concatenate([res_ring, res_ball_r, res_ball_z]) * 1e-2

    if guess is not None:
        start = np.concatenate([np.asarray(guess.ring, dtype=float) / _UNIT,
                                (np.asarray(guess.r) - 0.5 * g.pitch_diameter) / scale_r,
                                np.asarray(guess.z) / scale_r])
    else:
        start = _seated_guess(design, f_ext, theta, free_tilt) / np.concatenate(
            [_UNIT, np.full(2 * nz, scale_r)])
    from scipy.optimize import root  # on use: importing scipy.optimize takes ~0.6 s

    sol = root(residual, start, method="hybr", tol=1e-12)
    if np.max(np.abs(residual(sol.x))) > 1e-6:
        sol = root(residual, sol.x, method="lm", tol=1e-14)
    if not np.all(np.isfinite(sol.x)) or np.max(np.abs(residual(sol.x))) > 1e-6:
        raise SimulationError(f"static_state: no quasi-static equilibrium for loads {loads} "
                              f"({sol.message})")
    ring, dr, z = unpack(sol.x)
    r = 0.5 * g.pitch_diameter + dr
    c = _contacts(design, ring, r, z, theta, smooth)
    return StaticState(ring=ring, r=r, z=z, q_inner=c["inner"][0], q_outer=c["outer"][0],
                       alpha_inner=c["inner"][2], alpha_outer=c["outer"][2])


def _two_force_balls(design: BearingDesign, ring: np.ndarray, theta: np.ndarray):
    """Balls as two-force members between their groove centres (no body forces).

    Returns the loads on the ring ``(Fx, Fy, Fz, Mx, My)`` and the ball centres ``(dr, z)``
    (radial offset from the pitch circle, axial position) [N, N m, m].
    """
    g = design.geometry
    x, y, z, tx, ty = ring
    e_r = np.array([np.cos(theta), np.sin(theta), 0.0 * theta])
    lever = design.rho_inner * e_r
    o_inner = lever + np.array([x, y, z])[:, None]
    o_inner[2] += design.rho_inner * (tx * e_r[1] - ty * e_r[0])
    o_outer = design.rho_outer * e_r
    d = o_inner - o_outer
    d_r, d_z = np.sum(d * e_r, axis=0), d[2]
    length = np.hypot(d_r, d_z)
    a = (g.fi + g.fo - 1.0) * g.ball_diameter
    k = (design.k_inner ** (-2 / 3) + design.k_outer ** (-2 / 3)) ** -1.5
    q = k * np.maximum(length - a, 0.0) ** 1.5
    n = np.array([d_r / length * e_r[0], d_r / length * e_r[1], d_z / length])
    force = -(q * n)
    moment = np.cross((o_inner - np.array([x, y, z])[:, None]).T, force.T).T
    approach_o = (q / design.k_outer) ** (2 / 3)
    reach = (g.fo - 0.5) * g.ball_diameter + approach_o
    ball_r = design.rho_outer + reach * d_r / length
    ball_z = reach * d_z / length
    return (np.concatenate([force.sum(axis=1), moment[:2].sum(axis=1)]),
            ball_r - 0.5 * g.pitch_diameter, ball_z)


def _seated_guess(design: BearingDesign, f_ext: np.ndarray, theta: np.ndarray,
                  free_tilt: bool) -> np.ndarray:
    """Ring displacement that balances each loaded direction alone (1-D roots), summed, with the
    two-force ball centres there: ``(ring (5), dr (Z), z (Z))`` [m, rad]."""
    from scipy.optimize import brentq  # on use: importing scipy.optimize takes ~0.6 s

    ring = np.zeros(5)
    for k in np.flatnonzero(f_ext[:5 if free_tilt else 3]):
        unit = np.zeros(5)
        unit[k] = np.sign(f_ext[k]) * _UNIT[k]

        def residual(t, unit=unit, k=k):
            return _two_force_balls(design, t * unit, theta)[0][k] + f_ext[k]

        hi = 1.0
        while np.sign(residual(hi)) == np.sign(residual(0.0)) and hi < 1e7:
            hi *= 2.0
        if np.sign(residual(hi)) != np.sign(residual(0.0)):
            ring += brentq(residual, 0.0, hi, xtol=1e-12) * unit
    _, dr, z = _two_force_balls(design, ring, theta)
    return np.concatenate([ring, dr, z])
