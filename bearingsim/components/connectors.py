"""Connectors: what components exchange at their ports.

Each connector carries potential variables (equal at a connection) and flow variables (summing to
zero at a connection; positive into the owning component). Domains:

* :class:`Flange`: 1-D rotation about a fixed axis (angle, torque);
* :class:`RingFrame`: the 5-DOF frame of a ring or shaft section (three translations, two tilts;
  three forces, two moments); z is the bearing axis;
* :class:`BallFrame`: a ball centre in its azimuthal frame (position, orbit, spin; force and
  moment on the ball);
* :class:`CageFrame`: the cage's planar position and rotation (force and moment on the cage).
"""

from __future__ import annotations

from bearingsim.language import Connector, Flow, Potential

__all__ = ["BallFrame", "CageFrame", "FRAME_FLOWS", "FRAME_POTENTIALS", "Flange", "RingFrame"]


class Flange(Connector):
    """Rotational flange.

    Connectors
    ----------
    phi : Potential [rad]
        Absolute rotation angle.
    tau : Flow [N m]
        Cut torque into the owning component.
    """

    phi = Potential(unit="rad", description="absolute rotation angle")
    tau = Flow(unit="N.m", description="cut torque acting on the component")


FRAME_POTENTIALS = ("x", "y", "z", "tx", "ty")
FRAME_FLOWS = ("Fx", "Fy", "Fz", "Mx", "My")


class RingFrame(Connector):
    """5-DOF ring frame connector.

    Connectors
    ----------
    x, y, z : Potential [m]
        Displacement of the reference point (z axial).
    tx, ty : Potential [rad]
        Small tilts about the x and y axes.
    Fx, Fy, Fz : Flow [N]
        Force acting on the owning body.
    Mx, My : Flow [N m]
        Moment about x and y acting on the owning body.
    """

    x, y, z = Potential.each("m", "radial displacement x", "radial displacement y",
                             "axial displacement")
    tx, ty = Potential.each("rad", "tilt about x", "tilt about y")
    Fx, Fy, Fz = Flow.each("N", "force x on the body", "force y on the body",
                           "axial force on the body")
    Mx, My = Flow.each("N.m", "moment about x on the body", "moment about y on the body")

    def displacement(self):
        """(x, y, z, tx, ty) symbols.

        Returns
        -------
        list
            The frame's potentials x, y, z [m], tx, ty [rad].
        """
        return [getattr(self, k) for k in FRAME_POTENTIALS]

    def loads(self):
        """(Fx, Fy, Fz, Mx, My) symbols.

        Returns
        -------
        list
            The frame's flows Fx, Fy, Fz [N], Mx, My [N m].
        """
        return [getattr(self, k) for k in FRAME_FLOWS]


class BallFrame(Connector):
    """Position, velocity and spin of a ball centre; force and moment on the ball.

    Connectors
    ----------
    r, z : Potential [m]
        Radial and axial position of the ball centre.
    theta : Potential [rad]
        Orbital (azimuth) angle.
    vr, vz : Potential [m/s]
        Radial and axial velocity (zero for quasi-static balls).
    w_orbit : Potential [rad/s]
        Orbital speed ``d theta / dt``.
    wr, wt, wz : Potential [rad/s]
        Absolute angular velocity of the ball in its azimuthal frame.
    Fr, Ft, Fz : Flow [N]
        Force on the ball along ``e_r, e_t, e_z``.
    Mr, Mt, Mz : Flow [N m]
        Moment on the ball about its centre along ``e_r, e_t, e_z``.
    """

    r = Potential(unit="m", description="radial position of the ball centre")
    theta = Potential(unit="rad", description="orbital angle")
    z = Potential(unit="m", description="axial position of the ball centre")
    vr, vz = Potential.each("m/s", "radial velocity", "axial velocity")
    w_orbit, wr, wt, wz = Potential.each(
        "rad/s", "orbital speed", *(f"ball angular velocity along e_{a}" for a in "rtz"))
    Fr, Ft, Fz = Flow.each("N", *(f"force on the ball along e_{a}" for a in "rtz"))
    Mr, Mt, Mz = Flow.each("N.m", *(f"moment on the ball along e_{a}" for a in "rtz"))


class CageFrame(Connector):
    """Planar position and rotation of the cage; force and moment on the cage.

    Connectors
    ----------
    x, y : Potential [m]
        Cage centre.
    phi : Potential [rad]
        Cage rotation angle about z.
    Fx, Fy : Flow [N]
        Force on the cage.
    Mz : Flow [N m]
        Moment on the cage about its centre.
    """

    x, y = Potential.each("m", "cage centre x", "cage centre y")
    phi = Potential(unit="rad", description="cage angle")
    Fx, Fy = Flow.each("N", "force x on the cage", "force y on the cage")
    Mz = Flow(unit="N.m", description="moment about z on the cage")
