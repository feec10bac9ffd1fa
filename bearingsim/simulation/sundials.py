"""CVODES and IDAS through CasADi, on compiled kernels, with the set-up paid once: one run.

What a run costs besides the integration itself, and where it is paid:

1. the kernel (right-hand side or DAE residual with its exact Jacobian, generated C or the VM):
   once per system and form (:func:`~bearingsim.simulation.kernels.kernel`); a library
   once per machine (content hash);
2. the integrator (``casadi.integrator`` on an MX oracle that calls the kernel, with the inputs
   ``u(t, q)`` composed around the call): once per system, form, input structure, method,
   tolerances, linear solver and *normalized* output grid
   (:mod:`~bearingsim.simulation.sundials_integrators`, which builds and keeps them).

:func:`sundials_run` integrates with a kept integrator in one call, observes the outputs and
reports the counts; a failed call is integrated again interval by interval to say where it
failed, and a spent wall-time budget ends the call through the progress clock.
"""

from __future__ import annotations

import contextlib
import math
import time
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import BudgetExceededError, ParameterError, SimulationError
from bearingsim.simulation.budget import RunBudget
from bearingsim.simulation.diagnostics import diverged, sundials_failure
from bearingsim.simulation.fastcall import columns_call
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.kernels import Kernel
from bearingsim.simulation.native_streams import held_stderr, interrupts, quiet_stdout
from bearingsim.simulation.progress import progress_bar, shows_progress
from bearingsim.simulation.sundials_integrators import (
    CLOCK,
    LINEAR_SOLVERS,
    Built,
    build_integrator,
    choose_linear_solver,
    jacobian_size,
    normalized_grid,
)

__all__ = ["SundialsRun", "observe_at", "sundials_run"]


@dataclass(frozen=True)
class SundialsRun:
    """The outcome of :func:`sundials_run`.

    Attributes
    ----------
    t, x : ndarray
        Output times [s] and states (one column per time).
    z : ndarray or None
        Algebraic states (DAE form).
    values : ndarray
        Every observed variable, one column per time.
    stats : dict
        Counts, backend and set-up (see :func:`sundials_run`).
    """

    t: np.ndarray
    x: np.ndarray
    z: np.ndarray | None
    values: np.ndarray
    stats: dict[str, Any]


class _Stop(Exception):
    """Raised by a run's clock observer to end the integrator call (the budget is spent)."""


