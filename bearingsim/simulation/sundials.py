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

A progress bar needs the run in pieces: with a bar shown, :func:`sundials_run` makes
:data:`PROGRESS_CHUNKS` calls of equal length (equally spaced output points grouped, one cached
integrator for all of them) and moves the bar between them; without one, a single call. Each
call restarts BDF; on the 6304 massive-ball model (76 states, compiled kernels, 501 output
points; ``python -m bench.sundials_compiled chunks --cases massive``) a restart cost 1.3-1.8 ms
of CPU time and 5-6 Jacobians: 20 calls made a 20 ms start-up run (1474 steps, 0.18 s CPU)
19 % dearer (+6 % steps, +76 % Jacobians; 10 calls +11 %, 50 calls +60 %) and a 300 ms run
(12951 steps, 0.56 s CPU) 4 % dearer (+0.4 % steps, +10 % Jacobians; 10 calls +2 %). The
chunked runs were as far from a run at ``rtol = 1e-9`` as the single call (at most 742-5185
against 1479-2892 times ``rtol |x| + atol``, in the balls' ``dz``): within the run's own
accuracy. A bar appears only after :data:`~bearingsim.simulation.progress.DELAY` (2 s), so 20 calls
cost under 2 % of any run that shows one; a shorter run on a terminal (``progress=None``)
finishes in one call after the first.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import signal
import sys
import threading
import time
import weakref
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation.diagnostics import diverged
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.kernels import Kernel
from bearingsim.simulation.ordering import fill_reducing_order
from bearingsim.simulation.progress import DELAY, progress_bar

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

PROGRESS_CHUNKS = 20
"""Integrator calls of a run with a progress bar (:func:`sundials_run`); their cost is measured
in the module docstring."""

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
        """The integrator built for ``key``, if any."""
        with self._lock:
            return self._by_system.get(id(system), {}).get(key)

    def put(self, system: System, key: tuple, built: _Built) -> None:
        """Keep ``built`` for later runs with ``key``."""
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
    even = np.linspace(0.0, 1.0, n + 1)[1:]
    if np.max(np.abs(tau - even)) <= 1e-12:
        return even, ("linspace", n)
    return tau, ("grid", tau.tobytes())


def _oracle(kernel: Kernel, signal: InputSignal, n_x: int, n_p: int,
            order: np.ndarray | None = None) -> ca.Function:
    """The DAE in normalized time: ``dx/dtau = T f(t0 + T tau, x, [z,] u(t0 + T tau, q), p)``,
    ``0 = g(...)``; integrator parameters ``[p, q, t0, T]``; with ``order``, in the states
    ``x[order]``."""
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
    return ca.Function("dae", [tau, x_int, z, pp, ca.MX(0, 1)],
                       [span * ode, alg, ca.MX(0, 1), ca.MX(0, 1)],
                       ["t", "x", "z", "p", "u"], ["ode", "alg", "quad", "zero"],
                       {"max_num_dir": MAX_NUM_DIR})


def _jacobian_size(kernel: Kernel, n_x: int) -> tuple[int, int]:
    """(unknowns, structural non-zeros) of the Newton matrix ``I - gamma J``."""
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


@dataclass(frozen=True)
class _Chunk:
    """One integrator call of a run: normalized time ``tau`` in [0, 1] is ``t = a + (b - a)
    tau``."""

    a: float
    """Start [s]."""
    b: float
    """End of normalized time [s]."""
    tau: np.ndarray
    """Output times of the call, normalized."""
    grid_key: tuple
    """Cache key of ``tau`` (:func:`_normalized_grid`)."""
    keep: np.ndarray | None
    """Which of the call's outputs are the run's output times (None: all)."""


def _plan(t0: float, t1: float, t_out: np.ndarray, n_chunks: int) -> list[_Chunk]:
    """The integrator calls of a run: one over every output time (``n_chunks <= 1``), else
    ``n_chunks`` calls one after the other.

    Equally spaced output times (ending at ``t1``) give calls over equal numbers of equal
    intervals, of ``m`` or ``m + 1`` intervals (two cached integrators at most), each output
    interval split into as many intervals as make ``n_chunks`` calls (the extra points are
    dropped); other output times are split into groups of consecutive times.
    """
    tau, grid_key = _normalized_grid(t0, t1, t_out)
    if n_chunks <= 1:
        return [_Chunk(t0, t1, tau, grid_key, None)]
    span = t1 - t0
    if grid_key[0] == "linspace":
        sub = -(-n_chunks // tau.size)
        fine = tau.size * sub
        bounds = np.rint(np.linspace(0, fine, n_chunks + 1)).astype(int)
        return [_Chunk(t0 + span * lo / fine, t0 + span * hi / fine,
                       np.linspace(0.0, 1.0, hi - lo + 1)[1:], ("linspace", int(hi - lo)),
                       np.arange(lo + 1, hi + 1) % sub == 0)
                for lo, hi in zip(bounds[:-1], bounds[1:], strict=True)]
    chunks, a = [], t0
    for group in np.array_split(t_out, min(n_chunks, t_out.size)):
        b = float(group[-1])
        chunks.append(_Chunk(a, b, *_normalized_grid(a, b, group), None))
        a = b
    return chunks


def _merge(chunks: list[_Chunk]) -> _Chunk:
    """One call over consecutive ``chunks``."""
    a, b = chunks[0].a, chunks[-1].b
    times = np.concatenate([c.a + (c.b - c.a) * c.tau for c in chunks])
    tau, grid_key = _normalized_grid(a, b, times)
    keep = None
    if any(c.keep is not None for c in chunks):
        keep = np.concatenate([np.ones(c.tau.size, bool) if c.keep is None else c.keep
                               for c in chunks])
    return _Chunk(a, b, tau, grid_key, keep)


def _integrator(method: str, system: System, kernel: Kernel, signal: InputSignal, n_p: int,
                chunk: _Chunk, opts: dict[str, Any]) -> tuple[_Built, bool]:
    """The integrator of one call (from the cache or built now) and whether it was cached."""
    # the kernel by what it evaluates (kernels are rebuilt after clear_kernel_cache)
    kernel_key = (kernel.form, kernel.backend, str(kernel.library))
    key = (method, kernel_key, signal.key, chunk.grid_key,
           tuple(sorted((k, repr(v)) for k, v in opts.items())))
    built = _INTEGRATORS.get(system, key)
    if built is not None:
        return built, True
    start = time.perf_counter()
    order = _state_order(kernel, opts["linear_solver"])
    oracle = _oracle(kernel, signal, system.n_states, n_p, order)
    integ = ca.integrator(f"{method}_{kernel.form}", method, oracle, 0.0, chunk.tau, opts)
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
        Progress bar (:mod:`~bearingsim.simulation.progress`). Without one (``False``, or
        ``None`` and standard error not a terminal) the run is one integrator call; with one,
        :data:`PROGRESS_CHUNKS` calls, the bar moving between them, except that for ``None``
        the rest of the run is one call when the first call, extrapolated, says the whole run
        takes less than :data:`~bearingsim.simulation.progress.DELAY` (the bar would not
        appear).
    budget : RunBudget, optional
        The run's budget (:mod:`~bearingsim.simulation.budget`): its ``max_steps`` is
        ``max_num_steps`` of each call (default 100000).

    Returns
    -------
    SundialsRun
        ``stats``: ``method``, ``form``, ``backend`` ("compiled C" or "CasADi VM") and
        ``backend_reason``, ``library``, ``linear_solver``, ``setup_time`` [s] (building the
        integrators; 0 when they came from the cache), ``integrator_cached``, ``chunks``
        (integrator calls), and CVODES/IDAS counts summed over the calls: ``nsteps``,
        ``nfevals`` (right-hand side or residual), ``njevals`` (exact Jacobian),
        ``nlinsetups`` (factorizations), ``nniters``, ``netfails``, ``rhs_time``/``jac_time``
        [s] (CasADi's timers of those calls), ``state_order`` (``"system"``, or ``"minimum
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
    bar = progress_bar(t0, t1, progress)
    pending = _plan(t0, t1, t_out, PROGRESS_CHUNKS if bar is not None else 1)
    x, z = np.asarray(x0, dtype=float), z0
    xs_parts: list[np.ndarray] = []
    zs_parts: list[np.ndarray] = []
    totals: dict[str, float] = {}
    setup_time, cached, calls = 0.0, True, 0
    try:
        while pending:
            chunk = pending.pop(0)
            span = chunk.b - chunk.a
            opts = dict(base)
            if np.isfinite(max_step):
                opts["max_step_size"] = float(max_step) / span
            built, hit = _integrator(method, system, kernel, signal, p.size, chunk, opts)
            cached &= hit
            setup_time += 0.0 if hit else built.build_time
            p_ext = np.concatenate([p, signal.q, [chunk.a, span]])
            args = {"x0": built.to_integrator(x), "p": p_ext}
            if kernel.form == "dae":
                args["z0"] = z
            called = time.perf_counter()
            try:
                with _interrupts() as interrupted:
                    out = built.integrator(**args)
            except RuntimeError as exc:
                if interrupted.is_set():  # CasADi reports Ctrl-C as a failed evaluation
                    raise KeyboardInterrupt(f"{method.upper()} run interrupted") from None
                _locate_failure(method, system, built, opts, p_ext, x, z, x0, chunk.a, span,
                                chunk.tau, exc)
                raise
            _add_counts(totals, built.integrator.stats())
            xk = built.from_integrator(
                np.asarray(out["xf"], dtype=float).reshape(n_x, chunk.tau.size))
            if not np.all(np.isfinite(xk)):
                k = int(np.argmax(~np.all(np.isfinite(xk), axis=0)))
                raise SimulationError(
                    f"{method.upper()} produced non-finite states by "
                    f"t = {chunk.a + span * chunk.tau[k]:.6g} s; {diverged(system, xk[:, k], x0)}"
                )
            x = xk[:, -1]
            xs_parts.append(xk if chunk.keep is None else xk[:, chunk.keep])
            if kernel.form == "dae":
                zk = np.asarray(out["zf"], dtype=float).reshape(z0.size, chunk.tau.size)
                z = zk[:, -1]
                zs_parts.append(zk if chunk.keep is None else zk[:, chunk.keep])
            calls += 1
            if bar is not None:
                bar.update(span)
            if (calls == 1 and progress is None and len(pending) > 1
                    and (time.perf_counter() - called) * (len(pending) + 1) < DELAY):
                pending = [_merge(pending)]  # no bar would appear: the rest in one call
    finally:
        if bar is not None:
            bar.close()
    xs = np.hstack(xs_parts)
    zs = np.hstack(zs_parts) if kernel.form == "dae" else None
    ts = t_out
    if t_eval[0] <= t0:
        ts = np.concatenate([[t0], t_out])
        xs = np.hstack([np.asarray(x0, dtype=float)[:, None], xs])
        if zs is not None:
            zs = np.hstack([np.asarray(z0, dtype=float)[:, None], zs])
    values = observe_at(kernel, signal, p, ts, xs, zs)
    stats = _stats(method, kernel, linear_solver, setup_time, cached, totals)
    stats["chunks"] = calls
    stats["state_order"] = "system" if built.order is None else "minimum degree"
    return SundialsRun(ts, xs, zs, values, stats)


@contextlib.contextmanager
def _interrupts() -> Iterator[threading.Event]:
    """Record Ctrl-C (SIGINT) during a SUNDIALS run: CasADi checks for it between evaluations
    and turns it into a failed evaluation (a RuntimeError); the event tells the two apart, so
    an interrupted run raises KeyboardInterrupt instead of being diagnosed as a failure.
    Outside the main thread (where Python delivers signals) the event stays clear."""
    event = threading.Event()
    if threading.current_thread() is not threading.main_thread():
        yield event
        return
    previous = signal.getsignal(signal.SIGINT)

    def handler(signum, frame):
        event.set()
        if callable(previous):
            previous(signum, frame)
        raise KeyboardInterrupt

    signal.signal(signal.SIGINT, handler)
    try:
        yield event
    finally:
        signal.signal(signal.SIGINT, previous)


def observe_at(kernel: Kernel, signal: InputSignal, p: np.ndarray, ts: np.ndarray,
               xs: np.ndarray, zs: np.ndarray | None) -> np.ndarray:
    """Every observed variable at the output times (the kernel's backend, one mapped call)."""
    n = ts.size
    us = np.asarray(signal.u.map(n)(ts[None, :], np.repeat(signal.q[:, None], n, axis=1)),
                    dtype=float).reshape(-1, n)
    ps = np.repeat(p[:, None], n, axis=1)
    args = (ts[None, :], xs, us, ps) if zs is None else (ts[None, :], xs, zs, us, ps)
    return np.asarray(kernel.observe.map(n)(*args), dtype=float)


_COUNTS = {"nsteps": "nsteps", "nfevals": "nfevals", "nlinsetups": "nlinsetups",
           "nniters": "nniters", "netfails": "netfails", "nncfails": "nncfails",
           "njevals": "n_call_jacF", "rhs_time": "t_wall_daeF", "jac_time": "t_wall_jacF"}
"""Counts and timers of a run (summed over its integrator calls) by CasADi's stats names."""


def _add_counts(totals: dict[str, float], st: dict[str, Any]) -> None:
    """Add one integrator call's counts and timers (``Function.stats()``) to ``totals``."""
    for name, key in _COUNTS.items():
        if key in st:
            totals[name] = totals.get(name, 0) + st[key]


def _stats(method: str, kernel: Kernel, linear_solver: str, setup_time: float, cached: bool,
           totals: dict[str, float]) -> dict[str, Any]:
    stats: dict[str, Any] = {"method": method if kernel.form == "ode" else f"{method} (dae)",
                             "form": kernel.form, **kernel.describe(),
                             "linear_solver": linear_solver, "setup_time": setup_time,
                             "integrator_cached": cached}
    for name in ("nsteps", "nfevals", "nlinsetups", "nniters", "netfails", "nncfails"):
        if name in totals:
            stats[name] = int(totals[name])
    stats["njevals"] = int(totals.get("njevals", 0))
    stats["rhs_time"] = float(totals.get("rhs_time", 0.0))
    stats["jac_time"] = float(totals.get("jac_time", 0.0))
    if kernel.form == "dae":
        stats["algebraic_states"] = int(kernel.function.size1_in(2))
    return stats


def _locate_failure(method: str, system: System, built: _Built, opts: dict, p_ext: np.ndarray,
                    x_start: np.ndarray, z_start: np.ndarray | None, x0: np.ndarray, t0: float,
                    span: float, tau: np.ndarray, exc: RuntimeError) -> None:
    """Integrate the failed call interval by interval, from ``x_start`` (and ``z_start``) at
    ``t0`` [s], to report where it failed; ``x0`` is the run's start state, which the states
    reached are compared with (failure path only)."""
    with _quiet_stdout():
        _locate(method, system, built, opts, p_ext, x_start, z_start, x0, t0, span, tau, exc)


def _locate(method: str, system: System, built: _Built, opts: dict, p_ext: np.ndarray,
            x_start: np.ndarray, z_start: np.ndarray | None, x0: np.ndarray, t0: float,
            span: float, tau: np.ndarray, exc: RuntimeError) -> None:
    x, z, tau_prev = np.asarray(x_start, dtype=float), z_start, 0.0
    for tau_next in tau:
        step = ca.integrator("locate", method, built.oracle, tau_prev, [float(tau_next)], opts)
        args = {"x0": built.to_integrator(x), "p": p_ext, **({"z0": z} if z is not None else {})}
        try:
            out = step(**args)
            x_new = built.from_integrator(np.asarray(out["xf"], dtype=float).ravel())
            z = np.asarray(out["zf"], dtype=float).ravel() if z is not None else None
        except RuntimeError:
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
