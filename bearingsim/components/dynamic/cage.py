"""Cage body, ball-pocket contact and outer-ring land guidance of a dynamic ball bearing."""

from __future__ import annotations

import math

from bearingsim import symbolic as op
from bearingsim.components.connectors import BallFrame, CageFrame, Flange
from bearingsim.components.dynamic.ball import MICRON
from bearingsim.components.dynamic.rigid_body import PartialRigidBody
from bearingsim.language import Component, Parameter, Variable, der
from bearingsim.physics.cage import (
    SIGMA_BALL,
    SIGMA_CAGE,
    ball_pocket_force,
    cage_guidance_force,
    pocket_gap,
)
from bearingsim.physics.traction import regularized_coulomb
from bearingsim.vectors import add, azimuth_frame, cross, dot, scale, sub

__all__ = ["Cage", "PocketContact", "LandGuidance"]

SIGMA = math.hypot(SIGMA_BALL, SIGMA_CAGE)
"""Composite roughness of ball and pocket [m]."""


class Cage(PartialRigidBody):
    """Rigid cage moving in its plane: translation x, y and rotation phi about the axis z.

    ``m der(vx) = Fx``, ``m der(vy) = Fy``, ``J der(w) = Mz`` with the forces of the pockets and
    the guiding land (Gupta, *Advanced Dynamics of Rolling Elements*, ch. 5). Gravity is
    neglected.

    Parameters
    ----------
    mass : float
        [kg], > 0.
    inertia : float
        Polar moment of inertia [kg m^2], > 0.
    w0 : float
        Initial angular speed [rad/s].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    frame : CageFrame

    Variables
    ---------
    x, y [m] (states x_um, y_um [um]), vx, vy [m/s], phi [rad], w [rad/s]
    """

    def __init__(self, mass: float, inertia: float, w0: float = 0.0, name=None):
        super().__init__(mass, inertia, "cage", "polar inertia", name)
        self.frame = CageFrame()
        self.x_um = Variable(0.0, "um", "cage centre x (state)")
        self.y_um = Variable(0.0, "um", "cage centre y (state)")
        self.x = Variable(unit="m", description="cage centre x")
        self.y = Variable(unit="m", description="cage centre y")
        self.vx = Variable(0.0, "m/s", "cage velocity x")
        self.vy = Variable(0.0, "m/s", "cage velocity y")
        self.phi = Variable(0.0, "rad", "cage angle")
        self.w = Variable(w0, "rad/s", "cage angular speed")

    def equations(self):
        f = self.frame
        return [
            f.x == self.x, f.y == self.y, f.phi == self.phi,
            self.x == MICRON * self.x_um, self.y == MICRON * self.y_um,
            MICRON * der(self.x_um) == self.vx, MICRON * der(self.y_um) == self.vy,
            der(self.phi) == self.w,
            self.m * der(self.vx) == f.Fx,
            self.m * der(self.vy) == f.Fy,
            self.J * der(self.w) == f.Mz,
        ]


