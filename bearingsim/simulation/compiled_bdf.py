"""A BDF integrator in C that calls the compiled kernels directly: ``method="compiled_bdf"``.

CVODES and IDAS evaluate the compiled kernels through CasADi, whose integrator interface costs
as much per step as the kernels themselves on the ball-level models (``docs/benchmarks.md``,
section "SUNDIALS on compiled kernels"). This integrator is the step loop in C
(``c/bdf.c`` on the stepping core ``c/bsm_bdf.c``, which the FMU's co-simulation stepper shares):
scipy's variable-order BDF (numerical differentiation formulas, orders 1-5) with
CVODES' reuse of the Newton matrix's LU while the step size changes little, calling the kernel
library's ``ode`` and ``jac_ode`` through function pointers. The Newton matrix is factorised
by the sparse LU ``c/bsm_lu.c`` (shared with the FMU's stepper) with the states in a
fill-reducing order, on the pattern of the Jacobian and the diagonal in that order
(:func:`~bearingsim.simulation.ordering.newton_pattern`): the pivot order and the factors'
pattern are found once and reused while the pivots stay acceptable. The inputs ``u(t, q)``
are generated C in a small library of their own, compiled once per input structure and cached
like the kernels (a new structure compiles that file, not the integrator). The observed
variables at the output times come from the kernel library's ``observe``, called by the
driver too. Each thread keeps its solver of a model between runs (reset to new at each run).

It needs a C compiler; without one it raises
:class:`~bearingsim.simulation.c_compiler.CompileError` (``method="cvodes"`` falls back to
CasADi's VM).
"""

from __future__ import annotations

import ctypes
import threading
import time
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import SimulationError
from bearingsim.simulation.c_compiler import CompileError
from bearingsim.simulation.c_units import generate_source
from bearingsim.simulation.compile import source_library
from bearingsim.simulation.diagnostics import diverged, listed_names, no_value_cause
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.kernels import COMPILED, Kernel
from bearingsim.simulation.ordering import NewtonPattern, kept_order, newton_pattern
from bearingsim.simulation.progress import progress_bar

__all__ = ["DRIVER_SOURCE", "CompiledRun", "compiled_bdf_run"]

C_DIR = Path(__file__).with_name("c")
"""The integrator's C sources: the driver ``bdf.c``, the stepping core ``bsm_bdf.c`` and the LU
``bsm_lu.c`` with their headers."""

DRIVER_SOURCE = C_DIR / "bdf.c"
"""The integrator's driver: the kernels, the LU and the output times."""

CORE_SOURCES = ("bsm_bdf.c", "bsm_lu.c")
"""The BDF stepping core and the LU, shared with the FMU's co-simulation stepper."""

CORE_HEADERS = ("bsm_bdf.h", "bsm_lu.h")

FLAGS = ("-O3", f"-I{C_DIR}")
"""Compiler flags of the integrator library (a small file: -O3 costs nothing to speak of, and
vectorises the stepping core's loops over the states, which -O2 leaves scalar; no -march, so
the library runs on any machine of the architecture)."""

SIGNAL_FLAGS = ("-O2",)
"""Compiler flags of the inputs' library (a few operations per input)."""

STATUS = {
    1: "the step size fell below 10 ulp of t (a discontinuity or a blow-up here)",
    2: "the Newton matrix I - c J is singular",
    3: "the model returned non-finite values",
    4: "a model function reported an error",
}
"""Failure codes of ``bsm_bdf_advance`` (``c/bdf.c``)."""

STAT_NAMES = ("nsteps", "nfevals", "njevals", "nlinsetups", "netfails", "nncfails",
              "npivotings")
"""The integrator's counts, in the order of ``bsm_bdf_stats`` (``npivotings``: the LU
factorisations that chose a new pivot order and fill pattern, of ``nlinsetups``)."""

STEPS_PER_CALL = 1000
"""Steps per call of the C loop (about 30 ms on the 6304 massive-ball level): between calls
the progress bar moves and Ctrl-C is seen, however few the output times."""

KEPT_OUTPUT_TIMES = 1000
"""Most output times a kept solver's output arrays hold between runs (a run with more gets
arrays of its own, freed with its result)."""

_LOCK = threading.Lock()


@dataclass
class CompiledRun:
    """States and observed variables at the output times (one column per time) and the run's
    statistics."""

    t: np.ndarray
    x: np.ndarray
    values: np.ndarray
    stats: dict


