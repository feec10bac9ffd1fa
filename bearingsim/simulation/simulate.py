"""Time integration of an assembled system with scipy's ``solve_ivp`` or CasADi's CVODES."""

from __future__ import annotations

import time as _time
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np
import scipy.integrate
import scipy.optimize

from bearingsim.assembler.system import System
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation.fastcall import BufferedFunction
from bearingsim.simulation.inputs import check_input_ranges, input_expression
from bearingsim.simulation.result import Result
from bearingsim.validation import check_choice, check_range

__all__ = ["ClosedModel", "close_inputs", "simulate", "initial_state"]

SCIPY_METHODS = ("BDF", "Radau", "LSODA", "RK45", "DOP853", "RK23")
CASADI_METHODS = ("cvodes", "idas")
IMPLICIT = ("BDF", "Radau", "LSODA")


@dataclass
class ClosedModel:
    """The system with its inputs bound: ``f(t, x, p)``, ``J(t, x, p)``, ``observe(t, x, p)``."""

    f: ca.Function
    jac: ca.Function
    observe: ca.Function
    u: ca.Function
    symbolic: bool


def close_inputs(system: System, inputs: dict[str, Any] | None,
                 symbolic: bool = False) -> ClosedModel:
    """Compose the system's functions with symbolic input signals of time.

    With ``symbolic=True`` the symbolic originals of a compiled system are used (needed where
    CasADi differentiates the functions, as in its integrators).
    """
    funcs = (system.symbolic_functions or system.functions) if symbolic else system.functions
    ode, obs, jac = (funcs[k] for k in ("ode", "observe", "jac_x"))
    t_sx = ca.SX.sym("t")
    u_expr = input_expression(system, inputs, t_sx)
    u_fn = ca.Function("u", [t_sx], [u_expr])
    sx = ode.is_a("SXFunction")
    sym = ca.SX if sx else ca.MX
    t = sym.sym("t")
    x = sym.sym("x", system.n_states)
    p = sym.sym("p", len(system.params))
    u = u_fn(t)
    args, names = [t, x, p], ["t", "x", "p"]
    return ClosedModel(
        f=ca.Function("f", args, [ode(t, x, u, p)], names, ["xdot"]),
        jac=ca.Function("J", args, [jac(t, x, u, p)], names, ["J"]),
        observe=ca.Function("obs", args, [obs(t, x, u, p)], names, ["y"]),
        u=u_fn,
        symbolic=sx,
    )


def initial_state(
    system: System, closed: ClosedModel, p: np.ndarray, x0: np.ndarray, t0: float, steady: bool
) -> np.ndarray:
    """Consistent initial states: initial equations and, on request, a steady state."""
    x = x0.copy()
    if system.init_residual is not None:
        free = system.free_initial_states
        u0 = np.asarray(closed.u(t0), dtype=float).ravel()

        def res(z):
            xx = x.copy()
            xx[free] = z
            return np.asarray(system.init_residual(t0, xx, u0, p), dtype=float).ravel()

        sol = scipy.optimize.root(res, x[free], tol=1e-12)
        if not sol.success:
            raise SimulationError(
                "initial equations could not be solved for "
                + ", ".join(system.state_names[k] for k in free)
                + f": {sol.message}"
            )
        x[free] = sol.x
    if steady:
        from bearingsim.simulation.steady import steady_state

        x = steady_state(system, closed=closed, p=p, x_guess=x, t=t0)
    return x


