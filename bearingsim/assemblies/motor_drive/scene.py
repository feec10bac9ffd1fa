"""The scene face of the motor drive: arguments (the double-layer bearing's nested under
``bearing``) and the build from scene arguments."""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies import double_layer
from bearingsim.assemblies.motor_drive.drive import MotorDrive, motor_drive
from bearingsim.assemblies.motor_drive.figures import motor_drive_plots
from bearingsim.assemblies.spec import ArgSpec, AssemblySpec, factory_default, nested_post
from bearingsim.components.motor import MOTOR_DRIVES


def _motor_drive_from_scene(args: dict[str, Any], fidelity: str) -> MotorDrive:
    """Build the drive from the scene arguments of :data:`SCENE_SPEC` (defaults filled in)."""
    bearing = double_layer.double_layer_from_scene(args["bearing"], fidelity, drive="flange")
    return motor_drive(bearing, motor=args["motor"], speed_ref=None,
                       load_torque=args["load_torque"],  # None: the model's input load.tau_in
                       shaft_inertia=args["shaft_inertia"],
                       motor_options=dict(args["motor_options"] or {}) or None)


_BEARING = double_layer.SCENE_SPEC

SCENE_SPEC = AssemblySpec(
    name="motor_drive",
    description="speed-controlled DC or PMSM motor -> shaft inertia -> double-layer bearing; "
                "inputs motor.w_ref [rad/s], bearing.Fr, bearing.Fa [N] (torque level) and "
                "the load torque load.tau_in [N m] unless the argument load_torque builds it in",
    build=_motor_drive_from_scene,
    args={
        "motor": ArgSpec("choice", factory_default(MotorDrive, "motor"),
                         "motor type with its PI speed control", choices=tuple(MOTOR_DRIVES)),
        "load_torque": ArgSpec("signal", None,
                               "load torque on the shaft [N.m] (positive drives it) built into "
                               "the model: a number or an expression of t; left out, the "
                               "model's input load.tau_in (0 unless [inputs] give it: one "
                               "model for a sweep over it, an input of an exported FMU)"),
        "shaft_inertia": ArgSpec("float", factory_default(MotorDrive, "shaft_inertia"),
                                 "shaft and spindle inertia [kg m^2]", low=0.0),
        "motor_options": ArgSpec("floats", factory_default(MotorDrive, "motor_options"),
                                 "motor and controller constants (e.g. kp_w, ki_w for the PMSM, "
                                 "kp, ki, R, L, k, J for the DC motor)"),
        "bearing": ArgSpec("table", None, "the double-layer bearing", table=_BEARING.args),
    },
    fidelities=_BEARING.fidelities,
    auto_fidelities=_BEARING.auto_fidelities,
    output_fidelity=[("bearing." + pattern, fid) for pattern, fid in _BEARING.output_fidelity]
    + [(name, _BEARING.auto_fidelities[0]) for name in ("motor.w_ref", "load.tau_in")],
    default_outputs=["shaft.w", "bearing.w_middle", "bearing.Rs", "bearing.M_shaft"],
    post=lambda args: nested_post(_BEARING.post(args["bearing"]), "bearing."),
    parametric_args={"bearing." + name: (lambda args, holds=holds: holds(args["bearing"]))
                     for name, holds in _BEARING.parametric_args.items()},
    optional_inputs=("load.tau_in", *("bearing." + p for p in _BEARING.optional_inputs)),
    reference_fidelity=_BEARING.reference_fidelity,
    level_errors={level: {"motor.w_ref": 0.0, "load.tau_in": 0.0,  # inputs: exact at every level
                          **{"bearing." + pattern: error for pattern, error in errors.items()}}
                  for level, errors in _BEARING.level_errors.items()},
    plots=motor_drive_plots,
)
"""The motor drive with a double-layer bearing as a scene assembly (:mod:`bearingsim.scenes`)."""
