"""Linearization: A, B, C, D from the exact Jacobians; modes, frequencies and damping."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.solver.result import Result
from bearingsim.solver.system import System

__all__ = ["LinearModel", "linearize"]


@dataclass
class LinearModel:
    """``dx = A dx + B du``, ``dy = C dx + D du`` around an operating point.

    Attributes
    ----------
    eigenvalues : ndarray
        Eigenvalues of A [1/s].
    natural_frequencies : ndarray
        Undamped natural frequencies of the oscillatory modes [Hz], ascending.
    damping_ratios : ndarray
        Damping ratio of each oscillatory mode [1].
    mode_shapes : ndarray
        Columns: eigenvectors of the oscillatory modes, scaled to a largest entry of 1.
    """

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    state_names: list[str]
    input_names: list[str]
    output_names: list[str]
    x_op: np.ndarray
    u_op: np.ndarray
    eigenvalues: np.ndarray
    natural_frequencies: np.ndarray
    damping_ratios: np.ndarray
    mode_shapes: np.ndarray

    @property
    def angular_frequencies(self) -> np.ndarray:
        """Undamped natural angular frequencies [rad/s]."""
        return 2.0 * np.pi * self.natural_frequencies


def _modes(a: np.ndarray, tol: float = 1e-6):
    lam, vec = np.linalg.eig(a)
    scale = max(np.max(np.abs(lam)) if lam.size else 1.0, 1.0)
    osc = [k for k in range(lam.size) if lam[k].imag > tol * scale]
    osc.sort(key=lambda k: abs(lam[k]))
    wn = np.array([abs(lam[k]) for k in osc])
    zeta = np.array([-lam[k].real / abs(lam[k]) for k in osc])
    shapes = np.zeros((a.shape[0], len(osc)), dtype=complex)
    for j, k in enumerate(osc):
        v = vec[:, k]
        shapes[:, j] = v / v[np.argmax(np.abs(v))]
    return lam, wn / (2.0 * np.pi), zeta, shapes


def linearize(
    system: System,
    operating_point: dict[str, float] | Result | np.ndarray | None = None,
    *,
    t: float = 0.0,
    inputs: dict[str, float] | None = None,
    parameters: dict[str, float] | None = None,
) -> LinearModel:
    """Linearize a system around an operating point.

    Parameters
    ----------
    system : System
    operating_point : dict or Result or array, optional
        State values by name (others at their start values), the last point of a result, or a
        full state vector. Default: the start values.
    t : float
        Time [s].
    inputs : dict, optional
        Constant input values by name (default: input defaults).
    parameters : dict, optional
        Parameter overrides.

    Returns
    -------
    LinearModel
    """
    p = system.p0(parameters)
    x = _state_vector(system, operating_point)
    u = system.u_default()
    for name, val in (inputs or {}).items():
        if name not in system.input_names:
            from bearingsim.errors import ParameterError

            raise ParameterError(f"unknown input {name!r}; inputs: {system.input_names}")
        u[system.input_names.index(name)] = float(val)
    fns = system.functions

    def dense(key: str) -> np.ndarray:
        return np.asarray(fns[key](t, x, u, p).full(), dtype=float)

    a, b, c, d = (dense(k) for k in ("jac_x", "jac_u", "out_jac_x", "out_jac_u"))
    lam, fn, zeta, shapes = _modes(a)
    return LinearModel(a, b, c, d, system.state_names, system.input_names, system.output_names,
                       x, u, lam, fn, zeta, shapes)


def _state_vector(system: System, op: Any) -> np.ndarray:
    if op is None:
        return system.x0()
    if isinstance(op, Result):
        return np.array([op.final(n) for n in system.state_names])
    if isinstance(op, dict):
        return system.x0(op)
    x = np.asarray(op, dtype=float).ravel()
    if x.size != system.n_states:
        from bearingsim.errors import ParameterError

        raise ParameterError(f"operating point has {x.size} values for {system.n_states} states")
    return x
