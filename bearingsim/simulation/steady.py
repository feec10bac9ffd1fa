"""Steady states: Newton on the state derivatives with the exact Jacobian.

The right-hand side and its Jacobian are the system's kernel
(:func:`~bearingsim.simulation.kernels.kernel`): generated C when a compiler exists (the
library cached by content, parameters free, so a new parameter value compiles nothing), else
CasADi's VM, with the same numbers either way.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from bearingsim.assembler.numeric import thread_kept
from bearingsim.assembler.system import System, as_system
from bearingsim.entry_points import entry_point
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation.input_ranges import check_input_ranges
from bearingsim.simulation.inputs import input_signal
from bearingsim.simulation.kernels import kernel
from bearingsim.simulation.native_streams import casadi_dumps_dropped
from bearingsim.simulation.steady_messages import not_found, running_off, speed_inputs
from bearingsim.validation import check_flag, check_quantity, check_range, check_vector

__all__ = ["steady_state", "integrator_states", "turning_angles"]


def _dependencies(system: System) -> tuple[np.ndarray, np.ndarray]:
    """(derivative, state) index pairs of every structural nonzero of ``d ode / d x``, from
    its sparsity (the Jacobian itself not built)."""
    rows, cols = system.functions["ode"].jac_sparsity(0, 1).get_triplet()
    return np.asarray(rows, dtype=int), np.asarray(cols, dtype=int)


def integrator_states(system: System) -> list[int]:
    """States no derivative depends on (angles of free rotors): they have no steady value.

    Parameters
    ----------
    system : System
        The closed system.

    Returns
    -------
    list of int
        Indices of those states.
    """
    cols = set(_dependencies(system)[1].tolist())
    return [k for k in range(system.n_states) if k not in cols]


def turning_angles(system: System) -> list[str]:
    """Names of the states that make the model's steady running periodic when a speed input
    turns it (empty: the model may have a fixed point): angles (in rad) whose derivative is
    one other state (their speed) and no input, and that some derivative depends on (a ball's
    or cage's position, which the contact geometry reads). A free rotor's angle, which nothing
    reads, is not one (:func:`integrator_states`), nor the integral of a speed error (a PI
    speed controller's ``xi' = w_ref - w``, in rad too, which settles where ``w = w_ref``).

    Parameters
    ----------
    system : System
        The closed system, its ``ode`` function's structure read.

    Returns
    -------
    list of str
        The angles' names.
    """
    rows, cols = _dependencies(system)
    names, units = system.state_names, system.variable_units
    alone = np.bincount(rows, minlength=len(names)) == 1  # a derivative of one state only
    rate = dict(zip(rows[alone[rows]].tolist(), cols[alone[rows]].tolist(), strict=True))
    read = set(cols.tolist())
    driven = set(system.functions["ode"].jac_sparsity(0, 2).get_triplet()[0])  # by an input
    return [name for k, name in enumerate(names) if units.get(name) == "rad" and k in read
            and k in rate and k not in driven and units.get(names[rate[k]]) == "rad/s"]


@entry_point
def steady_state(
    system: System,
    *,
    inputs: dict | None = None,
    parameters: dict | None = None,
    p: np.ndarray | None = None,
    x_guess: np.ndarray | None = None,
    t: float | str = 0.0,
    tol: float = 1e-12,
    residual_tol: float = 1e-9,
    require_unique: bool = True,
    compiled: bool | str = "auto",
) -> np.ndarray:
    """Solve ``dx/dt = 0`` for every state that some derivative depends on: Newton with a line
    search from the guess, then MINPACK's ``hybr``, then the loads raised from 0 in steps
    (each step's Newton started from the last one's solution).

    States that nothing depends on (pure integrators such as free rotor angles) keep their guess;
    their derivatives (the speeds) are still set to zero by the other equations when the model
    asks for it.

    Parameters
    ----------
    system : System
    inputs, parameters : dict, optional
        As for :func:`simulate`.
    p : array, optional
        Parameter vector (overrides ``parameters``): one finite value per
        ``system.parameter_names`` in its SI unit, each within its declared range.
    x_guess : array, optional
        Starting guess (default: start values).
    t : float or str
        Time at which inputs are evaluated [s], or a number with a unit (``"2 ms"``).
    tol : float
        Relative step tolerance of the solver, in (0, 1].
    residual_tol : float
        A solution whose largest derivative is below this is accepted even if the solver
        stalls [state units/s], > 0 and finite, provided a Newton step from it moves the
        states by at most ``sqrt(tol)`` of their norm (else the derivatives vanish only as
        states run off, ``y' = exp(y)`` towards minus infinity: no steady state).
    require_unique : bool
        Raise when the steady state is not unique (the Jacobian is singular at the solution,
        e.g. two free bodies coupled by dampers, or a ring without any torque): the solver's
        answer then depends on the guess. ``False`` accepts any one of the steady states (as
        a start for a simulation).
    compiled : bool or "auto"
        Evaluate the right-hand side and its Jacobian as generated C (``True``), on CasADi's
        VM (``False``) or C when a compiler exists (``"auto"``; see
        :func:`~bearingsim.simulation.kernels.kernel`).

    Returns
    -------
    numpy.ndarray
        The steady state vector.

    Raises
    ------
    ParameterError
        For an argument outside its range, or a ``p`` of the wrong length, not finite or with
        a value outside a parameter's range.
    SimulationError
        If no steady state is found, or if it is not unique (the Jacobian is singular there,
        naming the states that stay undetermined).
    """
    where = "steady_state"
    system = as_system(system, where)
    t = float(check_quantity(t, "t", "s", where=where))
    check_range(tol, "tol", "1", 0.0, 1.0, low_inclusive=False, where=where)
    check_range(residual_tol, "residual_tol", "state units/s", 0.0, None, low_inclusive=False,
                where=where)
    check_flag(require_unique, "require_unique", where)
    signal = input_signal(system, inputs)
    check_input_ranges(system, signal, np.array([float(t)]))  # bounds, limiting speeds
    u = signal.at(t)[:, 0]
    if p is None:
        p = system.p0(parameters)
    else:  # each value checked against its parameter's declaration, by name
        names = system.parameter_names
        values = check_vector(p, len(names), "p", "SI units of system.parameter_names", where)
        try:
            p = system.p0(dict(zip(names, values.tolist(), strict=True)))
        except ParameterError as exc:
            raise ParameterError(f"{where}: p: {exc}") from None
    x = (system.x0() if x_guess is None  # a copy: the caller's guess is not overwritten
         else check_vector(x_guess, system.n_states, "x_guess", "state units", where).copy())
    free = _free_states(system)
    if not free.size:
        return x
    newton = _newton_call(_newton_function(kernel(system, "ode", compiled).function), free)
    newton.start(t, x, u, p)
    last: list = [None, None]  # the point last evaluated and its Jacobian
    unsolved = [0]  # evaluations a nonlinear block of the model found no root in

    def res(z):
        try:
            f, j = newton(z)
        except RuntimeError:  # no root of a Newton block there: no residual, try elsewhere
            unsolved[0] += 1
            f, j = np.full(free.size, np.nan), np.full((free.size, free.size), np.nan)
        else:  # a compiled block without a root gives NaN instead of an error
            unsolved[0] += bool(system.rootfinder) and not np.isfinite(f).all()
        last[0], last[1] = z.copy(), j
        return f

    def jac(z):
        if last[0] is None or not (last[0] == z).all():
            res(z)
        return last[1]

    def load_at(u_now: np.ndarray) -> None:  # the residual of other inputs from here on
        newton.start(t, x, u_now, p)
        last[0] = None

    with casadi_dumps_dropped():  # a block without a root on the VM: said below, not dumped
        try:
            solution = _solve(system, res, jac, x[free], tol, residual_tol, free, unsolved,
                              speed_inputs(system, u))
        except SimulationError:
            solution = _load_continuation(system, u, load_at, res, jac, x[free], tol,
                                          residual_tol)
            if solution is None:
                raise
        if require_unique:
            _check_determined(system, jac(solution), free)
    x[free] = solution
    return x


def _solve(system: System, res, jac, z: np.ndarray, tol: float, residual_tol: float,
           free: np.ndarray, unsolved: list[int], speeds: list[str]) -> np.ndarray:
    """The free states' steady values: Newton from ``z`` (:func:`_newton`), else MINPACK's
    trust-region method (``hybr``) from ``z``; ``unsolved[0]`` counts the points where the
    model had no value (a Newton block without a root) and ``speeds`` are the inputs that
    turn the model (``name = value rad/s``), for the message."""
    solution = _newton(res, jac, z, tol, residual_tol)
    if solution is not None:
        return solution
    from scipy.optimize import root  # on use: importing scipy.optimize takes ~0.6 s

    sol = root(res, z, jac=jac, method="hybr", tol=tol)
    r = res(sol.x)
    converged = np.all(np.isfinite(sol.x)) and np.max(np.abs(r)) <= residual_tol
    if converged and not sol.success:  # stalled where the derivatives are small: a root, or
        step = _newton_step(jac(sol.x), r)  # states running off (y' = exp(y) at y = -138)
        if step is not None and _norm(step) > math.sqrt(tol) * max(_norm(sol.x), 1.0):
            raise SimulationError(running_off(system, sol, r, step, free))
    if not (sol.success or converged) or not np.all(np.isfinite(sol.x)):
        raise SimulationError(not_found(system, sol, r, turning_angles(system), free, speeds,
                                        unsolved[0]))
    return sol.x


def _newton_step(jacobian: np.ndarray, r: np.ndarray) -> np.ndarray | None:
    """The Newton step ``-J^-1 r`` (LAPACK's gesv); None for a singular ``J``."""
    from scipy.linalg.lapack import dgesv  # on use, as in _newton

    _, _, step, info = dgesv(jacobian, -r)
    return step if info == 0 else None


def _norm(x: np.ndarray) -> float:
    """The 2-norm of ``x``."""
    return math.sqrt(x.dot(x))


LOAD_UNITS = ("N", "N.m")
"""Units of the inputs :func:`_load_continuation` scales: forces and moments."""
LOAD_FRACTION_STEP = (0.25, 2.0**-6)
"""First and smallest step of the load fraction in :func:`_load_continuation` [-]."""


def _load_continuation(system: System, u: np.ndarray, load_at, res, jac, z: np.ndarray,
                       tol: float, residual_tol: float) -> np.ndarray | None:
    """The steady state under the inputs ``u`` reached through a rising load: the inputs in
    :data:`LOAD_UNITS` scaled by a fraction that rises from 0 to 1, each fraction's Newton
    started from the last one's solution (a step that fails is halved, down to the smallest
    of :data:`LOAD_FRACTION_STEP`; one that succeeds is doubled, up to 0.5). A heavy load
    can put the full problem out of Newton's reach from the unloaded start (a spindle under
    15 kN), while each small rise stays within it. None when no such path is found, or the
    inputs hold no load; ``load_at(u)`` sets the inputs of ``res`` and ``jac``, left at
    ``u``."""
    units = system.variable_units
    loads = np.array([units.get(n) in LOAD_UNITS for n in system.input_names], dtype=bool)
    loads &= u != 0.0
    if not loads.any():
        return None
    first, smallest = LOAD_FRACTION_STEP
    fraction, step, found = 0.0, first, None
    try:
        while fraction < 1.0 and step >= smallest:
            trial = min(1.0, fraction + step)
            scaled = u.copy()
            scaled[loads] *= trial
            load_at(scaled)
            solution = _newton(res, jac, z, tol, residual_tol)
            if solution is None:
                step *= 0.5
                continue
            fraction, z, step = trial, solution, min(2.0 * step, 0.5)
        found = z if fraction == 1.0 else None
    finally:
        load_at(u)
    return found


NEWTON_ITERATIONS = 40
"""Most Newton steps :func:`steady_state` tries before it hands the problem to MINPACK's
trust-region method (``hybr``) from the original guess. Each step lowers the residual (the
line search), so more steps cost only where Newton is on its way: a spindle under a 2 kN
radial load at 0.4 m roller distance needs 14 from its unloaded start (12 were allowed, and
MINPACK then stalled)."""
SMALLEST_STEP_FRACTION = 2.0**-10
"""Shortest fraction of a Newton step the line search of :func:`_newton` tries [-]."""
SUFFICIENT_DECREASE = 1e-4
"""Armijo's constant: a step of fraction ``lam`` is taken once it lowers the residual's
2-norm by at least ``SUFFICIENT_DECREASE * lam`` of it [-]."""


def _newton(res, jac, z: np.ndarray, tol: float, residual_tol: float) -> np.ndarray | None:
    """Newton steps on ``res(z) = 0`` with the exact Jacobian, each shortened by halving until
    it lowers the residual's 2-norm (Armijo's sufficient decrease; a full step wherever
    Newton converges by itself): the solution once a step is below ``tol`` relative to ``z``
    (as MINPACK's ``xtol``) and the residual is below ``residual_tol`` after it, else None (a
    singular Jacobian, a residual that is not finite at the start, no step fraction down to
    :data:`SMALLEST_STEP_FRACTION` that lowers it, no convergence in
    :data:`NEWTON_ITERATIONS` steps). Full steps alone oscillated with a growing residual
    from some start points of a steady sweep (a double-layer bearing's middle-ring speed),
    which then fell back to MINPACK, importing scipy.optimize for it (~0.6 s)."""
    from scipy.linalg.lapack import dgesv  # on use: scipy.linalg, ~0.25 s of every command

    r = res(z)
    if not np.isfinite(r).all():
        return None
    for _ in range(NEWTON_ITERATIONS):
        # LAPACK's gesv, as numpy.linalg.solve calls it, without numpy's per-call checks
        # (a tenth of a sweep point's time on the small models)
        _, _, step, info = dgesv(jac(z), -r)
        if info != 0:  # a singular Jacobian (an exact zero pivot)
            return None
        norm, lam = _norm(r), 1.0
        while True:
            taken = lam * step
            z_new = z + taken
            r_new = res(z_new)
            if (_norm(taken) <= tol * max(_norm(z_new), tol)
                    and np.abs(r_new).max() <= residual_tol):
                return z_new
            if (np.isfinite(r_new).all()
                    and _norm(r_new) <= (1.0 - SUFFICIENT_DECREASE * lam) * norm):
                break
            if lam <= SMALLEST_STEP_FRACTION:
                return None
            lam *= 0.5
        z, r = z_new, r_new
    return None


_NEWTON: dict[int, tuple[ca.Function, ca.Function]] = {}
"""By ``id(rhs)``: ``(rhs, [rhs, d rhs / dx])``, the first kept so that its id stays unique."""


def _newton_function(rhs: ca.Function) -> ca.Function:
    """The right-hand side ``f(t, x, u, p)`` and its state Jacobian ``df/dx`` in one function
    (one call per Newton iterate; built once per kernel function)."""
    found = _NEWTON.get(id(rhs))
    if found is None or found[0] is not rhs:
        jacobian = rhs.jacobian()  # (t, x, u, p, out) -> d/dt, d/dx, d/du, d/dp
        args = rhs.mx_in()
        value = rhs(*args)
        d_dx = jacobian(*args, ca.MX(*rhs.size_out(0)))[1]
        found = _NEWTON[id(rhs)] = (rhs, ca.Function("f_jac_x", args, [value, d_dx]))
    return found[1]


class NewtonCall:
    """``f(t, x, u, p)`` and ``df/dx`` on the free states through one ``Function.buffer``:
    ``t``, ``u``, ``p`` and the states that are not free set once per solve
    (:meth:`start`), the free states per iterate, the outputs scattered straight into the
    free rows and columns (structural zeros as 0.0). Not thread-safe: one per thread
    (:func:`_newton_call`).

    Parameters
    ----------
    fn : casadi.Function
        ``(t, x, u, p) -> (f, df/dx)`` (:func:`_newton_function`).
    free : numpy.ndarray
        Indices of the free states.
    """

    def __init__(self, fn: ca.Function, free: np.ndarray):
        self.fn, self.free = fn, free
        self._buf, self._eval = fn.buffer()
        self._inputs = [np.zeros(fn.nnz_in(k)) for k in range(4)]
        for k, array in enumerate(self._inputs):
            self._buf.set_arg(k, memoryview(array))
        self._outputs = [np.zeros(fn.nnz_out(k)) for k in range(2)]
        for k, array in enumerate(self._outputs):
            self._buf.set_res(k, memoryview(array))
        n_x, n = fn.size1_in(1), free.size
        where = np.full(n_x, -1)
        where[free] = np.arange(n)
        f_rows = where[np.asarray(fn.sparsity_out(0).row(), dtype=int)]
        self._f = (np.flatnonzero(f_rows >= 0), f_rows[f_rows >= 0])
        jac = fn.sparsity_out(1)
        rows, cols = (where[np.asarray(i, dtype=int)] for i in jac.get_triplet())
        kept = (rows >= 0) & (cols >= 0)
        self._j = (np.flatnonzero(kept), rows[kept] * n + cols[kept])

    def start(self, t: float, x: np.ndarray, u: np.ndarray, p: np.ndarray) -> None:
        """Set the fixed arguments of a solve.

        Parameters
        ----------
        t : float
            Time [s].
        x : ndarray
            States (the free ones are replaced per iterate).
        u : ndarray
            Inputs.
        p : ndarray
            Parameters.
        """
        t_in, x_in, u_in, p_in = self._inputs
        t_in[0] = t
        x_in[:] = x
        u_in[:] = u
        p_in[:] = p

    def __call__(self, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``f`` on the free states and its Jacobian block at free states ``z`` (new
        arrays)."""
        self._inputs[1][self.free] = z
        self._eval()
        if self._buf.ret() != 0:
            raise RuntimeError(f"evaluation of {self.fn.name()} failed (return code "
                               f"{self._buf.ret()})")
        n = self.free.size
        f, jac = np.zeros(n), np.zeros((n, n))
        taken, into = self._f
        f[into] = self._outputs[0][taken]
        taken, into = self._j
        jac.ravel()[into] = self._outputs[1][taken]
        return f, jac


NEWTON_CALLS_PER_THREAD = 64
"""Most :class:`NewtonCall` a thread keeps (the oldest are forgotten first)."""


def _newton_call(fn: ca.Function, free: np.ndarray) -> NewtonCall:
    """This thread's :class:`NewtonCall` of ``fn`` on the states ``free`` (made on first
    use)."""
    return thread_kept("newton", (id(fn), free.tobytes()), fn, lambda: NewtonCall(fn, free),
                       NEWTON_CALLS_PER_THREAD)


def _free_states(system: System) -> np.ndarray:
    """The states that some derivative depends on (all but :func:`integrator_states`), found
    once per system."""
    free = system.__dict__.get("_steady_free_states")
    if free is None:
        skip = set(integrator_states(system))
        free = np.array([k for k in range(system.n_states) if k not in skip], dtype=int)
        free.flags.writeable = False
        system.__dict__["_steady_free_states"] = free
    return free


def _check_determined(system: System, jacobian: np.ndarray, free: list[int],
                      rcond: float = 1e-12) -> None:
    """Raise if the steady state is not unique: a (numerically) singular Jacobian means some
    states can take any value (e.g. a ring that no torque acts on), and the solver has only
    returned its start guess for them."""
    if jacobian.size == 0:
        return
    from scipy.linalg.lapack import dgesdd  # on use, as in _newton

    # LAPACK's gesdd for the singular values alone, without numpy's per-call checks (a
    # fifth of a small model's sweep point); the vectors only to name the states
    _, sv, _, info = dgesdd(jacobian, compute_uv=0)
    if info == 0 and sv[0] > 0.0 and sv[-1] > rcond * sv[0]:
        return
    _, sv, vt = np.linalg.svd(jacobian)
    if sv[0] > 0.0 and sv[-1] > rcond * sv[0]:
        return
    null = np.abs(vt[-1])
    names = [system.state_names[free[k]] for k in np.flatnonzero(null > 0.1 * null.max())]
    raise SimulationError(
        "steady state not unique: no derivative depends on " + ", ".join(names[:8])
        + " at the solution (singular Jacobian, condition above "
        f"{1.0 / rcond:.0e}); they keep their start values, which are no answer. A body with "
        "no load acting on it at this point (e.g. no friction torque) has no steady value")
