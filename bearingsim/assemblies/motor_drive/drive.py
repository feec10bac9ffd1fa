"""The motor drive: a speed-controlled motor, a shaft inertia and a double-layer bearing
(:class:`MotorDrive`), and the motor side alone (:class:`MotorShaft`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from bearingsim.assemblies.double_layer import DoubleLayerBearing, double_layer_bearing
from bearingsim.assemblies.double_layer.speed import LIMIT_TEXT, shaft_speed_limit
from bearingsim.catalog.geometry import check_speed_limit, speed_input_bounds
from bearingsim.checks import checked
from bearingsim.components.motor import SpeedReference, speed_controlled_motor, speed_reference
from bearingsim.components.rotational import Inertia, TorqueSource
from bearingsim.language import Assembly, Component, Input, Variable, connect
from bearingsim.validation import check_quantity


class MotorDrive(Assembly):
    """Speed-controlled motor -> shaft inertia -> bearing; a load torque acts on the shaft.

    Parameters
    ----------
    bearing : Component, optional
        A bearing assembly with a ``shaft`` flange (default: a torque-level 61905/61907
        double-layer bearing with ``drive="flange"``).
    motor : {"dc", "pmsm"}
        Motor type (each with its PI speed control).
    speed_ref : callable or float or str or None
        Speed reference [rad/s]: ``f(t)``, a constant (a number with a unit such as
        ``"3000 rpm"`` is converted; finite, within the bearing's limiting speed), or None for
        an input ``motor.w_ref``.
    load_torque : callable or float or None
        Load torque on the shaft [N m] (positive drives the shaft): ``f(t)``, constant, or None
        for an input ``load.tau_in``.
    shaft_inertia : float
        Shaft (and spindle) inertia [kg m^2].
    motor_options : dict, optional
        Passed to the motor drive (gains, motor constants).
    name : str
        Instance name (the prefix of its variables' dotted names).
    """

    def __init__(self, bearing: Component | None = None, motor: str = "dc",
                 speed_ref: SpeedReference = None,
                 load_torque: Callable | float | None = 0.0, shaft_inertia: float = 1e-3,
                 motor_options: dict | None = None, name="drive"):
        super().__init__(name)
        speed_ref = speed_reference(speed_ref, "motor_drive")
        self.motor = speed_controlled_motor(motor, speed_ref, motor_options, "motor_drive")
        self.shaft = Inertia(_inertia(shaft_inertia, "motor_drive"))
        self.bearing = bearing if bearing is not None else double_layer_bearing(drive="flange")
        _limit_reference(self.motor, speed_ref, self.bearing)
        self.load = TorqueSource(load_torque)
        connect(self.motor.flange, self.shaft.flange_a)
        connect(self.shaft.flange_b, self.bearing.shaft, self.load.flange)


def _inertia(shaft_inertia: Any, where: str) -> float:
    """The shaft inertia [kg m^2], > 0: a number, or a number with a unit ("0.002 kg m^2")."""
    return float(check_quantity(shaft_inertia, "shaft_inertia", "kg.m2", 0.0,
                                low_inclusive=False, where=where))


def _limit_reference(motor: Component, speed_ref, bearing: Component) -> None:
    """Check the motor's speed reference against the bearing's limiting shaft speed
    (:func:`~bearingsim.assemblies.double_layer.shaft_speed_limit`; a bearing without
    ``geometries`` (inner, outer) is not checked): a constant now, the input ``w_ref`` (then
    required) by its bounds at every run."""
    geometries = getattr(bearing, "geometries", None)
    limit = shaft_speed_limit(*geometries) if geometries is not None else None
    if speed_ref is None:
        w_ref = motor.declarations["w_ref"]
        w_ref.required = True
        for key, value in speed_input_bounds(limit).items():
            setattr(w_ref, key, value)
    elif isinstance(speed_ref, (int, float)) and geometries is not None:
        check_speed_limit(speed_ref, limit, "motor_drive", LIMIT_TEXT.format(
            *(g.designation for g in geometries)))


@checked
def motor_drive(bearing: DoubleLayerBearing | None = None, **kwargs) -> MotorDrive:
    """Build a :class:`MotorDrive`.

    Parameters
    ----------
    bearing : DoubleLayerBearing, optional
        The bearing (default: see :class:`MotorDrive`).
    **kwargs
        Further keywords of :class:`MotorDrive`.

    Returns
    -------
    MotorDrive
        The drive assembly.
    """
    return MotorDrive(bearing, **kwargs)


class MotorShaft(Assembly):
    """A speed-controlled motor on a shaft inertia, loaded by the bearing's friction torque.

    Parameters
    ----------
    motor : {"dc", "pmsm"}
        :class:`~bearingsim.components.motor.DCMotorDrive` or
        :class:`~bearingsim.components.motor.PMSMDrive` (with their PI speed control).
    speed_ref : callable or float or str or None
        Speed reference [rad/s]: ``f(t)``, a constant (a number with a unit such as
        ``"3000 rpm"`` is converted), or None for the input ``w_ref``.
    shaft_inertia : float
        Shaft (and spindle) inertia [kg m^2], as in ``motor_drive``.
    motor_options : dict, optional
        Passed to the motor drive.
    name : str
        Instance name (the prefix of its variables' dotted names).

    Variables
    ---------
    w_ref (input) [rad/s], M_bearing (input) [N m]: friction torque of the bearing on the shaft
    (positive drives the shaft), w_shaft [rad/s]
    """

    def __init__(self, motor: str = "dc", speed_ref: SpeedReference = None,
                 shaft_inertia: float = 1e-3, motor_options: dict | None = None,
                 name="motor_shaft"):
        super().__init__(name)
        speed_ref = speed_reference(speed_ref, "MotorShaft")
        self.motor = speed_controlled_motor(motor, speed_ref, motor_options, "MotorShaft")
        self.shaft = Inertia(_inertia(shaft_inertia, "MotorShaft"))
        self.bearing_torque = TorqueSource(None)
        self.M_bearing = Input(0.0, "N.m", "friction torque of the bearing on the shaft")
        self.w_shaft = Variable(unit="rad/s", description="shaft speed")
        self._has_ref = speed_ref is None
        if self._has_ref:
            self.w_ref = Input(0.0, "rad/s", "speed reference", required=True)
        connect(self.motor.flange, self.shaft.flange_a)
        connect(self.shaft.flange_b, self.bearing_torque.flange)

    def equations(self):
        eqs = [self.bearing_torque.tau_in == self.M_bearing, self.w_shaft == self.shaft.w]
        if self._has_ref:
            eqs.append(self.motor.w_ref == self.w_ref)
        return eqs
