"""The double-layer bearing's figure: the steady speed ratio Rs against shaft speed over the
run's speed range (when the shaft speed varies; solved directly at the loads of the end of the
run, not the run's transient trajectory), with the run's final point and the pure-rolling ratio.

Figures are :class:`~bearingsim.plotting.FigureSpec` in SI, shown in engineering units by
:func:`bearingsim.plotting.render`; ``make(prep, result, series)`` receives the prepared scene
(:class:`bearingsim.scenes.preparation.Prepared`, whose ``steady``, ``observe`` and
``static_stiffness`` solve on the scene's system: a model never imports the runtime), the run's
result and its saved series.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.assemblies.spec import AssemblyPlot
from bearingsim.errors import BearingsimError
from bearingsim.physics.double_layer_theory import speed_ratio_pure_rolling
from bearingsim.plotting import Curve, FigureSpec, Panel

__all__ = ["STEADY_SPEEDS", "double_layer_plots", "rs_figure", "steady_speed_ratio"]

_SPEED_SPAN = 1.0  # rad/s: a shaft speed varying less than this over the run is not plotted
STEADY_SPEEDS = 15
"""Shaft speeds at which the Rs figure of a transient scene solves the steady speed ratio."""


def steady_speed_ratio(prep, result, speed_input: str, rs_name: str, speeds: np.ndarray
                       ) -> np.ndarray:
    """Steady speed ratio [-] at each of ``speeds`` [rad/s] of the input ``speed_input``, the
    other inputs and the assembly's signals at their values at the end of the run, solved
    directly (:func:`~bearingsim.simulation.steady_state`, each speed started from the
    previous solution); NaN where no steady state is found.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`bearingsim.scenes.preparation.Prepared`).
    result : SimulationResult
        The run's result (final state, inputs and parameters).
    speed_input : str
        Name of the input that sets the shaft speed [rad/s].
    rs_name : str
        Name of the speed ratio output.
    speeds : ndarray
        Shaft speeds [rad/s] to solve at, in the order of continuation.

    Returns
    -------
    ndarray
        Steady speed ratio [-] at each speed (NaN where none is found).
    """
    system = prep.system
    inputs = dict(result.inputs)
    t_end = float(result.t[-1])
    x = np.array([result.final(n) for n in system.state_names])
    rs = np.full(speeds.size, np.nan)
    for k, w in enumerate(speeds):
        inputs[speed_input] = float(w)
        try:
            x = prep.steady(inputs, result.parameters, x, t=t_end)
        except BearingsimError:
            continue
        rs[k] = prep.observe(t_end, x, inputs, result.parameters)[rs_name]
    return rs


def rs_figure(prefix: str, bearing_args: dict[str, Any], speed_input: str):
    """The figure maker of Rs against shaft speed for a double-layer bearing whose variables
    carry ``prefix`` (``""`` alone, ``"bearing."`` in the motor drive), its scene arguments
    ``bearing_args`` and the input ``speed_input`` that sets the shaft speed.

    Parameters
    ----------
    prefix : str
        Prefix of the bearing's variable names (``""`` or ending in ``"."``).
    bearing_args : dict
        The bearing's scene arguments (``inner`` and ``outer`` are used).
    speed_input : str
        Name of the input that sets the shaft speed [rad/s].

    Returns
    -------
    callable
        ``make(prep, result, series)`` -> :class:`~bearingsim.plotting.FigureSpec` or None
        (None when the run's shaft speed spans too little).
    """

    def make(prep, result, series) -> FigureSpec | None:
        w, rs = series[prefix + "w_shaft"], series[prefix + "Rs"]
        if np.ptp(w) < _SPEED_SPAN:
            return None
        top = float(np.max(np.abs(w)))
        speeds = np.linspace(top / STEADY_SPEEDS, top, STEADY_SPEEDS)
        steady = steady_speed_ratio(prep, result, speed_input, prefix + "Rs", speeds)
        kin = speed_ratio_pure_rolling(bearing_args["inner"], bearing_args["outer"])
        curves = [Curve(speeds, steady, "steady (loads as at the end of the run)",
                        {"linestyle": "-", "marker": "o", "markersize": 3}),
                  Curve(np.array([abs(w[-1])]), np.array([rs[-1]]),
                        f"the run at t = {result.t[-1]:g} s",
                        {"linestyle": "none", "marker": "x", "markersize": 8,
                         "color": "k"}),
                  Curve(np.array([speeds[0], top]), np.array([kin, kin]), "pure rolling",
                        {"linestyle": "--", "color": "0.5"})]
        panel = Panel(curves, "shaft speed", "rad/s", "speed ratio Rs = n_middle / n_shaft",
                      "1", scale="linear")
        return FigureSpec("rs_speed", "steady speed ratio against shaft speed", [panel])

    return make


def double_layer_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Rs against shaft speed (none at the quasi-static level: load sharing, no speeds).

    Parameters
    ----------
    args : dict
        Every argument of the assembly's ``SCENE_SPEC.args`` (defaults filled in).
    fidelity : str
        Fidelity level of the scene, one of the spec's levels.

    Returns
    -------
    list of AssemblyPlot
        The Rs figure, or none at the quasi-static level.
    """
    if fidelity == "quasi-static":
        return []
    return [AssemblyPlot("rs_speed", ("w_shaft", "Rs"), rs_figure("", args, "shaft_speed"))]
