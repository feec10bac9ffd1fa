"""The deep-groove ball bearing's figure: ball contact load against azimuth at the end of the run
(0 deg is the direction of the radial load), with the zero-clearance Stribeck load distribution
``Q_max = 4.37 Fr / Z`` for comparison.

Figures are :class:`~bearingsim.plotting.FigureSpec` in SI, shown in engineering units by
:func:`bearingsim.plotting.render`; ``make(prep, result, series)`` receives the prepared scene
(:class:`bearingsim.scenes.preparation.Prepared`, whose ``steady``, ``observe`` and
``static_stiffness`` solve on the scene's system: a model never imports the runtime), the run's
result and its saved series.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from bearingsim.assemblies.spec import AssemblyPlot
from bearingsim.catalog import resolve_bearing
from bearingsim.plotting import Curve, FigureSpec, Panel

__all__ = ["STRIBECK", "ball_loads", "deep_groove_plots"]

STRIBECK = 4.37
"""Stribeck's ratio ``Q_max Z / Fr`` of a radially loaded ball row with zero clearance
(Harris & Kotzalas, *Rolling Bearing Analysis*, section 7.2; 5 with the usual clearance)."""


def ball_loads(prep: Any, result: Any, series: dict[str, np.ndarray]
               ) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Ball contact loads at the inner race [N] at the end of the run, their azimuths [rad]
    from the radial load direction (wrapped to (-pi, pi]) and the radial load [N]; None
    without a radial load.

    The azimuths are those of the model: ``row.psi0 + 2 pi j / Z`` at the quasi-static level,
    the balls' orbital angles ``ball[j].theta`` at the dynamic levels.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`bearingsim.scenes.preparation.Prepared`).
    result : SimulationResult
        The run's result (its inputs and parameters).
    series : dict of str to ndarray
        The run's saved series by variable name.

    Returns
    -------
    tuple of (ndarray, ndarray, float) or None
        Loads [N], azimuths [rad] and radial load [N]; None without a radial load.
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
    orbital angle).

    Parameters
    ----------
    args : dict
        Every argument of the assembly's ``SCENE_SPEC.args`` (defaults filled in).
    fidelity : str
        Fidelity level of the scene, one of the spec's levels.

    Returns
    -------
    list of AssemblyPlot
        The ball-load figure and the series it needs.
    """
    z = resolve_bearing(args["bearing"]).ball_count
    if fidelity == "quasi-static":
        needs = tuple(f"row.Q_i[{j}]" for j in range(z))
    else:
        needs = (*(f"inner[{j}].Q" for j in range(z)), *(f"ball[{j}].theta" for j in range(z)))
    return [AssemblyPlot("ball_loads", needs, _ball_load_figure)]
