"""Time integration of an assembled system: argument checks, consistent start values, the
integrator chosen from :data:`~bearingsim.simulation.integrators.METHODS`, observed variables."""

from __future__ import annotations

import functools
import time as _time
import warnings
from typing import Any

import numpy as np

from bearingsim.assembler.system import System, as_system
from bearingsim.checks import check_tolerance
from bearingsim.entry_points import entry_point
from bearingsim.errors import LongRunWarning, ParameterError, SimulationError
from bearingsim.simulation.budget import DEFAULT_MAX_STEPS, RunBudget
from bearingsim.simulation.choice import choose_method
from bearingsim.simulation.closed import close_inputs
from bearingsim.simulation.diagnostics import listed_names, no_value_cause
from bearingsim.simulation.fastcall import evaluate, mapped_function
from bearingsim.simulation.input_ranges import check_input_ranges
from bearingsim.simulation.inputs import InputSignal, input_signal
from bearingsim.simulation.integrators import (
    BACKENDS,
    METHODS,
    IntegrationProblem,
    Trajectory,
    methods_of,
)
from bearingsim.simulation.result import Result, ResultLayout
from bearingsim.simulation.steady import steady_state
from bearingsim.simulation.sundials_integrators import LINEAR_SOLVERS
from bearingsim.units import is_quantity, quantity_to_si
from bearingsim.validation import check_choice, check_flag, check_range

__all__ = ["simulate", "initial_state"]


def initial_state(
    system: System, signal: InputSignal, p: np.ndarray, x0: np.ndarray, t0: float,
    steady: dict[str, Any] | None | bool,
) -> np.ndarray:
    """Consistent initial states: initial equations and, on request, a steady state.

    ``signal`` is the run's inputs; ``steady`` is False for none, else the run's input
    specification (``None`` or a dict) that the steady state is solved with.

    Parameters
    ----------
    system : System
        The closed system.
    signal : InputSignal
        The run's inputs.
    p : numpy.ndarray
        Parameter vector (SI).
    x0 : numpy.ndarray
        Start values of the states (SI).
    t0 : float
        Start time [s].
    steady : dict or None or bool
        False: no steady state; else the input specification it is solved with.

    Returns
    -------
    numpy.ndarray
        The initial states (SI).
    """
    x = x0.copy()
    if system.init_residual is not None:
        free = system.free_initial_states
        u0 = signal.at(t0)[:, 0]

        def res(z):
            xx = x.copy()
            xx[free] = z
            return np.asarray(system.init_residual(t0, xx, u0, p), dtype=float).ravel()

        from scipy.optimize import root  # on use: importing scipy.optimize takes ~0.6 s

        sol = root(res, x[free], tol=1e-12)
        if not sol.success:
            raise SimulationError(
                "initial equations could not be solved for "
                + ", ".join(system.state_names[k] for k in free)
                + f": {sol.message}"
            )
        x[free] = sol.x
    if steady is not False:
        x = steady_state(system, inputs=steady, p=p, x_guess=x, t=t0, require_unique=False)
    return x


