"""Quasi-static ball row: Z balls with Hertz contacts between an inner and an outer ring frame.

Geometry (Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., *Essential Concepts*, chapter
"Rolling bearing macrogeometry"; *Advanced Concepts*, chapters "Distribution of internal
loading" and "High-speed operation"). Ball ``j`` sits at the azimuth
``psi_j = psi0 + 2 pi j / Z`` (measured from x towards y). In the reference configuration the
inner and outer groove curvature centres of ball ``j`` are, in (radial, axial) coordinates of
its azimuth plane,

    C_i = (dm/2 + (fi - 1/2) Dw cos a0,  s (fi - 1/2) Dw sin a0)
    C_o = (dm/2 - (fo - 1/2) Dw cos a0, -s (fo - 1/2) Dw sin a0)

(``reference="touching"``: the balls just touch at the free contact angle ``a0``, so the groove
centres are ``A = (fi + fo - 1) Dw`` apart) or both at axial position 0 (``reference="centred"``:
a deep-groove bearing with its rings centred and the radial clearance ``Pd = 2 A (1 - cos a0)``).
``s = direction = +-1`` is the axial direction in which the inner ring must move relative to
the outer ring to load the row. The groove centres move with their rings by exact rigid-body
kinematics (:mod:`bearingsim.vectors`; the small-angle form is an option).

**Classic form** (``speed_effects=False``). Without body forces each ball is a two-force member:
its contact loads act along the line through both groove centres, the inner and outer contact
angles are equal, and the single unknown of the ball, its total elastic approach, follows
explicitly from ``d = C_i - C_o`` projected on the azimuth plane (the ball moves tangentially
with the cage, so the tangential part does not load it):

    delta_j = |d| - A,   Q_j = K delta_j^1.5,   alpha_j = atan2(s d_z, d_r)

with ``K = (K_i^(-2/3) + K_o^(-2/3))^(-3/2)`` (Jones 1960; Harris & Kotzalas). This is the
formulation behind ``Fa = Z K A^1.5 sin a (cos a0 / cos a - 1)^1.5`` for a pure axial load.

**Jones-Harris form** (``speed_effects=True``). The ball centre ``(b_r, b_z)`` in its azimuth
plane is an unknown of each ball (two algebraic unknowns, solved by the assembler's Newton
blocks). The inner and outer contacts have their own deflections and angles, and the ball's
equilibrium includes the centrifugal force ``Fc = m dm wm^2 / 2`` and the gyroscopic moment
``Mg = J wR wm sin(beta)`` carried by friction at the outer contact (outer raceway control,
``lambda_o = 2``, ``tan beta = sin a_o / (cos a_o + Dw / dm)``; Jones 1960, Harris & Kotzalas,
*Advanced Concepts*, chapter "Ball bearing kinematics" / "High-speed operation"). The orbital
and spin speeds ``wm``, ``wR`` follow from pure rolling at both contacts with the operating
contact angles.

**Regularization.** ``max(delta, 0)`` is replaced by ``(delta + sqrt(delta^2 + eps^2)) / 2``
(:func:`bearingsim.physics.hertz.contact_load` with ``smooth = eps``) so that unloaded balls keep
the equations differentiable. For a loaded contact the load is then too high by the relative
amount ``(3/8) (eps / delta)^2`` (3.75e-7 at ``delta = 1 um`` with the default ``eps = 1 nm``);
a contact that just touches carries ``K (eps/2)^1.5`` (about 1e-4 N for a 7020 ball), and one
with a gap ``g`` carries ``K (eps^2 / (4 g))^1.5``. In the Jones-Harris form a ball that is
unloaded at both contacts floats on these tiny forces: use it at speed (the centrifugal force
seats the ball) or with every ball preloaded.

Loads on the rings are summed per ball with the exact lever from the ring frame's point to the
groove centre (and to the outer contact point for the friction force).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np
import scipy.optimize

from bearingsim import symbolic as op
from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.connectors import RingFrame
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Parameter, Variable
from bearingsim.physics.hertz import (
    STEEL,
    Material,
    bearing_load_deflection_constants,
    combined_load_deflection_constant,
    contact_load,
)
from bearingsim.physics.ring_equilibrium import EquilibriumProblem
from bearingsim.validation import check_choice, check_range
from bearingsim.vectors import add, cross, rotate, rotation, scale

__all__ = [
    "BallRow",
    "RowParameters",
    "row_parameters",
    "row_loads",
    "axial_approach",
    "row_stiffness",
    "row_equilibrium",
    "RowEquilibrium",
    "REFERENCES",
]

REFERENCES = ("touching", "centred")
_MAX_ALPHA = math.radians(45.0)
STEEL_DENSITY = 7850.0
"""Density of bearing steel balls [kg/m^3]."""


@dataclass(frozen=True)
class RowParameters:
    """Numeric parameters of a ball row (SI units); the component's parameters have these names.

    Attributes
    ----------
    Dw, dm : ball and pitch diameter [m]
    fi, fo : groove curvature factors [-]
    alpha0 : free contact angle [rad]
    K_i, K_o : Hertz load-deflection constants of the inner and outer contact [N/m^1.5]
    psi0 : ball position angle (azimuth of ball 0) [rad]
    smooth : regularization length of the contact law [m]
    interference : how much farther apart the groove centres are than ``A`` at zero
        displacement [m]: ``-Pd / 2`` for a negative diametral clearance (an internal preload
        of a mounted deep-groove bearing), else 0
    """

    Dw: float
    dm: float
    fi: float
    fo: float
    alpha0: float
    K_i: float
    K_o: float
    psi0: float = 0.0
    smooth: float = 1e-9
    interference: float = 0.0


def row_parameters(bearing: str | BearingGeometry, contact_angle: float | None = None,
                   ball_position_angle: float = 0.0, smooth: float = 1e-9,
                   ball: Material = STEEL, ring: Material = STEEL,
                   method: str = "exact") -> RowParameters:
    """Row parameters of a catalogue bearing.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Designation or geometry.
    contact_angle : float, optional
        Free contact angle [rad] in [0, 45 deg]; the bearing's free contact angle by default.
    ball_position_angle : float
        Azimuth of ball 0 [rad].
    smooth : float
        Regularization length [m], > 0.
    ball, ring : Material
        Materials (Hertz constants).
    method : {"exact", "hamrock_brewe"}
        Elliptic integrals of the Hertz constants.

    Returns
    -------
    RowParameters
        With the Hertz constants evaluated at the free contact angle.
    """
    g = resolve_bearing(bearing)
    alpha0 = g.free_contact_angle if contact_angle is None else contact_angle
    check_range(alpha0, "contact_angle", "rad", 0.0, _MAX_ALPHA,
                where=f"row_parameters({g.designation})")
    check_range(smooth, "smooth", "m", 0.0, low_inclusive=False, where="row_parameters")
    k_i, k_o, _ = bearing_load_deflection_constants(g, ball, ring, alpha0, method)
    return RowParameters(g.ball_diameter, g.pitch_diameter, g.fi, g.fo, float(alpha0),
                         float(k_i), float(k_o), float(ball_position_angle), float(smooth),
                         max(-g.diametral_clearance, 0.0) / 2.0)


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
        loads = row_loads(p, [0.0, 0.0, dz, 0.0, 0.0], [0.0] * 5, n_balls, 1,
                          reference=reference, exact=exact)
        return -float(loads.inner_load[2]) - force

    hi = 1e-6 * p.Dw
    while residual(hi) < 0.0:
        hi *= 2.0
        if hi > p.Dw:
            raise ParameterError(f"axial_approach: the row cannot carry {force:g} N axially")
    return float(scipy.optimize.brentq(residual, 0.0, hi, xtol=1e-18, rtol=1e-14))


class BallRow(Component):
    """Quasi-static row of Z balls between an inner-ring and an outer-ring frame.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Catalogue designation or geometry (Dw, dm, fi, fo, Z, free contact angle).
    direction : {1, -1}
        Axial direction s of the row: the row is loaded when the inner ring moves along s z
        relative to the outer ring.
    contact_angle : float, optional
        Free contact angle a0 [rad] in [0, 45 deg] (default: the bearing's free contact angle;
        for a deep-groove bearing the one its radial clearance gives).
    ball_position_angle : float
        Azimuth psi0 of ball 0 from the x axis [rad].
    speed_effects : bool
        Jones-Harris form with centrifugal force and gyroscopic moment (two unknowns per ball)
        instead of the classic explicit form.
    reference : {"touching", "centred"}
        Reference configuration: balls just touching at a0 (angular contact rows), or the rings
        centred with the radial clearance (deep-groove rows).
    exact : bool
        Exact rigid-ring kinematics (default) or the small-angle form.
    smooth : float
        Regularization length of the contact law [m] (module docstring).
    ball, ring : Material
        Materials for the Hertz constants.
    ball_density : float
        Ball density [kg/m^3] (centrifugal force, gyroscopic moment).
    representative : bool
        Axisymmetric reduction for a pure axial load: ball 0 is solved alone under the axial
        displacement of the rings and stands for every ball (all per-ball outputs equal it);
        the row transmits ``Z`` times its axial load and no radial force or moment. Valid only
        while the rings do not move radially or tilt, which a pure axial load on a symmetric
        assembly guarantees.
    centre_start : sequence of (float, float), optional
        Jones-Harris form: start values (Newton guesses) of every ball's ``(b_r, b_z)`` [m],
        e.g. from :func:`row_equilibrium`; default 0 (the pitch circle).

    Parameters (model)
    ------------------
    Dw, dm [m]; fi, fo [-]; alpha0 [rad]; K_i, K_o [N/m^1.5]; psi0 [rad]; smooth [m];
    inner_speed, outer_speed [rad/s]; ball_density [kg/m^3].

    Variables
    ---------
    Q_i[j], Q_o[j] [N] : inner and outer contact loads of ball j
    alpha_i[j], alpha_o[j] [rad] : operating contact angles
    delta[j] [m] : total elastic approach of ball j (negative: clearance)
    b_r[j], b_z[j] [m] : ball centre offsets (Jones-Harris form only)

    Connectors
    ----------
    inner, outer : RingFrame (flows: loads of the rings on the row)
    """

    def __init__(self, bearing: str | BearingGeometry = "7020C", direction: int = 1, *,
                 contact_angle: float | None = None, ball_position_angle: float = 0.0,
                 speed_effects: bool = False, reference: str = "touching", exact: bool = True,
                 smooth: float = 1e-9, ball: Material = STEEL, ring: Material = STEEL,
                 ball_density: float = STEEL_DENSITY, representative: bool = False,
                 centre_start=None, name=None):
        super().__init__(name)
        self.geometry = resolve_bearing(bearing)
        self.representative = bool(representative)
        check_choice(direction, "direction", (1, -1), self.display_name)
        if reference not in REFERENCES:
            raise ParameterError(f"{self.display_name}: reference must be one of {REFERENCES}, "
                                 f"got {reference!r}")
        where = f"{type(self).__name__}({self.geometry.designation})"
        if contact_angle is not None:
            check_range(contact_angle, "contact_angle", "rad", 0.0, _MAX_ALPHA, where=where)
        rp = row_parameters(self.geometry, contact_angle, ball_position_angle, smooth, ball,
                            ring)
        self.n_balls = self.geometry.ball_count
        self.direction = direction
        self.reference = reference
        self.exact = exact
        self.speed_effects = speed_effects
        pos = {"low": 0.0, "low_inclusive": False}
        self.Dw = Parameter(rp.Dw, "m", "ball diameter", **pos)
        self.dm = Parameter(rp.dm, "m", "pitch diameter", **pos)
        self.fi = Parameter(rp.fi, "1", "inner groove curvature factor", low=0.5, high=1.0,
                            low_inclusive=False)
        self.fo = Parameter(rp.fo, "1", "outer groove curvature factor", low=0.5, high=1.0,
                            low_inclusive=False)
        self.alpha0 = Parameter(rp.alpha0, "rad", "free contact angle", low=0.0, high=_MAX_ALPHA)
        self.K_i = Parameter(rp.K_i, "N/m^1.5", "Hertz constant, inner contact", **pos)
        self.K_o = Parameter(rp.K_o, "N/m^1.5", "Hertz constant, outer contact", **pos)
        self.psi0 = Parameter(rp.psi0, "rad", "ball position angle (azimuth of ball 0)")
        self.smooth = Parameter(rp.smooth, "m", "contact regularization length", **pos)
        self.interference = Parameter(rp.interference, "m", "groove-centre interference of a "
                                      "preloaded deep-groove row (-Pd/2)", low=0.0)
        self.inner_speed = Parameter(0.0, "rad/s", "inner ring speed")
        self.outer_speed = Parameter(0.0, "rad/s", "outer ring speed")
        self.ball_density = Parameter(ball_density, "kg/m3", "ball density", **pos)
        self.inner = RingFrame()
        self.outer = RingFrame()
        z = self.n_balls
        labels = (("Q_i", "N", "inner contact load"), ("Q_o", "N", "outer contact load"),
                  ("alpha_i", "rad", "inner contact angle"),
                  ("alpha_o", "rad", "outer contact angle"),
                  ("delta", "m", "total elastic approach"))
        self._outputs = {key: [self.add(f"{key}[{j}]", Variable(unit=unit, description=text))
                               for j in range(z)] for key, unit, text in labels}
        self._centres = None
        if speed_effects:
            n_centres = 1 if self.representative else z
            starts = (np.zeros((n_centres, 2)) if centre_start is None
                      else np.asarray(centre_start, dtype=float).reshape(n_centres, 2))
            self._centres = [
                (self.add(f"b_r[{j}]", Variable(float(starts[j, 0]), "m",
                                                "ball centre radial offset", fixed=False)),
                 self.add(f"b_z[{j}]", Variable(float(starts[j, 1]), "m",
                                                "ball centre axial offset", fixed=False)))
                for j in range(n_centres)]

    def output_names(self, key: str) -> list[str]:
        """Dotted names of the per-ball variable ``key`` (e.g. "Q_i") in ball order."""
        return [f"{self.path}.{key}[{j}]" for j in range(self.n_balls)]

    def loads(self) -> BallContacts:
        """:func:`row_loads` on this row's symbols."""
        return row_loads(self, self.inner.displacement(), self.outer.displacement(),
                         self.n_balls, self.direction, reference=self.reference,
                         exact=self.exact, ball_centres=self._centres,
                         speeds=(self.inner_speed, self.outer_speed),
                         ball_density=self.ball_density)

    def representative_loads(self) -> BallContacts:
        """:func:`row_loads` of ball 0 alone under the axial part of the ring displacements."""
        def axial(frame):
            return [0.0, 0.0, frame.z, 0.0, 0.0]

        return row_loads(self, axial(self.inner), axial(self.outer), 1, self.direction,
                         reference=self.reference, exact=self.exact,
                         ball_centres=self._centres, speeds=(self.inner_speed, self.outer_speed),
                         ball_density=self.ball_density)

    def equations(self):
        if self.representative:
            return self._representative_equations()
        c = self.loads()
        eqs = [var == val for key, values in self._outputs.items()
               for var, val in zip(values, getattr(c, key), strict=True)]
        eqs += list(c.residual)
        # the row's connector flows are the loads of the rings on the row
        eqs += [f == -load for f, load in zip(self.inner.loads(), c.inner_load, strict=True)]
        eqs += [f == -load for f, load in zip(self.outer.loads(), c.outer_load, strict=True)]
        return eqs

    def _representative_equations(self):
        """Axisymmetric row: ball 0 stands for all balls; only the axial load is transmitted."""
        c = self.representative_loads()
        z = self.n_balls
        eqs = [var == getattr(c, key)[0] for key, values in self._outputs.items()
               for var in values]
        eqs += list(c.residual)
        for frame, load in ((self.inner, c.inner_load), (self.outer, c.outer_load)):
            fx, fy, fz, mx, my = frame.loads()
            eqs += [fz == -z * load[2], fx == 0, fy == 0, mx == 0, my == 0]
        return eqs