def _signal_function(signal: InputSignal) -> ca.Function:
    """``u(t, q)`` under the name the integrator calls."""
    sym = signal.u.sx_in()
    return ca.Function("bsm_signal", sym, signal.u.call(sym))


@cache
def _driver(cache_dir: str | None) -> ctypes.CDLL:
    """The integrator library (compiled once, cached on disk by its source)."""
    units = [DRIVER_SOURCE.read_text(), *[(C_DIR / name).read_text() for name in CORE_SOURCES]]
    headers = [(C_DIR / name).read_text() for name in CORE_HEADERS]
    lib = source_library(units, headers=headers, flags=FLAGS, cache_dir=cache_dir,
                         prefix="bsm_bdf")
    dll = ctypes.CDLL(str(lib))
    # arrays go in as addresses (:func:`_address_of`): cheaper than numpy's ctypes objects
    p, i, ll, d = ctypes.c_void_p, ctypes.c_int, ctypes.c_longlong, ctypes.c_double
    dll.bsm_bdf_new.restype = p
    dll.bsm_bdf_new.argtypes = [i, i, i, i, p, p, p, p, ll, p, p, p, p, p, ll, ll, ll, ll]
    dll.bsm_bdf_reset.argtypes = [p, p, d, d, d, d, d]
    dll.bsm_bdf_start.argtypes = [p]
    dll.bsm_bdf_advance.argtypes = [p, i, p, p, i, ctypes.POINTER(i)]
    dll.bsm_bdf_free.argtypes = [p]
    dll.bsm_bdf_time.restype = d
    dll.bsm_bdf_time.argtypes = [p]
    dll.bsm_bdf_state.argtypes = [p, p]
    dll.bsm_bdf_stats.argtypes = [p, p]
    dll.bsm_bdf_observe.argtypes = [p, i, p, p, i, p]
    return dll


@cache
def _signal_library(source: str, cache_dir: str | None) -> ctypes.CDLL:
    """The inputs' generated C ``bsm_signal`` in a library of its own (compiled once per input
    structure, cached on disk by its source): a sweep over input structures compiles this small
    file per structure, not the integrator with it."""
    return ctypes.CDLL(str(source_library([source], flags=SIGNAL_FLAGS, cache_dir=cache_dir,
                                          prefix="bsm_signal")))


def _address(dll: ctypes.CDLL, name: str) -> int:
    return ctypes.cast(getattr(dll, name), ctypes.c_void_p).value


def _address_of(a: np.ndarray) -> int:
    """The address of a contiguous array's first element (the caller keeps ``a`` alive)."""
    return a.__array_interface__["data"][0]


@dataclass(frozen=True)
class _Prepared:
    """What a run needs of a kernel library and an input structure, found once: the
    integrator library, the functions' addresses, the Newton matrix's pattern in the LU order
    of the states and the work sizes."""

    dll: ctypes.CDLL
    kernel_dll: ctypes.CDLL
    signal_dll: ctypes.CDLL | None
    ode: int
    jac: int
    signal: int | None
    observe: int
    n_y: int
    n_u: int
    jac_nnz: int
    newton: NewtonPattern
    newton_addresses: tuple[int, ...]
    """The addresses of ``newton``'s arrays, in ``bsm_bdf_new``'s order (``newton`` keeps
    them alive)."""
    sizes: tuple[int, int, int, int]
    solvers: threading.local = field(default_factory=threading.local, compare=False,
                                     repr=False)
    """Each thread's :class:`_Solver` of these functions, by the sizes of ``p`` and ``q``
    (attribute ``by_size``), made on first use."""

    def solver(self, n: int, n_p: int, n_q: int) -> _Solver:
        """This thread's solver for ``n`` states, ``n_p`` parameters and ``n_q`` input
        parameters, made on first use and kept."""
        kept = getattr(self.solvers, "by_size", None)
        if kept is None:
            kept = self.solvers.by_size = {}
        found = kept.get((n, n_p, n_q))
        if found is None:
            found = kept[n, n_p, n_q] = _Solver(self, n, n_p, n_q)
        return found


