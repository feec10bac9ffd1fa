"""The statics table: the quasi-static solution of each assembly that has one.

A ``statics`` scene (:mod:`bearingsim.scenes.analyses`) solves each load case with the
:class:`Statics` of its assembly (:data:`STATICS`, :func:`statics_of`); the figures
(:mod:`bearingsim.scenes.plots`) draw its columns.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.catalog import resolve_bearing
from bearingsim.scenes.scene import SceneError, line_of
from bearingsim.studies.deep_groove_statics import STATIC_PRESSURE_LIMIT
from bearingsim.studies.roller_statics import ROLLER_PRESSURE_LIMIT

__all__ = ["LIFE_AT_REST", "STATICS", "STATICS_INPUTS", "Statics", "statics_of"]

LIFE_AT_REST = "not defined at zero speed"
"""What a statics row gives for the life in hours ``L10h`` of a load case without a shaft speed
(0 or not given): a bearing at rest turns no revolutions, so its life in hours has no value
(the life in revolutions ``L10r`` still does). Text, so that no table shows a number
(``nan``, ``inf``, ``null``) for it."""


@dataclass(frozen=True)
class Statics:
    """The quasi-static solution of an assembly's load cases (a ``statics`` scene).

    ``solve(prep, inputs, args, guess) -> (row, state)`` solves one load case (inputs by
    name, SI); ``columns`` are the row's names -> (unit, description); ``figure`` the columns
    drawn per load case (bars); ``levels`` the fidelity levels it applies to (empty: all);
    ``pressure_limit`` the contact pressure of the static load rating [Pa] (ISO 76), drawn
    on a pressure panel.
    """

    solve: Callable[..., tuple[dict[str, float | str], np.ndarray]]
    columns: dict[str, tuple[str, str]]
    figure: tuple[str, ...]
    levels: tuple[str, ...] = ()
    pressure_limit: float = STATIC_PRESSURE_LIMIT


_DEEP_GROOVE_COLUMNS = {
    "Q_max": ("N", "largest ball load"),
    "p_max": ("Pa", "largest Hertz contact pressure"),
    "x": ("m", "inner ring displacement x"), "y": ("m", "inner ring displacement y"),
    "z": ("m", "inner ring displacement z (axial)"),
    "k_radial": ("N/m", "radial stiffness d Fx / d x"),
    "k_axial": ("N/m", "axial stiffness d Fz / d z"),
    "L10r": ("Mrev", "ISO/TS 16281 reference rating life L10r (10^6 revolutions)"),
    "L10h": ("h", "ISO/TS 16281 reference rating life L10r in hours at the case's shaft "
                  "speed"),  # a case at rest says LIFE_AT_REST in its cell
}


def _hours(life_mrev: float, inputs: dict[str, float]) -> float | str:
    """A life of ``life_mrev`` 10^6 revolutions in hours at the case's shaft speed
    (:data:`LIFE_AT_REST` without one)."""
    revolutions_per_hour = abs(float(inputs.get("shaft_speed", 0.0))) / (2.0 * math.pi) * 3600.0
    return life_mrev * 1e6 / revolutions_per_hour if revolutions_per_hour > 0.0 else LIFE_AT_REST


def _deep_groove_statics(prep: Any, inputs: dict[str, float], args: dict[str, Any],
                         guess: np.ndarray | None) -> tuple[dict[str, float | str], np.ndarray]:
    from bearingsim.studies.deep_groove_statics import LOAD_NAMES, deep_groove_statics

    loads = {k: float(inputs.get(f"load.{k}", 0.0)) for k in LOAD_NAMES}
    speed = abs(float(inputs.get("shaft_speed", 0.0)))
    resolve_bearing(args["bearing"]).check_speed(speed, "statics: inputs.shaft_speed")
    res = deep_groove_statics(args["bearing"], loads, method=prep.scene.statics_method,
                              guess=guess)
    life_h = _hours(res.reference_life, inputs)
    row = {"Q_max": float(np.max(res.ball_loads)), "p_max": float(res.max_pressure),
           "x": float(res.displacement[0]), "y": float(res.displacement[1]),
           "z": float(res.displacement[2]), "k_radial": float(res.stiffness[0, 0]),
           "k_axial": float(res.stiffness[2, 2]), "L10r": float(res.reference_life),
           "L10h": life_h}
    return row, res.state


_ROLLER_COLUMNS = {
    "Q_max": ("N", "largest roller load"),
    "p_max": ("Pa", "largest contact pressure (inner raceway)"),
    "x": ("m", "inner ring displacement x"), "y": ("m", "inner ring displacement y"),
    "k_radial": ("N/m", "radial stiffness d Fx / d x"),
    "Mx": ("N.m", "moment about x holding the misalignment"),
    "My": ("N.m", "moment about y holding the misalignment"),
    "L10r": ("Mrev", "ISO/TS 16281 roller-form reference rating life L10r (10^6 revolutions)"),
    "L10h": ("h", "ISO/TS 16281 roller-form reference rating life L10r in hours at the case's "
                  "shaft speed"),  # a case at rest says LIFE_AT_REST in its cell
}


def _roller_statics(prep: Any, inputs: dict[str, float], args: dict[str, Any],
                    guess: np.ndarray | None) -> tuple[dict[str, float | str], np.ndarray]:
    from bearingsim.assemblies.cylindrical_roller.scene import N_SLICES
    from bearingsim.catalog.rollers import resolve_roller_bearing
    from bearingsim.studies.roller_statics import LOAD_NAMES, roller_statics

    resolve_roller_bearing(args["bearing"]).check_speed(
        abs(float(inputs.get("shaft_speed", 0.0))), "statics: inputs.shaft_speed")
    res = roller_statics(args["bearing"], {k: float(inputs.get(f"load.{k}", 0.0))
                                           for k in LOAD_NAMES},
                         (args["tilt_x"], args["tilt_y"]), args["clearance"], N_SLICES)
    row = {"Q_max": float(np.max(res.roller_loads)), "p_max": res.max_pressure,
           "x": float(res.displacement[0]), "y": float(res.displacement[1]),
           "k_radial": float(res.stiffness[0, 0]), "Mx": float(res.moment[0]),
           "My": float(res.moment[1]), "L10r": res.reference_life,
           "L10h": _hours(res.reference_life, inputs)}
    return row, res.state


_NESTED_COLUMNS = {
    "Q_max_inner": ("N", "largest ball load of the inner layer"),
    "Q_max_outer": ("N", "largest ball load of the outer layer"),
    "x_shaft": ("m", "shaft displacement x"), "z_shaft": ("m", "shaft displacement z (axial)"),
    "x_middle": ("m", "middle ring displacement x"),
    "k_radial": ("N/m", "radial stiffness of the shaft against the housing"),
}


def _nested_statics(prep: Any, inputs: dict[str, float], args: dict[str, Any],
                    guess: np.ndarray | None) -> tuple[dict[str, float], np.ndarray]:
    from bearingsim.studies.nested_equilibrium import nested_equilibrium

    if abs(float(inputs.get("shaft.Fy", 0.0))) > 0.0:
        raise SceneError("the nested statics take the radial load along x (shaft.Fx) and the "
                         "axial load (shaft.Fz); shaft.Fy must be 0", "cases",
                         line_of(prep.scene.text, "cases"), "shaft.Fx, shaft.Fz",
                         prep.scene.path)
    eq = nested_equilibrium(prep.system, float(inputs.get("shaft.Fx", 0.0)),
                            float(inputs.get("shaft.Fz", 0.0)), guess)
    row = {"Q_max_inner": float(eq.inner_ball_loads.max()),
           "Q_max_outer": float(eq.outer_ball_loads.max()),
           "x_shaft": float(eq.shaft_displacement[0]),
           "z_shaft": float(eq.shaft_displacement[2]),
           "x_middle": float(eq.middle_displacement[0]),
           "k_radial": float(eq.stiffness[0, 0])}
    return row, eq.state


STATICS = {
    "deep_groove_ball_bearing": Statics(_deep_groove_statics, _DEEP_GROOVE_COLUMNS,
                                        ("L10h", "Q_max", "p_max")),
    "double_layer_bearing": Statics(_nested_statics, _NESTED_COLUMNS,
                                    ("Q_max_inner", "Q_max_outer", "x_shaft", "x_middle"),
                                    ("quasi-static",)),
    "cylindrical_roller_bearing": Statics(_roller_statics, _ROLLER_COLUMNS,
                                          ("L10h", "Q_max", "p_max"), ("quasi-static",),
                                          ROLLER_PRESSURE_LIMIT),
}
"""Assembly name -> its :class:`Statics`: the deep-groove ball bearing's ball loads, Hertz
pressure, stiffness and ISO/TS 16281 life
(:func:`~bearingsim.studies.deep_groove_statics.deep_groove_statics`), the double-layer
bearing's load sharing at its quasi-static level
(:func:`~bearingsim.studies.nested_equilibrium.nested_equilibrium`), the cylindrical roller
bearing's roller loads, contact pressure, stiffness, holding moment and roller-form life
(:func:`~bearingsim.studies.roller_statics.roller_statics`)."""
STATICS_INPUTS = ("shaft_speed",)
"""Inputs a statics load case may give beyond the model's: the shaft speed [rad/s] turns the
reference life in revolutions into hours (:data:`LIFE_AT_REST` without it)."""


def statics_of(prep: Any) -> Statics:
    """The :class:`Statics` of a prepared scene's assembly and level.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).

    Returns
    -------
    Statics
        The statics solution.

    Raises
    ------
    SceneError
        When the assembly (or its level) has no statics solution, naming those that have.
    """
    statics = STATICS.get(prep.spec.name)
    if statics is None or (statics.levels and prep.fidelity not in statics.levels):
        have = ", ".join(f"{name}" + (f" (fidelity {', '.join(st.levels)})" if st.levels
                                      else "") for name, st in STATICS.items())
        raise SceneError(f"no statics analysis for the assembly {prep.spec.name} at fidelity "
                         f"{prep.fidelity!r}", "analysis",
                         line_of(prep.scene.text, "analysis"), f"statics for {have}; steady "
                         "for the quasi-static equilibrium of the others", prep.scene.path)
    return statics