def row_stiffness(p: RowParameters, n_balls: int, inner=(0.0,) * 5, direction: int = 1, *,
                  reference: str = "touching", exact: bool = True) -> np.ndarray:
    """5x5 stiffness matrix of a ball row (classic form) from the exact CasADi Jacobian.

    ``K = -d(load on the inner ring) / d(inner ring displacement)`` with the outer ring fixed;
    rows and columns ordered (x, y, z, tx, ty) [N/m, N/rad, N m/m, N m/rad].

    Parameters
    ----------
    p : RowParameters
    n_balls : int
    inner : sequence of 5
        Inner ring displacement of the operating point [m, rad].
    direction, reference, exact
        As for :func:`row_loads`.

    Returns
    -------
    numpy.ndarray of shape (5, 5)
    """
    q = ca.SX.sym("q", 5)
    loads = row_loads(p, [q[k] for k in range(5)], [0.0] * 5, n_balls, direction,
                      reference=reference, exact=exact)
    jac = ca.Function("row_jac", [q], [ca.jacobian(ca.vertcat(*loads.inner_load), q)])
    return -np.asarray(jac(ca.DM(list(inner))).full(), dtype=float)


@dataclass(frozen=True)
class RowEquilibrium:
    """Result of :func:`row_equilibrium`."""

    inner: np.ndarray
    """Inner ring translation (x, y, z) against the outer ring [m] (tilts held at 0)."""
    centres: np.ndarray | None
    """Ball centres ``(b_r, b_z)`` per ball [m] (Jones-Harris form), else None."""


