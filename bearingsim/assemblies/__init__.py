"""Assemblies of real products built from components.

Each assembly module declares its scene spec (``SCENE_SPEC``, a
:class:`~bearingsim.assemblies.spec.AssemblySpec`) beside its factory; :data:`SCENE_SPECS` lists
them in the order ``bearingsim list`` shows them, and :mod:`bearingsim.scenes` reads it.
"""

from bearingsim.assemblies.cylindrical_roller import SCENE_SPEC as _CYLINDRICAL_ROLLER_SPEC
from bearingsim.assemblies.cylindrical_roller import cylindrical_roller_bearing
from bearingsim.assemblies.cylindrical_roller.spindle import SPINDLE_SCENE_SPEC as _SPINDLE_SPEC
from bearingsim.assemblies.cylindrical_roller.spindle import Spindle, spindle
from bearingsim.assemblies.deep_groove import SCENE_SPEC as _DEEP_GROOVE_SPEC
from bearingsim.assemblies.deep_groove import DeepGrooveBallBearing, deep_groove_ball_bearing
from bearingsim.assemblies.double_layer import SCENE_SPEC as _DOUBLE_LAYER_SPEC
from bearingsim.assemblies.double_layer import DoubleLayerBearing, double_layer_bearing
from bearingsim.assemblies.duplex import SCENE_SPEC as _DUPLEX_SPEC
from bearingsim.assemblies.duplex import DuplexPair, ShaftSpec, duplex_pair
from bearingsim.assemblies.motor_drive import SCENE_SPEC as _MOTOR_DRIVE_SPEC
from bearingsim.assemblies.motor_drive import MotorDrive, motor_drive

SCENE_SPECS = (_DOUBLE_LAYER_SPEC, _MOTOR_DRIVE_SPEC, _DEEP_GROOVE_SPEC, _DUPLEX_SPEC,
               _CYLINDRICAL_ROLLER_SPEC, _SPINDLE_SPEC)
"""The built-in scene assemblies."""

__all__ = [
    "SCENE_SPECS",
    "DeepGrooveBallBearing",
    "DoubleLayerBearing",
    "DuplexPair",
    "MotorDrive",
    "ShaftSpec",
    "Spindle",
    "cylindrical_roller_bearing",
    "deep_groove_ball_bearing",
    "double_layer_bearing",
    "duplex_pair",
    "motor_drive",
    "spindle",
]
