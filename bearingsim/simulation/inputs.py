"""System inputs given as constants, symbolic time functions or tables.

A ``(times, values)`` table is interpolated linearly between its rows and holds its first value
before the first time and its last value after the last time (no extrapolation), as a load or
speed recorded in a CSV file is meant.

Whatever can be expressed symbolically is composed into the compiled right-hand side, so no
Python runs inside the integration; other callables are evaluated numerically.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.entry_points import value_key
from bearingsim.errors import ParameterError
from bearingsim.keeps import kept
from bearingsim.language.symbols import of_time
from bearingsim.simulation.fastcall import evaluate, mapped_function
from bearingsim.units import is_quantity, to_si
from bearingsim.units.registry import si_factor
from bearingsim.validation import check_mapping

__all__ = ["InputSignal", "input_signal", "input_expression"]


def _table_column(values: Any, name: str, what: str, unit: str) -> np.ndarray:
    """One column of a (times, values) table: finite real numbers (a :class:`pint.Quantity`
    array converted to ``unit``)."""
    if is_quantity(values):
        factor, offset = si_factor(str(values.units), unit)
        values = np.asarray(values.magnitude, dtype=float) * factor + offset
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


def table_expression(t: ca.SX, times: ca.SX, values: ca.SX) -> ca.SX:
    """Linear interpolation in a table of ``n`` rows, the end values held outside it, built in
    O(n) (``casadi.pw_lin`` with symbolic breakpoints takes O(n^2): 277 s for 10^5 rows).

    Each segment contributes its line where ``t`` is in it and an exact zero elsewhere, so the
    value at a row is that row's value (no summation error).

    Parameters
    ----------
    t : casadi.SX
        Time [s] (scalar).
    times : casadi.SX
        The table's times [s], ``n`` increasing values (n >= 2).
    values : casadi.SX
        The table's values, ``n`` of them (in the input's unit).

    Returns
    -------
    casadi.SX
        The interpolated value at ``t``.
    """
    n = times.numel()
    held = ca.fmin(ca.fmax(t, times[0]), times[n - 1])
    t0, t1, v0, v1 = times[:n - 1], times[1:], values[:n - 1], values[1:]
    inside = (held >= t0) * (held < t1)
    lines = v0 + (v1 - v0) / (t1 - t0) * (held - t0)
    return ca.dot(inside, lines) + (held >= times[n - 1]) * values[n - 1]


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
    lifted : tuple of (int, int) or None
        Per input, the slice ``q[first:last]`` of its numbers (a constant: one number; a table:
        its times, then its values), or None for a function of time.
    """

    u: ca.Function
    q: np.ndarray
    key: str
    lifted: tuple[tuple[int, int] | None, ...] = ()
    _evaluated: dict[bytes, np.ndarray] = field(default_factory=dict, compare=False, repr=False)
    """:meth:`at`'s last results by the bytes of the times (``u`` is a pure function of ``t``
    and ``q``)."""

    def of_time(self) -> ca.Function:
        """``u(t)`` with this run's numbers substituted.

        Returns
        -------
        casadi.Function
            ``u(t)`` -> the input vector.
        """
        t = ca.SX.sym("t")
        return ca.Function("u", [t], [self.u(t, ca.DM(self.q))], ["t"], ["u"])

    def at(self, times: np.ndarray) -> np.ndarray:
        """Every input at ``times`` [s]: shape ``(n_inputs, len(times))`` (one mapped call of
        ``u``, the mapped function built once per structure and number of times; the last
        :data:`EVALUATED_PER_SIGNAL` results kept with the signal).

        Parameters
        ----------
        times : array_like
            Times [s].

        Returns
        -------
        numpy.ndarray
            The inputs, one row per input and one column per time (a new array).
        """
        times = np.atleast_1d(np.asarray(times, dtype=float))
        key = times.tobytes()
        found = self._evaluated.get(key)
        if found is None:
            n = times.size
            mapped = mapped_function(self.u, n)
            found = evaluate(mapped, times[None, :], np.repeat(self.q[:, None], n, axis=1))[0]
            if len(self._evaluated) >= EVALUATED_PER_SIGNAL:
                del self._evaluated[next(iter(self._evaluated))]
            self._evaluated[key] = found
        return found.copy()


EVALUATED_PER_SIGNAL = 8
"""Results of :meth:`InputSignal.at` a signal keeps (the oldest are dropped first)."""


