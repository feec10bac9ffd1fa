"""Ball-raceway contact: Hertz normal load from the exact ring-ball geometry, slice traction and
(optionally) the EHL hydrodynamic rolling resistance."""

from __future__ import annotations

import numbers

from bearingsim import symbolic as op
from bearingsim.components.connectors import BallFrame, Flange, RingFrame
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Parameter, Variable, der
from bearingsim.physics.contact_law import contact_load, contact_stiffness
from bearingsim.physics.groove_contact import groove_contact
from bearingsim.physics.lubricant import Lubricant, as_lubricant
from bearingsim.physics.rolling import rolling_resistance
from bearingsim.physics.traction import slice_traction
from bearingsim.validation import check_choice
from bearingsim.vectors import Vec, add, azimuth_frame, cross, dot, scale, sub

__all__ = ["RaceContact"]

_Q_SMOOTH = 1e-4
"""Width [N] of the smooth non-negative limit of the damped contact load (offset 5e-5 N)."""
_V_ROLL_REG = 1e-3
"""Regularization speed [m/s] of the direction of the rolling resistance (the ball centre moves
relative to the race at about the entrainment speed, metres per second)."""


def _slice_count(n_slices) -> int:
    """``n_slices`` as an int, or ParameterError if it is not a whole number >= 0."""
    whole = isinstance(n_slices, numbers.Integral) or (
        isinstance(n_slices, numbers.Real) and float(n_slices).is_integer())
    if isinstance(n_slices, bool) or not whole or n_slices < 0:
        raise ParameterError(f"RaceContact: n_slices must be an integer >= 0 (2 n + 1 traction "
                             f"slices) [-], got {n_slices!r}")
    return int(n_slices)


