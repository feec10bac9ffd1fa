"""Assemblies cut for co-simulation: a speed-controlled motor on its shaft, and the double-layer
bearing driven at an imposed shaft speed.

Coupled speed -> bearing and friction torque -> motor they are the monolithic
:class:`bearingsim.assemblies.motor_drive.MotorDrive` (same motor, shaft inertia and bearing):

========================  ===========================================  ======================
FMU                        inputs                                       outputs
========================  ===========================================  ======================
``motor_shaft``            ``w_ref`` [rad/s], ``M_bearing`` [N m]       ``w_shaft`` [rad/s]
``double_layer_bearing``   ``shaft_speed`` [rad/s], ``Fr``, ``Fa`` [N]  ``M_shaft`` [N m],
                                                                        ``w_middle``, ``Rs``
========================  ===========================================  ======================

``M_bearing`` and ``M_shaft`` share their sign convention (the friction torque acting *on the
shaft*, negative while the shaft turns forward), so the connection needs no sign change:
:data:`MOTOR_BEARING_CONNECTIONS`. :func:`export_motor_bearing` writes both FMUs and the SSP file.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from bearingsim.assemblies.motor_drive import MotorShaft

__all__ = [
    "BEARING_OUTPUTS",
    "MOTOR_BEARING_CONNECTIONS",
    "MOTOR_OUTPUTS",
    "bearing_model",
    "export_motor_bearing",
]

MOTOR_OUTPUTS = ["w_shaft"]
"""Outputs of the motor FMU."""

BEARING_OUTPUTS = ["M_shaft", "w_middle", "Rs"]
"""Outputs of the bearing FMU."""

MOTOR_BEARING_CONNECTIONS = [
    ("motor.w_shaft", "bearing.shaft_speed"),
    ("bearing.M_shaft", "motor.M_bearing"),
]
"""SSP connections of the pair (components named ``motor`` and ``bearing``)."""


def bearing_model(**kwargs):
    """The double-layer bearing driven at the input ``shaft_speed`` (torque level).

    ``kwargs`` go to :func:`bearingsim.assemblies.double_layer.double_layer_bearing`
    (``drive="speed"`` and ``speed=None`` are fixed).

    Parameters
    ----------
    **kwargs
        Keywords of :func:`~bearingsim.assemblies.double_layer.double_layer_bearing`.

    Returns
    -------
    Assembly
        The bearing, its shaft speed an input.
    """
    from bearingsim.assemblies.double_layer import double_layer_bearing

    return double_layer_bearing(drive="speed", speed=None, **kwargs)


def export_motor_bearing(directory: str | Path, motor: str = "dc",
                         speed_ref: float | Callable = 100.0,
                         Fr: float = 0.0, Fa: float = 0.0, fmi_version: str = "2.0",  # noqa: N803
                         shaft_inertia: float = 1e-3, bearing_options: dict | None = None,
                         ssp: bool = True) -> dict[str, Path]:
    """Export the motor FMU and the bearing FMU (co-simulation) and, optionally, their SSP file.

    Parameters
    ----------
    directory : str or pathlib.Path
        Where ``<motor>_motor.fmu``, ``bearing.fmu`` and ``<motor>_motor_bearing.ssp`` go.
    motor : {"dc", "pmsm"}
        Motor type.
    speed_ref : float or callable
        A number: start value of the motor FMU's input ``w_ref`` [rad/s] (a step at t = 0 when
        it is not changed). A callable ``f(t)`` (CasADi math): the reference is built into the
        motor FMU, which then has no ``w_ref`` input.
    Fr, Fa : float
        Start values of the bearing's load inputs [N].
    fmi_version : {"2.0", "3.0"}
        FMI version of both FMUs (the SSP file needs FMI 2.0 for fmpy's ``simulate_ssp``).
    shaft_inertia : float
        Shaft inertia [kg m^2].
    bearing_options : dict, optional
        Passed to :func:`bearing_model`.
    ssp : bool
        Also write the SSP file.

    Returns
    -------
    dict of str to pathlib.Path
        ``"motor"``, ``"bearing"`` and (with ``ssp``) ``"ssp"``.
    """
    from bearingsim.fmu.export import export_fmu
    from bearingsim.fmu.ssp import write_ssp

    directory = Path(directory)
    fixed = not callable(speed_ref)
    suffix = "" if fmi_version == "2.0" else "_fmi3"
    paths = {
        "motor": export_fmu(MotorShaft(motor, None if fixed else speed_ref,
                                       shaft_inertia=shaft_inertia),
                            directory / f"{motor}_motor{suffix}.fmu", outputs=MOTOR_OUTPUTS,
                            inputs={"w_ref": float(speed_ref)} if fixed else None,
                            kinds=("CS",), fmi_version=fmi_version,
                            model_name=f"{motor}_motor_shaft"),
        "bearing": export_fmu(bearing_model(**(bearing_options or {})),
                              directory / f"bearing{suffix}.fmu", outputs=BEARING_OUTPUTS,
                              inputs={"Fr": Fr, "Fa": Fa}, kinds=("CS",),
                              fmi_version=fmi_version, model_name="double_layer_bearing"),
    }
    if ssp:
        paths["ssp"] = write_ssp(directory / f"{motor}_motor_bearing{suffix}.ssp",
                                 {"motor": paths["motor"], "bearing": paths["bearing"]},
                                 MOTOR_BEARING_CONNECTIONS, name=f"{motor}_motor_bearing",
                                 observe=["bearing.w_middle", "bearing.Rs"])
    return paths
