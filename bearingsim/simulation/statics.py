"""Static stiffness from the exact Jacobians of a dynamic model at an equilibrium.

At a steady state ``f(x, u) = 0``; a small load change ``du`` moves it by ``dx = -A^-1 B du``
with ``A = df/dx`` and ``B = df/du``. Restricted to chosen displacement states and load inputs,
``C = -(A^-1 B)[rows, cols]`` is the static compliance and ``K = C^-1`` the stiffness matrix —
exact, with no finite differences.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import ParameterError

__all__ = ["static_compliance", "static_stiffness"]


def _index(names: list[str], wanted: Sequence[str], what: str) -> list[int]:
    missing = [n for n in wanted if n not in names]
    if missing:
        raise ParameterError(f"unknown {what} {', '.join(missing)}; known: {', '.join(names)}")
    return [names.index(n) for n in wanted]


def static_compliance(system: System, x: np.ndarray, displacements: Sequence[str],
                      loads: Sequence[str], inputs: dict[str, float] | None = None,
                      parameters: dict[str, float] | None = None, t: float = 0.0) -> np.ndarray:
    """Static compliance ``d displacement / d load`` at the steady state ``x``.

    Parameters
    ----------
    system : System
    x : array
        Steady state (e.g. from :func:`bearingsim.simulation.steady_state`).
    displacements : sequence of str
        State names of the displacements (rows).
    loads : sequence of str
        Input names of the loads (columns).
    inputs, parameters : dict, optional
        Input values and parameter overrides at the operating point.
    t : float
        Time [s].

    Returns
    -------
    numpy.ndarray
        Compliance matrix, shape (len(displacements), len(loads)).
    """
    rows = _index(system.state_names, displacements, "displacement state(s)")
    cols = _index(system.input_names, loads, "load input(s)")
    u = system.u_default()
    for name, val in (inputs or {}).items():
        u[_index(system.input_names, [name], "input")[0]] = float(val)
    args = (t, np.asarray(x, dtype=float), u, system.p0(parameters))
    a = np.asarray(system.functions["jac_x"](*args).full(), dtype=float)
    b = np.asarray(system.functions["jac_u"](*args).full(), dtype=float)
    return -np.linalg.solve(a, b[:, cols])[rows, :]


def static_stiffness(system: System, x: np.ndarray, displacements: Sequence[str],
                     loads: Sequence[str], inputs: dict[str, float] | None = None,
                     parameters: dict[str, float] | None = None, t: float = 0.0) -> np.ndarray:
    """Static stiffness matrix ``K = C^-1`` (see :func:`static_compliance`); square only.

    Parameters
    ----------
    system : System
        The closed system.
    x : array
        Steady state (e.g. from :func:`bearingsim.simulation.steady_state`).
    displacements : sequence of str
        State names of the displacements (rows).
    loads : sequence of str
        Input names of the loads (columns), as many as ``displacements``.
    inputs, parameters : dict, optional
        Input values and parameter overrides at the operating point.
    t : float
        Time [s].

    Returns
    -------
    numpy.ndarray
        Stiffness matrix, shape (len(loads), len(displacements)).
    """
    if len(displacements) != len(loads):
        raise ParameterError("static_stiffness needs as many displacements as loads")
    return np.linalg.inv(static_compliance(system, x, displacements, loads, inputs, parameters,
                                           t))