class _Solver:
    """A solver of ``c/bdf.c`` kept between the runs of one thread on one model: a run resets
    it (``bsm_bdf_reset``: as new, so that its result does not depend on the runs before)
    instead of allocating it, and passes its values and takes its outputs through arrays whose
    addresses are found once (allocation and address look-ups cost a run of a millisecond
    tens of microseconds). Freed with the last reference."""

    def __init__(self, prep: _Prepared, n: int, n_p: int, n_q: int):
        self.dll, self.newton, self.n, self.n_y = prep.dll, prep.newton, n, prep.n_y
        self.pointer = prep.dll.bsm_bdf_new(
            n, prep.n_u, n_p, n_q, prep.ode, prep.jac, prep.signal, prep.observe, prep.jac_nnz,
            *prep.newton_addresses, *prep.sizes)
        if not self.pointer:
            raise MemoryError("compiled_bdf: out of memory allocating the integrator")
        self.values = np.empty(n_p + n_q + n)
        """``(p, q, x0)`` of a run, one after the other."""
        self.values_at = _address_of(self.values)
        self.stats = np.zeros(len(STAT_NAMES), dtype=np.int64)
        self.stats_at = _address_of(self.stats)
        self.written = ctypes.c_int(0)
        self.written_at = ctypes.byref(self.written)
        self._outputs = self._new_outputs(0)

    def _new_outputs(self, m: int) -> tuple[tuple[np.ndarray, ...], tuple[int, ...]]:
        arrays = (np.empty(m), np.empty((m, self.n)), np.empty((m, self.n_y)))
        return arrays, tuple(_address_of(a) for a in arrays)

    def outputs(self, m: int) -> tuple[tuple[np.ndarray, ...], tuple[int, ...]]:
        """Arrays for ``m`` output times (times, states and observed variables, a row per
        time) and their addresses: kept for up to :data:`KEPT_OUTPUT_TIMES` (grown to the most
        a run had), made for the run alone above (a long series is not held after it)."""
        if m > KEPT_OUTPUT_TIMES:
            return self._new_outputs(m)
        if self._outputs[0][0].size < m:
            self._outputs = self._new_outputs(m)
        arrays, addresses = self._outputs
        return tuple(a[:m] for a in arrays), addresses

    def __del__(self) -> None:
        if getattr(self, "pointer", None):
            self.dll.bsm_bdf_free(self.pointer)


_PREPARED: dict[tuple, _Prepared] = {}
"""By (kernel library, input structure, cache folder)."""


def _prepare(kern: Kernel, signal: InputSignal, cache_dir: str | Path | None) -> _Prepared:
    """The set-up of runs on ``kern`` with inputs of ``signal``'s structure, once per process
    (repeated short runs and sweeps pay only the integration)."""
    key = (str(kern.library), signal.key, None if cache_dir is None else str(cache_dir))
    with _LOCK:
        found = _PREPARED.get(key)
        if found is not None:
            return found
        function = kern.function
        jacobian = function.jacobian()
        sig = _signal_function(signal)
        n_u = sig.size1_out(0)
        dll = _driver(key[2])
        signal_dll = _signal_library(generate_source([sig], "bsm_signal"), key[2]) if n_u else None
        kernel_dll = ctypes.CDLL(str(kern.library))
        sparsity = jacobian.sparsity_out(1)
        observe = kern.observe
        fns = (function, jacobian, sig, observe)
        newton = newton_pattern(sparsity, kept_order(sparsity, kern.library))
        found = _PREPARED[key] = _Prepared(
            dll, kernel_dll, signal_dll, _address(kernel_dll, function.name()),
            _address(kernel_dll, jacobian.name()),
            _address(signal_dll, "bsm_signal") if n_u else None,
            _address(kernel_dll, observe.name()), observe.size1_out(0), n_u, sparsity.nnz(),
            newton,
            tuple(_address_of(a) for a in (newton.order, newton.start, newton.index,
                                           newton.jac_slot, newton.diag_slot)),
            tuple(max(int(getattr(f, name)()) for f in fns)
                  for name in ("sz_arg", "sz_res", "sz_iw", "sz_w")))
        return found


def _not_finite_there(system: System, solver: _Solver, t: float, state: np.ndarray) -> str:
    """For a failure message: the variables that are not finite at the state the run reached
    (``""`` when all are: the integrator failed at a state it tried, not at this one), and
    why (:func:`~bearingsim.simulation.diagnostics.no_value_cause`)."""
    times, values = np.array([t]), np.empty(solver.n_y)
    status = solver.dll.bsm_bdf_observe(solver.pointer, 1, _address_of(times),
                                        _address_of(state), solver.n_y, _address_of(values))
    bad = [name for name, v in zip(system.observed_names, values, strict=True)
           if not np.isfinite(v)]
    if status or not bad:
        return ""
    return f": {listed_names(bad)} not finite at the state reached; {no_value_cause(system)}"


