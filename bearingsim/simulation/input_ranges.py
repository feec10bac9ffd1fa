"""Input signals checked against their inputs' declared ranges and limits before a run: a
value out of range is refused (naming the input, its unit, range and the first time it leaves
it), a value above its limit (a limiting speed, a static load rating) warns."""

from __future__ import annotations

import warnings
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.assembler.system import System
from bearingsim.errors import ParameterError
from bearingsim.input_limits import INPUT_LIMITS
from bearingsim.simulation.input_bounds import numbers_valid
from bearingsim.simulation.inputs import InputSignal
from bearingsim.simulation.intervals import locate_problem
from bearingsim.units import CUSTOMARY_DIFFERS, engineering, to_si

__all__ = ["check_input_ranges", "check_input_value"]

_T = ca.SX.sym("t")

_CHECKED: dict[tuple, bool] = {}
"""Signals found valid, by (the inputs' ranges, structure, numbers, time span)."""
_CHECKED_LIMIT = 1024


def check_input_ranges(system: System, signal: InputSignal, times: np.ndarray) -> None:
    """Check every input signal against its declared range and for singularities, at the given
    times and everywhere between the first and the last of them.

    Constants and tables are checked exactly on their numbers (a table, linear between its
    rows and held outside them, ranges over its values); functions of time at the given times
    and, by interval arithmetic (:mod:`~bearingsim.simulation.intervals`), between them. A
    signal found valid is remembered (by system, structure, numbers and time span), so
    repeated runs check it once.

    Parameters
    ----------
    system : System
        The closed system declaring the inputs' ranges.
    signal : InputSignal
        The run's inputs.
    times : numpy.ndarray
        The run's output times [s], increasing.

    Raises
    ------
    ParameterError
        Naming the input, its unit and range, and the first time it leaves the range; or the
        time span in which it is singular (a pole, a log of a non-positive number), undefined
        or overflows.
    """
    if not system.inputs or times.size == 0:
        return
    t0, t1 = float(times[0]), float(times[-1])
    key = (system.input_ranges, signal.key, signal.q.tobytes(), t0, t1)
    notes = _CHECKED.get(key)
    if notes is None:
        notes = _check_signal(system, signal, times)
        if len(_CHECKED) >= _CHECKED_LIMIT:
            del _CHECKED[next(iter(_CHECKED))]
        _CHECKED[key] = notes
    for category, note in notes:
        warnings.warn(note, category, stacklevel=3)


def check_input_value(system: System, name: str, value: Any) -> float:
    """A constant value of one input in the input's unit, checked as a run would check it
    (finite, within its declared range; a warning above its limit).

    Parameters
    ----------
    system : System
        The system declaring the input.
    name : str
        The input's name (one of ``system.input_names``).
    value : float or str or pint.Quantity
        A number [input unit] or a number with a unit (``"10000 rpm"``).

    Returns
    -------
    float
        The value [input unit].

    Raises
    ------
    ParameterError
        If the value is not a number (with a unit of the input's quantity), not finite or
        outside the input's range.
    """
    sig = system.inputs[system.input_names.index(name)]
    number = to_si(value, sig.unit, f"input {name}")
    if isinstance(number, (str, bool, np.bool_)) or not isinstance(number, (int, float,
                                                                            np.number)):
        raise ParameterError(f"input {name}: give a number in {sig.unit} or a number with a "
                             f"unit (e.g. '10000 rpm', '2 kN'), got {value!r:.60}")
    note = _check_values(sig, np.array([number], dtype=float), None)
    if note is not None:
        warnings.warn(note[1], note[0], stacklevel=2)
    return float(number)


