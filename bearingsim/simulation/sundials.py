"""CVODES and IDAS through CasADi, on compiled kernels, with the set-up paid once.

What a run costs besides the integration itself, and where it is paid:

1. the kernel (right-hand side or DAE residual with its exact Jacobian, generated C or the VM):
   once per system and form (:func:`~bearingsim.simulation.kernels.kernel`); a library
   once per machine (content hash);
2. the integrator (``casadi.integrator`` on an MX oracle that calls the kernel, with the inputs
   ``u(t, q)`` composed around the call): once per system, form, input structure, method,
   tolerances, linear solver and *normalized* output grid (:class:`IntegratorCache`).

CasADi fixes ``t0`` and the output times of an integrator when it is built. The oracle is
therefore written in normalized time ``tau`` in [0, 1], ``t = t0 + T tau`` with ``t0`` and
``T = t1 - t0`` appended to the integrator's parameter vector (and so are the lifted input
numbers ``q``, :class:`~bearingsim.simulation.inputs.InputSignal`): runs that differ in start
time, length, parameters, constant inputs or table values, with the same number of equally
spaced output points, reuse one integrator. Stepping a one-interval integrator over the grid
instead would restart the BDF method (order 1, tiny steps) at every output point.

The Jacobian CVODES and IDAS factorize is the kernel's own (``casadi.external`` calls the
generated ``jac_<name>``); CasADi's MX differentiation of the oracle multiplies it by its
seed matrix, in one sweep when the number of directions is at most ``max_num_dir``
(:data:`MAX_NUM_DIR`; with CasADi's default 64 the 76-state model called the Jacobian twice per
evaluation).

The states CVODES integrates are ordered for the linear solver: with the sparse LU
(``csparse``, which factorizes in the order it is given) they are permuted into a
minimum-degree order of the Jacobian's pattern
(:func:`~bearingsim.simulation.ordering.fill_reducing_order`), so that each
ball's states come before the ring and cage states they couple to and the factors keep the
Jacobian's sparsity instead of filling in; the permutation is applied around the integrator
call, and callers see the system's order.

A progress bar observes the run, it never changes it: every run is one integrator call. With
a bar (``progress=True``, or ``None`` with standard error a terminal) the integrator's oracle
subtracts the output of :class:`_Clock` from the right-hand side: a CasADi callback that
records the normalized time of each evaluation, moves the bar now and then, and returns exactly
``0.0``. ``x - 0.0 == x`` for every float (``-0.0`` included), so the run with a bar takes the
same steps and gives the same numbers bit for bit as the run without, on a terminal or piped, on
a fast or a slow machine (``tests/simulation/test_progress.py``). The callback costs a Python
call per
evaluation (``python -m bench.sundials_compiled progress``).
"""

from __future__ import annotations

import _signal
import atexit
import contextlib
import functools
import io
import math
import os
import signal
import sys
import tempfile
import threading
import time
import weakref
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import BudgetExceededError, ParameterError, SimulationError
from bearingsim.simulation.budget import RunBudget
from bearingsim.simulation.diagnostics import diverged
from bearingsim.simulation.fastcall import evaluate, mapped_function
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.kernels import Kernel
from bearingsim.simulation.ordering import fill_reducing_order
from bearingsim.simulation.progress import progress_bar, shows_progress

__all__ = ["LINEAR_SOLVERS", "SundialsRun", "choose_linear_solver", "clear_integrator_cache",
           "observe_at", "sundials_run"]

LINEAR_SOLVERS = ("lapacklu", "mumps", "csparse", "qr", "lapackqr")
"""CasADi linear solver plugins for CVODES and IDAS (``linear_solver``): dense LAPACK LU and QR,
MUMPS (sparse multifrontal), sparse LU (CSparse) and CasADi's own sparse QR (CasADi's
default). Left out: ``ldl`` (symmetric matrices only: CVODES fails to start), ``ma27`` (needs
an HSL library the casadi wheel does not ship)."""

DENSE_LIMIT = 200
"""Largest Newton matrix (states + algebraic states) that :func:`choose_linear_solver` gives
dense LAPACK LU; above it a sparse LU is faster on the ball-level models (the nested
double-layer bearing: ``bench/sundials_compiled.py``, ``linsol``; at the 76 states of the 6304
massive-ball model dense LU and the ordered sparse LU are even)."""

