"""Steady states: Newton on the state derivatives with the exact Jacobian."""

from __future__ import annotations

import numpy as np
import scipy.optimize

from bearingsim.assembler.system import System
from bearingsim.errors import SimulationError
from bearingsim.simulation.closed import ClosedModel, close_inputs

__all__ = ["steady_state", "integrator_states"]


def integrator_states(system: System) -> list[int]:
    """States no derivative depends on (angles of free rotors): they have no steady value."""
    sp = system.functions["jac_x"].sparsity_out(0)
    cols = set(sp.get_col())
    return [k for k in range(system.n_states) if k not in cols]


def steady_state(
    system: System,
    *,
    closed: ClosedModel | None = None,
    inputs: dict | None = None,
    parameters: dict | None = None,
    p: np.ndarray | None = None,
    x_guess: np.ndarray | None = None,
    t: float = 0.0,
    tol: float = 1e-12,
    residual_tol: float = 1e-9,
) -> np.ndarray:
    """Solve ``dx/dt = 0`` for every state that some derivative depends on.

    States that nothing depends on (pure integrators such as free rotor angles) keep their guess;
    their derivatives (the speeds) are still set to zero by the other equations when the model
    asks for it.

    Parameters
    ----------
    system : System
    closed : ClosedModel, optional
        Model with bound inputs (built from ``inputs`` if not given).
    inputs, parameters : dict, optional
        As for :func:`simulate`.
    p : array, optional
        Parameter vector (overrides ``parameters``).
    x_guess : array, optional
        Starting guess (default: start values).
    t : float
        Time at which inputs are evaluated [s].
    tol : float
        Relative step tolerance of the solver.
    residual_tol : float
        A solution whose largest derivative is below this is accepted even if the solver
        stalls [state units/s].

    Returns
    -------
    numpy.ndarray
        The steady state vector.
    """
    closed = closed if closed is not None else close_inputs(system, inputs)
    p = system.p0(parameters) if p is None else p
    x = system.x0() if x_guess is None else np.array(x_guess, dtype=float)
    skip = set(integrator_states(system))
    free = [k for k in range(system.n_states) if k not in skip]
    if not free:
        return x

    def res(z):
        xx = x.copy()
        xx[free] = z
        return np.asarray(closed.f(t, xx, p), dtype=float).ravel()[free]

    def jac(z):
        xx = x.copy()
        xx[free] = z
        return np.asarray(closed.jac(t, xx, p).sparse().toarray())[np.ix_(free, free)]

    sol = scipy.optimize.root(res, x[free], jac=jac, method="hybr", tol=tol)
    converged = np.all(np.isfinite(sol.x)) and np.max(np.abs(res(sol.x))) <= residual_tol
    if not (sol.success or converged) or not np.all(np.isfinite(sol.x)):
        raise SimulationError(
            "steady state not found: " + str(sol.message) + "; residual max "
            f"{np.max(np.abs(res(sol.x))):.3g} for states "
            + ", ".join(system.state_names[k] for k in free)
        )
    x[free] = sol.x
    return x
