"""Simulate a prepared scene: its inputs as the solver takes them (:func:`simulate_inputs`),
the run with the scene's settings (:func:`run_simulation`) and the requested outputs of the
result, post-processed ones computed (:func:`output_series`). Preparing the scene is
:func:`bearingsim.scenes.preparation.prepare`; running it and writing its files is
:func:`bearingsim.scenes.runner.run_scene`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.scenes.preparation import Prepared
from bearingsim.scenes.scene_types import simulate_inputs
from bearingsim.simulation import Result, simulate

__all__ = ["output_series", "run_simulation", "simulate_inputs"]


def run_simulation(prep: Prepared, parameters: dict[str, float] | None = None,
                   inputs: dict[str, Any] | None = None, progress: bool | None = False,
                   **overrides) -> Result:
    """Simulate a prepared scene (optionally with other parameters, inputs or settings;
    ``progress`` as :func:`~bearingsim.simulation.simulate` takes it).

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    parameters : dict of str to float, optional
        Parameter values over the scene's (SI units).
    inputs : dict, optional
        Inputs over the scene's.
    progress : bool or None
        Progress bar, as ``simulate`` takes it.
    **overrides
        Settings over the scene's ``simulation`` table (``t_end``, ``rtol``, ...).

    Returns
    -------
    Result
        The simulation result.
    """
    s = prep.scene.simulation
    opts = {"t_start": s.t_start, "method": s.method, "rtol": s.rtol, "atol": s.atol,
            "n_points": s.n_points, "max_step": s.max_step, "initial": s.initial,
            "max_steps": s.max_steps, "timeout": s.timeout}
    opts.update(overrides)
    t_end = opts.pop("t_end", s.t_end)
    params = {**prep.scene.parameters, **(parameters or {})}
    ins = simulate_inputs({**prep.scene.inputs, **(inputs or {})})
    return simulate(prep.system, t_end, inputs=ins, parameters=params,
                    x0=prep.scene.initial or None, progress=progress, **opts)


def output_series(prep: Prepared, result: Result) -> dict[str, np.ndarray]:
    """The requested outputs: model series from the result, post-processed ones computed.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    result : Result
        The run's result.

    Returns
    -------
    dict of str to ndarray
        Series (SI units) by output name.
    """
    series = {n: np.asarray(result[n]) for n in prep.model_outputs}
    out = {}
    for n in prep.outputs:
        if n in prep.post:
            out[n] = np.asarray(prep.post[n].compute(series), dtype=float)
        else:
            out[n] = series[n]
    return out