def compiled_bdf_run(system: System, kern: Kernel, signal: InputSignal, p: np.ndarray,
                     x0: np.ndarray, t0: float, t1: float, t_out: np.ndarray, rtol: float,
                     atol: float, max_step: float = np.inf, progress: bool | None = False,
                     cache_dir: str | Path | None = None, budget=None) -> CompiledRun:
    """Integrate ``x' = ode(t, x, u(t), p)`` from ``t0`` to ``t1`` in C, and evaluate the
    observed variables at the output times.

    Parameters
    ----------
    system : System
        The system (names for messages).
    kern : Kernel
        Its compiled ``ode`` kernel (:func:`~bearingsim.simulation.kernels.kernel`).
    signal : InputSignal
        The inputs.
    p : numpy.ndarray
        Parameters.
    x0 : numpy.ndarray
        Start state at ``t0``.
    t0, t1 : float
        Start and end time [s].
    t_out : numpy.ndarray
        Output times [s], increasing, in ``[t0, t1]``.
    rtol, atol : float
        Tolerances of the local error (weighted RMS norm, as scipy's BDF).
    max_step : float
        Largest step [s].
    progress : bool or None
        Progress bar (:mod:`~bearingsim.simulation.progress`).
    cache_dir : path, optional
        Library cache (default: the kernels').
    budget : RunBudget, optional
        The run's budget (:mod:`~bearingsim.simulation.budget`), counted per batch of
        ``STEPS_PER_CALL`` steps.

    Returns
    -------
    CompiledRun

    Raises
    ------
    CompileError
        If the kernel is not compiled C of the ODE form (no C compiler, or a DAE kernel).
    SimulationError
        If the integration fails (the time reached, why, and the states that grew most).
    """
    if kern.backend != COMPILED or kern.form != "ode":
        raise CompileError(
            f"method 'compiled_bdf' needs the compiled ODE kernel of {system.name!r}; got the "
            f"{kern.form} kernel on the {kern.backend} ({kern.reason}); use method='cvodes'")
    n = system.n_states
    prep = _prepare(kern, signal, cache_dir)
    dll = prep.dll
    p, q = np.asarray(p, dtype=float), np.asarray(signal.q, dtype=float)
    solver = prep.solver(n, p.size, q.size)
    values = solver.values
    values[:p.size], values[p.size:p.size + q.size], values[p.size + q.size:] = p, q, x0
    dll.bsm_bdf_reset(solver.pointer, solver.values_at, float(rtol), float(atol),
                      float(max_step) if np.isfinite(max_step) else float(t1 - t0), float(t0),
                      float(t1))
    (times, xs, ys), (times_at, xs_at, ys_at) = solver.outputs(t_out.size)
    times[:] = t_out
    bar = progress_bar(t0, t1, progress)
    start = time.thread_time()
    try:
        status = dll.bsm_bdf_start(solver.pointer)
        done, reached = 0, t0
        while status == 0 and done < times.size:
            status = dll.bsm_bdf_advance(solver.pointer, times.size - done, times_at + 8 * done,
                                         xs_at + 8 * n * done, STEPS_PER_CALL,
                                         solver.written_at)
            done += solver.written.value
            if budget is not None and status == 0 and done < times.size:
                budget.step(dll.bsm_bdf_time(solver.pointer), STEPS_PER_CALL)
            if bar is not None:
                now = min(dll.bsm_bdf_time(solver.pointer), t1)
                bar.update(now - reached)
                reached = now
        dll.bsm_bdf_stats(solver.pointer, solver.stats_at)
        integrate_cpu_time = time.thread_time() - start  # (the observed variables apart)
        if status != 0:
            failed_at = dll.bsm_bdf_time(solver.pointer)
            state = np.empty(n)
            dll.bsm_bdf_state(solver.pointer, _address_of(state))
            raise SimulationError(
                f"compiled_bdf failed at t = {failed_at:.6g} s: {STATUS.get(status, status)}"
                f"{_not_finite_there(system, solver, failed_at, state)}; "
                f"{diverged(system, state, np.asarray(x0, dtype=float))}")
        if dll.bsm_bdf_observe(solver.pointer, times.size, times_at, xs_at, prep.n_y, ys_at):
            raise SimulationError(f"{system.name}: the variables could not be evaluated at the "
                                  "output times (a model function reported an error)")
    finally:
        if bar is not None:
            bar.close()
    run_stats = dict(zip(STAT_NAMES, solver.stats.tolist(), strict=True))
    run_stats["integrate_cpu_time"] = integrate_cpu_time
    return CompiledRun(t_out, xs.T.copy(), ys.T.copy(), run_stats)
