"""The CVODES and IDAS integrators of the runs: built on an oracle in normalized time, kept
per system and set-up, and the progress clock in their right-hand side.

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
subtracts the output of :class:`Clock` from the right-hand side: a CasADi callback that
records the normalized time of each evaluation, moves the bar now and then, and returns exactly
``0.0``. ``x - 0.0 == x`` for every float (``-0.0`` included), so the run with a bar takes the
same steps and gives the same numbers bit for bit as the run without, on a terminal or piped, on
a fast or a slow machine (``tests/simulation/test_progress.py``). The callback costs a Python
call per
evaluation (``python -m bench.sundials_compiled progress``).
"""

from __future__ import annotations

import atexit
import contextlib
import functools
import os
import sys
import threading
import time
import weakref
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.integrator_calls import IntegratorCall
from bearingsim.simulation.kernels import Kernel
from bearingsim.simulation.native_streams import quiet_stdout
from bearingsim.simulation.ordering import kept_order

__all__ = ["CLOCK", "CLOCK_EVERY", "DENSE_LIMIT", "INTEGRATORS", "LINEAR_SOLVERS", "MAX_NUM_DIR",
           "Built", "Clock", "IntegratorCache", "build_integrator", "choose_linear_solver",
           "clear_integrator_cache", "jacobian_size", "normalized_grid"]

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


@dataclass
class Built:
    """A built integrator with its oracle, build time [s] and state order."""

    integrator: ca.Function
    oracle: ca.Function
    build_time: float
    order: np.ndarray | None = None
    """The integrator's state order (``x_integrator = x[order]``), or None: the system's."""
    _inverse: np.ndarray | None = field(init=False, repr=False, compare=False)
    _calls: threading.local = field(init=False, repr=False, compare=False,
                                    default_factory=threading.local)

    def __post_init__(self) -> None:
        self._inverse = None if self.order is None else np.argsort(self.order)

    def call(self) -> IntegratorCall:
        """This thread's buffered call of the integrator (made on first use, dropped with
        the integrator).

        Returns
        -------
        IntegratorCall
            The call through ``Function.buffer``.
        """
        made = getattr(self._calls, "call", None)
        if made is None:
            made = self._calls.call = IntegratorCall(self.integrator)
        return made

    def to_integrator(self, x: np.ndarray) -> np.ndarray:
        """States (one column per time, or a vector) in the integrator's order.

        Parameters
        ----------
        x : numpy.ndarray
            States in the system's order.

        Returns
        -------
        numpy.ndarray
            The same states in the integrator's order.
        """
        return x if self.order is None else x[self.order]

    def from_integrator(self, x: np.ndarray) -> np.ndarray:
        """States from the integrator's order back to the system's.

        Parameters
        ----------
        x : numpy.ndarray
            States in the integrator's order.

        Returns
        -------
        numpy.ndarray
            The same states in the system's order.
        """
        return x if self._inverse is None else x[self._inverse]


class IntegratorCache:
    """Integrators of one process, per system (dropped with the system) and set-up key."""

    def __init__(self) -> None:
        self._by_system: dict[int, dict[tuple, Built]] = {}
        self._lock = threading.Lock()

    def get(self, system: System, key: tuple) -> Built | None:
        """The integrator built for ``key``, if any.

        Parameters
        ----------
        system : System
            The closed system.
        key : tuple
            The integrator's settings.

        Returns
        -------
        Built or None
            The kept integrator, None if there is none.
        """
        with self._lock:
            return self._by_system.get(id(system), {}).get(key)

    def put(self, system: System, key: tuple, built: Built) -> None:
        """Keep ``built`` for later runs with ``key``.

        Parameters
        ----------
        system : System
            The closed system (its integrators are dropped with it).
        key : tuple
            The integrator's settings.
        built : Built
            The integrator.
        """
        with self._lock:
            per = self._by_system.get(id(system))
            if per is None:
                per = self._by_system[id(system)] = {}
                weakref.finalize(system, self._drop, id(system))
            per[key] = built

    def _drop(self, system_id: int) -> None:
        with self._lock, quiet_stdout():
            self._by_system.pop(system_id, None)

    def clear(self) -> None:
        """Forget every integrator."""
        with self._lock, quiet_stdout():
            self._by_system.clear()