def simulate(
    system: System,
    t_end: float,
    *,
    t_start: float = 0.0,
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
    max_step: float = np.inf,
    progress: bool | None = None,
) -> Result:
    """Integrate a system and return every variable as a named series.

    Parameters
    ----------
    system : System
        From :func:`bearingsim.assembler.assemble`.
    t_end : float
        End time [s].
    t_start : float
        Start time [s].
    inputs : dict, optional
        Input name -> constant, ``f(t)`` (symbolic) or ``(times, values)`` table (linear
        between the rows, holding the first and last value outside the table's times).
    parameters : dict, optional
        Parameter name -> value (validated; no recompilation).
    x0 : dict, optional
        State name -> initial value, overriding start values.
    initial : {"start", "steady"}
        ``"steady"`` starts from the steady state at ``t_start``.
    method : str, optional
        Backend ``"scipy"``: ``"BDF"`` (the default), ``"Radau"``, ``"LSODA"`` (these with the
        exact sparse Jacobian), ``"RK45"``, ``"DOP853"``, ``"RK23"``; backend ``"casadi"``:
        ``"cvodes"`` (its default) or ``"idas"`` (SUNDIALS; any letter case).
    backend : {"scipy", "casadi"}, optional
        Integrator family; by default the one ``method`` belongs to. A method of the other
        family raises :class:`~bearingsim.errors.ParameterError`.
    rtol, atol : float
        Relative tolerance in (0, 1] and absolute tolerance > 0.
    n_points : int
        Number of equally spaced output points in ``[t_start, t_end]``, an integer >= 2
        (ignored when ``t_eval`` is given).
    t_eval : array_like, optional
        Output times [s]: finite, strictly increasing, within ``[t_start, t_end]``.
    max_step : float
        Largest step [s], > 0 (``inf``: no limit); CVODES and IDAS get it as
        ``max_step_size``.
    progress : bool, optional
        Show a progress bar (scipy methods); default: only for runs that take longer than
        about 2 s.

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
    """
    check_range(t_start, "t_start", "s", where="simulate")
    check_range(t_end, "t_end", "s", t_start, None, low_inclusive=False, where="simulate")
    check_range(rtol, "rtol", "1", 0.0, 1.0, low_inclusive=False, where="simulate")
    check_range(atol, "atol", "1", 0.0, None, low_inclusive=False, where="simulate")
    if max_step != np.inf:
        check_range(max_step, "max_step", "s", 0.0, None, low_inclusive=False, where="simulate")
    method, backend = _method_backend(method, backend)
    check_choice(initial, "initial", ("start", "steady"), "simulate")
    t_eval = _output_times(t_start, t_end, n_points, t_eval)
    p = system.p0(parameters)
    closed = close_inputs(system, inputs)
    x_start = initial_state(system, closed, p, system.x0(x0), t_start, initial == "steady")
    check_input_ranges(system, closed.u, np.union1d(t_eval, [t_start, t_end]))
    wall = _time.perf_counter()
    if system.n_states == 0:
        ts, xs, stats = t_eval, np.zeros((0, t_eval.size)), {}
    elif backend == "scipy":
        ts, xs, stats = _run_scipy(system, closed, p, x_start, t_start, t_end, t_eval, method,
                                   rtol, atol, max_step, progress)
    elif method.lower() == "idas" and "dae_ode" in system.functions:
        ts, xs, values, stats = _run_idas_dae(system, closed, p, x_start, t_start, t_eval,
                                              _sundials_options(rtol, atol, max_step))
    else:
        sym_closed = close_inputs(system, inputs, symbolic=True)
        ts, xs, stats = _run_casadi(system, sym_closed, p, x_start, t_start, t_eval,
                                    _sundials_options(rtol, atol, max_step), method)
    stats["wall_time"] = _time.perf_counter() - wall
    if "dae" not in stats.get("method", ""):
        obs = closed.observe.map(ts.size)
        values = np.asarray(obs(ts[None, :], xs, np.repeat(p[:, None], ts.size, axis=1)),
                            dtype=float)
    units = _units(system)
    u_end = np.asarray(closed.u(ts[-1]), dtype=float).ravel()
    return Result(ts, list(system.observed_names), values, units, stats,
                  inputs=dict(zip(system.input_names, u_end.tolist(), strict=True)),
                  parameters=dict(zip(system.parameter_names, p.tolist(), strict=True)))


def _method_backend(method: str | None, backend: str | None) -> tuple[str, str]:
    """Checked ``(method, backend)``: each backend with its own methods, defaults filled in."""
    methods = {"scipy": SCIPY_METHODS, "casadi": CASADI_METHODS}
    valid = "; ".join(f"backend {b!r}: {', '.join(m)}" for b, m in methods.items())
    if backend is not None:
        check_choice(backend, "backend", tuple(methods), "simulate")
    if method is None:
        return ("cvodes", "casadi") if backend == "casadi" else ("BDF", "scipy")
    if not isinstance(method, str):
        raise ParameterError(f"simulate: method must be a string ({valid}), got {method!r}")
    owner = ("casadi" if method.lower() in CASADI_METHODS
             else "scipy" if method in SCIPY_METHODS else None)
    if owner is None:
        raise ParameterError(f"simulate: unknown method {method!r}; valid methods are {valid}")
    if backend is not None and backend != owner:
        raise ParameterError(
            f"simulate: method {method!r} belongs to backend {owner!r}, not backend "
            f"{backend!r}; valid methods are {valid}"
        )
    return (method.lower() if owner == "casadi" else method), owner


