"""The cylindrical roller bearing (NU type) as a product: options, levels, factory, scene face.

* :mod:`.options`: :class:`CylindricalRollerOptions`, every argument checked once;
* :mod:`.quasi_static`: the rollers' load distribution (sliced line contacts, clearance,
  misalignment) under a radial load;
* :mod:`.torque`: the friction torque (Palmgren, SKF) between shaft and housing;
* :mod:`.factory`: :func:`cylindrical_roller_bearing`;
* :mod:`.scene`: :data:`SCENE_SPEC` (arguments, post-processed roller load, pressure and life,
  the roller-load figure);
* :mod:`.spindle`: the NU bearing as the non-locating bearing of a spindle beside a duplex pair
  (its own scene assembly, ``spindle``).
"""

from bearingsim.assemblies.cylindrical_roller.factory import cylindrical_roller_bearing
from bearingsim.assemblies.cylindrical_roller.options import (
    FIDELITIES,
    FRICTION_MODELS,
    CylindricalRollerOptions,
)
from bearingsim.assemblies.cylindrical_roller.quasi_static import QuasiStaticCylindricalRoller
from bearingsim.assemblies.cylindrical_roller.scene import SCENE_SPEC
from bearingsim.assemblies.cylindrical_roller.torque import CylindricalRollerTorque

__all__ = ["FIDELITIES", "FRICTION_MODELS", "SCENE_SPEC", "CylindricalRollerOptions",
           "CylindricalRollerTorque", "QuasiStaticCylindricalRoller",
           "cylindrical_roller_bearing"]
