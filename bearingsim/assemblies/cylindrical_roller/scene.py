"""The scene face of the cylindrical roller bearing: arguments, post-processed quantities
(largest roller load and contact pressure, ISO/TS 16281 roller-form life) and the roller-load
figure."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from bearingsim.assemblies.cylindrical_roller.factory import cylindrical_roller_bearing
from bearingsim.assemblies.cylindrical_roller.options import FIDELITIES, FRICTION_MODELS, MAX_TILT
from bearingsim.assemblies.spec import ArgSpec, AssemblyPlot, AssemblySpec, PostQuantity
from bearingsim.catalog.rollers import (
    find_roller_bearing,
    list_roller_bearings,
    resolve_roller_bearing,
)
from bearingsim.components.roller_row import roller_row_lives
from bearingsim.physics.life import line_load_integrals
from bearingsim.plotting import Curve, FigureSpec, Panel

__all__ = ["SCENE_SPEC", "N_SLICES", "roller_loads_figure", "reference_life"]

N_SLICES = 10
"""Slices per roller of the scene's quasi-static level."""
_TORQUE, _QUASI_STATIC = FIDELITIES
_DISPLACEMENT = ("row.inner.x", "row.inner.y", "row.inner.tx", "row.inner.ty")


def _build(args: dict[str, Any], fidelity: str):
    """Build the bearing from the scene arguments of :data:`SCENE_SPEC` (defaults filled in)."""
    if fidelity == _TORQUE:
        return cylindrical_roller_bearing(args["bearing"], _TORQUE, lubricant=args["lubricant"],
                                          friction_model=args["friction_model"])
    return cylindrical_roller_bearing(args["bearing"], _QUASI_STATIC,
                                      clearance=args["clearance"], n_slices=N_SLICES,
                                      misalignment=(args["tilt_x"], args["tilt_y"]))


def reference_life(args: dict[str, Any], series: dict[str, np.ndarray]) -> np.ndarray:
    """ISO/TS 16281 roller-form reference rating life L10r [10^6 rev] at every saved time,
    from the inner ring's displacement (rotating inner ring).

    Parameters
    ----------
    args : dict
        Scene arguments (bearing, clearance).
    series : dict of str to numpy.ndarray
        The saved series of :data:`_DISPLACEMENT` ("row.inner.x", ...).

    Returns
    -------
    numpy.ndarray
        L10r [10^6 revolutions] (inf without load).
    """
    x, y, tx, ty = (np.asarray(series[n], dtype=float) for n in _DISPLACEMENT)
    return roller_row_lives(args["bearing"], args["clearance"],
                            np.column_stack([x, y, np.zeros_like(x), tx, ty]), N_SLICES)


def _post(args: dict[str, Any]) -> dict[str, PostQuantity]:
    z = resolve_roller_bearing(args["bearing"]).roller_count
    loads = tuple(f"row.Q[{j}]" for j in range(z))
    pressures = tuple(f"row.p_max[{j}]" for j in range(z))
    return {
        "Q_max": PostQuantity("Q_max", "N", "largest roller load", loads,
                              lambda s: np.max([s[n] for n in loads], axis=0), _QUASI_STATIC),
        "p_max": PostQuantity("p_max", "Pa", "largest contact pressure (inner raceway)",
                              pressures, lambda s: np.max([s[n] for n in pressures], axis=0),
                              _QUASI_STATIC),
        "L10r": PostQuantity("L10r", "Mrev", "ISO/TS 16281 roller-form reference rating life "
                             "(10^6 revolutions)", _DISPLACEMENT,
                             lambda s: reference_life(args, s), _QUASI_STATIC),
    }


