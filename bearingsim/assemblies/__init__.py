"""Assemblies of real products built from components."""

from bearingsim.assemblies.deep_groove import DeepGrooveBallBearing, deep_groove_ball_bearing
from bearingsim.assemblies.double_layer import DoubleLayerBearing, double_layer_bearing
from bearingsim.assemblies.duplex import DuplexPair, ShaftSpec, duplex_pair
from bearingsim.assemblies.motor_drive import MotorDrive, motor_drive

__all__ = [
    "DeepGrooveBallBearing",
    "DoubleLayerBearing",
    "DuplexPair",
    "MotorDrive",
    "ShaftSpec",
    "deep_groove_ball_bearing",
    "double_layer_bearing",
    "duplex_pair",
    "motor_drive",
]
