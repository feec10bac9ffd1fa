"""A motor driving a shaft that runs in a bearing assembly, with an optional load torque."""

from __future__ import annotations

from collections.abc import Callable

from bearingsim.assemblies.double_layer import DoubleLayerBearing, double_layer_bearing
from bearingsim.components.motor import DCMotorDrive, PMSMDrive
from bearingsim.components.rotational import Inertia, TorqueSource
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Component, connect

__all__ = ["MotorDrive", "motor_drive"]


class MotorDrive(Assembly):
    """Speed-controlled motor -> shaft inertia -> bearing; a load torque acts on the shaft.

    Parameters
    ----------
    bearing : Component, optional
        A bearing assembly with a ``shaft`` flange (default: a torque-level 61905/61907
        double-layer bearing with ``drive="flange"``).
    motor : {"dc", "pmsm"}
        Motor type (each with its PI speed control).
    speed_ref : callable or float or None
        Speed reference [rad/s]: ``f(t)``, constant, or None for an input ``motor.w_ref``.
    load_torque : callable or float or None
        Load torque on the shaft [N m] (positive drives the shaft): ``f(t)``, constant, or None
        for an input ``load.tau_in``.
    shaft_inertia : float
        Shaft (and spindle) inertia [kg m^2].
    motor_options : dict, optional
        Passed to the motor drive (gains, motor constants).
    """

    def __init__(self, bearing: Component | None = None, motor: str = "dc",
                 speed_ref: Callable | float | None = None,
                 load_torque: Callable | float | None = 0.0, shaft_inertia: float = 1e-3,
                 motor_options: dict | None = None, name="drive"):
        super().__init__(name)
        drives = {"dc": DCMotorDrive, "pmsm": PMSMDrive}
        if motor not in drives:
            raise ParameterError(f"motor_drive: motor must be one of {', '.join(drives)}, got "
                                 f"{motor!r}")
        self.motor = drives[motor](speed_ref, **(motor_options or {}))
        self.shaft = Inertia(shaft_inertia)
        self.bearing = bearing if bearing is not None else double_layer_bearing(drive="flange")
        self.load = TorqueSource(load_torque)
        connect(self.motor.flange, self.shaft.flange_a)
        connect(self.shaft.flange_b, self.bearing.shaft, self.load.flange)


def motor_drive(bearing: DoubleLayerBearing | None = None, **kwargs) -> MotorDrive:
    """Build a :class:`MotorDrive`."""
    return MotorDrive(bearing, **kwargs)