INTEGRATORS = IntegratorCache()
_MUMPS_USED = threading.Event()


def _discard_native_stdout_at_exit() -> None:
    """After a process used MUMPS: at exit, flush Python's standard output, then destroy the
    integrators and send what native code still writes to file descriptor 1 (the MUMPS banner,
    buffered by the Fortran runtime until the process ends) to the null device."""
    if not _MUMPS_USED.is_set():
        return
    INTEGRATORS.clear()
    try:
        sys.stdout.flush()
        os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
    except (OSError, ValueError, AttributeError):
        pass


atexit.register(_discard_native_stdout_at_exit)


def clear_integrator_cache() -> None:
    """Forget every integrator built in this process."""
    INTEGRATORS.clear()


def normalized_grid(t0: float, t1: float, t_eval: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, tuple]:
    """The output times after ``t0``, the same in ``tau = (t - t0) / (t1 - t0)``, and the
    key of the normalized grid: ``("linspace", n)`` for equally spaced times ending at ``t1``
    (then exactly ``linspace(0, 1, n)[1:]``), else the bytes of ``tau``. Found once per
    ``t0``, ``t1`` and output times of up to :data:`GRIDS_KEPT_UP_TO` points.

    Parameters
    ----------
    t0, t1 : float
        Start and end of the run [s].
    t_eval : numpy.ndarray
        Output times [s], increasing, from ``t0`` on.

    Returns
    -------
    tuple
        ``(t_out, tau, key)``; the arrays are read-only (shared by the runs with these
        times).
    """
    times = np.ascontiguousarray(t_eval, dtype=float)
    if times.size > GRIDS_KEPT_UP_TO:
        return _grid(float(t0), float(t1), times)
    return _kept_grid(float(t0).hex(), float(t1).hex(), times.tobytes())


GRIDS_KEPT_UP_TO = 4096
"""Most output times whose normalized grid :func:`normalized_grid` keeps (64 grids at most)."""


@functools.lru_cache(maxsize=64)
def _kept_grid(t0: str, t1: str, times: bytes) -> tuple[np.ndarray, np.ndarray, tuple]:
    """:func:`_grid` of the times given by their bits (``float.hex``, ``tobytes``)."""
    return _grid(float.fromhex(t0), float.fromhex(t1), np.frombuffer(times, dtype=float))


def _grid(t0: float, t1: float, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, tuple]:
    """:func:`normalized_grid`, computed."""
    t_out = times[times > t0]
    tau = (t_out - t0) / (t1 - t0)
    n = tau.size
    even = _even_grid(n)
    t_out.flags.writeable = False
    if np.max(np.abs(tau - even)) <= 1e-12:
        return t_out, even, ("linspace", n)
    tau.flags.writeable = False
    return t_out, tau, ("grid", tau.tobytes())


@functools.lru_cache(maxsize=64)
def _even_grid(n: int) -> np.ndarray:
    """``linspace(0, 1, n + 1)[1:]``, made once per ``n`` (read-only)."""
    even = np.linspace(0.0, 1.0, n + 1)[1:]
    even.flags.writeable = False
    return even


class Clock(ca.Callback):
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
        exception it raises stops the run).

        Parameters
        ----------
        observer : callable
            Called with the normalized time of every :data:`CLOCK_EVERY`-th evaluation.

        Yields
        ------
        None
        """
        self._local.observer, self._local.calls = observer, 0
        try:
            yield
        finally:
            self._local.observer = None


CLOCK_EVERY = 16
"""Right-hand-side evaluations between two calls of a run's progress observer."""

CLOCK = Clock()