def _check_signal(system: System, signal: InputSignal, times: np.ndarray
                  ) -> list[tuple[type[UserWarning], str]]:
    """:func:`check_input_ranges` without the memory: raises for an input out of range,
    returns the warnings (their category and text: inputs above their limit)."""
    t0, t1 = float(times[0]), float(times[-1])
    if None not in signal.lifted and numbers_valid(system, signal.key, signal.q, signal.lifted):
        return []
    notes: list[tuple[type[UserWarning], str] | None] = []
    functions = []
    for k, (sig, piece) in enumerate(zip(system.inputs, signal.lifted, strict=True)):
        if piece is None:
            functions.append(k)
            continue
        first, last = piece
        values = signal.q[first:last] if last - first == 1 else \
            signal.q[first + (last - first) // 2:last]
        notes.append(_check_values(sig, values, None if last - first == 1 else "table value"))
    if functions:
        u = signal.u(_T, ca.DM(signal.q))
        for k in functions:
            sig = system.inputs[k]
            problem = locate_problem(ca.Function(f"u{k}", [_T], [u[k]]), t0, t1, sig.low,
                                     sig.high)
            if problem is not None:
                raise ParameterError(
                    f"input {sig.name} [{sig.unit}]: {problem.reason} between t = "
                    f"{problem.t_lo:.9g} s and {problem.t_hi:.9g} s (checked by interval "
                    f"arithmetic over [{t0:g}, {t1:g}] s, between the output points too)"
                    f"{_bare_number_hint(sig)}")
        values = signal.at(times)
        notes += [_check_values(system.inputs[k], values[k], times) for k in functions]
    return [note for note in notes if note is not None]


def _check_values(sig, values: np.ndarray, times: np.ndarray | str | None
                  ) -> tuple[type[UserWarning], str] | None:
    """Values of one input: finite and within its declared range (else ParameterError); the
    warning (category, text) when they exceed the input's limit (``warn_above``), else None.
    ``times``: the times of the values [s], or a word naming them (``"table value"``), or None
    for a constant."""
    bad = ~np.isfinite(values)

    def where(k: int) -> str:
        if times is None:
            return ""
        return f" ({times} {k})" if isinstance(times, str) else f" at t = {times[k]:g} s"

    if bad.any():
        k = int(np.argmax(bad))
        raise ParameterError(f"input {sig.name} = {values[k]:g} [{sig.unit}]{where(k)} is not "
                             f"a finite number")
    if sig.low is not None:
        bad |= values < sig.low
    if sig.high is not None:
        bad |= values > sig.high
    if bad.any():
        k = int(np.argmax(bad))
        lo = "-inf" if sig.low is None else f"{sig.low:g}"
        hi = "inf" if sig.high is None else f"{sig.high:g}"
        raise ParameterError(
            f"input {sig.name} = {values[k]:g} [{sig.unit}]{where(k)} is outside its valid "
            f"range [{lo}, {hi}] [{sig.unit}]{_bare_number_hint(sig)}")
    limit = getattr(sig, "warn_above", None)
    if limit is not None and values.size and np.max(np.abs(values)) > limit:
        k = int(np.argmax(np.abs(values)))
        kind = INPUT_LIMITS[sig.limit]
        return kind.warning, (
            f"input {sig.name} reaches {engineering(abs(values[k]), sig.unit, both=True)}"
            f"{where(k)}, above its limit {engineering(limit, sig.unit, both=True)} "
            f"({kind.name}: {kind.effect})")
    return None


def _bare_number_hint(sig) -> str:
    """The limit behind an input's bounds and, for an input whose SI unit is not the
    customary one (rad/s, m, N m), how to give another unit (docs/units.md)."""
    limit = getattr(sig, "warn_above", None)
    text = ""
    if limit is not None and sig.high is not None:
        text = (f"; the bound is {sig.high / limit:g} x {INPUT_LIMITS[sig.limit].name}: "
                f"{engineering(limit, sig.unit, both=True)}")
    if sig.unit in CUSTOMARY_DIFFERS:
        text += (f"; a bare number is in {sig.unit}, a number with a unit converts "
                 f"(e.g. '10000 rpm', '25 µm', '30 N mm')")
    return text
