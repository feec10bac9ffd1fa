"""System inputs given as constants, symbolic time functions or tables.

A ``(times, values)`` table is interpolated linearly between its rows and holds its first value
before the first time and its last value after the last time (no extrapolation), as a load or
speed recorded in a CSV file is meant.

Whatever can be expressed symbolically is composed into the compiled right-hand side, so no
Python runs inside the integration; other callables are evaluated numerically.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import ParameterError
from bearingsim.simulation.intervals import locate_problem
from bearingsim.validation import check_mapping

__all__ = ["InputSignal", "input_signal", "input_expression", "check_input_ranges"]


def _table_column(values: Any, name: str, what: str, unit: str) -> np.ndarray:
    """One column of a (times, values) table: finite real numbers."""
    if isinstance(values, (str, bytes)):
        raise ParameterError(f"input {name}: table {what} must be numbers [{unit}], got text")
    try:
        column = np.asarray(values, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ParameterError(f"input {name}: table {what} must be numbers [{unit}], got "
                             f"{values!r:.60}") from None
    if not np.all(np.isfinite(column)):
        raise ParameterError(f"input {name}: table {what} must be finite [{unit}]")
    return column


@dataclass(frozen=True)
class InputSignal:
    """The inputs of a run as ``u(t, q)``: every number the user gave (constants, table rows)
    lifted into the vector ``q``, so that runs whose inputs differ only in those numbers share
    one function (and one integrator built on it).

    Attributes
    ----------
    u : casadi.Function
        ``u(t, q)`` -> the input vector in the system's input order (SX).
    q : numpy.ndarray
        The lifted numbers of this run.
    key : str
        The structure of ``u``: equal keys mean the same function of ``(t, q)``.
    """

    u: ca.Function
    q: np.ndarray
    key: str

    def of_time(self) -> ca.Function:
        """``u(t)`` with this run's numbers substituted."""
        t = ca.SX.sym("t")
        return ca.Function("u", [t], [self.u(t, ca.DM(self.q))], ["t"], ["u"])


def _one(name: str, spec: Any, t: ca.SX, unit: str,
         lifted: list[float]) -> tuple[ca.SX | None, str]:
    """One input: its expression in ``t``, or None when its numbers were appended to
    ``lifted`` (a constant: one number; a table: its times, then its values), and its
    structure key."""
    if isinstance(spec, (bool, np.bool_)):
        raise ParameterError(f"input {name} must be a number in {unit}, a function of time or "
                             f"a (times, values) table, got {spec!r}")
    if isinstance(spec, (int, float, np.floating, np.integer)):
        if not abs(spec) <= sys.float_info.max:  # NaN, inf, or an int beyond float (10**400)
            raise ParameterError(f"input {name} must be finite, got {spec!r:.40}")
        lifted.append(float(spec))
        return None, "const"
    if isinstance(spec, tuple) and len(spec) == 2:
        times = _table_column(spec[0], name, "times", "s")
        vals = _table_column(spec[1], name, "values", unit)
        if times.size != vals.size or times.size < 2 or np.any(np.diff(times) <= 0):
            raise ParameterError(
                f"input {name}: a table needs two equally long arrays (times strictly "
                "increasing, at least two points)"
            )
        lifted.extend(times.tolist())
        lifted.extend(vals.tolist())
        return None, f"table[{times.size}]"
    if callable(spec):
        try:
            out = spec(t)
        except Exception as exc:  # noqa: BLE001 - report any failure of the user's function
            raise ParameterError(
                f"input {name}: the function could not be evaluated symbolically ({exc}); "
                "write it with casadi or bearingsim.symbolic math"
            ) from None
        expr = ca.SX(out)
        return expr, f"f:{expr}"
    raise ParameterError(
        f"input {name}: expected a number, a function of time or a (times, values) table, "
        f"got {type(spec).__name__}"
    )