MAX_NUM_DIR = 1024
"""Directions per sweep when CasADi differentiates the oracle (all colours of the Jacobian's
sparsity in one call of the kernel Jacobian)."""


def choose_linear_solver(n: int, nnz: int, form: str = "ode") -> str:
    """Linear solver for an ``n x n`` Newton matrix with ``nnz`` structural non-zeros.

    Dense LAPACK LU up to :data:`DENSE_LIMIT` unknowns or above 30 % fill; above, the sparse
    LU (CSparse) on the states in a fill-reducing order for CVODES (``form="ode"``), MUMPS
    (which orders by itself) for the DAE form when the casadi build has it. CasADi's QR is
    never chosen, nor CSparse in the system's own order: the rows and columns of the rings and
    cages couple every ball, and their fill-in makes them slower than dense LU from 100
    unknowns on (``bench/sundials_compiled.py``, ``linsol``).

    Parameters
    ----------
    n : int
        Unknowns of the Newton matrix (>= 0).
    nnz : int
        Its structural non-zeros (0 to ``n**2``).
    form : {"ode", "dae"}
        The integrator's form (CVODES or IDAS).

    Returns
    -------
    str
        ``"lapacklu"``, ``"csparse"`` or ``"mumps"`` (one of :data:`LINEAR_SOLVERS`).
    """
    if n <= DENSE_LIMIT or nnz > 0.3 * n * n:
        return "lapacklu"
    if form == "ode":
        return "csparse"
    return "mumps" if ca.has_linsol("mumps") else "lapacklu"


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


@dataclass
class _Built:
    integrator: ca.Function
    oracle: ca.Function
    build_time: float
    order: np.ndarray | None = None
    """The integrator's state order (``x_integrator = x[order]``), or None: the system's."""

    def to_integrator(self, x: np.ndarray) -> np.ndarray:
        """States (one column per time, or a vector) in the integrator's order."""
        return x if self.order is None else x[self.order]

    def from_integrator(self, x: np.ndarray) -> np.ndarray:
        """States from the integrator's order back to the system's."""
        return x if self.order is None else x[np.argsort(self.order)]


class IntegratorCache:
    """Integrators of one process, per system (dropped with the system) and set-up key."""

    def __init__(self) -> None:
        self._by_system: dict[int, dict[tuple, _Built]] = {}
        self._lock = threading.Lock()

    def get(self, system: System, key: tuple) -> _Built | None:
        """The integrator built for ``key``, if any.

        Parameters
        ----------
        system : System
            The closed system.
        key : tuple
            The integrator's settings.

        Returns
        -------
        _Built or None
            The kept integrator, None if there is none.
        """
        with self._lock:
            return self._by_system.get(id(system), {}).get(key)

    def put(self, system: System, key: tuple, built: _Built) -> None:
        """Keep ``built`` for later runs with ``key``.

        Parameters
        ----------
        system : System
            The closed system (its integrators are dropped with it).
        key : tuple
            The integrator's settings.
        built : _Built
            The integrator.
        """
        with self._lock:
            per = self._by_system.get(id(system))
            if per is None:
                per = self._by_system[id(system)] = {}
                weakref.finalize(system, self._drop, id(system))
            per[key] = built

    def _drop(self, system_id: int) -> None:
        with self._lock, _quiet_stdout():
            self._by_system.pop(system_id, None)

    def clear(self) -> None:
        """Forget every integrator."""
        with self._lock, _quiet_stdout():
            self._by_system.clear()


@contextlib.contextmanager
def _quiet_stdout() -> Iterator[None]:
    """Send the process's standard output (file descriptor 1) to the null device: MUMPS prints
    a banner on standard output when CasADi destroys one of its solvers, and has no option
    against it (CasADi's MUMPS interface sets none)."""
    try:
        sys.stdout.flush()
        saved = os.dup(1)
    except (OSError, ValueError, AttributeError):  # no standard output to protect
        yield
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(devnull)