def _classic_centres(p: Any, inner: np.ndarray, n_balls: int, reference: str,
                     density: float, speeds: tuple[float, float]) -> np.ndarray:
    """Ball centres of the two-force (classic) ball, pressed out by the centrifugal force of the
    cage speed where it carries no load: a start for the Jones-Harris unknowns [m]."""
    k_ball = combined_load_deflection_constant(p.K_i, p.K_o)
    g = p.Dw / p.dm
    w_cage = speeds[0] * 0.5 * (1.0 - g) + speeds[1] * 0.5 * (1.0 + g)
    f_c = 0.5 * density * math.pi * p.Dw**3 / 6.0 * p.dm * w_cage**2
    out = np.zeros((n_balls, 2))
    for j in range(n_balls):
        psi = p.psi0 + 2.0 * math.pi * j / n_balls
        c_i0, c_o0 = _groove_centres(p, psi, 1, reference)
        c_i = (c_i0[0] + inner[0], c_i0[1] + inner[1], c_i0[2] + inner[2])
        ci = (math.cos(psi) * c_i[0] + math.sin(psi) * c_i[1], c_i[2])
        co = (math.cos(psi) * c_o0[0] + math.sin(psi) * c_o0[1], c_o0[2])
        d = (ci[0] - co[0], ci[1] - co[1])
        length = math.hypot(*d)
        q = k_ball * max(length - (p.fi + p.fo - 1.0) * p.Dw, 0.0) ** 1.5
        reach = (p.fo - 0.5) * p.Dw + ((q + f_c) / p.K_o) ** (2.0 / 3.0)
        out[j] = (co[0] + reach * d[0] / length - 0.5 * p.dm, co[1] + reach * d[1] / length)
    return out


