"""The duplex pair's figure: natural frequencies of the shaft on its rows by mode name ("radial
x", "axial", ...) over the run, from the exact static stiffness at the equilibrium under each
time's loads; and the names of the modes of a ``modes`` scene (:data:`MODE_NAMES_BY_STATE`).

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
from bearingsim.physics.shaft_modes import DOFS, MODE_NAMES, modal_analysis
from bearingsim.plotting import Curve, FigureSpec, Panel

__all__ = ["MODE_NAMES_BY_STATE", "MODE_SAMPLES", "duplex_plots", "mode_frequencies"]

MODE_SAMPLES = 41
"""Save points at which the duplex pair's modes are computed (evenly spread over the run)."""
_ACCEL_TOL = 1e-7  # m/s^2, rad/s^2: equilibrium residual, as in the duplex studies
MODE_NAMES_BY_STATE = {f"shaft.{dof}": name for dof, name in zip(DOFS, MODE_NAMES, strict=True)}
"""State name -> the name of the mode it dominates."""
_POSITIONS = tuple(f"shaft.{k}" for k in ("x", "y", "z", "tx", "ty"))
_LOADS = tuple(f"shaft.{k}" for k in ("Fx", "Fy", "Fz", "Mx", "My"))


def mode_frequencies(prep, result, samples: int = MODE_SAMPLES
                     ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Sample times [s] and the natural frequencies [Hz] by mode name there: the modes of
    ``K phi = w^2 M phi`` at the quasi-static equilibrium under the scene's loads at that time
    (Newton from the saved state), K the exact static stiffness of the model there
    (:func:`bearingsim.physics.shaft_modes.modal_analysis`). The equilibrium, not the saved state:
    after a load step the undamped shaft oscillates about it, and the stiffness at the
    swinging states would show the oscillation rather than the pair.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`bearingsim.scenes.preparation.Prepared`).
    result : SimulationResult
        The run's result (inputs over time and parameters).
    samples : int
        Number of sample times spread over the run, >= 1.

    Returns
    -------
    tuple of (ndarray, dict of str to ndarray)
        Sample times [s] and natural frequencies [Hz] by mode name.
    """
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
            x = prep.steady(inputs, result.parameters, guess, residual_tol=_ACCEL_TOL)
            stiffness = prep.static_stiffness(x, _POSITIONS, _LOADS, inputs,
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
    ball per row has no radial or tilt stiffness).

    Parameters
    ----------
    args : dict
        Every argument of the assembly's ``SCENE_SPEC.args`` (defaults filled in).
    fidelity : str
        Fidelity level of the scene, one of the spec's levels.

    Returns
    -------
    list of AssemblyPlot
        The mode-frequency figure, or none for the axisymmetric reduction.
    """
    if args.get("axisymmetric"):
        return []
    return [AssemblyPlot("modes", _POSITIONS, _modes_figure)]
