"""Torque level: the bearing as a friction torque between the shaft and the housing.

No roller is resolved: a :class:`~bearingsim.components.bearing_torque.PalmgrenBearing` or
:class:`~bearingsim.components.bearing_torque.SkfBearing` with the roller geometry (the
rolling-element seam picks the cylindrical-roller rows of the friction tables: Palmgren's f0,
f1 = 0.0003, P1 = Fr; SKF's R1, S1, S2 of the bearing's series, Kz = 5.1, mu_EHL = 0.02)
between a shaft turned at the input speed ``drive.w_in`` and a fixed housing, loaded by the
inputs ``bearing.Fr``, ``bearing.Fa``.
"""

from __future__ import annotations

from bearingsim.assemblies.cylindrical_roller.options import CylindricalRollerOptions
from bearingsim.components.bearing_torque import PalmgrenBearing, SkfBearing
from bearingsim.components.rotational import Fixed, SpeedSource
from bearingsim.language import Assembly, connect

__all__ = ["CylindricalRollerTorque"]


class CylindricalRollerTorque(Assembly):
    """Friction torque of a cylindrical roller bearing on a speed-driven shaft.

    Parameters
    ----------
    options : CylindricalRollerOptions
        ``friction_model`` and ``lubricant`` are used.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Attributes
    ----------
    options : CylindricalRollerOptions
    geometry : RollerBearingGeometry
    """

    def __init__(self, options: CylindricalRollerOptions, name="bearing"):
        super().__init__(name)
        self.options = options
        self.geometry = options.geometry
        model = PalmgrenBearing if options.friction_model == "palmgren" else SkfBearing
        self.bearing = model(options.geometry, options.lubricant)
        self.drive = SpeedSource()
        self.housing = Fixed()
        connect(self.drive.flange, self.bearing.inner)
        connect(self.housing.flange, self.bearing.outer)
