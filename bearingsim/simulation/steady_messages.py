"""The messages of :func:`~bearingsim.simulation.steady.steady_state` when it finds no steady
state: a turning model whose steady running is periodic, or the derivatives left where the
solver stopped."""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.assembler.system import System
from bearingsim.units.fmi import derivative_unit

__all__ = ["SHOWN_STATES", "not_found", "running_off", "speed_inputs"]


def speed_inputs(system: System, u: np.ndarray) -> list[str]:
    """The inputs in rad/s that are not zero, as ``name = value rad/s``.

    Parameters
    ----------
    system : System
        The model.
    u : numpy.ndarray
        Its input values (SI).

    Returns
    -------
    list of str
        One ``name = value rad/s`` per turning input.
    """
    units = system.variable_units
    return [f"{n} = {v:.6g} rad/s" for n, v in zip(system.input_names, u.tolist(), strict=True)
            if units.get(n) == "rad/s" and v != 0.0]


def _free_names(system: System, free: np.ndarray) -> tuple[list[str], dict[str, str]]:
    """The free states' names and the model's units by variable name."""
    return [system.state_names[k] for k in free], system.variable_units


SHOWN_STATES = 6
"""Most states a message of :func:`~bearingsim.simulation.steady.steady_state` names."""


def not_found(system: System, sol: Any, r: np.ndarray, angles: list[str],
              free: np.ndarray, speeds: list[str], unsolved: int) -> str:
    """Why no steady state was found, in one line: with a speed input turning the model and
    angle states in it (:func:`~bearingsim.simulation.steady.turning_angles`), its steady
    running is periodic, not a fixed point; else the largest derivatives left at the
    closest point MINPACK reached, with their units. And the points where the model had no
    value.

    Parameters
    ----------
    system : System
        The model.
    sol : scipy.optimize.OptimizeResult
        MINPACK's result (its message).
    r : numpy.ndarray
        The derivatives of the free states at ``sol.x`` [state units/s].
    angles : list of str
        The model's turning angles.
    free : numpy.ndarray
        Indices of the free states in ``system.state_names``.
    speeds : list of str
        :func:`speed_inputs`.
    unsolved : int
        Points tried where a nonlinear block of the model found no root.

    Returns
    -------
    str
        The message.
    """
    names, units = _free_names(system, free)

    def listed(items: list[str]) -> str:
        more = len(items) - SHOWN_STATES
        return ", ".join(items[:SHOWN_STATES]) + (f" and {more} more" if more > 0 else "")

    if angles and speeds:
        text = (f"{system.name}: no steady state: the inputs turn it ({', '.join(speeds)}) "
                f"and its angles turn with it ({listed(angles)}: each one's derivative is a "
                "speed), so its steady running is periodic, not a fixed point; run it in time "
                "(simulate, a transient scene) or use a model without these angles (a "
                "quasi-static level)")
    else:
        finite = np.isfinite(r)
        order = np.argsort(-np.where(finite, np.abs(r), np.inf))
        text = ("steady state not found: " + " ".join(str(sol.message).split())  # one line
                + "; the largest derivatives left: " + listed(
                    [f"{names[i]} {r[i]:.3g} {derivative_unit(units.get(names[i], '1'))}"
                     for i in order]))
    if unsolved:
        text += (f"; at {unsolved} of the points tried a nonlinear block of the model found no "
                 "root (the model has no value there)")
    return text


def running_off(system: System, sol: Any, r: np.ndarray, step: np.ndarray,
                free: np.ndarray) -> str:
    """Why a point where the derivatives are small is no steady state: a Newton step from it
    still moves the states by much (their derivatives vanish only as they run off to a limit:
    ``y' = exp(y)`` has derivatives below any tolerance at y = -138, and none at zero). Names
    the states that step moves most relative to their values.

    Parameters
    ----------
    system : System
        The model.
    sol : scipy.optimize.OptimizeResult
        MINPACK's result: the point ``sol.x`` and its evaluations ``sol.nfev``.
    r : numpy.ndarray
        The derivatives of the free states at ``sol.x`` [state units/s].
    step : numpy.ndarray
        The Newton step from ``sol.x`` [state units].
    free : numpy.ndarray
        Indices of the free states in ``system.state_names``.

    Returns
    -------
    str
        The message.
    """
    names, units = _free_names(system, free)
    moved = np.abs(step) / np.maximum(np.abs(sol.x), np.finfo(float).tiny)
    shown = []
    for i in np.argsort(-moved)[:SHOWN_STATES]:
        unit = units.get(names[i], "1")
        shown.append(f"{names[i]} = {sol.x[i]:.6g}{'' if unit in ('', '1') else ' ' + unit} "
                     f"(derivative {r[i]:.3g} {derivative_unit(unit)}, Newton step "
                     f"{step[i]:+.3g})")
    return ("steady state not found: the derivatives fall toward zero only as the states run "
            f"off: where the solver stopped after {sol.nfev} evaluations, "
            + "; ".join(shown) + ". A steady state would take no Newton step; this model's "
            "derivatives vanish only in a limit (a state without bound), so it has no steady "
            "state at these inputs and parameters: run it in time (simulate) to see where it "
            "goes")
