"""Linearization: A, B, C, D from the exact Jacobians; modes, frequencies and damping."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.assembler.system import System, as_system
from bearingsim.entry_points import entry_point
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation.diagnostics import listed_names, no_value_cause
from bearingsim.simulation.kernels import kernel
from bearingsim.simulation.result import Result
from bearingsim.validation import check_mapping, check_quantity, check_vector

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
        """Undamped natural angular frequencies [rad/s].

        Returns
        -------
        numpy.ndarray
            ``2 pi`` times :attr:`natural_frequencies` [rad/s].
        """
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


@entry_point
def linearize(
    system: System,
    operating_point: dict[str, float] | Result | np.ndarray | None = None,
    *,
    t: float | str | None = None,
    inputs: dict[str, float | str] | None = None,
    parameters: dict[str, float] | None = None,
    compiled: bool | str = "auto",
) -> LinearModel:
    """Linearize a system around an operating point.

    ``A`` and ``B`` are the exact Jacobians of the system's kernel
    (:func:`~bearingsim.simulation.kernels.kernel`: generated C when a compiler exists, else
    CasADi's VM, the same numbers either way); ``C`` and ``D`` those of its outputs.

    With a :class:`~bearingsim.simulation.Result` from :func:`~bearingsim.simulation.simulate` the
    operating point is the run's end point: its final states, the input values at its last
    output time, its parameter values and that time. ``inputs`` and ``parameters`` override
    single entries of it by name. Any other operating point uses the inputs' default values and
    the default parameters unless ``inputs`` / ``parameters`` say otherwise.

    Parameters
    ----------
    system : System
        From :func:`~bearingsim.assembler.assemble`.
    operating_point : dict or Result or array, optional
        State values by name (others at their start values), a result (its last point, inputs
        and parameters) or a full state vector. Default: the start values.
    t : float or str, optional
        Time [s] or a number with a unit (``"2 ms"``); default the result's last time, else 0.
    inputs : dict, optional
        Constant input values by name (in the input's SI unit, or with a unit: ``"5000
        rpm"``, as :func:`~bearingsim.simulation.simulate` takes them), overriding the
        result's (or the default) values.
    parameters : dict, optional
        Parameter values by name, overriding the result's (or the default) values.
    compiled : bool or "auto"
        Backend of ``A`` and ``B``: generated C (``True``), CasADi's VM (``False``) or C when a
        compiler exists (``"auto"``).

    Returns
    -------
    LinearModel

    Raises
    ------
    ParameterError
        For an unknown input or parameter name, a bad value, an operating-point vector of the
        wrong size, or a result whose recorded inputs or parameters are not this system's.
    """
    system = as_system(system, "linearize")
    x = _state_vector(system, operating_point)
    run = operating_point if isinstance(operating_point, Result) else None
    p = system.p0()
    u = system.u_default()
    if run is not None:
        _take_recorded(p, system.parameter_names, run.parameters, "parameters")
        _take_recorded(u, system.input_names, run.inputs, "inputs")
        if t is None:
            t = float(run.t[-1])
    if parameters:
        given = system.p0(parameters)
        for name in parameters:
            k = system.parameter_names.index(name)
            p[k] = given[k]
    for name, val in check_mapping(inputs, "inputs", "linearize", "input names").items():
        if name not in system.input_names:
            raise ParameterError(
                f"linearize: unknown input {name!r}; inputs: {system.input_names}"
            )
        sig = system.inputs[system.input_names.index(name)]
        u[system.input_names.index(name)] = float(
            check_quantity(val, name, sig.unit, sig.low, sig.high, where="linearize: inputs"))
    t = 0.0 if t is None else float(check_quantity(t, "t", "s", where="linearize"))
    fns = system.functions
    kern = kernel(system, "ode", compiled)
    _, d_dx, d_du, _ = kern.function.jacobian()(t, x, u, p, 0.0)
    a, b = (np.asarray(m.full(), dtype=float) for m in (d_dx, d_du))
    c, d = (np.asarray(fns[k](t, x, u, p).full(), dtype=float) for k in ("out_jac_x",
                                                                          "out_jac_u"))
    _check_finite(system, t, np.asarray(kern.observe(t, x, u, p).full(), dtype=float).ravel(),
                  np.hstack([a, b]), np.hstack([c, d]))
    lam, fn, zeta, shapes = _modes(a)
    return LinearModel(a, b, c, d, system.state_names, system.input_names, system.output_names,
                       x, u, lam, fn, zeta, shapes)


def _check_finite(system: System, t: float, values: np.ndarray, ab: np.ndarray,
                  cd: np.ndarray) -> None:
    """Raise when a variable at the operating point (``values``: every observed variable) or
    an entry of the linear model is not finite (a nonlinear block without a solution there, a
    square root of a negative value), naming them: the modes would be empty or NaN."""
    names = [n for n, v in zip(system.observed_names, values, strict=True)
             if not np.isfinite(v)]
    where = "its variables are not finite at the operating point"
    if not names:
        names = [f"der({n})" for n, row in zip(system.state_names, ab, strict=True)
                 if not np.isfinite(row).all()]
        names += [n for n, row in zip(system.output_names, cd, strict=True)
                  if not np.isfinite(row).all()]
        where = "the Jacobian is not finite at the operating point in the rows of"
    if names:
        raise SimulationError(f"linearize: {system.name}: {where} (t = {t:g} s): "
                              f"{listed_names(names)}; {no_value_cause(system)}")


def _take_recorded(vector: np.ndarray, names: list[str], recorded: dict[str, float],
                   what: str) -> None:
    """Copy a result's recorded values into ``vector`` (in place), checking that they match."""
    if not recorded:
        return
    if set(recorded) != set(names):
        extra = sorted(set(recorded) - set(names))
        missing = sorted(set(names) - set(recorded))
        raise ParameterError(
            f"linearize: the result's recorded {what} are not this system's "
            f"(not in the system: {extra}; not in the result: {missing}); was the result "
            f"made with another system?"
        )
    for k, name in enumerate(names):
        vector[k] = float(recorded[name])


def _state_vector(system: System, op: Any) -> np.ndarray:
    if op is None:
        return system.x0()
    if isinstance(op, Result):
        return np.array([op.final(n) for n in system.state_names])
    if isinstance(op, dict):
        return system.x0(op)
    if isinstance(op, (str, bytes)):
        raise ParameterError(f"linearize: operating_point must be a dict of state values, a "
                             f"Result or a state vector, got {op!r}")
    return check_vector(op, system.n_states, "operating_point", "state units", "linearize")
