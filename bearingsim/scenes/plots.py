"""The plots that answer each built-in assembly's question (:data:`BUILTIN_PLOTS`, keyed by
assembly name; the runner draws them beside the time traces, as it does the figures a
registered assembly declares in its spec's ``plots``). They live in the scene layer because
they use the runtime (stiffness and modes of :mod:`bearingsim.studies`), which the models never
import.

* deep-groove ball bearing: ball contact load against azimuth at the end of the run (0 deg is
  the direction of the radial load), with the zero-clearance Stribeck load distribution
  ``Q_max = 4.37 Fr / Z`` for comparison;
* double-layer bearing (alone or in the motor drive): speed ratio Rs against shaft speed (when
  the shaft speed varies), with the pure-rolling ratio;
* duplex pair: natural frequencies of the shaft on its rows by mode name ("radial x", "axial",
  ...) over the run, from the exact static stiffness at the equilibrium under each time's
  loads.

Each ``*_plots(args, fidelity)`` returns :class:`~bearingsim.assemblies.spec.AssemblyPlot`
objects; their figures are :class:`~bearingsim.plotting.FigureSpec` in SI, shown in engineering
units by :func:`bearingsim.plotting.render`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from bearingsim.assemblies.spec import AssemblyPlot
from bearingsim.catalog import resolve_bearing
from bearingsim.physics.double_layer_theory import speed_ratio_pure_rolling
from bearingsim.plotting import Curve, FigureSpec, Panel
from bearingsim.simulation import steady_state
from bearingsim.simulation.statics import static_stiffness
from bearingsim.studies.duplex import MODE_NAMES, modal_analysis

__all__ = ["BUILTIN_PLOTS", "STRIBECK", "MODE_SAMPLES", "ball_loads", "deep_groove_plots",
           "double_layer_plots", "duplex_plots", "mode_frequencies", "motor_drive_plots"]

STRIBECK = 4.37
"""Stribeck's ratio ``Q_max Z / Fr`` of a radially loaded ball row with zero clearance
(Harris & Kotzalas, *Rolling Bearing Analysis*, section 7.2; 5 with the usual clearance)."""
MODE_SAMPLES = 41
"""Save points at which the duplex pair's modes are computed (evenly spread over the run)."""
_ACCEL_TOL = 1e-7  # m/s^2, rad/s^2: equilibrium residual, as in the duplex studies
_SPEED_SPAN = 1.0  # rad/s: a shaft speed varying less than this over the run is not plotted


# --------------------------------------------------------------------------- deep groove
def ball_loads(prep: Any, result: Any, series: dict[str, np.ndarray]
               ) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Ball contact loads at the inner race [N] at the end of the run, their azimuths [rad]
    from the radial load direction (wrapped to (-pi, pi]) and the radial load [N]; None
    without a radial load.

    The azimuths are those of the model: ``row.psi0 + 2 pi j / Z`` at the quasi-static level,
    the balls' orbital angles ``ball[j].theta`` at the dynamic levels.
    """
    z = resolve_bearing(prep.args["bearing"]).ball_count
    fx, fy = (float(result.inputs.get(f"load.{k}", 0.0)) for k in ("Fx", "Fy"))
    fr = math.hypot(fx, fy)
    if fr == 0.0:
        return None
    if prep.fidelity == "quasi-static":
        psi0 = float(result.parameters.get("row.psi0", 0.0))
        psi = psi0 + 2.0 * math.pi * np.arange(z) / z
        q = np.array([series[f"row.Q_i[{j}]"][-1] for j in range(z)])
    else:
        psi = np.array([series[f"ball[{j}].theta"][-1] for j in range(z)])
        q = np.array([series[f"inner[{j}].Q"][-1] for j in range(z)])
    psi = np.angle(np.exp(1j * (psi - math.atan2(fy, fx))))
    order = np.argsort(psi)
    return psi[order], q[order], fr


def _ball_load_figure(prep, result, series) -> FigureSpec | None:
    loads = ball_loads(prep, result, series)
    if loads is None:
        return None
    psi, q, fr = loads
    z = psi.size
    grid = np.linspace(-0.5 * math.pi, 0.5 * math.pi, 91)
    stribeck = STRIBECK * fr / z * np.cos(grid) ** 1.5
    panel = Panel([Curve(psi, q, "model (balls at the end of the run)",
                         {"linestyle": "-", "marker": "o"}),
                   Curve(grid, stribeck, f"zero clearance: {STRIBECK} Fr/Z cos^1.5",
                         {"linestyle": "--", "color": "0.5"})],
                  "azimuth from the load direction", "rad", "ball load at the inner race", "N",
                  scale="linear")
    return FigureSpec("ball_loads", f"ball loads at t = {result.t[-1]:g} s, Fr = "
                      f"{fr:.4g} N, Z = {z}", [panel])


def deep_groove_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Ball contact load against azimuth (every ball's load and, at the dynamic levels, its
    orbital angle)."""
    z = resolve_bearing(args["bearing"]).ball_count
    if fidelity == "quasi-static":
        needs = tuple(f"row.Q_i[{j}]" for j in range(z))
    else:
        needs = (*(f"inner[{j}].Q" for j in range(z)), *(f"ball[{j}].theta" for j in range(z)))
    return [AssemblyPlot("ball_loads", needs, _ball_load_figure)]