def sundials_run(method: str, system: System, kernel: Kernel, signal: InputSignal,
                 p: np.ndarray, x0: np.ndarray, t0: float, t1: float, t_eval: np.ndarray,
                 rtol: float, atol: float, max_step: float = np.inf,
                 linear_solver: str | None = None, z0: np.ndarray | None = None,
                 options: dict[str, Any] | None = None,
                 progress: bool | None = False, budget=None) -> SundialsRun:
    """Integrate with CVODES (``kernel.form == "ode"``) or IDAS (either form).

    Parameters
    ----------
    method : {"cvodes", "idas"}
    system : System
        Owner of the kernel (cache scope, names in messages).
    kernel : Kernel
        From :func:`~bearingsim.simulation.kernels.kernel`.
    signal : InputSignal
        The run's inputs.
    p : ndarray
        Parameter vector.
    x0 : ndarray
        Consistent start state at ``t0``.
    t0, t1 : float
        Time span [s].
    t_eval : ndarray
        Output times in ``[t0, t1]``, increasing (``t_eval[0]`` may equal ``t0``).
    rtol, atol : float
        Tolerances.
    max_step : float
        Largest step [s].
    linear_solver : str, optional
        One of :data:`LINEAR_SOLVERS`; default :func:`choose_linear_solver`.
    z0 : ndarray, optional
        Algebraic start values (DAE form), a guess IDAS makes consistent.
    options : dict, optional
        Further CasADi integrator options (e.g. ``newton_scheme``), part of the cache key.
    progress : bool or None
        Progress bar (:mod:`~bearingsim.simulation.progress`), moved by the progress clock
        in the oracle (:class:`Clock`); the run is one integrator call either way, with the
        same numbers bit for bit.
    budget : RunBudget, optional
        The run's budget (:mod:`~bearingsim.simulation.budget`): its ``max_steps`` is
        ``max_num_steps`` of the integrator call (default 100000); its ``timeout`` is
        checked by the progress clock (:class:`Clock`, which the oracle then has: about
        5 us per right-hand side, 10-20 % of a compiled ball-level run), every
        :data:`CLOCK_EVERY` evaluations, and stops the call.

    Returns
    -------
    SundialsRun
        ``stats``: ``method``, ``form``, ``backend`` ("compiled C" or "CasADi VM") and
        ``backend_reason``, ``library``, ``linear_solver``, ``setup_time`` [s] (building the
        integrator; 0 when it came from the cache), ``integrator_cached``,
        ``progress_observed`` (the oracle had the progress clock), ``integrate_cpu_time``
        [s] (CPU time of the integrator call alone), and CVODES/IDAS counts:
        ``nsteps``,
        ``nfevals`` (right-hand side or residual), ``njevals`` (exact Jacobian),
        ``nlinsetups`` (factorizations), ``nniters``, ``netfails``, ``rhs_time``/``jac_time``
        [s] (CasADi's timers), ``state_order`` (``"system"``, or ``"minimum
        degree"``: the order
        :func:`~bearingsim.simulation.ordering.fill_reducing_order` gave the sparse LU).
    """
    if method not in ("cvodes", "idas") or (method == "cvodes" and kernel.form != "ode"):
        raise ParameterError(f"sundials_run: method {method!r} cannot integrate the "
                             f"{kernel.form} form")
    if linear_solver is not None and linear_solver not in LINEAR_SOLVERS:
        raise ParameterError(f"linear_solver must be one of {', '.join(LINEAR_SOLVERS)}, got "
                             f"{linear_solver!r}")
    n_x = system.n_states
    if linear_solver is None:
        linear_solver = choose_linear_solver(*jacobian_size(kernel, n_x), kernel.form)
    # a failure raises with its reason: no warning per failed evaluation (hundreds of lines)
    opts: dict[str, Any] = {"abstol": atol, "reltol": rtol,
                            "max_num_steps": budget.max_steps if budget else 100000,
                            "linear_solver": linear_solver, "show_eval_warnings": False,
                            "disable_internal_warnings": True, **(options or {})}
    span = t1 - t0
    t_out, tau, grid_key = normalized_grid(t0, t1, t_eval)
    if math.isfinite(max_step):
        opts["max_step_size"] = float(max_step) / span
    timed = budget is not None and budget.timeout is not None
    observed = shows_progress(progress) or timed
    built, cached = build_integrator(method, system, kernel, signal, p.size, tau, grid_key, opts,
                                     observed)
    call = built.call()
    p_ext = np.concatenate((p, signal.q, (t0, span)))
    x_start = built.to_integrator(np.asarray(x0, dtype=float))
    starts = bool(t_eval[0] <= t0)  # the start values are the first output
    xs_run = _outputs(x_start, tau.size, starts)
    zs = None
    if kernel.form == "dae":
        z0 = np.asarray(z0, dtype=float)
        zs = _outputs(z0, tau.size, starts)
    bar = progress_bar(t0, t1, progress)
    reached = [0.0]
    stopped: list[BudgetExceededError] = []

    def observe(tau_now: float) -> None:
        tau_now = min(tau_now, 1.0)
        if tau_now > reached[0]:
            if bar is not None:
                bar.update(span * (tau_now - reached[0]))
            reached[0] = tau_now  # also the time a late failure reports against the budget
        if timed:
            try:  # the wall-time budget, checked as the clock ticks (no steps counted)
                budget.step(t0 + span * tau_now, 0)
            except BudgetExceededError as exc:
                stopped.append(exc)
                raise _Stop from None  # fails the evaluation: the integrator call returns

    xf = _after(xs_run, n_x, starts)
    zf = None if zs is None else _after(zs, z0.size, starts)
    called = time.thread_time()
    try:
        with interrupts() as interrupted, (CLOCK.observing(observe) if observed
                                            else contextlib.nullcontext()), \
                held_stderr((timed or method == "idas") and bar is None):
            call(x_start, p_ext, z0, xf, zf)
        integrate_cpu_time = time.thread_time() - called
        observe(1.0)
    except RuntimeError as exc:
        if interrupted.is_set():  # CasADi reports Ctrl-C as a failed evaluation
            raise KeyboardInterrupt(f"{method.upper()} run interrupted") from None
        if stopped:  # the wall-time budget, reported by the clock as a failed evaluation
            raise stopped[0] from None
        if timed:  # a failure once the budget is spent is reported as such, not located
            budget.step(t0 + span * reached[0], 0)
        _locate_failure(method, system, built, opts, p_ext, x0, z0, x0, t0, span, tau, exc,
                        budget)
        raise
    finally:
        if bar is not None:
            bar.close()
    xs = built.from_integrator(xs_run)
    if not _all_finite(xf):
        k = int(np.argmax(~np.isfinite(xs[:, 1:] if starts else xs).all(axis=0)))
        raise SimulationError(
            f"{method.upper()} produced non-finite states by t = {t_out[k]:.6g} s; "
            f"{diverged(system, xs[:, k + starts], x0)}")
    ts = np.concatenate(((t0,), t_out)) if starts else t_out.copy()
    values = observe_at(kernel, signal, p, ts, xs, zs)
    stats = _stats(method, kernel, linear_solver, 0.0 if cached else built.build_time, cached,
                   call.stats())
    stats["progress_observed"] = observed
    stats["integrate_cpu_time"] = integrate_cpu_time
    stats["state_order"] = "system" if built.order is None else "minimum degree"
    return SundialsRun(ts, xs, zs, values, stats)


def _outputs(start: np.ndarray, cols: int, starts: bool) -> np.ndarray:
    """A new ``rows x cols`` array (column-major) for an integrator's outputs at ``cols``
    output times; with ``starts``, one more column first, holding ``start``."""
    out = np.empty((start.size, cols + starts), order="F")
    if starts:
        out[:, 0] = start
    return out


