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
import scipy.optimize

from bearingsim.errors import ParameterError, SimulationError
from bearingsim.physics.bearing_design import POSITION_REGULARIZATION, BearingDesign
from bearingsim.physics.groove_contact import groove_contact
from bearingsim.physics.hertz import contact_load

__all__ = ["StaticState", "static_state"]


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
                 free_tilt: bool = False) -> StaticState:
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
        return v[:5] * np.array([scale_r] * 3 + [1e-4] * 2), v[5:5 + nz] * scale_r, \
            v[5 + nz:] * scale_r

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

    f_r = np.hypot(f_ext[0], f_ext[1])
    guess = np.zeros(5 + 2 * nz)
    if f_r > 0:
        shift = (g.diametral_clearance / 2 + (f_r / (design.k_inner * 0.5)) ** (2 / 3)) / scale_r
        guess[:2] = f_ext[:2] / f_r * shift
        guess[5:5 + nz] = 0.5 * np.maximum(guess[0] * np.cos(theta) + guess[1] * np.sin(theta), 0)
    if f_ext[2] != 0.0:
        z_free = g.groove_centre_distance * np.sin(design.free_contact_angle) / scale_r
        guess[2] = np.sign(f_ext[2]) * 1.2 * z_free
        guess[5 + nz:] = 0.5 * guess[2]
    sol = scipy.optimize.root(residual, guess, method="hybr", tol=1e-12)
    if np.max(np.abs(residual(sol.x))) > 1e-6:
        sol = scipy.optimize.root(residual, sol.x, method="lm", tol=1e-14)
    if not np.all(np.isfinite(sol.x)) or np.max(np.abs(residual(sol.x))) > 1e-6:
        raise SimulationError(f"static_state: no quasi-static equilibrium for loads {loads} "
                              f"({sol.message})")
    ring, dr, z = unpack(sol.x)
    r = 0.5 * g.pitch_diameter + dr
    c = _contacts(design, ring, r, z, theta, smooth)
    return StaticState(ring=ring, r=r, z=z, q_inner=c["inner"][0], q_outer=c["outer"][0],
                       alpha_inner=c["inner"][2], alpha_outer=c["outer"][2])