# --------------------------------------------------------------------------- double layer
def _rs_figure(prefix: str, bearing_args: dict[str, Any]):
    def make(prep, result, series) -> FigureSpec | None:
        w, rs = series[prefix + "w_shaft"], series[prefix + "Rs"]
        if np.ptp(w) < _SPEED_SPAN:
            return None
        kin = speed_ratio_pure_rolling(bearing_args["inner"], bearing_args["outer"])
        panel = Panel([Curve(w, rs, "model", {"linestyle": "-", "marker": ".",
                                              "markersize": 3}),
                       Curve(np.array([np.min(w), np.max(w)]), np.array([kin, kin]),
                             "pure rolling", {"linestyle": "--", "color": "0.5"})],
                      "shaft speed", "rad/s", "speed ratio Rs = n_middle / n_shaft", "1")
        return FigureSpec("rs_speed", "speed ratio against shaft speed", [panel])

    return make


def double_layer_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Rs against shaft speed."""
    return [AssemblyPlot("rs_speed", ("w_shaft", "Rs"), _rs_figure("", args))]


def motor_drive_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Rs of the bearing against shaft speed."""
    return [AssemblyPlot("rs_speed", ("bearing.w_shaft", "bearing.Rs"),
                         _rs_figure("bearing.", args["bearing"]))]


# --------------------------------------------------------------------------- duplex
_POSITIONS = tuple(f"shaft.{k}" for k in ("x", "y", "z", "tx", "ty"))
_LOADS = tuple(f"shaft.{k}" for k in ("Fx", "Fy", "Fz", "Mx", "My"))


def mode_frequencies(prep, result, samples: int = MODE_SAMPLES
                     ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Sample times [s] and the natural frequencies [Hz] by mode name there: the modes of
    ``K phi = w^2 M phi`` at the quasi-static equilibrium under the scene's loads at that time
    (Newton from the saved state), K the exact static stiffness of the model there
    (:func:`bearingsim.studies.duplex.modal_analysis`). The equilibrium, not the saved state:
    after a load step the undamped shaft oscillates about it, and the stiffness at the
    swinging states would show the oscillation rather than the pair."""
    system = prep.system
    m = result.parameters["shaft.mass"]
    jt = result.parameters["shaft.transverse_inertia"]
    mass = np.diag([m, m, m, jt, jt])
    index = np.unique(np.linspace(0, result.t.size - 1, samples).round().astype(int))
    freqs = {n: np.empty(index.size) for n in MODE_NAMES}
    solved: dict[tuple[float, ...], dict[str, float]] = {}
    for k, i in enumerate(index):
        inputs = {n: float(result[n][i]) for n in system.input_names}
        key = tuple(inputs.values())
        if key not in solved:
            guess = np.array([result[n][i] for n in system.state_names])
            x = steady_state(system, inputs=inputs, parameters=result.parameters,
                             x_guess=guess, residual_tol=_ACCEL_TOL)
            stiffness = static_stiffness(system, x, _POSITIONS, _LOADS, inputs,
                                         result.parameters)
            solved[key] = modal_analysis(stiffness, mass).by_name()
        for name, f in solved[key].items():
            freqs[name][k] = f
    return result.t[index], freqs


def _modes_figure(prep, result, series) -> FigureSpec:
    t, freqs = mode_frequencies(prep, result)
    panel = Panel([Curve(t, f, name) for name, f in freqs.items()], "time", "s",
                  "natural frequency", "Hz")
    return FigureSpec("modes", "natural frequencies of the shaft by mode at the equilibrium "
                      "under the loads of each time", [panel])


def duplex_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Natural frequencies by mode name over the run; none for the axisymmetric reduction (one
    ball per row has no radial or tilt stiffness)."""
    if args.get("axisymmetric"):
        return []
    return [AssemblyPlot("modes", _POSITIONS, _modes_figure)]


BUILTIN_PLOTS = {
    "deep_groove_ball_bearing": deep_groove_plots,
    "double_layer_bearing": double_layer_plots,
    "motor_drive": motor_drive_plots,
    "duplex_pair": duplex_plots,
}
"""Assembly name -> ``plots(args, fidelity)`` of the built-in assemblies."""
