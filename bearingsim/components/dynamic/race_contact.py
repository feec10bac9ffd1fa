"""Ball-raceway contact: Hertz normal load from the exact ring-ball geometry and slice traction."""

from __future__ import annotations

from bearingsim import _ops as op
from bearingsim.components.dynamic.frames import (
    BallFrame,
    Vec,
    add,
    azimuth_frame,
    cross,
    dot,
    groove_contact,
    scale,
    sub,
)
from bearingsim.components.frame import RingFrame
from bearingsim.components.rotational import Flange
from bearingsim.errors import ParameterError
from bearingsim.language import Component, Parameter, Variable, der
from bearingsim.physics.hertz import contact_load, contact_stiffness
from bearingsim.physics.lubricant import Lubricant
from bearingsim.physics.traction import slice_traction

__all__ = ["RaceContact"]

_Q_SMOOTH = 1e-4
"""Width [N] of the smooth non-negative limit of the damped contact load (offset 5e-5 N)."""


class RaceContact(Component):
    """Contact of one ball with the inner or outer raceway of a (possibly displaced) ring.

    Geometry: approach ``delta`` and normal ``n`` (ball centre to contact) from the exact
    rigid-ring kinematics of :func:`~bearingsim.components.dynamic.frames.groove_contact`
    (the groove centre moves with the ring's 5-DOF displacement).

    Normal load: ``Q = < K <delta>^1.5 (1 + c_d d(delta)/dt) + beta k(delta) d(delta)/dt >``:
    Hertz with the smooth ramp of :func:`~bearingsim.physics.hertz.contact_load`, Hunt and
    Crossley (1975) material damping ``c_d`` and the squeeze damping of the lubricant film,
    proportional to the tangent contact stiffness ``k = dQ/d delta``
    (:func:`~bearingsim.physics.hertz.contact_stiffness`) with the time constant ``beta``; the
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
        ``2 n + 1`` slices.
    smooth : float
        Width of the smooth contact ramp [m].
    traction_scale : float
        Multiplier of the traction [-] (0 switches traction off).

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
                 smooth: float = 2e-8,
                 traction_scale: float = 1.0, name=None):
        super().__init__(name)
        if race not in ("inner", "outer"):
            raise ParameterError(f"RaceContact: race must be 'inner' or 'outer', got {race!r}")
        if not isinstance(lubricant, Lubricant):
            raise ParameterError(f"RaceContact: lubricant must be a Lubricant, got "
                                 f"{type(lubricant).__name__}")
        self.race, self.moving, self.n_slices = race, bool(moving), int(n_slices)
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
        return [
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