def row_equilibrium(p: RowParameters, n_balls: int, loads=(0.0, 0.0, 0.0), *,
                    speeds=(0.0, 0.0), speed_effects: bool = False,
                    reference: str = "centred",
                    ball_density: float = STEEL_DENSITY) -> RowEquilibrium:
    """Numeric equilibrium of a row with the inner ring held straight, e.g. for start values.

    Solved by :class:`~bearingsim.physics.ring_equilibrium.EquilibriumProblem` (seated start,
    Levenberg-Marquardt on the exact Jacobian): first the classic form, then, with
    ``speed_effects``, the Jones-Harris form from it (ball centres pressed out by the centrifugal
    force as the start).

    Parameters
    ----------
    p : RowParameters
    n_balls : int
        Number of balls Z.
    loads : (Fx, Fy, Fz)
        External load on the inner ring [N].
    speeds : (float, float)
        Inner and outer ring speeds [rad/s].
    speed_effects : bool
        Jones-Harris form (centrifugal force, gyroscopic moment).
    reference : {"touching", "centred"}
    ball_density : float
        [kg/m^3].

    Returns
    -------
    RowEquilibrium

    Raises
    ------
    SimulationError
        If no equilibrium is found (named by the speed with ``speed_effects``).
    """
    a_play = (p.fi + p.fo - 1.0) * p.Dw * math.sin(p.alpha0) if reference == "centred" else 0.0
    x = ca.SX.sym("x", 3)
    ring = [x[0], x[1], x[2], 0.0, 0.0]
    classic = row_loads(p, ring, [0.0] * 5, n_balls, 1, reference=reference)
    problem = EquilibriumProblem(ca.Function("row", [x], [ca.vertcat(*classic.inner_load[:3])]),
                                 3, [1e-5] * 3, [1.0] * 3, play=a_play, axial=2,
                                 name=f"row_equilibrium({n_balls} balls)")
    inner = problem.solve(np.asarray(loads, dtype=float))
    if not speed_effects:
        return RowEquilibrium(inner, None)
    b = ca.SX.sym("b", 2 * n_balls)
    centres = [(b[2 * j], b[2 * j + 1]) for j in range(n_balls)]
    jh = row_loads(p, ring, [0.0] * 5, n_balls, 1, reference=reference, ball_centres=centres,
                   speeds=speeds, ball_density=ball_density)
    v = ca.vertcat(x, b)
    problem = EquilibriumProblem(
        ca.Function("row_jh", [v], [ca.vertcat(*jh.inner_load[:3], *jh.residual)]),
        3, [1e-5] * 3 + [1e-6] * (2 * n_balls), [1.0] * (3 + 2 * n_balls),
        extra_start=lambda r: _classic_centres(p, r, n_balls, reference, ball_density,
                                                speeds).ravel(),
        play=a_play, axial=2,
        name=f"row_equilibrium at inner-ring speed {speeds[0]:g} rad/s "
             f"({speeds[0] * 30 / math.pi:.0f} r/min)")
    guess = np.concatenate([inner, _classic_centres(p, inner, n_balls, reference, ball_density,
                                                    speeds).ravel()])
    sol = problem.solve(np.asarray(loads, dtype=float), guess)
    return RowEquilibrium(sol[:3], sol[3:].reshape(n_balls, 2))
