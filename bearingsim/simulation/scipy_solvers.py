"""scipy's ``solve_ivp`` solver classes as bearingsim runs them: every method counts its steps
against the run's budget (:func:`budgeted`), and BDF's Newton iteration accepts corrections that
stagnate at round-off (:func:`bdf_newton`). :class:`~bearingsim.simulation.integrators.
ScipyIntegrator` runs them.
"""

from __future__ import annotations

import types

import numpy as np
import scipy.integrate
import scipy.integrate._ivp.bdf as scipy_bdf

from bearingsim.simulation.budget import RunBudget

__all__ = ["NEWTON_STAGNATION", "SCIPY_SOLVERS", "StagnationTolerantBDF", "bdf_newton",
           "budgeted"]

NEWTON_STAGNATION = 1.0
"""Multiple of the Newton tolerance below which two successive BDF corrections that stop
shrinking count as converged (:func:`bdf_newton`)."""


def bdf_newton(fun, t_new, y_predict, c, psi, LU, solve_lu, scale, tol):
    """The simplified Newton iteration of one BDF step (scipy's ``solve_bdf_system`` contract:
    returns ``converged, n_iter, y, d``), with a stagnation rule.

    scipy declares the iteration diverged as soon as a correction is not smaller than the one
    before (rate >= 1). When the predictor is already exact to round-off (a damped system
    settled at its equilibrium) the corrections are the right-hand side's round-off noise
    times the step size: they do not shrink, the step is refused, halved and refused again,
    and the step size random-walks near 1e-12 s for ever. The shipped ``duplex_pair_axial``
    scene with ``method = "BDF"`` stalled this way at t = 1.4966 ms (corrections 1e-9 of the
    tolerance, 13 000 steps in 30 s). Here corrections that stagnate below
    :data:`NEWTON_STAGNATION` times the tolerance count as converged: the iterate is as
    accurate as the arithmetic allows, and the step's error test still decides on it.

    Parameters
    ----------
    fun : callable
        ``fun(t, y)``: the right-hand side.
    t_new : float
        Time at the end of the step [s].
    y_predict : numpy.ndarray
        The predictor (the iteration's start).
    c : float
        Step size over the BDF order's coefficient [s].
    psi : numpy.ndarray
        The BDF history term.
    LU : object
        Factorization of the iteration matrix, as ``solve_lu`` takes it.
    solve_lu : callable
        ``solve_lu(LU, b)``: solves with the iteration matrix.
    scale : numpy.ndarray
        Error weights (``atol + rtol |y|``).
    tol : float
        Newton tolerance on the scaled correction (> 0).

    Returns
    -------
    tuple of (bool, int, numpy.ndarray, numpy.ndarray)
        Whether it converged, the iterations used, the corrected state and the sum of the
        corrections.
    """
    y = y_predict.copy()
    d = np.zeros_like(y)
    dy_norm_old = None
    for k in range(scipy_bdf.NEWTON_MAXITER):
        f = fun(t_new, y)
        if not np.all(np.isfinite(f)):
            return False, k + 1, y, d
        dy = solve_lu(LU, c * f - psi - d)
        dy_norm = scipy_bdf.norm(dy / scale)
        rate = None if dy_norm_old is None else dy_norm / dy_norm_old
        if rate is not None and (
                rate >= 1 or rate ** (scipy_bdf.NEWTON_MAXITER - k) / (1 - rate) * dy_norm > tol):
            stagnated = max(dy_norm, dy_norm_old) < NEWTON_STAGNATION * tol
            return stagnated, k + 1, y, d
        y += dy
        d += dy
        if dy_norm == 0 or (rate is not None and rate / (1 - rate) * dy_norm < tol):
            return True, k + 1, y, d
        dy_norm_old = dy_norm
    return False, scipy_bdf.NEWTON_MAXITER, y, d


class StagnationTolerantBDF(scipy_bdf.BDF):
    """scipy's BDF with :func:`bdf_newton` as its Newton iteration (the same step code, run
    with the module's ``solve_bdf_system`` bound to :func:`bdf_newton`)."""

    _step_impl = types.FunctionType(
        scipy_bdf.BDF._step_impl.__code__,
        {**vars(scipy_bdf), "solve_bdf_system": bdf_newton},
        "_step_impl", scipy_bdf.BDF._step_impl.__defaults__,
        scipy_bdf.BDF._step_impl.__closure__)


def budgeted(solver: type) -> type:
    """A subclass of the scipy ``OdeSolver`` class ``solver`` that counts every step against
    the run's budget, given as the solver option ``budget`` (a
    :class:`~bearingsim.simulation.budget.RunBudget`; raising
    :class:`~bearingsim.errors.BudgetExceededError` when it is spent).

    Parameters
    ----------
    solver : type
        A subclass of ``scipy.integrate.OdeSolver``.

    Returns
    -------
    type
        The budgeted subclass (keyword ``budget`` required).
    """

    def __init__(self, *args, budget: RunBudget, **kwargs):
        self.budget = budget
        solver.__init__(self, *args, **kwargs)

    def _step_impl(self):
        self.budget.step(self.t)
        return solver._step_impl(self)

    return type(f"Budgeted{solver.__name__}", (solver,),
                {"__init__": __init__, "_step_impl": _step_impl})


SCIPY_SOLVERS: dict[str, type] = {
    name: budgeted(solver) for name, solver in (
        ("BDF", StagnationTolerantBDF),
        ("Radau", scipy.integrate.Radau),
        ("LSODA", scipy.integrate.LSODA),
        ("RK45", scipy.integrate.RK45),
        ("DOP853", scipy.integrate.DOP853),
        ("RK23", scipy.integrate.RK23),
    )
}
"""The ``solve_ivp`` solver class of each scipy method name (made once: each counts its steps
against the budget passed as the option ``budget``)."""
