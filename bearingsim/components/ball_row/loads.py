"""A ball row's contact loads from its rings' displacements, classic and Jones-Harris forms
(:func:`row_loads`), and the axial approach under a pure axial force (:func:`axial_approach`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from bearingsim import symbolic as op
from bearingsim.components.ball_row.parameters import STEEL_DENSITY, RowParameters
from bearingsim.errors import ParameterError
from bearingsim.physics.contact_law import contact_load
from bearingsim.physics.hertz import (
    combined_load_deflection_constant,
)
from bearingsim.validation import check_range
from bearingsim.vectors import add, cross, rotate, rotation, scale


def _groove_centres(p: Any, psi: Any, direction: int, reference: str):
    """Inner and outer groove centres of a ball at azimuth ``psi``, body coordinates [m]."""
    ci, co = (p.fi - 0.5) * p.Dw, (p.fo - 0.5) * p.Dw
    ca, sa = op.cos(p.alpha0), op.sin(p.alpha0)
    cp, sp = op.cos(psi), op.sin(psi)
    r_i = 0.5 * p.dm + ci * ca + 0.5 * p.interference
    r_o = 0.5 * p.dm - co * ca - 0.5 * p.interference
    z_i, z_o = (direction * ci * sa, -direction * co * sa) if reference == "touching" else (0, 0)
    return [r_i * cp, r_i * sp, z_i], [r_o * cp, r_o * sp, z_o]


def _ring_points(disp, exact: bool):
    u = [disp[0], disp[1], disp[2]]
    return u, rotation(disp[3], disp[4], exact)


@dataclass
class BallContacts:
    """Per-ball results and the summed loads of :func:`row_loads` (floats or SX).

    Attributes
    ----------
    Q_i, Q_o : contact loads at the inner and outer race [N]
    alpha_i, alpha_o : operating contact angles [rad]
    delta : total elastic approach of the ball's two contacts [m]
    residual : ball equilibrium residuals (Jones-Harris form only) [N]
    inner_load, outer_load : (Fx, Fy, Fz, Mx, My) acting on the inner and outer ring [N, N m]
    """

    Q_i: list
    Q_o: list
    alpha_i: list
    alpha_o: list
    delta: list
    residual: list
    inner_load: list
    outer_load: list


def _moment(lever, force):
    m = cross(lever, force)
    return [m[0], m[1]]


def _accumulate(total, force, moment):
    return [t + v for t, v in zip(total, list(force) + list(moment), strict=True)]


def row_loads(p: Any, inner, outer, n_balls: int, direction: int = 1, *,
              reference: str = "touching", exact: bool = True, ball_centres=None,
              speeds=(0.0, 0.0), ball_density=STEEL_DENSITY) -> BallContacts:
    """Contact loads of a ball row and the loads it puts on its rings.

    Works on floats and CasADi symbols alike; the :class:`BallRow` component writes its
    equations with it and the studies evaluate it with numbers.

    Parameters
    ----------
    p : RowParameters or BallRow
        Anything with the attributes of :class:`RowParameters`.
    inner, outer : sequence of 5
        Displacements (x, y, z, tx, ty) of the inner and outer ring frames [m, rad].
    n_balls : int
        Number of balls Z.
    direction : {1, -1}
        Axial direction s that loads the row (inner ring moving along +s z).
    reference : {"touching", "centred"}
        Reference geometry (module docstring).
    exact : bool
        Exact or small-angle rigid-ring kinematics.
    ball_centres : sequence of (b_r, b_z), optional
        Ball centre offsets from the pitch circle in each azimuth plane [m]; given, the
        Jones-Harris form is used and ``residual`` holds the ball equilibrium equations.
    speeds : (float, float)
        Inner and outer ring speeds [rad/s] (Jones-Harris form).
    ball_density : float
        Ball density [kg/m^3] (Jones-Harris form).

    Returns
    -------
    BallContacts
    """
    u_i, r_i = _ring_points(inner, exact)
    u_o, r_o = _ring_points(outer, exact)
    a = (p.fi + p.fo - 1.0) * p.Dw
    k_ball = combined_load_deflection_constant(p.K_i, p.K_o)
    out = BallContacts([], [], [], [], [], [], [0.0] * 5, [0.0] * 5)
    s = direction
    for j in range(n_balls):
        psi = p.psi0 + 2.0 * math.pi * j / n_balls
        e_r = [op.cos(psi), op.sin(psi), 0.0]
        c_i0, c_o0 = _groove_centres(p, psi, s, reference)
        lever_i, lever_o = rotate(r_i, c_i0), rotate(r_o, c_o0)
        c_i, c_o = add(u_i, lever_i), add(u_o, lever_o)
        ci_plane = (e_r[0] * c_i[0] + e_r[1] * c_i[1], c_i[2])
        co_plane = (e_r[0] * c_o[0] + e_r[1] * c_o[1], c_o[2])

        def to_space(v, e_r=e_r):
            return [v[0] * e_r[0], v[0] * e_r[1], v[1]]

        if ball_centres is None:
            d = (ci_plane[0] - co_plane[0], ci_plane[1] - co_plane[1])
            length = op.sqrt(d[0] * d[0] + d[1] * d[1])
            delta = length - a
            q = contact_load(k_ball, delta, p.smooth)
            alpha = op.atan2(s * d[1], d[0])
            on_balls = to_space((q * d[0] / length, q * d[1] / length))
            out.Q_i.append(q)
            out.Q_o.append(q)
            out.alpha_i.append(alpha)
            out.alpha_o.append(alpha)
            out.delta.append(delta)
            out.inner_load = _accumulate(out.inner_load, scale(-1.0, on_balls),
                                         _moment(lever_i, scale(-1.0, on_balls)))
            out.outer_load = _accumulate(out.outer_load, on_balls, _moment(lever_o, on_balls))
            continue
        b = (0.5 * p.dm + ball_centres[j][0], ball_centres[j][1])
        res, f_inner, f_outer, friction_plane = _jones_harris_ball(
            p, s, b, ci_plane, co_plane, speeds, ball_density, out)
        out.residual += res
        f_i3, f_o3 = to_space(f_inner), to_space(f_outer)
        friction, normal_o = to_space(friction_plane[0]), to_space(friction_plane[1])
        lever_contact = add(to_space(b), scale(0.5 * p.Dw, normal_o), scale(-1.0, u_o))
        moment_o = add(cross(lever_o, add(f_o3, friction)),
                       cross(lever_contact, scale(-1.0, friction)))
        out.inner_load = _accumulate(out.inner_load, f_i3, _moment(lever_i, f_i3))
        out.outer_load = _accumulate(out.outer_load, f_o3, moment_o[:2])
    return out


def _jones_harris_ball(p, s, b, ci_plane, co_plane, speeds, density, out: BallContacts):
    """Equilibrium of one ball with centrifugal force and gyroscopic moment.

    Returns the two residuals, the loads on the inner and outer ring in the azimuth plane
    (the outer one includes the friction force), and (friction force, outer contact normal).
    """
    d_i = (ci_plane[0] - b[0], ci_plane[1] - b[1])
    d_o = (b[0] - co_plane[0], b[1] - co_plane[1])
    l_i = op.sqrt(d_i[0] ** 2 + d_i[1] ** 2)
    l_o = op.sqrt(d_o[0] ** 2 + d_o[1] ** 2)
    delta_i, delta_o = l_i - (p.fi - 0.5) * p.Dw, l_o - (p.fo - 0.5) * p.Dw
    q_i = contact_load(p.K_i, delta_i, p.smooth)
    q_o = contact_load(p.K_o, delta_o, p.smooth)
    n_i = (d_i[0] / l_i, d_i[1] / l_i)
    n_o = (d_o[0] / l_o, d_o[1] / l_o)
    a_i, a_o = op.atan2(s * n_i[1], n_i[0]), op.atan2(s * n_o[1], n_o[0])
    g = p.Dw / p.dm
    w_in, w_out = speeds
    beta = op.atan2(op.sin(a_o), op.cos(a_o) + g)
    rho = ((1.0 - g * op.cos(a_i)) * op.cos(a_o - beta)
           / ((1.0 + g * op.cos(a_o)) * op.cos(a_i - beta)))
    w_cage_rel = (w_in - w_out) * rho / (1.0 + rho)
    w_m = w_out + w_cage_rel
    w_spin = w_cage_rel * (1.0 + g * op.cos(a_o)) / (g * op.cos(a_o - beta))
    mass = density * math.pi * p.Dw**3 / 6.0
    f_c = 0.5 * mass * p.dm * w_m * w_m
    m_g = 0.1 * mass * p.Dw**2 * w_spin * w_m * op.sin(beta)
    f_mag = 2.0 * m_g / p.Dw
    friction = (-f_mag * op.sin(a_o), s * f_mag * op.cos(a_o))
    res = [q_i * n_i[0] - q_o * n_o[0] + f_c + friction[0],
           q_i * n_i[1] - q_o * n_o[1] + friction[1]]
    out.Q_i.append(q_i)
    out.Q_o.append(q_o)
    out.alpha_i.append(a_i)
    out.alpha_o.append(a_o)
    out.delta.append(delta_i + delta_o)
    f_inner = (-q_i * n_i[0], -q_i * n_i[1])
    f_outer = (q_o * n_o[0] - friction[0], q_o * n_o[1] - friction[1])
    return res, f_inner, f_outer, (friction, n_o)


def axial_approach(p: RowParameters, n_balls: int, force: float, *, reference="touching",
                   exact: bool = True) -> float:
    """Axial displacement of the inner ring relative to the outer ring that makes a row carry
    the axial ``force`` (classic form, no speed effects).

    Parameters
    ----------
    p : RowParameters
    n_balls : int
        Number of balls.
    force : float
        Axial load of the row [N], > 0.
    reference : {"touching", "centred"}
    exact : bool

    Returns
    -------
    float
        The displacement along the row's loading direction [m], > 0.
    """
    check_range(force, "force", "N", 0.0, low_inclusive=False, where="axial_approach")

    def residual(dz):
        # a purely axial approach loads every ball alike: the row carries Z times one ball's
        # load (the balls of the whole row differ only by the rounding of their azimuths)
        loads = row_loads(p, [0.0, 0.0, dz, 0.0, 0.0], [0.0] * 5, 1, 1,
                          reference=reference, exact=exact)
        return -n_balls * float(loads.inner_load[2]) - force

    hi = 1e-6 * p.Dw
    while residual(hi) < 0.0:
        hi *= 2.0
        if hi > p.Dw:
            raise ParameterError(f"axial_approach: the row cannot carry {force:g} N axially")
    from scipy.optimize import brentq  # on use: importing scipy.optimize takes ~0.6 s

    return float(brentq(residual, 0.0, hi, xtol=1e-18, rtol=1e-14))
