"""A ball of a rolling bearing: orbital motion, three-component spin, radial and axial position."""

from __future__ import annotations

from bearingsim.components.connectors import BallFrame
from bearingsim.components.dynamic.rigid_body import PartialRigidBody
from bearingsim.language import Parameter, Variable, der
from bearingsim.physics.bearing_design import POSITION_REGULARIZATION

__all__ = ["Ball"]

VELOCITY_REGULARIZATION = 1e-2
"""Damping coefficient [N s/m] of a quasi-static ball's radial and axial motion.

A massless ball's velocity follows from its force balance through the contact damping; a ball
out of contact with both races has none, and this weak damper (the regularizing spring times
1e-5 s, the film damping time constant) keeps that balance solvable. It moves a free ball at
about 30 m/s under a 0.3 N centrifugal force, so it reaches a race within nanoseconds.
"""

MICRON = 1e-6
"""Positions are states in micrometres (so that one absolute tolerance suits positions and
speeds)."""
_FORCE_SCALE = 1e-3
"""Scale of the quasi-static force balances [1/N]: the assembler's Newton tolerance (1e-12)
then means 1e-9 N."""


class Ball(PartialRigidBody):
    """Ball with orbital and spin dynamics; radial/axial position quasi-static or with mass.

    Equations in the ball's azimuthal frame (Gupta, *Advanced Dynamics of Rolling Elements*,
    ch. 4; Harris & Kotzalas, *Advanced Concepts*, ch. "Ball and roller dynamics"), with
    ``F, M`` the sums of the connected contact, cage and drag forces and moments:

    * orbit: ``der(theta) = w_orbit``, ``m (r der(w_orbit) + 2 vr w_orbit) = Ft``;
    * spin (Euler's equations of a sphere written in the frame turning at ``w_orbit``):
      ``J (der(wr) - w_orbit wt) = Mr``, ``J (der(wt) + w_orbit wr) = Mt``, ``J der(wz) = Mz``;
    * position, ``massive=True``: ``m (der(vr) - r w_orbit^2) = Fr``, ``m der(vz) = Fz``;
      ``massive=False`` (quasi-static, as in the study, docs/studies.md, section C): no radial and
      axial inertia, the force balances ``Fr + m r w_orbit^2 = 0`` and ``Fz = 0`` hold at every
      instant (the centrifugal force included). The contact forces depend on the ball's
      velocity through their damping, so the balances are solved (by Newton with a line
      search, nonlinear blocks of the assembler) for ``vr = der(r)``, ``vz = der(z)``: the
      positions follow the balance through the contacts' damping. Setting ``vr = vz = 0``
      instead (balance in the positions alone) drops the contact damping from the ring's
      motion; the ring's axial mode then grows until the equilibrium is lost (measured: the
      ring drifted 26 um axially within 20 ms of the validation start-up of docs/studies.md,
      section C). A weak spring :data:`POSITION_REGULARIZATION` towards ``(r, z) = (pitch_radius,
      0)`` and a weak damper :data:`VELOCITY_REGULARIZATION` keep balls that touch neither race
      determinate.

    Gravity is neglected.

    Parameters
    ----------
    mass : float
        Ball mass m [kg], > 0.
    inertia : float
        Moment of inertia J [kg m^2], > 0 (``m Dw^2 / 10`` for a solid sphere).
    r0 : float
        Initial (or guessed, quasi-static) radial position [m], > 0.
    pitch_radius : float
        dm / 2 [m], > 0 (centre of the regularizing spring of quasi-static balls).
    theta0 : float
        Initial orbital angle [rad].
    z0 : float
        Initial (or guessed) axial position [m].
    w_orbit0 : float
        Initial orbital speed [rad/s].
    spin0 : (float, float, float)
        Initial angular velocity (wr, wt, wz) [rad/s].
    massive : bool
        Radial and axial motion with inertia (True) or quasi-static (False).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    frame : BallFrame

    Variables
    ---------
    theta [rad], w_orbit [rad/s], wr, wt, wz [rad/s], r [m], z [m], vr, vz [m/s];
    dr, dz [um] (the position states: offset from the pitch circle, axial position)
    """

    def __init__(self, mass: float, inertia: float, r0: float, pitch_radius: float,
                 theta0: float = 0.0, z0: float = 0.0, w_orbit0: float = 0.0, spin0=(0.0, 0.0, 0.0),
                 massive: bool = False, name=None):
        super().__init__(mass, inertia, "ball", "moment of inertia", name)
        self.massive = bool(massive)
        self.pitch_radius = Parameter(pitch_radius, "m", "pitch radius", low=0.0,
                                      low_inclusive=False)
        self.frame = BallFrame()
        self.theta = Variable(theta0, "rad", "orbital angle")
        self.w_orbit = Variable(w_orbit0, "rad/s", "orbital speed")
        self.wr = Variable(spin0[0], "rad/s", "angular velocity along e_r")
        self.wt = Variable(spin0[1], "rad/s", "angular velocity along e_t")
        self.wz = Variable(spin0[2], "rad/s", "angular velocity along e_z")
        self.needs_line_search = not self.massive
        self.dr = Variable((r0 - pitch_radius) / MICRON, "um",
                           "radial offset of the ball centre from the pitch circle")
        self.dz = Variable(z0 / MICRON, "um", "axial position of the ball centre")
        self.r = Variable(unit="m", description="radial position of the ball centre")
        self.z = Variable(unit="m", description="axial position of the ball centre")
        self.vr = Variable(0.0, "m/s", "radial velocity", fixed=self.massive)
        self.vz = Variable(0.0, "m/s", "axial velocity", fixed=self.massive)

    def equations(self):
        f, m, w = self.frame, self.m, self.w_orbit
        eqs = [
            f.r == self.r, f.z == self.z, f.theta == self.theta, f.vr == self.vr,
            f.vz == self.vz, f.w_orbit == w, f.wr == self.wr, f.wt == self.wt, f.wz == self.wz,
            self.r == self.pitch_radius + MICRON * self.dr,
            self.z == MICRON * self.dz,
            der(self.theta) == w,
            m * (self.r * der(w) + 2.0 * self.vr * w) == f.Ft,
            self.J * (der(self.wr) - w * self.wt) == f.Mr,
            self.J * (der(self.wt) + w * self.wr) == f.Mt,
            self.J * der(self.wz) == f.Mz,
        ]
        eqs += [MICRON * der(self.dr) == self.vr, MICRON * der(self.dz) == self.vz]
        if self.massive:
            eqs += [
                m * (der(self.vr) - self.r * w * w) == f.Fr,
                m * der(self.vz) == f.Fz,
            ]
        else:
            eqs += [
                _FORCE_SCALE * (f.Fr + m * self.r * w * w
                                - POSITION_REGULARIZATION * MICRON * self.dr
                                - VELOCITY_REGULARIZATION * self.vr) == 0.0,
                _FORCE_SCALE * (f.Fz - POSITION_REGULARIZATION * self.z
                                - VELOCITY_REGULARIZATION * self.vz) == 0.0,
            ]
        return eqs