def input_signal(system: System, inputs: dict[str, Any] | None) -> InputSignal:
    """The system's inputs as ``u(t, q)`` with the given numbers lifted into ``q``.

    Parameters
    ----------
    system : System
        The assembled system.
    inputs : dict, optional
        Input name -> number, symbolic function of time, or ``(times, values)`` table
        (piecewise linear, the end values held outside ``[times[0], times[-1]]``). Inputs not
        given take their start values.

    Returns
    -------
    InputSignal

    Raises
    ------
    ParameterError
        For an unknown input name or a malformed value.
    """
    inputs = check_mapping(inputs, "inputs", "simulate", "input names")
    unknown = set(inputs) - set(system.input_names)
    if unknown:
        raise ParameterError(
            f"unknown input(s) {', '.join(sorted(unknown))}; the system's inputs are: "
            + (", ".join(system.input_names) or "none")
        )
    t = ca.SX.sym("t")
    lifted: list[float] = []
    exprs, keys, slices = [], [], []
    for sig in system.inputs:
        first = len(lifted)
        expr, kind = _one(sig.name, inputs.get(sig.name, sig.start), t, sig.unit,
                          lifted)
        exprs.append(expr)
        keys.append(f"{sig.name}={kind}")
        slices.append((first, len(lifted)))
    q = ca.SX.sym("q", len(lifted))
    for k, (first, last) in enumerate(slices):
        if last - first == 1:
            exprs[k] = q[first]
        elif last > first:
            n = (last - first) // 2
            times, vals = q[first:first + n], q[first + n:last]
            # hold the end values outside the table (pw_lin alone would extrapolate linearly)
            held = ca.fmin(ca.fmax(t, times[0]), times[n - 1])
            exprs[k] = ca.pw_lin(held, times, vals)
    u = ca.vertcat(*exprs) if exprs else ca.SX(0, 1)
    return InputSignal(ca.Function("u", [t, q], [u], ["t", "q"], ["u"]),
                       np.array(lifted, dtype=float), "|".join(keys))


def input_expression(system: System, inputs: dict[str, Any] | None, t: ca.SX) -> ca.SX:
    """Vector of input expressions of ``t`` in the system's input order (numbers inlined; see
    :func:`input_signal` for the arguments and errors)."""
    signal = input_signal(system, inputs)
    return signal.u(t, ca.DM(signal.q))


def check_input_ranges(system: System, u_fn: ca.Function, times: np.ndarray) -> None:
    """Check every input signal against its declared range and for singularities, at the given
    times and, by interval arithmetic (:mod:`~bearingsim.simulation.intervals`), everywhere
    between the first and the last of them.

    Raises
    ------
    ParameterError
        Naming the input, its unit and range, and the first time it leaves the range; or the
        time span in which it is singular (a pole, a log of a non-positive number), undefined
        or overflows.
    """
    if not system.inputs or times.size == 0:
        return
    t = ca.SX.sym("t")
    u = u_fn(t)
    for k, sig in enumerate(system.inputs):
        component = ca.Function(f"u{k}", [t], [u[k]])
        problem = locate_problem(component, float(times[0]), float(times[-1]), sig.low,
                                 sig.high)
        if problem is not None:
            raise ParameterError(
                f"input {sig.name} [{sig.unit}]: {problem.reason} between t = "
                f"{problem.t_lo:.9g} s and {problem.t_hi:.9g} s (checked by interval "
                f"arithmetic over [{times[0]:g}, {times[-1]:g}] s, between the output points "
                f"too)")
    _check_sampled(system, u_fn, times)


def _check_sampled(system: System, u_fn: ca.Function, times: np.ndarray) -> None:
    """Every input at ``times``: finite and within its declared range."""
    values = np.asarray(u_fn.map(times.size)(times[None, :]), dtype=float).reshape(
        len(system.inputs), times.size)
    for sig, row in zip(system.inputs, values, strict=True):
        bad = ~np.isfinite(row)
        if bad.any():
            k = int(np.argmax(bad))
            raise ParameterError(f"input {sig.name} = {row[k]:g} [{sig.unit}] at t = "
                                 f"{times[k]:g} s is not a finite number")
        if sig.low is not None:
            bad |= row < sig.low
        if sig.high is not None:
            bad |= row > sig.high
        if bad.any():
            k = int(np.argmax(bad))
            lo = "-inf" if sig.low is None else f"{sig.low:g}"
            hi = "inf" if sig.high is None else f"{sig.high:g}"
            raise ParameterError(
                f"input {sig.name} = {row[k]:g} [{sig.unit}] at t = {times[k]:g} s is outside its "
                f"valid range [{lo}, {hi}] [{sig.unit}]"
            )
