"""A motor driving a shaft that runs in a bearing assembly, with an optional load torque; and the
motor side alone (:class:`MotorShaft`), loaded by a bearing torque input, for co-simulation.

* :mod:`.drive`: :class:`MotorDrive`, :func:`motor_drive`, :class:`MotorShaft`;
* :mod:`.figures`: the bearing's steady speed ratio against shaft speed;
* :mod:`.scene`: :data:`SCENE_SPEC` (the motor's arguments and the double-layer bearing's
  nested under ``bearing``).
"""

from bearingsim.assemblies.motor_drive.drive import MotorDrive, MotorShaft, motor_drive
from bearingsim.assemblies.motor_drive.scene import SCENE_SPEC

__all__ = ["SCENE_SPEC", "MotorDrive", "MotorShaft", "motor_drive"]