@entry_point
def simulate(
    system: System,
    t_end: float | str,
    *,
    t_start: float | str = 0.0,
    inputs: dict[str, Any] | None = None,
    parameters: dict[str, float] | None = None,
    x0: dict[str, float] | None = None,
    initial: str = "start",
    method: str | None = None,
    backend: str | None = None,
    rtol: float = 1e-6,
    atol: float = 1e-8,
    n_points: int = 501,
    t_eval: np.ndarray | None = None,
    max_step: float | str = np.inf,
    progress: bool | None = None,
    compiled: bool | str = "auto",
    linear_solver: str | None = None,
    max_steps: int = DEFAULT_MAX_STEPS,
    timeout: float | str | None = None,
) -> Result:
    """Integrate a system and return every variable as a named series.

    Parameters
    ----------
    system : System
        From :func:`bearingsim.assembler.assemble`.
    t_end : float or str
        End time [s] (this and the other times also as a time with a unit: ``"50 ms"``).
    t_start : float or str
        Start time [s].
    inputs : dict, optional
        Input name -> constant, ``f(t)`` (symbolic) or ``(times, values)`` table (linear
        between the rows, holding the first and last value outside the table's times).
    parameters : dict, optional
        Parameter name -> value (validated; no recompilation).
    x0 : dict, optional
        State name -> initial value (SI, or with a unit: ``"100 rpm"``), overriding start
        values.
    initial : {"start", "steady"}
        ``"steady"`` starts from the steady state at ``t_start``.
    method : str, optional
        By default (neither ``method`` nor ``backend`` given) the fastest accurate method for
        the system (:func:`~bearingsim.simulation.choice.choose_method`): ``"compiled_bdf"``
        for the stiff ODE form when a C compiler exists (a short first run on a cold cache:
        ``"cvodes"`` on the VM while C compiles), ``"cvodes"`` without one, ``"idas"`` for
        models whose nonlinear blocks only the DAE form compiles; ``Result.stats["method"]``
        and ``stats["method_reason"]`` say which and why (``"none"`` for a model without
        states: nothing is integrated, whatever ``method`` says).
        Backend ``"scipy"``: ``"BDF"`` (its default), ``"Radau"``, ``"LSODA"`` (these with the
        exact sparse Jacobian), ``"RK45"``, ``"DOP853"``, ``"RK23"``; backend ``"casadi"``:
        ``"cvodes"`` (its default) or ``"idas"`` (SUNDIALS; any letter case); backend
        ``"compiled"``: ``"compiled_bdf"``, a variable-order BDF whose step loop is C calling
        the compiled kernels directly (:mod:`~bearingsim.simulation.compiled_bdf`; an LU that
        skips the Jacobian's structural zeros, in a fill-reducing order of the states; needs a
        C compiler).
    backend : {"scipy", "casadi", "compiled"}, optional
        Integrator family; by default the one ``method`` belongs to. A method of another
        family raises :class:`~bearingsim.errors.ParameterError`.
    rtol, atol : float
        Relative tolerance in :data:`~bearingsim.checks.RTOL_RANGE` and absolute tolerance
        [state units] in :data:`~bearingsim.checks.ATOL_RANGE`.
    n_points : int
        Number of equally spaced output points in ``[t_start, t_end]``, an integer >= 2
        (ignored when ``t_eval`` is given).
    t_eval : array_like, optional
        Output times [s]: finite, strictly increasing, within ``[t_start, t_end]``.
    max_step : float or str
        Largest step [s], > 0 (``inf``: no limit); CVODES and IDAS get it as
        ``max_step_size``.
    progress : bool, optional
        Show a progress bar of the simulated time on standard error (``True``), never
        (``False``), or by default only when standard error is a terminal and the run takes
        longer than about 2 s (:mod:`~bearingsim.simulation.progress`). The bar observes the
        run and never changes it: the same numbers bit for bit with or without it.
    compiled : bool or "auto"
        Backend ``"compiled"``: ``True`` or ``"auto"`` (the kernel is compiled now if it is not
        cached; ``False`` raises :class:`~bearingsim.errors.ParameterError`).
        Backend ``"casadi"``: evaluate the right-hand side (or DAE residual) and its exact
        Jacobian as generated C (``True``: compiling now if needed; raises
        :class:`~bearingsim.simulation.c_compiler.CompileError` when impossible), on CasADi's VM
        (``False``), or ``"auto"``: C when a compiler exists and the model is not tiny, a
        library not yet cached being compiled in the background while this run uses the VM
        (both give the same numbers). ``Result.stats["backend"]`` says which ran and
        ``stats["backend_reason"]`` why.
    linear_solver : str, optional
        Backend ``"casadi"``: the SUNDIALS linear solver, one of
        :data:`~bearingsim.simulation.sundials_integrators.LINEAR_SOLVERS`; default by size
        (:func:`~bearingsim.simulation.sundials_integrators.choose_linear_solver`).
    max_steps : int
        Step budget of the run [-], >= 1 (default
        :data:`~bearingsim.simulation.budget.DEFAULT_MAX_STEPS`; CVODES and IDAS get it as
        ``max_num_steps`` per call).
    timeout : float or str, optional
        Wall-time budget of the integration [s], > 0 (``None``: none). Exceeding either budget
        raises :class:`~bearingsim.errors.BudgetExceededError` with the time reached.

    Returns
    -------
    Result
        The series, with ``inputs`` (every input's value at the last output time) and
        ``parameters`` (the run's parameter values) recorded, so that
        :func:`~bearingsim.simulation.linearize` can linearize at the run's end point.

    Raises
    ------
    ParameterError
        For a bad argument (naming it, its unit and valid range) or a method that is not one
        of ``backend``'s.
    SimulationError
        With the time reached and the variables that diverged.
    BudgetExceededError
        When the run uses up ``max_steps`` or ``timeout``, with the time reached.
    """
    system = as_system(system, "simulate")
    t_start, t_end, max_step, timeout = (  # "50 ms" -> 0.05
        _seconds(v, name) for v, name in ((t_start, "t_start"), (t_end, "t_end"),
                                          (max_step, "max_step"), (timeout, "timeout")))
    settings = (t_start, t_end, rtol, atol, max_step, method, backend, initial, progress,
                compiled, linear_solver)
    try:
        method, backend = _checked_settings(*settings)
    except TypeError:  # an argument that is not hashable: checked without the memory
        method, backend = _check_settings(*settings)
    budget = RunBudget(max_steps, timeout, method, t_end)
    t_eval = _output_times(t_start, t_end, n_points, t_eval)
    _check_work(system, t_start, t_end, t_eval.size, max_step)
    setup = _time.perf_counter()
    if system.n_states == 0:  # nothing to integrate, whatever the method
        reason = NO_STATES if method is None else f"method={method!r} given; {NO_STATES}"
        method = method or "cvodes"  # (its backend decides below whether inputs are closed)
    elif method is None:
        choice = choose_method(system, t_end - t_start, compiled)
        method, compiled, reason = choice.method, choice.compiled, choice.reason
    else:
        reason = f"method={method!r} given"
    p = system.p0(parameters)
    signal = input_signal(system, inputs)
    x_start = initial_state(system, signal, p, system.x0(x0), t_start,
                            inputs if initial == "steady" else False)
    check_input_ranges(system, signal, _check_times(t_eval, t_start, t_end))
    # scipy's integrators call the closed functions from Python; SUNDIALS builds its own
    closed = (close_inputs(system, inputs, signal=signal)
              if METHODS[method].backend == "scipy" else None)
    wall = _time.perf_counter()
    budget.start()
    if system.n_states == 0:
        traj = Trajectory(t_eval, np.zeros((0, t_eval.size)), None, {"method": "none"})
    else:
        problem = IntegrationProblem(system, closed, inputs, p, x_start, t_start, t_end, t_eval,
                                     rtol, atol, max_step, progress, signal, compiled,
                                     linear_solver, budget)
        traj = METHODS[method].run(problem)
    ts, xs, values, stats = traj.t, traj.x, traj.values, traj.stats
    stats["method_reason"] = reason
    stats["wall_time"] = _time.perf_counter() - wall
    stats["prepare_time"] = wall - setup
    if values is None:
        closed = closed or close_inputs(system, inputs, signal=signal)
        obs = mapped_function(closed.observe, ts.size)
        try:
            values = evaluate(obs, ts[None, :], xs, np.repeat(p[:, None], ts.size, axis=1))[0]
        except RuntimeError as exc:  # a Newton block of an algebraic loop did not converge
            raise SimulationError(
                f"{system.name}: the variables could not be evaluated at the output times: "
                f"{str(exc).splitlines()[0][:300]}") from None
    _check_finite(system, ts, values)
    return Result.of_run(ts, values, _result_layout(system), stats, signal.at(ts)[:, -1], p)