class PocketContact(Component):
    """Ball in a stadium-shaped pocket: Hertz contact with Coulomb friction or short-bearing film.

    The pocket ``j`` sits at ``phi_p = phi_cage + phase`` (``phase = 2 pi j / Z``, a parameter so
    that every pocket is the same function of its own parameters) on the pitch circle of the cage,
    its axis along ``e_r(phi_p)``; the stadium (straight length ``Sp`` along the bearing axis,
    end radius ``Rp``) lies in the plane ``(e_z, e_t(phi_p))``. Forces from
    :func:`~bearingsim.physics.cage.ball_pocket_force` (docs/studies.md, section C; Gupta ch. 5):
    Hertz + Coulomb when the gap is below the composite roughness, the Ocvirk film otherwise,
    blended smoothly. Its reaction acts on the cage at the contact point.

    Parameters
    ----------
    index : int
        Pocket number j [-].
    count : int
        Number of pockets Z [-].
    pitch_radius : float
        Radius of the pocket centres [m].
    ball_radius, pocket_radius, straight : float
        Rb, Rp, Sp [m].
    web : float
        Pocket length along its axis (film width) [m].
    k_hertz : float
        Ball-pocket Hertz constant [N/m^1.5].
    mu : float
        Ball-pocket Coulomb coefficient [-].
    eta : float
        Dynamic viscosity of the lubricant in the pocket [Pa s].
    damping : float
        Hunt-Crossley coefficient of the Hertz part [s/m], >= 0: the contact force grows by
        ``c_d`` times the approach speed times the Hertz force (dissipation of dry impacts).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    ball : BallFrame
    cage : CageFrame

    Variables
    ---------
    F [N] normal (collision) force, gap [m], F_t [N] tangential (orbital-direction) force on
    the ball
    """

    def __init__(self, index: int, count: int, pitch_radius: float, ball_radius: float,
                 pocket_radius: float, straight: float, web: float, k_hertz: float,
                 mu: float, eta: float, damping: float = 0.0, name=None):
        super().__init__(name)
        self.phase = Parameter(2.0 * math.pi * index / count, "rad",
                               "angular position of the pocket on the cage", low=0.0,
                               high=2.0 * math.pi)
        self.Rb, self.Rp, self.Sp, self.web = ball_radius, pocket_radius, straight, web
        self.pitch = Parameter(pitch_radius, "m", "pocket centre radius", low=0.0,
                               low_inclusive=False)
        self.K = Parameter(k_hertz, "N/m^1.5", "ball-pocket Hertz constant", low=0.0)
        self.mu = Parameter(mu, "1", "ball-pocket friction coefficient", low=0.0, high=2.0)
        self.eta = Parameter(eta, "Pa.s", "lubricant viscosity in the pocket", low=0.0)
        self.c_d = Parameter(damping, "s/m", "Hunt-Crossley damping coefficient", low=0.0)
        self.ball = BallFrame()
        self.cage = CageFrame()
        self.F = Variable(unit="N", description="ball-pocket normal (collision) force")
        self.gap = Variable(unit="m", description="ball-pocket gap")
        self.F_t = Variable(unit="N", description="pocket force on the ball along its orbit")

    def equations(self):
        b, cg = self.ball, self.cage
        e_r, e_t, e_z = azimuth_frame(b.theta)
        p_b = add(scale(b.r, e_r), scale(b.z, e_z))
        v_b = add(scale(b.vr, e_r), scale(b.r * b.w_orbit, e_t), scale(b.vz, e_z))
        w_b = add(scale(b.wr, e_r), scale(b.wt, e_t), scale(b.wz, e_z))
        c = (cg.x, cg.y, 0.0)
        v_c = (der(cg.x), der(cg.y), 0.0)
        w_c = der(cg.phi)
        p_r, p_t, _ = azimuth_frame(cg.phi + self.phase)
        d = sub(p_b, add(c, scale(self.pitch, p_r)))
        x, y = dot(d, e_z), dot(d, p_t)

        def cage_velocity(point):
            return add(v_c, cross((0.0, 0.0, w_c), sub(point, c)))

        v_rel = sub(v_b, cage_velocity(p_b))
        geo = pocket_gap(x, y, self.Rb, self.Rp, self.Sp)
        n3 = add(scale(geo.nx, e_z), scale(geo.ny, p_t))
        t3 = add(scale(-geo.ny, e_z), scale(geo.nx, p_t))
        arm = scale(self.Rb, n3)
        slide = sub(add(v_b, cross(w_b, arm)), cage_velocity(add(p_b, arm)))
        pf = ball_pocket_force(
            x, y, dot(v_rel, e_z), dot(v_rel, p_t), dot(slide, t3), dot(slide, p_r),
            dot(sub(w_b, (0.0, 0.0, w_c)), p_r),
            Rb=self.Rb, Rp=self.Rp, Sp=self.Sp, width=self.web, K=self.K, mu=self.mu,
            eta=self.eta,
        )
        overlap = op.smooth_max0(-geo.gap, 1e-3 * SIGMA)
        f_damp = (pf.contact_weight * self.K * overlap * op.sqrt(overlap) * self.c_d
                  * dot(v_rel, n3))
        force = add(scale(pf.fx, e_z), scale(pf.fy, p_t), scale(pf.fz, p_r), scale(-f_damp, n3))
        moment = cross(arm, force)
        m_cage = cross(sub(add(p_b, arm), c), scale(-1.0, force))[2]
        return [
            self.F == pf.normal + f_damp,
            self.gap == geo.gap,
            self.F_t == dot(force, e_t),
            b.Fr == -dot(force, e_r), b.Ft == -dot(force, e_t), b.Fz == -dot(force, e_z),
            b.Mr == -dot(moment, e_r), b.Mt == -dot(moment, e_t), b.Mz == -dot(moment, e_z),
            cg.Fx == force[0], cg.Fy == force[1], cg.Mz == -m_cage,
        ]