def _after(outputs: np.ndarray, rows: int, starts: bool) -> np.ndarray:
    """The columns of ``outputs`` the integrator writes (after the start column, if any), as
    one contiguous vector viewing them."""
    return outputs.reshape(-1, order="F")[rows if starts else 0:]


def _all_finite(values: np.ndarray | list[float]) -> bool:
    """Whether every number is finite (one pass in C; no sum that finite numbers could
    overflow)."""
    return bool(np.isfinite(values).all())


def observe_at(kernel: Kernel, signal: InputSignal, p: np.ndarray, ts: np.ndarray,
               xs: np.ndarray, zs: np.ndarray | None) -> np.ndarray:
    """Every observed variable at the output times (the kernel's backend, one mapped call).

    Parameters
    ----------
    kernel : Kernel
        The run's kernel (its ``observe`` function).
    signal : InputSignal
        The run's inputs.
    p : numpy.ndarray
        Parameter vector (SI).
    ts : numpy.ndarray
        Output times [s].
    xs : numpy.ndarray
        States, one column per time.
    zs : numpy.ndarray or None
        Algebraic states, one column per time (DAE form), else None.

    Returns
    -------
    numpy.ndarray
        Observed variables, one column per time.
    """
    us = signal.at(ts)
    call = columns_call(kernel.observe, ts.size)
    if zs is None:
        return call(ts, xs, us, p, repeated=3)
    return call(ts, xs, zs, us, p, repeated=4)


def _stats(method: str, kernel: Kernel, linear_solver: str, setup_time: float, cached: bool,
           counts: dict[str, Any]) -> dict[str, Any]:
    """A run's statistics (:func:`sundials_run`), its counts and timers from the integrator
    call's ``Function.stats()``."""
    stats: dict[str, Any] = {"method": method if kernel.form == "ode" else f"{method} (dae)",
                             "form": kernel.form, **kernel.describe(),
                             "linear_solver": linear_solver, "setup_time": setup_time,
                             "integrator_cached": cached}
    for name in ("nsteps", "nfevals", "nlinsetups", "nniters", "netfails", "nncfails"):
        if name in counts:
            stats[name] = int(counts[name])
    stats["njevals"] = int(counts.get("n_call_jacF", 0))
    stats["rhs_time"] = float(counts.get("t_wall_daeF", 0.0))
    stats["jac_time"] = float(counts.get("t_wall_jacF", 0.0))
    if kernel.form == "dae":
        stats["algebraic_states"] = int(kernel.function.size1_in(2))
    return stats


def _locate_failure(method: str, system: System, built: Built, opts: dict, p_ext: np.ndarray,
                    x_start: np.ndarray, z_start: np.ndarray | None, x0: np.ndarray, t0: float,
                    span: float, tau: np.ndarray, exc: RuntimeError,
                    budget: RunBudget | None = None) -> None:
    """Integrate the failed call interval by interval, from ``x_start`` (and ``z_start``) at
    ``t0`` [s], to report where it failed; ``x0`` is the run's start state, which the states
    reached are compared with (failure path only). An interval that used up the step budget
    (SUNDIALS' ``max_num_steps``, "TOO_MUCH_WORK") raises the ``budget``'s error."""
    with quiet_stdout(), held_stderr(True):  # it raises, saying why
        _locate(method, system, built, opts, p_ext, x_start, z_start, x0, t0, span, tau, exc,
                budget)


def _locate(method: str, system: System, built: Built, opts: dict, p_ext: np.ndarray,
            x_start: np.ndarray, z_start: np.ndarray | None, x0: np.ndarray, t0: float,
            span: float, tau: np.ndarray, exc: RuntimeError,
            budget: RunBudget | None = None) -> None:
    x, z, tau_prev = np.asarray(x_start, dtype=float), z_start, 0.0
    for tau_next in tau:
        step = ca.integrator("locate", method, built.oracle, tau_prev, [float(tau_next)], opts)
        args = {"x0": built.to_integrator(x), "p": p_ext, **({"z0": z} if z is not None else {})}
        try:
            out = step(**args)
            x_new = built.from_integrator(np.asarray(out["xf"], dtype=float).ravel())
            z = np.asarray(out["zf"], dtype=float).ravel() if z is not None else None
        except RuntimeError as failed:
            if budget is not None and "TOO_MUCH_WORK" in str(failed):
                budget.step(t0 + span * tau_prev, budget.max_steps + 1 - budget.steps)
            x_new = None
        if x_new is None or not np.all(np.isfinite(x_new)):
            a, b = t0 + span * tau_prev, t0 + span * tau_next
            why = sundials_failure(exc)
            raise SimulationError(
                f"{method.upper()} failed between t = {a:.6g} s and {b:.6g} s"
                f"{': ' + why if why else ''}; states at t = {a:.6g} s: "
                f"{diverged(system, x, x0)}"
            ) from None
        x, tau_prev = x_new, float(tau_next)
    raise SimulationError(f"{method.upper()} failed ({str(exc).splitlines()[0]}; not "
                          "reproducible interval by interval)")
