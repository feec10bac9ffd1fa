"""Assemblies of real products built from components."""

from bearingsim.assemblies.double_layer import DoubleLayerBearing, double_layer_bearing
from bearingsim.assemblies.motor_drive import MotorDrive, motor_drive

__all__ = ["DoubleLayerBearing", "MotorDrive", "double_layer_bearing", "motor_drive"]