def _seconds(value: Any, name: str) -> Any:
    """A time argument of :func:`simulate` in s: a number with a unit converted (``"50 ms"``),
    anything else as given (checked with the other settings)."""
    if isinstance(value, str) or is_quantity(value):
        return quantity_to_si(value, "s", f"simulate: {name}")
    return value


def _check_settings(t_start: Any, t_end: Any, rtol: Any, atol: Any, max_step: Any,
                    method: Any, backend: Any, initial: Any, progress: Any, compiled: Any,
                    linear_solver: Any) -> tuple[str, str] | tuple[None, None]:
    """Check the scalar settings of a :func:`simulate` call (raising
    :class:`~bearingsim.errors.ParameterError` for a bad one); the checked
    ``(method, backend)`` (:func:`_method_backend`)."""
    check_flag(progress, "progress", "simulate", allow_none=True)
    check_range(t_start, "t_start", "s", where="simulate")
    check_range(t_end, "t_end", "s", t_start, None, low_inclusive=False, where="simulate")
    check_tolerance(rtol, "rtol", "rtol", "simulate")
    check_tolerance(atol, "atol", "atol", "simulate")
    if max_step != np.inf:
        check_range(max_step, "max_step", "s", 0.0, None, low_inclusive=False, where="simulate")
    checked = _method_backend(method, backend)
    check_choice(initial, "initial", ("start", "steady"), "simulate")
    if compiled not in (True, False, "auto"):
        raise ParameterError(f"simulate: compiled must be True, False or 'auto', got "
                             f"{compiled!r}")
    if linear_solver is not None:
        check_choice(linear_solver, "linear_solver", LINEAR_SOLVERS, "simulate")
    return checked