class RaceContact(Component):
    """Contact of one ball with the inner or outer raceway of a (possibly displaced) ring.

    Geometry: approach ``delta`` and normal ``n`` (ball centre to contact) from the exact
    rigid-ring kinematics of :func:`~bearingsim.physics.groove_contact.groove_contact`
    (the groove centre moves with the ring's 5-DOF displacement).

    Normal load: ``Q = < K <delta>^1.5 (1 + c_d d(delta)/dt) + beta k(delta) d(delta)/dt >``:
    Hertz with the smooth ramp of :func:`~bearingsim.physics.contact_law.contact_load`, Hunt and
    Crossley (1975) material damping ``c_d`` and the squeeze damping of the lubricant film,
    proportional to the tangent contact stiffness ``k = dQ/d delta``
    (:func:`~bearingsim.physics.contact_law.contact_stiffness`) with the time constant ``beta``; the
    sum is kept non-negative (a contact cannot pull). Hunt-Crossley damping alone is
    proportional to the load, so the lightly loaded contacts of the balls outside the load zone
    (centrifugal force only, below 1 N) would ring at 5-10 kHz with damping ratios near 0.001
    for tens of milliseconds; a lubricated contact is far better damped. ``beta`` of the order
    1e-5 s is the classical estimate for rolling bearings, damping 0.25e-5 .. 2.5e-5 times the
    stiffness (Kramer, *Dynamics of Rotors and Foundations*, 1993; used per contact by Sopanen
    and Mikkola, Proc. IMechE K 217, 2003); it gives damping ratios ``beta w / 2`` of 0.2-0.6
    to the ball's contact modes (``w`` = 4e4 .. 1.3e5 rad/s) and leaves the motion at the ball
    pass frequency (below 1e3 rad/s) undamped to within 1 %.

    Traction: the ellipse (semi-major axis ``a = a1 Q^(1/3)`` along ``e_a = n x e_roll``) is
    cut into ``2 n_slices + 1`` slices (:func:`~bearingsim.physics.traction.slice_traction`);
    slice points lie on the pressure surface of radius ``R = 2 f Dw / (2 f + 1)`` (Harris &
    Kotzalas), ``r_s = (Dw/2 - x^2 / (2R)) n + x e_a``, and slide at
    ``du = v_b + w_b x r_s - v_ring - w_ring e_z x (p_b + r_s - c)``; the coefficient comes from
    the swappable lubricant (``Lubricant.traction_coefficient``), odd and smooth in the slip.

    Rolling resistance (``rolling_resistance=True``): the hydrodynamic rolling force ``F_R`` of
    the EHL inlet (:func:`~bearingsim.physics.rolling.rolling_resistance`, Houpert's curve fit at
    the elastic load, the entrainment speed and the lubricant's ``eta``, ``alpha``, which are
    parameters) acts on the ball at its centre, against the ball centre's velocity relative to
    the ring, ``v_rel = (v_b - v_ring(p_b)) . e_roll``, and on the ring as the equal and
    opposite force at the contact plus the couple of the inlet-shifted pressure that makes the
    pair collinear (so angular momentum about the axis is conserved: the ring feels the force
    at the ball centre's radius). It is a pure rolling loss: its power
    ``P_roll = F_R |v_rel|`` is dissipated even in pure rolling (where a force pair at the
    contact point would do no work), and on a ring it is a drag torque ``F_R r_b`` towards the
    ball's motion: the outer ring of a bearing with a turning inner ring is dragged forwards.

    Parameters
    ----------
    race : {"inner", "outer"}
        Which raceway (sets the default sign conventions only through ``rho``).
    rho : float
        Radius of the groove curvature-centre circle [m].
    groove_factor : float
        f = groove radius / Dw [-], in (0.5, 1).
    ball_diameter : float
        Dw [m].
    k_hertz : float
        Load-deflection constant K [N/m^1.5].
    a1 : float
        Semi-major axis at 1 N [m].
    lubricant : Lubricant
        Traction law.
    moving : bool
        Whether the ring moves (its frame potentials and flange angle are differentiated).
    damping : float
        Hunt-Crossley coefficient c_d [s/m], >= 0.
    film_damping : float
        Stiffness-proportional (lubricant film) damping time constant beta [s], >= 0.
    n_slices : int
        ``2 n + 1`` slices, an integer >= 0.
    smooth : float
        Width of the smooth contact ramp [m].
    traction_scale : float
        Multiplier of the traction [-] (0 switches traction off).
    rolling_resistance : bool
        Add the EHL hydrodynamic rolling resistance (needs a viscous lubricant and ``rx``,
        ``ry``, ``e_eff``).
    rx, ry : float, optional
        Reduced radii of the contact along and across rolling [m] (rolling resistance).
    e_eff : float, optional
        Effective modulus ``E'`` [Pa] (rolling resistance).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    ball : BallFrame
    ring : RingFrame
    flange : Flange (ring rotation)

    Variables
    ---------
    Q [N] normal load, delta [m] approach, alpha [rad] contact angle, F_roll, F_axial [N]
    traction on the ball along the rolling direction and the major axis, u_entrain [m/s]
    entrainment speed, slip [m/s] sliding speed at the contact centre along rolling
    """

    def __init__(self, race: str, rho: float, groove_factor: float, ball_diameter: float,
                 k_hertz: float, a1: float, lubricant: Lubricant, moving: bool = False,
                 damping: float = 0.0, film_damping: float = 0.0, n_slices: int = 2,
                 smooth: float = 2e-8, traction_scale: float = 1.0,
                 rolling_resistance: bool = False, rx: float | None = None,
                 ry: float | None = None, e_eff: float | None = None, name=None):
        super().__init__(name)
        check_choice(race, "race", ("inner", "outer"), "RaceContact")
        lubricant = as_lubricant(lubricant, "RaceContact")
        self.race, self.moving = race, bool(moving)
        self.n_slices = _slice_count(n_slices)
        self.lubricant, self.smooth = lubricant, float(smooth)
        self.rho = Parameter(rho, "m", "groove curvature-centre radius", low=0.0,
                             low_inclusive=False)
        self.f = Parameter(groove_factor, "1", "groove curvature factor", low=0.5, high=1.0,
                           low_inclusive=False)
        self.Dw = Parameter(ball_diameter, "m", "ball diameter", low=0.0, low_inclusive=False)
        self.K = Parameter(k_hertz, "N/m^1.5", "Hertz load-deflection constant", low=0.0)
        self.a1 = Parameter(a1, "m", "semi-major axis at 1 N", low=0.0)
        self.c_d = Parameter(damping, "s/m", "Hunt-Crossley damping coefficient", low=0.0)
        self.beta = Parameter(film_damping, "s", "film damping / contact stiffness", low=0.0)
        self.mu_scale = Parameter(traction_scale, "1", "traction multiplier", low=0.0)
        self.rolling = bool(rolling_resistance)
        if self.rolling:
            if rx is None or ry is None or e_eff is None:
                raise ParameterError("RaceContact: rolling_resistance needs rx, ry [m] and "
                                     "e_eff [Pa]")
            if not lubricant.is_viscous:
                raise ParameterError(f"RaceContact: rolling_resistance needs a viscous "
                                     f"lubricant, got {lubricant.describe()}")
            self.Rx = Parameter(rx, "m", "reduced radius along rolling", low=0.0,
                                low_inclusive=False)
            self.Ry = Parameter(ry, "m", "reduced radius across rolling", low=0.0,
                                low_inclusive=False)
            self.E_eff = Parameter(e_eff, "Pa", "effective modulus E'", low=0.0,
                                   low_inclusive=False)
            self.eta = Parameter(float(lubricant.dynamic_viscosity()), "Pa.s",
                                 "lubricant viscosity at the inlet", low=0.0)
            self.alpha_p = Parameter(float(lubricant.pressure_viscosity()), "1/Pa",
                                     "pressure-viscosity coefficient", low=0.0)
            self.F_rr = Variable(unit="N", description="rolling resistance on the ball along "
                                                       "the rolling direction")
            self.P_roll = Variable(unit="W", description="rolling resistance loss")
        self.ball = BallFrame()
        self.ring = RingFrame()
        self.flange = Flange()
        self.Q = Variable(unit="N", description="normal contact load")
        self.delta = Variable(unit="m", description="elastic approach")
        self.alpha = Variable(unit="rad", description="contact angle")
        self.F_roll = Variable(unit="N", description="traction on the ball along rolling")
        self.F_axial = Variable(unit="N", description="traction on the ball along the major axis")
        self.u_entrain = Variable(unit="m/s", description="entrainment speed")
        self.slip = Variable(unit="m/s", description="sliding speed at the centre along rolling")

    def _ring_motion(self):
        g = self.ring
        if not self.moving:
            return (0.0, 0.0, 0.0), 0.0
        return (der(g.x), der(g.y), der(g.z)), der(self.flange.phi)

    def equations(self):
        b, g = self.ball, self.ring
        e_r, e_t, e_z = azimuth_frame(b.theta)
        p_b = scale(b.r, e_r)
        p_b = (p_b[0], p_b[1], b.z)
        v_b = add(scale(b.vr, e_r), scale(b.r * b.w_orbit, e_t), scale(b.vz, e_z))
        w_b = add(scale(b.wr, e_r), scale(b.wt, e_t), scale(b.wz, e_z))
        c = (g.x, g.y, g.z)
        v_c, w_ring = self._ring_motion()
        delta, n, ep = groove_contact(p_b, g.displacement(), self.rho, self.f, self.Dw)
        e_roll = cross(e_z, ep)
        e_a = cross(n, e_roll)
        d_delta = dot(n, sub(v_b, v_c))
        q_el = contact_load(self.K, self.delta, smooth=self.smooth)
        k_lin = contact_stiffness(self.K, self.delta, smooth=self.smooth)
        q = op.smooth_max0(q_el * (1.0 + self.c_d * d_delta) + self.beta * k_lin * d_delta,
                           _Q_SMOOTH)
        radius = 2.0 * self.f * self.Dw / (2.0 * self.f + 1.0)
        half = 0.5 * self.Dw

        def offset(x) -> Vec:
            return add(scale(half - x * x / (2.0 * radius), n), scale(x, e_a))

        def sliding(x):
            r_s = offset(x)
            v_ball = add(v_b, cross(w_b, r_s))
            v_race = add(v_c, cross((0.0, 0.0, w_ring), sub(add(p_b, r_s), c)))
            du = sub(v_ball, v_race)
            return dot(du, e_roll), dot(du, e_a)

        def traction(s):
            return self.mu_scale * self.lubricant.traction_coefficient(s)

        a = self.a1 * op.power(q_el + 1e-9, 1.0 / 3.0)
        tr = slice_traction(q_el, a, sliding, traction, n=self.n_slices)
        force = scale(-q, n)
        moment = (0.0, 0.0, 0.0)
        for x, fr, fa in zip(tr.positions, tr.forces_r, tr.forces_t, strict=True):
            f_s = add(scale(fr, e_roll), scale(fa, e_a))
            force = add(force, f_s)
            moment = add(moment, cross(offset(x), f_s))
        # reaction on the ring about its centre: sum of (p_b + r_s - c) x (-f_s)
        p_contact = add(p_b, scale(half, n))
        f_ring = scale(-1.0, force)
        m_ring = sub(cross(sub(p_b, c), f_ring), moment)
        # entrainment: surface speeds relative to the contact point (which orbits with the ball)
        r0 = scale(half, n)
        v_cp = cross((0.0, 0.0, b.w_orbit), p_contact)
        u_ball = dot(sub(add(v_b, cross(w_b, r0)), v_cp), e_roll)
        u_race = dot(sub(add(v_c, cross((0.0, 0.0, w_ring), sub(p_contact, c))), v_cp), e_roll)
        slip0 = sliding(0.0)[0]
        eqs = []
        if self.rolling:
            # ring material at the ball centre: the pair (force at the ball centre, reaction at
            # the contact plus the couple of the shifted pressure) acts on the ring as if at p_b
            v_ring_b = add(v_c, cross((0.0, 0.0, w_ring), sub(p_b, c)))
            v_rel = dot(sub(v_b, v_ring_b), e_roll)
            f_r = rolling_resistance(q_el + 1e-9, self.u_entrain, self.Rx, self.Ry, self.E_eff,
                                     self.eta, self.alpha_p)
            f_rr = -f_r * v_rel / op.smooth_abs(v_rel, _V_ROLL_REG)
            force = add(force, scale(f_rr, e_roll))
            f_ring = scale(-1.0, force)
            m_ring = sub(cross(sub(p_b, c), f_ring), moment)
            eqs += [self.F_rr == f_rr, self.P_roll == -f_rr * v_rel]
        return eqs + [
            self.delta == delta,
            self.Q == q,
            self.alpha == op.atan2(n[2], op.fabs(dot(n, ep)) + 1e-12),
            self.F_roll == tr.force_r,
            self.F_axial == tr.force_t,
            self.u_entrain == 0.5 * op.smooth_abs(u_ball + u_race, 1e-9),
            self.slip == slip0,
            # flows: force on this element from the ball / ring = minus what it exerts
            b.Fr == -dot(force, e_r), b.Ft == -dot(force, e_t), b.Fz == -dot(force, e_z),
            b.Mr == -dot(moment, e_r), b.Mt == -dot(moment, e_t), b.Mz == -dot(moment, e_z),
            g.Fx == -f_ring[0], g.Fy == -f_ring[1], g.Fz == -f_ring[2],
            g.Mx == -m_ring[0], g.My == -m_ring[1],
            self.flange.tau == -m_ring[2],
        ]
