"""Integrator backends behind one small interface, and the table of methods by name.

An :class:`Integrator` takes an :class:`IntegrationProblem` (a closed system, parameters, start
state, time span, output times, tolerances) and returns a :class:`Trajectory`. Contract for
subclasses:

1. set ``name`` (the ``method`` a user passes to :func:`~bearingsim.simulation.simulate`) and
   ``backend`` (``"scipy"``, ``"casadi"`` or ``"compiled"``);
2. implement :meth:`Integrator.run`: the states at every output time in ``problem.t_eval``
   (``t_eval[0]`` may equal ``t0``), and, where the integrator computes them itself, the observed
   variables at those times (else ``None``; :func:`~bearingsim.simulation.simulate` evaluates
   them);
3. on failure raise :class:`~bearingsim.errors.SimulationError` naming the time reached and the
   states that diverged (:func:`~bearingsim.simulation.diagnostics.diverged`).

:data:`METHODS` maps every method name to its integrator; scenes and the command line read it.
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation.budget import RunBudget
from bearingsim.simulation.closed import ClosedModel
from bearingsim.simulation.compiled_bdf import compiled_bdf_run
from bearingsim.simulation.diagnostics import diverged, evaluation_failure
from bearingsim.simulation.fastcall import buffered_function
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.kernels import kernel
from bearingsim.simulation.native_streams import casadi_dumps_dropped
from bearingsim.simulation.progress import progress_bar
from bearingsim.simulation.sundials import sundials_run

__all__ = [
    "BACKENDS",
    "METHODS",
    "CompiledIntegrator",
    "IntegrationProblem",
    "Integrator",
    "ScipyIntegrator",
    "SundialsIntegrator",
    "Trajectory",
    "methods_of",
]


@dataclass(frozen=True)
class IntegrationProblem:
    """Everything an integrator needs for one run."""

    system: System
    closed: ClosedModel | None
    """The system with its inputs bound (numeric functions; built for scipy's methods)."""
    inputs: dict[str, Any] | None
    """The user's input specification (for integrators that close the inputs themselves)."""
    p: np.ndarray
    """Parameter vector."""
    x0: np.ndarray
    """Consistent start state at ``t0``."""
    t0: float
    """Start time [s]."""
    t1: float
    """End time [s]."""
    t_eval: np.ndarray
    """Output times [s], increasing, within ``[t0, t1]``."""
    rtol: float
    """Relative tolerance [-]."""
    atol: float
    """Absolute tolerance [state units]."""
    max_step: float
    """Largest step [s] (``inf``: no limit)."""
    progress: bool | None
    """Progress bar: on, off, or (None) on a terminal for runs longer than about 2 s
    (:mod:`~bearingsim.simulation.progress`)."""
    signal: InputSignal
    """The inputs as ``u(t, q)`` with the run's numbers lifted out (SUNDIALS builds on it)."""
    compiled: bool | str = "auto"
    """Evaluation backend of the SUNDIALS kernels (True, False or "auto")."""
    linear_solver: str | None = None
    """SUNDIALS linear solver (None: by size)."""
    budget: RunBudget | None = None
    """Step and wall-time budget (None: the default step budget, no time limit)."""


@dataclass
class Trajectory:
    """What an integrator returns."""

    t: np.ndarray
    """Output times [s]."""
    x: np.ndarray
    """States, one column per output time."""
    values: np.ndarray | None
    """Observed variables, one column per output time, if the integrator computed them."""
    stats: dict[str, Any]
    """Solver statistics (``method`` and counts)."""


class Integrator(ABC):
    """Base class of the integrator backends (contract in the module docstring)."""

    name: str
    backend: str

    @abstractmethod
    def run(self, problem: IntegrationProblem) -> Trajectory:
        """Integrate ``problem`` and return the trajectory at its output times.

        Parameters
        ----------
        problem : IntegrationProblem
            The closed system, its start state, time span, output times and options.

        Returns
        -------
        Trajectory
            States (and algebraic variables) at the output times, with the run's statistics.
        """


class ScipyIntegrator(Integrator):
    """scipy's ``solve_ivp``; the implicit methods get the exact sparse Jacobian. BDF runs
    with :func:`~bearingsim.simulation.scipy_solvers.bdf_newton`'s Newton iteration; every
    method counts its steps against the run's
    :class:`~bearingsim.simulation.budget.RunBudget`.

    Parameters
    ----------
    name : str
        ``solve_ivp`` method: "BDF", "Radau", "LSODA" (implicit) or "RK45", "DOP853", "RK23".
    implicit : bool
        Whether the method uses the Jacobian (LSODA gets it dense).
    """

    backend = "scipy"

    def __init__(self, name: str, implicit: bool):
        self.name = name
        self.implicit = implicit

    def run(self, problem: IntegrationProblem) -> Trajectory:
        """Integrate with ``solve_ivp`` (see :class:`Integrator`).

        Parameters
        ----------
        problem : IntegrationProblem
            The closed system, its start state, time span, output times and options.

        Returns
        -------
        Trajectory
            States (and algebraic variables) at the output times, with the run's statistics.
        """
        # on use: scipy.integrate (with scipy.optimize) takes ~0.6 s to import
        import scipy.integrate

        from bearingsim.simulation.scipy_solvers import SCIPY_SOLVERS

        pb, system = problem, problem.system
        f, jac = buffered_function(pb.closed.f), buffered_function(pb.closed.jac)
        n_f = [0]
        bar = progress_bar(pb.t0, pb.t1, pb.progress)
        last = [pb.t0, pb.x0]

        def fun(t, x):
            n_f[0] += 1
            out = f.vector(t, x, pb.p)
            if not np.all(np.isfinite(out)):
                bad = [n for n, v in zip(system.state_names, out, strict=True)
                       if not np.isfinite(v)]
                raise SimulationError(
                    f"the right-hand side is not finite at t = {t:.6g} s for "
                    f"der({', '.join(bad[:8])}); states there: {diverged(system, x, pb.x0)}"
                )
            if t > last[0]:
                if bar is not None:
                    bar.update(t - last[0])
                last[0] = t
            last[1] = x
            return out

        kwargs: dict[str, Any] = {}
        if self.implicit:
            def jacobian(t, x):
                matrix = jac.sparse(t, x, pb.p)
                return matrix.toarray() if self.name == "LSODA" else matrix
            kwargs["jac"] = jacobian
        called = time.thread_time()
        budget = pb.budget or RunBudget(method=self.name, t_end=pb.t1)
        try:
            with casadi_dumps_dropped():
                sol = scipy.integrate.solve_ivp(
                    fun, (pb.t0, pb.t1), pb.x0, method=SCIPY_SOLVERS[self.name],
                    t_eval=pb.t_eval, rtol=pb.rtol, atol=pb.atol, max_step=pb.max_step,
                    budget=budget, **kwargs,
                )
        except (ArithmeticError, ValueError, RuntimeError, np.linalg.LinAlgError) as exc:
            if isinstance(exc, SimulationError):
                raise
            what = evaluation_failure(exc) if isinstance(exc, RuntimeError) else \
                f"{type(exc).__name__}: {exc}"
            raise SimulationError(
                f"{self.name} failed near t = {last[0]:.6g} s of {pb.t1:g} s ({what}); "
                f"{diverged(system, last[1], pb.x0)}"
            ) from None
        finally:
            if bar is not None:
                bar.close()
        if sol.status < 0:
            # with t_eval, scipy leaves sol.t an empty list when no output time was reached
            times = np.asarray(sol.t, dtype=float)
            t_reached = max(last[0], times[-1] if times.size else pb.t0)
            raise SimulationError(
                f"{self.name} failed at t = {t_reached:.6g} s of {pb.t1:g} s: {sol.message}; "
                f"{diverged(system, last[1], pb.x0)}"
            )
        stats = {"method": self.name, "nfev": sol.nfev, "njev": sol.njev, "nlu": sol.nlu,
                 "n_rhs_calls": n_f[0], "n_steps": budget.steps,
                 "integrate_cpu_time": time.thread_time() - called}
        return Trajectory(sol.t, sol.y, None, stats)


class SundialsIntegrator(Integrator):
    """SUNDIALS CVODES or IDAS through CasADi (:mod:`~bearingsim.simulation.sundials`) on the
    system's compiled (or VM) kernels, with kernels and integrators cached.

    IDAS on a system with nonlinear blocks integrates the semi-explicit DAE form instead
    (``dae_ode``, ``dae_alg``): the blocks' tearing variables become algebraic states that IDAS
    iterates on, warm-started from step to step; that form is pure SX and compiles whatever
    rootfinder the blocks use.

    Parameters
    ----------
    name : {"cvodes", "idas"}
        CasADi integrator plugin.
    """

    backend = "casadi"

    def __init__(self, name: str):
        self.name = name

    def run(self, problem: IntegrationProblem) -> Trajectory:
        """Integrate with CVODES or IDAS (see :class:`Integrator`).

        Parameters
        ----------
        problem : IntegrationProblem
            The closed system, its start state, time span, output times and options.

        Returns
        -------
        Trajectory
            States (and algebraic variables) at the output times, with the run's statistics.
        """
        pb, system = problem, problem.system
        form = "dae" if self.name == "idas" and "dae_ode" in system.functions else "ode"
        start = time.perf_counter()
        kern = kernel(system, form, pb.compiled)
        kernel_time = time.perf_counter() - start
        z0 = None
        if form == "dae":
            funcs = system.symbolic_functions or system.functions
            u0 = np.asarray(pb.signal.u(pb.t0, pb.signal.q), dtype=float).ravel()
            z0 = np.asarray(funcs["dae_z"](pb.t0, pb.x0, u0, pb.p), dtype=float).ravel()
        run = sundials_run(self.name, system, kern, pb.signal, pb.p, pb.x0, pb.t0, pb.t1,
                           pb.t_eval, pb.rtol, pb.atol, pb.max_step, pb.linear_solver, z0,
                           progress=pb.progress, budget=pb.budget)
        return Trajectory(run.t, run.x, run.values, {**run.stats, "kernel_time": kernel_time})


class CompiledIntegrator(Integrator):
    """The BDF step loop in C on the compiled ODE kernel
    (:mod:`~bearingsim.simulation.compiled_bdf`): no interpreter between the steps.

    ``compiled=False`` is refused (the method is compiled C); ``"auto"`` compiles the kernel
    now if it is not cached, as ``True`` does.
    """

    backend = "compiled"
    name = "compiled_bdf"

    def run(self, problem: IntegrationProblem) -> Trajectory:
        """Integrate with the compiled BDF (see :class:`Integrator`).

        Parameters
        ----------
        problem : IntegrationProblem
            The closed system, its start state, time span, output times and options.

        Returns
        -------
        Trajectory
            States (and algebraic variables) at the output times, with the run's statistics.
        """
        pb, system = problem, problem.system
        if pb.compiled is False:
            raise ParameterError(
                "simulate: method 'compiled_bdf' runs compiled C only; compiled=False asks for "
                "CasADi's VM (use method='cvodes' for that)")
        start = time.perf_counter()
        kern = kernel(system, "ode", True)
        kernel_time = time.perf_counter() - start
        run = compiled_bdf_run(system, kern, pb.signal, pb.p, pb.x0, pb.t0, pb.t1, pb.t_eval,
                               pb.rtol, pb.atol, pb.max_step, pb.progress,
                               budget=pb.budget)
        stats = {"method": self.name, "form": "ode", **kern.describe(),
                 "linear_solver": "sparse-skipping LU, fill-reducing order", **run.stats,
                 "kernel_time": kernel_time}
        return Trajectory(run.t, run.x, run.values, stats)


METHODS: dict[str, Integrator] = {
    m.name: m for m in (
        ScipyIntegrator("BDF", implicit=True),
        ScipyIntegrator("Radau", implicit=True),
        ScipyIntegrator("LSODA", implicit=True),
        ScipyIntegrator("RK45", implicit=False),
        ScipyIntegrator("DOP853", implicit=False),
        ScipyIntegrator("RK23", implicit=False),
        SundialsIntegrator("cvodes"),
        SundialsIntegrator("idas"),
        CompiledIntegrator(),
    )
}
"""Every integration method by the name :func:`~bearingsim.simulation.simulate` takes."""

BACKENDS: dict[str, str] = {"scipy": "BDF", "casadi": "cvodes", "compiled": "compiled_bdf"}
"""Integrator families and their default methods."""


def methods_of(backend: str) -> tuple[str, ...]:
    """Names of the methods of one backend, in :data:`METHODS` order.

    Parameters
    ----------
    backend : {"scipy", "casadi", "compiled"}
        The integrator family (a key of :data:`BACKENDS`).

    Returns
    -------
    tuple of str
        Its method names.
    """
    return _METHODS_OF.get(backend, ())


_METHODS_OF = {b: tuple(name for name, m in METHODS.items() if m.backend == b) for b in BACKENDS}
"""The method names of every backend, in :data:`METHODS` order (:func:`methods_of`)."""
