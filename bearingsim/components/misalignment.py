"""A ring frame held at an imposed tilt (misalignment) and axial position, free radially."""

from __future__ import annotations

from bearingsim.components.connectors import RingFrame
from bearingsim.language import Component, Parameter

__all__ = ["MisalignmentGuide"]

_MAX_TILT = 0.01  # rad: 10 mrad, far beyond what a cylindrical roller bearing tolerates


class MisalignmentGuide(Component):
    """Holds a ring frame at the tilt ``(tx, ty)`` and at ``z = 0``; takes no radial force.

    The shaft's other supports impose the misalignment and take the moment and the axial force
    (a non-locating roller bearing has no axial load path); the radial position stays free, so
    the bearing's own equilibrium sets it.

    Parameters
    ----------
    tx, ty : float
        Tilt of the frame about x and y [rad], in [-0.01, 0.01] (model parameters: changeable
        without recompiling).
    name : str
        Instance name (the prefix of its variables' dotted names).

    Parameters (model)
    ------------------
    tx, ty [rad].

    Connectors
    ----------
    frame : RingFrame
    """

    def __init__(self, tx: float = 0.0, ty: float = 0.0, name=None):
        super().__init__(name)
        self.tx = Parameter(tx, "rad", "imposed tilt about x (misalignment)", low=-_MAX_TILT,
                            high=_MAX_TILT)
        self.ty = Parameter(ty, "rad", "imposed tilt about y (misalignment)", low=-_MAX_TILT,
                            high=_MAX_TILT)
        self.frame = RingFrame()

    def equations(self):
        f = self.frame
        return [f.z == 0.0, f.tx == self.tx, f.ty == self.ty, f.Fx == 0.0, f.Fy == 0.0]