def _oracle(kernel: Kernel, signal: InputSignal, n_x: int, n_p: int,
            order: np.ndarray | None = None, observed: bool = False) -> ca.Function:
    """The DAE in normalized time: ``dx/dtau = T f(t0 + T tau, x, [z,] u(t0 + T tau, q), p)``,
    ``0 = g(...)``; integrator parameters ``[p, q, t0, T]``; with ``order``, in the states
    ``x[order]``; ``observed``: minus the progress clock's ``0.0`` (:class:`Clock`)."""
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
        rate = rate - CLOCK(tau)
    return ca.Function("dae", [tau, x_int, z, pp, ca.MX(0, 1)],
                       [rate, ca.densify(alg), ca.MX(0, 1), ca.MX(0, 1)],
                       ["t", "x", "z", "p", "u"], ["ode", "alg", "quad", "zero"],
                       {"max_num_dir": MAX_NUM_DIR})


_SIZES: dict[int, tuple[Kernel, tuple[int, int]]] = {}
""":func:`jacobian_size` by ``id(kernel)``, the kernel kept so that its id stays unique."""


def jacobian_size(kernel: Kernel, n_x: int) -> tuple[int, int]:
    """(unknowns, structural non-zeros) of the Newton matrix ``I - gamma J`` (found once per
    kernel).

    Parameters
    ----------
    kernel : Kernel
        The run's kernel.
    n_x : int
        States.

    Returns
    -------
    tuple of int
        ``(unknowns, non-zeros)``.
    """
    found = _SIZES.get(id(kernel))
    if found is not None and found[0] is kernel:
        return found[1]
    if len(_SIZES) >= 256:
        del _SIZES[next(iter(_SIZES))]
    size = _SIZES[id(kernel)] = (kernel, _count_jacobian(kernel, n_x))
    return size[1]


def _count_jacobian(kernel: Kernel, n_x: int) -> tuple[int, int]:
    """:func:`jacobian_size` without the memory."""
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
    return kept_order(jac.sparsity_out(jac.name_out().index("jac_ode_x")), kernel.library)


def build_integrator(method: str, system: System, kernel: Kernel, signal: InputSignal,
                     n_p: int, tau: np.ndarray, grid_key: tuple, opts: dict[str, Any],
                     observed: bool) -> tuple[Built, bool]:
    """The integrator of a run (from the cache or built now) and whether it was cached.

    Parameters
    ----------
    method : {"cvodes", "idas"}
        The integrator.
    system : System
        The system (cache scope).
    kernel : Kernel
        The run's kernel.
    signal : InputSignal
        The run's inputs (their structure is part of the key).
    n_p : int
        Parameters.
    tau : numpy.ndarray
        Normalized output times.
    grid_key : tuple
        Their key (:func:`normalized_grid`).
    opts : dict
        CasADi integrator options.
    observed : bool
        Whether the oracle has the progress clock.

    Returns
    -------
    tuple
        ``(Built, cached)``.
    """
    # the kernel by what it evaluates (kernels are rebuilt after clear_kernel_cache)
    kernel_key = (kernel.form, kernel.backend, str(kernel.library))
    settings = tuple(sorted(opts.items()))  # the names are unique: values never compared
    key = (method, kernel_key, signal.key, grid_key, observed, settings)
    try:
        built = INTEGRATORS.get(system, key)
    except TypeError:  # an option value that is not hashable (a list): keyed by its text
        key = (*key[:-1], tuple((name, repr(value)) for name, value in settings))
        built = INTEGRATORS.get(system, key)
    if built is not None:
        return built, True
    start = time.perf_counter()
    order = _state_order(kernel, opts["linear_solver"])
    oracle = _oracle(kernel, signal, system.n_states, n_p, order, observed)
    integ = ca.integrator(f"{method}_{kernel.form}", method, oracle, 0.0, tau, opts)
    built = Built(integ, oracle, time.perf_counter() - start, order)
    if opts["linear_solver"] == "mumps":
        _MUMPS_USED.set()
    INTEGRATORS.put(system, key, built)
    return built, False