_SIGNALS: dict[str, ca.Function] = {}
"""``u(t, q)`` by the signal's structure key (names, kinds, expressions of ``t``)."""
_SIGNALS_LIMIT = 256


def _one(name: str, spec: Any, t: ca.SX, unit: str,
         lifted: list[float]) -> tuple[ca.SX | None, str]:
    """One input: its expression in ``t``, or None when its numbers were appended to
    ``lifted`` (a constant: one number; a table: its times, then its values), and its
    structure key. A number with a unit (text or :class:`pint.Quantity`) is converted to
    ``unit`` first. A scene expression's numbers are appended to ``lifted`` too, its expression
    written in ``t`` and the symbols of :data:`_LIFTED` (which :func:`_signal_function`
    replaces by the numbers' places in ``q``)."""
    if type(spec) is float and abs(spec) <= sys.float_info.max:  # the common case, at once
        lifted.append(spec)
        return None, "const"
    spec = to_si(spec, unit, f"input {name}")
    if isinstance(spec, str):
        raise ParameterError(
            f"input {name}: {spec!r:.60} is not a number with a unit; give a number in {unit}, "
            f"a number with a unit (e.g. '10000 rpm', '2 kN'), a function of time or a "
            f"(times, values) table")
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
        expr, key, numbers = _function_of_time(name, spec, t)
        lifted.extend(numbers)
        return expr, key
    raise ParameterError(
        f"input {name}: expected a number, a function of time or a (times, values) table, "
        f"got {type(spec).__name__}"
    )


_EXPRESSIONS: dict[str, tuple[ca.SX, str, tuple[float, ...]]] = {}
"""Expressions of time, their structure keys and lifted numbers by the text of a scene
expression."""
_EXPRESSIONS_LIMIT = 256


def _function_of_time(name: str, spec: Any, t: ca.SX) -> tuple[ca.SX, str, tuple[float, ...]]:
    """An input given as a function of time: its expression in ``t``, structure key and
    lifted numbers.

    A function that carries its text as ``expression`` (a scene expression,
    :func:`~bearingsim.scenes.expressions.compile_expression`) is a pure function of that
    text: it is evaluated once per text, not per run, and its numbers are lifted (its
    ``lifted`` form: the expression in ``t`` and :data:`_LIFTED`, keyed by the text with
    the numbers left out), so that expressions that differ only in their numbers share one
    structure. Any other function is evaluated on every call (it may read values that change
    between runs) and its numbers are part of its structure.
    """
    text = getattr(spec, "expression", None)
    text = text if isinstance(text, str) and t is _T else None
    found = None if text is None else _EXPRESSIONS.get(text)
    if found is not None:
        return found
    form = getattr(spec, "lifted", None) if text is not None else None
    if form is not None and len(form.numbers) <= _LIFTED.numel():
        found = (ca.SX(form.build(t, _LIFTED)), f"e:{form.template}", form.numbers)
    else:
        expr = of_time(spec, t, f"input {name}")
        found = (expr, f"f:{expr}", ())
    if text is not None:
        if len(_EXPRESSIONS) >= _EXPRESSIONS_LIMIT:
            del _EXPRESSIONS[next(iter(_EXPRESSIONS))]
        _EXPRESSIONS[text] = found
    return found


def input_signal(system: System, inputs: dict[str, Any] | None) -> InputSignal:
    """The system's inputs as ``u(t, q)`` with the given numbers lifted into ``q``.

    Parameters
    ----------
    system : System
        The assembled system.
    inputs : dict, optional
        Input name -> number (in the input's SI unit), number with a unit (``"10000 rpm"``, a
        :class:`pint.Quantity`), symbolic function of time, or ``(times, values)`` table
        (piecewise linear, the end values held outside ``[times[0], times[-1]]``). Inputs not
        given take their start values, except the required ones (a shaft speed).

    Returns
    -------
    InputSignal

    Raises
    ------
    ParameterError
        For an unknown input name, a required input not given, a malformed value or a unit of
        another quantity.
    """
    inputs = check_mapping(inputs, "inputs", "simulate", "input names")
    key = _given_key(inputs)
    if key is None:
        return _new_signal(system, inputs)

    def shared() -> InputSignal:
        signal = _new_signal(system, inputs)
        signal.q.flags.writeable = False  # shared by the runs with these inputs
        return signal

    return kept(system.__dict__.setdefault("_input_signals", {}), key, shared,
                SIGNALS_PER_SYSTEM)