_checked_settings = functools.lru_cache(maxsize=256, typed=True)(_check_settings)
""":func:`_check_settings` remembered per settings of the same values and types (the checks
are pure functions of them; a setting that fails raises each time)."""


def _result_layout(system: System) -> ResultLayout:
    """The names, units, descriptions and shown outputs every result of ``system`` shares
    (made once per system). Shown first: the outputs the system was assembled for, else the
    assembly's own variables (undotted names: ``Rs``, ``w_shaft``, not connector torques)."""
    layout = system.__dict__.get("_result_layout")
    if layout is None:
        requested = getattr(system, "requested_outputs", None)
        shown = ([n for n in requested if n in system.observed_units] if requested else
                 [n for n in system.observed_names if "." not in n and not n.startswith("der(")])
        layout = system.__dict__["_result_layout"] = ResultLayout(
            tuple(system.observed_names), system.variable_units,
            dict(system.observed_descriptions), tuple(shown), tuple(system.input_names),
            tuple(system.parameter_names))
    return layout


def _method_backend(method: str | None, backend: str | None
                    ) -> tuple[str, str] | tuple[None, None]:
    """Checked ``(method, backend)``: each backend with its own methods, a backend's default
    method filled in; ``(None, None)`` when neither is given (:func:`choose_method` decides).

    SUNDIALS method names are accepted in any letter case, scipy's as scipy spells them.
    """
    if backend is not None:
        check_choice(backend, "backend", tuple(BACKENDS), "simulate")
    if method is None:
        return (None, None) if backend is None else (BACKENDS[backend], backend)
    if not isinstance(method, str):
        raise ParameterError(f"simulate: method must be a string ({_valid_methods()}), got "
                             f"{method!r}")
    name = method.lower() if method.lower() in methods_of("casadi") else method
    if name not in METHODS:
        raise ParameterError(f"simulate: unknown method {method!r}; valid methods are "
                             f"{_valid_methods()}")
    owner = METHODS[name].backend
    if backend is not None and backend != owner:
        raise ParameterError(
            f"simulate: method {method!r} belongs to backend {owner!r}, not backend "
            f"{backend!r}; valid methods are {_valid_methods()}"
        )
    return name, owner


def _valid_methods() -> str:
    """Every backend with its methods, for messages."""
    return "; ".join(f"backend {b!r}: {', '.join(methods_of(b))}" for b in BACKENDS)


NO_STATES = "no states: nothing to integrate, the variables solved at each output time"
"""``Result.stats["method_reason"]`` of a model without states (``stats["method"]`` is
``"none"``)."""

MAX_OUTPUT_BYTES = 2 * 1024**3
"""Largest result a run may produce (output points x observed variables x 8 bytes)."""
WARN_OUTPUT_BYTES = 256 * 1024**2
MAX_STEPS = 10_000_000
"""Most steps ``max_step`` may force on a run ((t_end - t_start) / max_step)."""
WARN_STEPS = 1_000_000


