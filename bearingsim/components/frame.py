"""The 5-DOF ring frame: translations and tilts of a rigid ring or shaft section.

Coordinates: z is the bearing axis; x, y are radial. A ring frame carries the displacement of
the body's reference point (three translations, small tilts about x and y; rotation about z is
the rotational ``Flange``'s business) and, as flows, the forces and moments acting on the body
that owns the connector.
"""

from __future__ import annotations

from bearingsim.language import Connector, Flow, Potential

__all__ = ["RingFrame", "FRAME_POTENTIALS", "FRAME_FLOWS"]

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

    x = Potential(unit="m", description="radial displacement x")
    y = Potential(unit="m", description="radial displacement y")
    z = Potential(unit="m", description="axial displacement")
    tx = Potential(unit="rad", description="tilt about x")
    ty = Potential(unit="rad", description="tilt about y")
    Fx = Flow(unit="N", description="force x on the body")
    Fy = Flow(unit="N", description="force y on the body")
    Fz = Flow(unit="N", description="axial force on the body")
    Mx = Flow(unit="N.m", description="moment about x on the body")
    My = Flow(unit="N.m", description="moment about y on the body")

    def displacement(self):
        """(x, y, z, tx, ty) symbols."""
        return [getattr(self, k) for k in FRAME_POTENTIALS]

    def loads(self):
        """(Fx, Fy, Fz, Mx, My) symbols."""
        return [getattr(self, k) for k in FRAME_FLOWS]