def roller_loads_figure(prep: Any, result: Any, series: dict[str, np.ndarray]
                        ) -> FigureSpec | None:
    """Roller loads against azimuth from the load direction at the end of the run, with the
    zero-clearance line-contact distribution ``Q_max = Fr / (Z Jr) = 4.08 Fr / Z`` (None without
    a radial load).

    Parameters
    ----------
    prep : Prepared
        The prepared scene.
    result : Result
    series : dict of str to numpy.ndarray

    Returns
    -------
    FigureSpec or None
    """
    z = resolve_roller_bearing(prep.args["bearing"]).roller_count
    fx, fy = (float(result.inputs.get(f"load.{k}", 0.0)) for k in ("Fx", "Fy"))
    fr = math.hypot(fx, fy)
    if fr == 0.0:
        return None
    psi0 = float(result.parameters.get("row.psi0", 0.0))
    psi = np.angle(np.exp(1j * (psi0 + 2.0 * math.pi * np.arange(z) / z - math.atan2(fy, fx))))
    q = np.array([series[f"row.Q[{j}]"][-1] for j in range(z)])
    order = np.argsort(psi)
    ratio = 1.0 / line_load_integrals(0.5)[0]
    grid = np.linspace(-0.5 * math.pi, 0.5 * math.pi, 91)
    panel = Panel([Curve(psi[order], q[order], "model (rollers at the end of the run)",
                         {"linestyle": "-", "marker": "o"}),
                   Curve(grid, ratio * fr / z * np.cos(grid) ** (10.0 / 9.0),
                         f"zero clearance: {ratio:.2f} Fr/Z cos^(10/9)",
                         {"linestyle": "--", "color": "0.5"})],
                  "azimuth from the load direction", "rad", "roller load", "N", scale="linear")
    return FigureSpec("roller_loads", f"roller loads at t = {result.t[-1]:g} s, Fr = "
                      f"{fr:.4g} N, Z = {z}", [panel])


def _plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    if fidelity != _QUASI_STATIC:
        return []
    z = resolve_roller_bearing(args["bearing"]).roller_count
    return [AssemblyPlot("roller_loads", tuple(f"row.Q[{j}]" for j in range(z)),
                         roller_loads_figure)]


SCENE_SPEC = AssemblySpec(
    name="cylindrical_roller_bearing",
    description="single cylindrical roller bearing (NU): quasi-static roller load distribution "
                "(sliced line contacts, clearance, misalignment; inputs load.Fx, Fy [N]) or "
                "friction torque (Palmgren/SKF; inputs drive.w_in [rad/s], bearing.Fr, Fa [N])",
    build=_build,
    args={
        "bearing": ArgSpec("bearing", "NU206", "catalogue designation",
                           known=list_roller_bearings, find=find_roller_bearing),
        "clearance": ArgSpec("float", None, "diametral clearance [m] (default: catalogue, "
                             "normal group)", low=0.0, low_inclusive=True),
        "tilt_x": ArgSpec("float", 0.0, "misalignment about x [rad]", low=-MAX_TILT,
                          high=MAX_TILT, low_inclusive=True),
        "tilt_y": ArgSpec("float", 0.0, "misalignment about y [rad]", low=-MAX_TILT,
                          high=MAX_TILT, low_inclusive=True),
        "lubricant": ArgSpec("lubricant", "ISO VG 32", "lubricant name (torque level)"),
        "friction_model": ArgSpec("choice", "palmgren", "friction model (torque level)",
                                  choices=FRICTION_MODELS),
    },
    fidelities=FIDELITIES,
    auto_fidelities=FIDELITIES,
    output_fidelity=[("bearing.*", _TORQUE), ("drive.*", _TORQUE), ("housing.flange*", _TORQUE),
                     ("row.*", _QUASI_STATIC), ("load.*", _QUASI_STATIC),
                     ("guide.*", _QUASI_STATIC)],
    default_outputs=["row.Q[0]", "row.p_max[0]"],
    post=_post,
    # the misalignment is the guide's parameters (the Newton start does not depend on it)
    parametric_args={"tilt_x": lambda args: True, "tilt_y": lambda args: True},
    optional_inputs=("load.*", "bearing.F*"),
    plots=_plots,
)
"""The single cylindrical roller bearing as a scene assembly (:mod:`bearingsim.scenes`)."""