def _check_work(system: System, t_start: float, t_end: float, n_out: int,
                max_step: float) -> None:
    """Refuse (above the MAX_ limits) or warn about runs whose size alone makes them minutes or
    gigabytes long, with the estimate."""
    size = n_out * (len(system.observed_names) + 1) * 8
    if size > WARN_OUTPUT_BYTES:
        shape = f"{n_out} output points x {len(system.observed_names)} variables"
        _bound(size, MAX_OUTPUT_BYTES, f"{shape} would take {size / 1024**3:.1f} GiB",
               f"(limit {MAX_OUTPUT_BYTES / 1024**3:.0f} GiB); ask for fewer n_points or "
               f"prune the model to the outputs you need (assemble(outputs=...))")
    steps = (t_end - t_start) / max_step
    if steps > WARN_STEPS:
        _bound(steps, MAX_STEPS, f"max_step = {max_step:g} s over {t_end - t_start:g} s "
               f"forces at least {steps:.3g} steps",
               f"(limit {MAX_STEPS:.0e}); give a larger max_step [s] or a shorter run")


def _bound(amount: float, limit: float, what: str, remedy: str) -> None:
    """Raise ParameterError when ``amount`` exceeds ``limit``, else warn (LongRunWarning; called
    for amounts above the warning threshold)."""
    if amount > limit:
        raise ParameterError(f"simulate: {what} {remedy}")
    warnings.warn(f"simulate: {what}", LongRunWarning, stacklevel=4)


def _output_times(t_start: float, t_end: float, n_points: Any, t_eval: Any) -> np.ndarray:
    """Checked output times: ``t_eval`` or ``n_points`` equally spaced in [t_start, t_end]."""
    if t_eval is None:
        if isinstance(n_points, bool) or not isinstance(n_points, (int, np.integer)):
            raise ParameterError(
                f"simulate: n_points must be an integer >= 2 [1], got {n_points!r}"
            )
        check_range(n_points, "n_points", "1", 2, MAX_OUTPUT_BYTES // 16, where="simulate")
        if type(t_start) is float and type(t_end) is float:
            return _even_times(t_start.hex(), t_end.hex(), int(n_points)).copy()
        return np.linspace(t_start, t_end, int(n_points))
    times = np.asarray(check_range(t_eval, "t_eval", "s", where="simulate"), dtype=float)
    if times.ndim != 1 or times.size == 0:
        raise ParameterError(
            f"simulate: t_eval must be a non-empty one-dimensional array of times [s], got "
            f"shape {times.shape}"
        )
    check_range(times, "t_eval", "s", t_start, t_end, where="simulate")
    if np.any(np.diff(times) <= 0.0):
        k = int(np.argmax(np.diff(times) <= 0.0))
        raise ParameterError(
            f"simulate: t_eval must be strictly increasing [s], got t_eval[{k + 1}] = "
            f"{times[k + 1]:g} s after t_eval[{k}] = {times[k]:g} s"
        )
    return times


@functools.lru_cache(maxsize=64)
def _even_times(t_start: str, t_end: str, n: int) -> np.ndarray:
    """``numpy.linspace(t_start, t_end, n)`` of the times given by their bits
    (``float.hex``: ``-0.0`` is not ``0.0``), made once per span and number (read-only)."""
    times = np.linspace(float.fromhex(t_start), float.fromhex(t_end), n)
    times.flags.writeable = False
    return times


def _check_times(t_eval: np.ndarray, t_start: float, t_end: float) -> np.ndarray:
    """The times the inputs are checked at: the output times with the start and end time."""
    if t_eval[0] == t_start and t_eval[-1] == t_end:
        return t_eval
    return np.union1d(t_eval, [t_start, t_end])


def _check_finite(system: System, ts: np.ndarray, values: np.ndarray) -> None:
    """Raise if a variable is not finite at an output time (e.g. a Newton block of an algebraic
    loop that did not converge), naming the first time and the variables."""
    finite = np.isfinite(values)
    if finite.all():
        return
    bad = ~finite
    k = int(np.argmax(bad.any(axis=0)))
    names = [n for n, b in zip(system.observed_names, bad[:, k], strict=True) if b]
    raise SimulationError(
        f"{system.name}: {len(names)} variable(s) are not finite at t = {ts[k]:.6g} s: "
        f"{listed_names(names)}; {no_value_cause(system)}")