SIGNALS_PER_SYSTEM = 64
"""Input specifications whose :class:`InputSignal` a system keeps (the oldest dropped first)."""


def _given_key(inputs: dict[str, Any]) -> tuple | None:
    """What determines the signal of ``inputs``, hashable: every value a number or text
    (:func:`~bearingsim.entry_points.value_key`) or a scene expression (by its text); None when a
    value is anything else (a table, a quantity, a function that may read values that
    change)."""
    key = []
    for name, spec in inputs.items():
        found = value_key(spec)
        if found is None:
            text = getattr(spec, "expression", None)
            if not (isinstance(text, str) and callable(spec)):
                return None
            found = ("expression", text)
        key.append((name, found))
    return tuple(key)


def _new_signal(system: System, inputs: dict[str, Any]) -> InputSignal:
    """:func:`input_signal` without the memory (``inputs`` checked to be a dict)."""
    unknown = set(inputs) - set(system.input_names)
    if unknown:
        raise ParameterError(
            f"unknown input(s) {', '.join(sorted(unknown))}; the system's inputs are: "
            + (", ".join(system.input_names) or "none")
        )
    missing = [sig for sig in system.inputs
               if getattr(sig, "required", False) and sig.name not in inputs]
    if missing:
        raise ParameterError(
            "input(s) not given: " + ", ".join(f"{s.name} [{s.unit}]" for s in missing)
            + " (the run would hold them at their start value, e.g. a speed of 0); give each "
              "as a number in its unit, a number with a unit ('10000 rpm'), a function of time "
              "or a (times, values) table")
    t = _T
    lifted: list[float] = []
    exprs, keys, slices = [], [], []
    spans = []
    for sig in system.inputs:
        first = len(lifted)
        expr, kind = _one(sig.name, inputs.get(sig.name, sig.start), t, sig.unit,
                          lifted)
        exprs.append(expr)
        keys.append(f"{sig.name}={kind}")
        spans.append((first, len(lifted)))
        slices.append(spans[-1] if expr is None else None)
    key = "|".join(keys)
    u = _SIGNALS.get(key)
    if u is None:
        u = _signal_function(exprs, slices, spans, len(lifted))
        if len(_SIGNALS) >= _SIGNALS_LIMIT:
            del _SIGNALS[next(iter(_SIGNALS))]
        _SIGNALS[key] = u
    return InputSignal(u, np.array(lifted, dtype=float), key, tuple(slices))


_T = ca.SX.sym("t")
"""The time symbol of every input expression (one symbol: equal expressions, equal keys)."""

_LIFTED = ca.SX.sym("c", 64)
"""The symbols of a scene expression's lifted numbers (an expression with more keeps its
numbers in its structure)."""


def _signal_function(exprs: list[ca.SX | None], slices: list[tuple[int, int] | None],
                     spans: list[tuple[int, int]], n_q: int) -> ca.Function:
    """``u(t, q)`` from the inputs' expressions of ``t`` and the slices of ``q`` holding the
    lifted constants and tables; ``spans``: each input's numbers in ``q`` (an expression's
    lifted numbers, the symbols :data:`_LIFTED`, there)."""
    q = ca.SX.sym("q", n_q)
    exprs = list(exprs)
    for k, piece in enumerate(slices):
        if piece is None:
            first, last = spans[k]
            if last > first:
                exprs[k] = ca.substitute(exprs[k], _LIFTED[:last - first], q[first:last])
            continue
        first, last = piece
        if last - first == 1:
            exprs[k] = q[first]
        else:
            n = (last - first) // 2
            exprs[k] = table_expression(_T, q[first:first + n], q[first + n:last])
    u = ca.vertcat(*exprs) if exprs else ca.SX(0, 1)
    return ca.Function("u", [_T, q], [u], ["t", "q"], ["u"])


def input_expression(system: System, inputs: dict[str, Any] | None, t: ca.SX) -> ca.SX:
    """Vector of input expressions of ``t`` in the system's input order (numbers inlined; see
    :func:`input_signal` for the arguments and errors).

    Parameters
    ----------
    system : System
        The closed system.
    inputs : dict, optional
        Input name -> constant, table or function of time, as
        :func:`input_signal` takes them.
    t : casadi.SX
        Time [s] (scalar).

    Returns
    -------
    casadi.SX
        The input vector as expressions of ``t``.
    """
    signal = input_signal(system, inputs)
    return signal.u(t, ca.DM(signal.q))