class _Stop(Exception):
    """Raised by a run's clock observer to end the integrator call (the budget is spent)."""


@contextlib.contextmanager
def _held_stderr(hold: bool, drop: Any) -> Iterator[None]:
    """With ``hold``, send the process's standard error (file descriptor 2, and Python's
    ``sys.stderr``) aside while the context lasts, then copy it to standard error unless
    ``drop()`` is true:
    a run its budget stopped ends in a failed evaluation, which the Python layer, CasADi and
    SUNDIALS each report on standard error; the budget's own error says what happened.

    Parameters
    ----------
    hold : bool
        Whether to hold standard error at all.
    drop : callable
        Called at the end: true discards what was held.
    """
    if not hold:
        yield
        return
    try:
        sys.stderr.flush()
        saved = os.dup(2)
    except (OSError, ValueError, AttributeError):  # no standard error to hold
        yield
        return
    python_level = io.StringIO()  # Python's own reports go to sys.stderr, not always fd 2
    with tempfile.TemporaryFile() as held, contextlib.redirect_stderr(python_level):
        os.dup2(held.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            if not drop():
                held.seek(0)
                text = held.read()
                if text:
                    os.write(2, text)
    if not drop() and python_level.getvalue():
        sys.stderr.write(python_level.getvalue())


_INTEGRATORS = IntegratorCache()
_MUMPS_USED = threading.Event()


def _discard_native_stdout_at_exit() -> None:
    """After a process used MUMPS: at exit, flush Python's standard output, then destroy the
    integrators and send what native code still writes to file descriptor 1 (the MUMPS banner,
    buffered by the Fortran runtime until the process ends) to the null device."""
    if not _MUMPS_USED.is_set():
        return
    _INTEGRATORS.clear()
    try:
        sys.stdout.flush()
        os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    except (OSError, ValueError, AttributeError):
        pass


atexit.register(_discard_native_stdout_at_exit)


def clear_integrator_cache() -> None:
    """Forget every integrator built in this process."""
    _INTEGRATORS.clear()


def _normalized_grid(t0: float, t1: float, t_out: np.ndarray) -> tuple[np.ndarray, tuple]:
    """Output times in ``tau = (t - t0) / (t1 - t0)`` and their cache key: ``("linspace", n)``
    for equally spaced times ending at ``t1`` (then exactly ``linspace(0, 1, n)[1:]``), else
    the bytes of ``tau``."""
    tau = (t_out - t0) / (t1 - t0)
    n = tau.size
    even = _even_grid(n)
    if np.max(np.abs(tau - even)) <= 1e-12:
        return even, ("linspace", n)
    return tau, ("grid", tau.tobytes())


@functools.lru_cache(maxsize=64)
def _even_grid(n: int) -> np.ndarray:
    """``linspace(0, 1, n + 1)[1:]``, made once per ``n`` (read-only)."""
    even = np.linspace(0.0, 1.0, n + 1)[1:]
    even.flags.writeable = False
    return even


class _Clock(ca.Callback):
    """Observer of a run's progress inside the integrator's oracle: records the normalized time
    ``tau`` of every right-hand-side evaluation, passes it to the calling thread's
    :attr:`observer` every :data:`CLOCK_EVERY` evaluations, and returns exactly ``0.0`` (which
    the oracle subtracts: the integration is unchanged bit for bit). An observer that raises
    fails the evaluation, which ends the integrator call."""

    def __init__(self) -> None:
        ca.Callback.__init__(self)
        self._local = threading.local()
        self.construct("progress_clock", {})

    def get_n_in(self) -> int:
        return 1

    def get_n_out(self) -> int:
        return 1

    def has_eval_buffer(self) -> bool:
        return True

    def eval_buffer(self, arg, res) -> int:
        res[0].cast("d")[0] = 0.0
        local = self._local
        local.calls = getattr(local, "calls", 0) + 1
        observer = getattr(local, "observer", None)
        if observer is not None and local.calls % CLOCK_EVERY == 0:
            observer(arg[0].cast("d")[0])
        return 0

    @contextlib.contextmanager
    def observing(self, observer: Any) -> Iterator[None]:
        """Call ``observer(tau)`` from this thread's evaluations while the context lasts (an
        exception it raises stops the run)."""
        self._local.observer, self._local.calls = observer, 0
        try:
            yield
        finally:
            self._local.observer = None


CLOCK_EVERY = 16
"""Right-hand-side evaluations between two calls of a run's progress observer."""

_CLOCK = _Clock()


def _oracle(kernel: Kernel, signal: InputSignal, n_x: int, n_p: int,
            order: np.ndarray | None = None, observed: bool = False) -> ca.Function:
    """The DAE in normalized time: ``dx/dtau = T f(t0 + T tau, x, [z,] u(t0 + T tau, q), p)``,
    ``0 = g(...)``; integrator parameters ``[p, q, t0, T]``; with ``order``, in the states
    ``x[order]``; ``observed``: minus the progress clock's ``0.0`` (:class:`_Clock`)."""
    tau, x_int = ca.MX.sym("t"), ca.MX.sym("x", n_x)
    x = x_int if order is None else x_int[[int(i) for i in np.argsort(order)]]
    n_q = signal.q.size
    pp = ca.MX.sym("p", n_p + n_q + 2)
    p, q, t0, span = pp[:n_p], pp[n_p:n_p + n_q], pp[n_p + n_q], pp[n_p + n_q + 1]
    t = t0 + span * tau
    u = signal.u(t, q)
    fn = kernel.function
    if kernel.form == "dae":
        z = ca.MX.sym("z", fn.size1_in(2))
        ode, alg = fn(t, x, z, u, p)
    else:
        z = ca.MX(0, 1)
        ode, alg = fn(t, x, u, p), ca.MX(0, 1)
    if order is not None:
        ode = ode[[int(i) for i in order]]
    rate = ca.densify(span * ode)  # a structurally zero derivative is a stored 0 for SUNDIALS
    if observed:
        rate = rate - _CLOCK(tau)
    return ca.Function("dae", [tau, x_int, z, pp, ca.MX(0, 1)],
                       [rate, ca.densify(alg), ca.MX(0, 1), ca.MX(0, 1)],
                       ["t", "x", "z", "p", "u"], ["ode", "alg", "quad", "zero"],
                       {"max_num_dir": MAX_NUM_DIR})


_SIZES: dict[int, tuple[Kernel, tuple[int, int]]] = {}
""":func:`_jacobian_size` by ``id(kernel)``, the kernel kept so that its id stays unique."""


def _jacobian_size(kernel: Kernel, n_x: int) -> tuple[int, int]:
    """(unknowns, structural non-zeros) of the Newton matrix ``I - gamma J`` (found once per
    kernel)."""
    found = _SIZES.get(id(kernel))
    if found is not None and found[0] is kernel:
        return found[1]
    if len(_SIZES) >= 256:
        del _SIZES[next(iter(_SIZES))]
    size = _SIZES[id(kernel)] = (kernel, _count_jacobian(kernel, n_x))
    return size[1]


def _count_jacobian(kernel: Kernel, n_x: int) -> tuple[int, int]:
    """:func:`_jacobian_size` without the memory."""
    jac = kernel.function.jacobian()
    names = jac.name_out()
    blocks = ["jac_ode_x"] + (["jac_ode_z", "jac_alg_x", "jac_alg_z"]
                              if kernel.form == "dae" else [])
    nnz = sum(jac.sparsity_out(names.index(b)).nnz() for b in blocks) + n_x
    n = n_x + (kernel.function.size1_in(2) if kernel.form == "dae" else 0)
    return n, nnz


def _state_order(kernel: Kernel, linear_solver: str) -> np.ndarray | None:
    """The integrator's state order: fill-reducing for CSparse on the ODE form, else None."""
    if linear_solver != "csparse" or kernel.form != "ode":
        return None
    jac = kernel.function.jacobian()
    return fill_reducing_order(jac.sparsity_out(jac.name_out().index("jac_ode_x")))


def _integrator(method: str, system: System, kernel: Kernel, signal: InputSignal, n_p: int,
                tau: np.ndarray, grid_key: tuple, opts: dict[str, Any],
                observed: bool) -> tuple[_Built, bool]:
    """The integrator of a run (from the cache or built now) and whether it was cached."""
    # the kernel by what it evaluates (kernels are rebuilt after clear_kernel_cache)
    kernel_key = (kernel.form, kernel.backend, str(kernel.library))
    key = (method, kernel_key, signal.key, grid_key, observed,
           tuple(sorted((k, repr(v)) for k, v in opts.items())))
    built = _INTEGRATORS.get(system, key)
    if built is not None:
        return built, True
    start = time.perf_counter()
    order = _state_order(kernel, opts["linear_solver"])
    oracle = _oracle(kernel, signal, system.n_states, n_p, order, observed)
    integ = ca.integrator(f"{method}_{kernel.form}", method, oracle, 0.0, tau, opts)
    built = _Built(integ, oracle, time.perf_counter() - start, order)
    if opts["linear_solver"] == "mumps":
        _MUMPS_USED.set()
    _INTEGRATORS.put(system, key, built)
    return built, False


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
        in the oracle (:class:`_Clock`); the run is one integrator call either way, with the
        same numbers bit for bit.
    budget : RunBudget, optional
        The run's budget (:mod:`~bearingsim.simulation.budget`): its ``max_steps`` is
        ``max_num_steps`` of the integrator call (default 100000); its ``timeout`` is
        checked by the progress clock (:class:`_Clock`, which the oracle then has: about
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
    t_out = t_eval[t_eval > t0]
    n_x = system.n_states
    if linear_solver is None:
        linear_solver = choose_linear_solver(*_jacobian_size(kernel, n_x), kernel.form)
    base: dict[str, Any] = {"abstol": atol, "reltol": rtol,
                            "max_num_steps": budget.max_steps if budget else 100000,
                            "linear_solver": linear_solver, **(options or {})}
    span = t1 - t0
    tau, grid_key = _normalized_grid(t0, t1, t_out)
    opts = dict(base)
    if np.isfinite(max_step):
        opts["max_step_size"] = float(max_step) / span
    timed = budget is not None and budget.timeout is not None
    observed = shows_progress(progress) or timed
    built, cached = _integrator(method, system, kernel, signal, p.size, tau, grid_key, opts,
                                observed)
    p_ext = np.concatenate([p, signal.q, [t0, span]])
    args = {"x0": built.to_integrator(np.asarray(x0, dtype=float)), "p": p_ext}
    if kernel.form == "dae":
        args["z0"] = z0
    bar = progress_bar(t0, t1, progress)
    reached = [0.0]
    stopped: list[BudgetExceededError] = []

    def observe(tau_now: float) -> None:
        if bar is not None and tau_now > reached[0]:
            bar.update(span * (min(tau_now, 1.0) - reached[0]))
            reached[0] = min(tau_now, 1.0)
        if timed:
            try:  # the wall-time budget, checked as the clock ticks (no steps counted)
                budget.step(t0 + span * min(tau_now, 1.0), 0)
            except BudgetExceededError as exc:
                stopped.append(exc)
                raise _Stop from None  # fails the evaluation: the integrator call returns

    called = time.thread_time()
    try:
        with _interrupts() as interrupted, (_CLOCK.observing(observe) if observed
                                            else contextlib.nullcontext()), \
                _held_stderr(timed and bar is None, lambda: bool(stopped)):
            out = built.integrator(**args)
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
    starts = bool(t_eval[0] <= t0)  # the start values are the first output
    reached = out["xf"].nonzeros()
    xs = built.from_integrator(_dense(reached, n_x, tau.size, args["x0"] if starts else None))
    if not _all_finite(reached):
        k = int(np.argmax(~np.isfinite(xs[:, 1:] if starts else xs).all(axis=0)))
        raise SimulationError(
            f"{method.upper()} produced non-finite states by t = {t_out[k]:.6g} s; "
            f"{diverged(system, xs[:, k + starts], x0)}")
    zs = (_dense(out["zf"].nonzeros(), z0.size, tau.size,
                 np.asarray(z0, dtype=float) if starts else None)
          if kernel.form == "dae" else None)
    ts = np.concatenate(([t0], t_out)) if starts else t_out
    values = observe_at(kernel, signal, p, ts, xs, zs)
    stats = _stats(method, kernel, linear_solver, 0.0 if cached else built.build_time, cached,
                   built.integrator.stats())
    stats["progress_observed"] = observed
    stats["integrate_cpu_time"] = integrate_cpu_time
    stats["state_order"] = "system" if built.order is None else "minimum degree"
    return SundialsRun(ts, xs, zs, values, stats)


def _dense(nonzeros: list[float], rows: int, cols: int, first: np.ndarray | None = None
           ) -> np.ndarray:
    """A dense integrator output as a ``rows x cols`` array, from its nonzeros (``DM.nonzeros``,
    column-major; half the cost of ``DM.full``); with ``first``, that column before them
    (``cols + 1`` columns, in one array)."""
    if first is not None:
        nonzeros, cols = first.tolist() + nonzeros, cols + 1
    return np.array(nonzeros, dtype=float).reshape(rows, cols, order="F")


def _all_finite(values: list[float]) -> bool:
    """Whether every number is finite: their sum is (one pass in C), else each one is (finite
    numbers may sum to inf)."""
    return math.isfinite(sum(values)) or all(map(math.isfinite, values))


class _Interrupted:
    """Whether Ctrl-C came during a run (set from the SIGINT handler, in the main thread)."""

    __slots__ = ("value",)

    def __init__(self) -> None:
        self.value = False

    def is_set(self) -> bool:
        return self.value


@contextlib.contextmanager
def _interrupts() -> Iterator[_Interrupted]:
    """Record Ctrl-C (SIGINT) during a SUNDIALS run: CasADi checks for it between evaluations
    and turns it into a failed evaluation (a RuntimeError); the flag tells the two apart, so
    an interrupted run raises KeyboardInterrupt instead of being diagnosed as a failure.
    Outside the main thread (where Python delivers signals) the flag stays clear.

    The handler is swapped with ``_signal.signal``, the C function under ``signal.signal``:
    the latter's conversion of the previous handler to an enum costs tens of microseconds per
    call (a failed enum lookup for a function), a tenth of a short run's fixed cost. The
    values are the same (SIG_DFL and SIG_IGN as plain ints, which are not callable either).
    """
    flag = _Interrupted()
    if threading.current_thread() is not threading.main_thread():
        yield flag
        return

    def handler(signum, frame):
        flag.value = True
        if callable(previous):
            previous(signum, frame)
        raise KeyboardInterrupt

    previous = _signal.signal(signal.SIGINT, handler)
    try:
        yield flag
    finally:
        _signal.signal(signal.SIGINT, previous)


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
    n = ts.size
    us = signal.at(ts)
    ps = np.concatenate((p,) * n)  # one column per time, column-major
    args = (ts[None, :], xs, us, ps) if zs is None else (ts[None, :], xs, zs, us, ps)
    return evaluate(mapped_function(kernel.observe, n), *args)[0]


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


def _locate_failure(method: str, system: System, built: _Built, opts: dict, p_ext: np.ndarray,
                    x_start: np.ndarray, z_start: np.ndarray | None, x0: np.ndarray, t0: float,
                    span: float, tau: np.ndarray, exc: RuntimeError,
                    budget: RunBudget | None = None) -> None:
    """Integrate the failed call interval by interval, from ``x_start`` (and ``z_start``) at
    ``t0`` [s], to report where it failed; ``x0`` is the run's start state, which the states
    reached are compared with (failure path only). An interval that used up the step budget
    (SUNDIALS' ``max_num_steps``, "TOO_MUCH_WORK") raises the ``budget``'s error."""
    with _quiet_stdout():
        _locate(method, system, built, opts, p_ext, x_start, z_start, x0, t0, span, tau, exc,
                budget)


def _locate(method: str, system: System, built: _Built, opts: dict, p_ext: np.ndarray,
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
            raise SimulationError(
                f"{method.upper()} failed between t = {a:.6g} s and {b:.6g} s; states at "
                f"t = {a:.6g} s: {diverged(system, x, x0)}"
            ) from None
        x, tau_prev = x_new, float(tau_next)
    raise SimulationError(f"{method.upper()} failed ({str(exc).splitlines()[0]}; not "
                          "reproducible interval by interval)")