class LandGuidance(Component):
    """Outer-ring land guidance of the cage: short journal-bearing film plus a land contact.

    Film forces and drag moment from :func:`~bearingsim.physics.cage.cage_guidance_force`
    (docs/studies.md, section C; Gupta ch. 5), all proportional to the speeds. Where the rail
    reaches the land (eccentricity beyond ``Cg``) a Hertz-type penalty ``K <e - Cg>^1.5`` pushes
    the cage back, with regularized Coulomb friction ``mu`` on the land; this carries the cage
    when the lubricant is dry (no film).

    Parameters
    ----------
    radius, width, clearance : float
        Land radius Rg, width Bg, radial clearance Cg [m].
    eta : float
        Viscosity [Pa s], >= 0.
    k_land : float
        Land contact constant [N/m^1.5].
    mu : float
        Land friction coefficient [-].
    damping : float
        Hunt-Crossley coefficient of the land contact [s/m].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    cage : CageFrame
    ring : Flange (rotation of the guiding ring; connect it to a fixed flange for a fixed ring)

    Variables
    ---------
    eps [-] eccentricity ratio, M [N m] drag moment on the cage
    """

    def __init__(self, radius: float, width: float, clearance: float, eta: float,
                 k_land: float, mu: float, damping: float = 0.0, name=None):
        super().__init__(name)
        self.Rg, self.Bg, self.Cg = radius, width, clearance
        self.eta = Parameter(eta, "Pa.s", "lubricant viscosity at the land", low=0.0)
        self.K = Parameter(k_land, "N/m^1.5", "land contact constant", low=0.0)
        self.mu = Parameter(mu, "1", "land friction coefficient", low=0.0, high=2.0)
        self.c_d = Parameter(damping, "s/m", "Hunt-Crossley damping coefficient", low=0.0)
        self.cage = CageFrame()
        self.ring = Flange()
        self.eps = Variable(unit="1", description="cage eccentricity ratio")
        self.M = Variable(unit="N.m", description="guidance moment on the cage")

    def equations(self):
        cg = self.cage
        w_ring = der(self.ring.phi)
        w = der(cg.phi) - w_ring  # cage speed relative to the guiding ring
        film = cage_guidance_force(cg.x, cg.y, der(cg.x), der(cg.y), der(cg.phi), w_ring,
                                   Rg=self.Rg, Bg=self.Bg, Cg=self.Cg, eta=self.eta)
        e = op.sqrt(cg.x * cg.x + cg.y * cg.y + 1e-18)
        over = op.smooth_max0(e - self.Cg, 1e-8)
        e_rate = (cg.x * der(cg.x) + cg.y * der(cg.y)) / e
        fn = self.K * over * op.sqrt(over) * op.smooth_max0(1.0 + self.c_d * e_rate, 1e-3)
        m_fric = -regularized_coulomb(self.Rg * w, 1.0, 1e-3) * self.mu * fn * self.Rg
        fx = film.fx - fn * cg.x / e
        fy = film.fy - fn * cg.y / e
        return [
            self.eps == e / self.Cg,
            self.M == film.moment + m_fric,
            cg.Fx == -fx, cg.Fy == -fy, cg.Mz == -(film.moment + m_fric),
            self.ring.tau == film.moment + m_fric,
        ]