def _output_times(t_start: float, t_end: float, n_points: Any, t_eval: Any) -> np.ndarray:
    """Checked output times: ``t_eval`` or ``n_points`` equally spaced in [t_start, t_end]."""
    if t_eval is None:
        if isinstance(n_points, bool) or not isinstance(n_points, (int, np.integer)):
            raise ParameterError(
                f"simulate: n_points must be an integer >= 2 [1], got {n_points!r}"
            )
        check_range(n_points, "n_points", "1", 2, None, where="simulate")
        return np.linspace(t_start, t_end, int(n_points))
    try:
        times = np.asarray(t_eval, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(
            f"simulate: t_eval must be an array of times [s], got {type(t_eval).__name__}"
        ) from None
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


def _units(system: System) -> dict[str, str]:
    units = dict(system.observed_units)
    units.update({s.name: s.unit for s in system.states + system.inputs + system.outputs})
    return units


def _diverged(system: System, x: np.ndarray, x0: np.ndarray) -> str:
    bad = [n for n, v in zip(system.state_names, x, strict=True) if not np.isfinite(v)]
    if bad:
        return "non-finite: " + ", ".join(bad[:10])
    growth = np.abs(x) / (np.abs(x0) + 1.0)
    order = np.argsort(growth)[::-1][:5]
    return "largest growth: " + ", ".join(
        f"{system.state_names[k]}={x[k]:.3g}" for k in order
    )


def _run_scipy(system, closed, p, x0, t0, t1, t_eval, method, rtol, atol, max_step, progress):
    f, jac = BufferedFunction(closed.f), BufferedFunction(closed.jac)
    n_f = [0]
    bar = _progress_bar(t0, t1, progress)
    last = [t0, x0]

    def fun(t, x):
        n_f[0] += 1
        out = f.vector(t, x, p)
        if not np.all(np.isfinite(out)):
            bad = [n for n, v in zip(system.state_names, out, strict=True) if not np.isfinite(v)]
            raise SimulationError(
                f"the right-hand side is not finite at t = {t:.6g} s for der({', '.join(bad[:8])})"
                f"; states there: {_diverged(system, x, x0)}"
            )
        if t > last[0]:
            if bar is not None:
                bar.update(t - last[0])
            last[0] = t
        last[1] = x
        return out

    kwargs: dict[str, Any] = {}
    if method in IMPLICIT:
        def jacobian(t, x):
            matrix = jac.sparse(t, x, p)
            return matrix.toarray() if method == "LSODA" else matrix
        kwargs["jac"] = jacobian
    try:
        sol = scipy.integrate.solve_ivp(
            fun, (t0, t1), x0, method=method, t_eval=t_eval, rtol=rtol, atol=atol,
            max_step=max_step, **kwargs,
        )
    except (ArithmeticError, ValueError, RuntimeError, np.linalg.LinAlgError) as exc:
        if isinstance(exc, SimulationError):
            raise
        raise SimulationError(
            f"{method} failed near t = {last[0]:.6g} s of {t1:g} s ({type(exc).__name__}: {exc}); "
            f"{_diverged(system, last[1], x0)}"
        ) from None
    finally:
        if bar is not None:
            bar.close()
    if sol.status < 0:
        t_reached = sol.t[-1] if sol.t.size else t0
        raise SimulationError(
            f"{method} failed at t = {t_reached:.6g} s of {t1:g} s: {sol.message}; "
            f"{_diverged(system, last[1], x0)}"
        )
    stats = {"method": method, "nfev": sol.nfev, "njev": sol.njev, "nlu": sol.nlu,
             "n_rhs_calls": n_f[0]}
    return sol.t, sol.y, stats


def _sundials_options(rtol: float, atol: float, max_step: float) -> dict[str, Any]:
    """Options of CasADi's CVODES / IDAS integrators (``max_step`` only when finite)."""
    opts: dict[str, Any] = {"abstol": atol, "reltol": rtol, "max_num_steps": 100000}
    if np.isfinite(max_step):
        opts["max_step_size"] = float(max_step)
    return opts


def _run_casadi(system, closed, p, x0, t0, t_eval, opts, plugin):
    sym = ca.SX if closed.symbolic else ca.MX
    x = sym.sym("x", system.n_states)
    pp = sym.sym("p", len(p))
    t = sym.sym("t")
    dae = {"x": x, "p": pp, "t": t, "ode": closed.f(t, x, pp)}
    grid = t_eval[t_eval > t0]
    integ = ca.integrator(plugin, plugin, dae, float(t0), grid, opts)
    try:
        out = integ(x0=x0, p=p)
    except RuntimeError:
        _locate_casadi_failure(system, dae, plugin, opts, float(t0), grid, x0, p)
        raise
    xs = np.asarray(out["xf"], dtype=float)
    if not np.all(np.isfinite(xs)):
        k = int(np.argmax(~np.all(np.isfinite(xs), axis=0)))
        raise SimulationError(
            f"{plugin.upper()} produced non-finite states by t = {grid[k]:.6g} s; "
            f"{_diverged(system, xs[:, k], x0)}"
        )
    if t_eval[0] <= t0:
        xs = np.hstack([x0[:, None], xs])
        ts = np.concatenate([[t0], grid])
    else:
        ts = grid
    stats = {"method": plugin}
    st = integ.stats()
    for key in ("nsteps", "nfevals", "nlinsetups"):
        if key in st:
            stats[key] = st[key]
    return ts, xs, stats


def _run_idas_dae(system, closed, p, x0, t0, t_eval, opts):
    """IDAS on the semi-explicit DAE: the nonlinear blocks' tearing variables are algebraic
    states that IDAS iterates on, warm-started from step to step."""
    funcs = system.symbolic_functions or system.functions
    f, g, obs, z_of = (funcs[k] for k in ("dae_ode", "dae_alg", "dae_observe", "dae_z"))
    t = ca.MX.sym("t")
    x = ca.MX.sym("x", system.n_states)
    z = ca.MX.sym("z", g.size1_out(0))
    pp = ca.MX.sym("p", len(p))
    u = closed.u(t)
    dae = {"x": x, "z": z, "p": pp, "t": t, "ode": f(t, x, z, u, pp), "alg": g(t, x, z, u, pp)}
    grid = t_eval[t_eval > t0]
    integ = ca.integrator("idas_dae", "idas", dae, float(t0), grid, opts)
    u0 = np.asarray(closed.u(t0), dtype=float).ravel()
    z0 = np.asarray(z_of(t0, x0, u0, p), dtype=float).ravel()
    try:
        out = integ(x0=x0, z0=z0, p=p)
    except RuntimeError as exc:
        raise SimulationError(f"IDAS (DAE form) failed: {str(exc).splitlines()[0]}; start "
                              f"states: {_diverged(system, x0, x0)}") from None
    xs = np.asarray(out["xf"], dtype=float)
    zs = np.asarray(out["zf"], dtype=float).reshape(z0.size, grid.size)
    if t_eval[0] <= t0:
        xs, zs = np.hstack([x0[:, None], xs]), np.hstack([z0[:, None], zs])
        ts = np.concatenate([[t0], grid])
    else:
        ts = grid
    us = np.asarray(closed.u.map(ts.size)(ts[None, :]), dtype=float).reshape(-1, ts.size)
    values = np.asarray(obs.map(ts.size)(ts[None, :], xs, zs, us,
                                         np.repeat(p[:, None], ts.size, axis=1)), dtype=float)
    stats = {"method": "idas (dae)", "algebraic_states": int(z0.size)}
    return ts, xs, values, stats


def _locate_casadi_failure(system, dae, plugin, opts, t0, grid, x0, p):
    """Integrate interval by interval to report where a SUNDIALS run failed (failure path only)."""
    x, t_prev = np.asarray(x0, dtype=float), t0
    for t_next in grid:
        step = ca.integrator(plugin, plugin, dae, t_prev, [float(t_next)], opts)
        try:
            x_new = np.asarray(step(x0=x, p=p)["xf"], dtype=float).ravel()
        except RuntimeError:
            x_new = None
        if x_new is None or not np.all(np.isfinite(x_new)):
            raise SimulationError(
                f"{plugin.upper()} failed between t = {t_prev:.6g} s and {t_next:.6g} s; "
                f"states at t = {t_prev:.6g} s: {_diverged(system, x, x0)}"
            ) from None
        x, t_prev = x_new, float(t_next)
    raise SimulationError(f"{plugin.upper()} failed (not reproducible interval by interval)")


def _progress_bar(t0, t1, progress):
    if progress is False:
        return None
    from tqdm import tqdm

    return tqdm(total=t1 - t0, unit="s(sim)", delay=0 if progress else 2.0, leave=False,
                bar_format="{l_bar}{bar}| {n:.3g}/{total:.3g} s [{elapsed}<{remaining}]")
