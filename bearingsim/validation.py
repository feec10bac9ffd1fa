"""Argument checks shared by every layer: numbers and ranges, choices, counts, flags, vectors,
mappings, keyword options and data-table entries. Each raises
:class:`~bearingsim.errors.ParameterError` (:class:`~bearingsim.errors.CatalogError` for a table
entry) naming the argument, its unit and valid range. Checks of physical quantities (diameters in
metres, contact radii, moduli, regularization widths) are in :mod:`bearingsim.physical_checks`.
"""

from __future__ import annotations

import difflib
import inspect
import math
import numbers
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from bearingsim.errors import CatalogError, ParameterError
from bearingsim.symbolic import is_symbolic
from bearingsim.units.registry import is_quantity, quantity_to_si

__all__ = [
    "check_finite",
    "check_flag",
    "check_mapping",
    "check_vector",
    "check_choice",
    "check_count",
    "check_number",
    "check_quantity",
    "check_options",
    "options_object",
    "check_range",
    "keyword_names",
    "table_entry",
]


def check_range(
    value: Any,
    name: str,
    unit: str = "-",
    low: float | None = None,
    high: float | None = None,
    *,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
    where: str = "",
) -> Any:
    """Check that a numeric value (scalar or array) is finite and within ``[low, high]``.

    Symbolic (CasADi) values are passed through unchecked: they are checked when numbers are bound.

    Parameters
    ----------
    value : float or array_like or casadi.SX
        The value to check.
    name : str
        Name of the parameter or variable, used in the message.
    unit : str
        Unit shown in the message.
    low, high : float, optional
        Bounds; ``None`` means unbounded.
    low_inclusive, high_inclusive : bool
        Whether the bounds themselves are allowed.
    where : str
        Component path or function name, used in the message.

    Returns
    -------
    The value unchanged.

    Raises
    ------
    ParameterError
        If the value is not a number, is NaN or infinite, or lies outside the range.
    """
    if _plain_in_range(value, low, high, low_inclusive, high_inclusive):
        return value  # the common case, without numpy (a failure takes the path below)
    if is_symbolic(value):
        return value
    label = f"{where}: {name}" if where else name
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ParameterError(
            f"{label} must be a number in {unit}, got {value!r} ({type(value).__name__})")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(
            f"{label} must be a number in {unit}, got {value!r:.60} ({type(value).__name__})"
        ) from None
    if not np.all(np.isfinite(arr)):
        raise ParameterError(f"{label} must be finite, got {value!r} [{unit}]")
    lo_ok = True if low is None else np.all(arr >= low if low_inclusive else arr > low)
    hi_ok = True if high is None else np.all(arr <= high if high_inclusive else arr < high)
    if not (lo_ok and hi_ok):
        lo = "-inf" if low is None else f"{low:g}"
        hi = "inf" if high is None else f"{high:g}"
        lb = "[" if (low is None or low_inclusive) and low is not None else "("
        rb = "]" if (high is None or high_inclusive) and high is not None else ")"
        if low is None:
            lb = "("
        if high is None:
            rb = ")"
        shown = value if arr.ndim == 0 else f"array with min {arr.min():g}, max {arr.max():g}"
        slip = (" (a value in mm^2/s? give m^2/s: 1 mm^2/s = 1e-6 m^2/s)"
                if unit in ("m2/s", "m^2/s") and not hi_ok else "")
        raise ParameterError(
            f"{label} = {shown} [{unit}] is outside the valid range {lb}{lo}, {hi}{rb} [{unit}]"
            f"{slip}")
    if arr.ndim == 0 and not math.isfinite(float(arr)):
        raise ParameterError(f"{label} must be finite [{unit}]")
    return value



def check_quantity(value: Any, name: str, unit: str, low: float | None = None,
                   high: float | None = None, *, low_inclusive: bool = True,
                   high_inclusive: bool = True, where: str = "") -> Any:
    """A number in ``unit``, or a number with a unit converted to ``unit``, within its range:
    the API's arguments take what scenes and ``simulate`` inputs take (docs/units.md).

    Parameters
    ----------
    value : float or array_like or str or pint.Quantity
        A bare number (taken as ``unit``), a number with a unit as text (``"3000 rpm"``,
        ``"20 um"``) or a :class:`pint.Quantity`.
    name : str
        Name of the argument, used in the message.
    unit : str
        Its SI unit, model notation (``"rad/s"``, ``"m"``).
    low, high : float, optional
        Bounds [``unit``]; ``None`` means unbounded.
    low_inclusive, high_inclusive : bool
        Whether the bounds themselves are allowed.
    where : str
        Component path or function name, used in the message.

    Returns
    -------
    The value in ``unit`` (a bare number unchanged).

    Raises
    ------
    ParameterError
        As :func:`check_range`; for text that is not a number with a unit, or a unit of another
        quantity, :class:`~bearingsim.units.UnitError` (a ParameterError) naming the accepted
        forms.
    """
    if isinstance(value, str) or is_quantity(value):
        value = quantity_to_si(value, unit, f"{where}: {name}" if where else name)
    return check_range(value, name, unit, low, high, low_inclusive=low_inclusive,
                       high_inclusive=high_inclusive, where=where)


_PLAIN_INT_LIMIT = 2**53
"""Largest magnitude of a Python ``int`` the fast path of :func:`check_range` takes (exact as a
float; larger ones, up to those beyond the float range, go through numpy)."""
_PLAIN = (float, int)


def _plain_in_range(value: Any, low: float | None, high: float | None, low_inclusive: bool,
                    high_inclusive: bool) -> bool:
    """Whether ``value`` is a Python ``float`` or ``int`` (not ``bool``), finite and within the
    bounds: :func:`check_range`'s answer for plain numbers without building an array."""
    if not (low is None or type(low) in _PLAIN) or not (high is None or type(high) in _PLAIN):
        return False
    kind = type(value)
    if kind is float:
        if not math.isfinite(value):
            return False
    elif kind is not int or not -_PLAIN_INT_LIMIT <= value <= _PLAIN_INT_LIMIT:
        return False
    if low is not None and not (value >= low if low_inclusive else value > low):
        return False
    return high is None or (value <= high if high_inclusive else value < high)


def check_choice(value: Any, name: str, allowed: tuple, where: str = "") -> Any:
    """Check that ``value`` is one of ``allowed``.

    Parameters
    ----------
    value : Any
        The value to check.
    name : str
        Name of the argument, used in the message.
    allowed : tuple
        The valid values.
    where : str
        Component path or function name, used in the message.

    Returns
    -------
    The value unchanged.

    Raises
    ------
    ParameterError
        ``"<where>: <name> must be 'a', 'b' or 'c', got <value>"``.
    """
    if value in allowed:
        return value
    names = [repr(a) for a in allowed]
    options = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]
    label = f"{where}: {name}" if where else name
    raise ParameterError(f"{label} must be {options}, got {value!r}")


def check_count(value, name: str, low: int = 1, where: str = ""):
    """Check that a count (number of rows, balls, ...) is a whole number ``>= low``.

    Floats with an integral value (``2.0``) are accepted; booleans, fractions, NaN and
    infinities are not. Symbolic (CasADi) values pass unchecked, as in
    :func:`check_range`.

    Parameters
    ----------
    value : int, float, array or casadi.SX
        The count [-].
    name : str
        Argument name, used in the message.
    low : int
        Smallest valid count [-].
    where : str
        Function name, used in the message.

    Returns
    -------
    The value unchanged.

    Raises
    ------
    ParameterError
        ``"<where>: <name> must be a whole number >= <low> [-], got <value>"``.
    """
    if type(value) is int and low <= value <= _PLAIN_INT_LIMIT:
        return value  # the common case, without numpy
    if is_symbolic(value):
        return value
    label = f"{where}: {name}" if where else name
    arr = np.asarray(value)
    if arr.dtype == bool or arr.dtype.kind not in "iuf":
        raise ParameterError(f"{label} must be a whole number >= {low} [-], got {value!r}")
    check_range(value, name, "-", low, where=where)
    if np.any(arr != np.round(arr)):
        raise ParameterError(f"{label} must be a whole number >= {low} [-], got {value!r}")
    return value


def check_number(value: Any, name: str, unit: str, high: float | None, where: str) -> None:
    """Check a real number (not a bool or string) in ``[0, high]``.

    Parameters
    ----------
    value : object
        The value to check.
    name : str
        Argument name, for the message.
    unit : str
        Unit of the value, for the message.
    high : float or None
        Upper bound (None: none).
    where : str
        The component or function, for the message.

    Raises
    ------
    ParameterError
        For a non-number or a value outside the range, naming ``name``, ``unit`` and ``where``.
    """
    if isinstance(value, (bool, str, bytes)) or not isinstance(value, numbers.Real):
        raise ParameterError(f"{where}: {name} must be a number in [{unit}], got {value!r} "
                             f"({type(value).__name__})")
    check_range(value, name, unit, 0.0, high, where=where)


def keyword_names(func: Callable, exclude: tuple[str, ...] = ()) -> tuple[str, ...]:
    """Names ``func`` accepts as keywords, from its signature (``self`` and ``exclude`` left out).

    Parameters
    ----------
    func : callable
        A function or class (its constructor's signature).
    exclude : tuple of str
        Names the caller sets itself.

    Returns
    -------
    tuple of str
        In signature order; a ``**kwargs`` catch-all is not listed.
    """
    kinds = (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    return tuple(n for n, p in inspect.signature(func).parameters.items()
                 if p.kind in kinds and n != "self" and n not in exclude)


def check_options(options: dict[str, Any], accepted: tuple[str, ...], where: str,
                  what: str, context: str = "", owner: Callable | None = None) -> None:
    """Raise for keyword options that are not among ``accepted``.

    Parameters
    ----------
    options : dict
        The options given.
    accepted : tuple of str
        The valid option names (e.g. from :func:`keyword_names`).
    where : str
        Function or component name, used in the message.
    what : str
        What the options are called (e.g. ``"layer_options"``).
    context : str
        Appended to the name list (e.g. ``"at fidelity 'torque'"``).
    owner : callable, optional
        The function that takes them: its arguments are listed too (read for the message only).

    Raises
    ------
    ParameterError
        ``"<where>: unknown <what> 'a' <context>; accepted: ...; did you mean 'c'?"``.
    """
    unknown = [k for k in options if k not in accepted]
    if unknown:
        ctx = f" {context}" if context else ""
        arguments = keyword_names(owner) if owner is not None else ()
        valid = [*accepted, *arguments]
        close = next((c for k in unknown if isinstance(k, str)
                      for c in difflib.get_close_matches(k, valid, n=1)), None)
        hint = f"; did you mean {close!r}?" if close else ""
        listed = ", ".join(accepted) or "none"
        if arguments:
            listed += f"; and the arguments {', '.join(arguments)}"
        raise ParameterError(f"{where}: unknown {what} {', '.join(map(repr, unknown))}{ctx}; "
                             f"accepted: {listed}{hint}")


def options_object(options: Any, kind: type, where: str) -> Any:
    """An options object of type ``kind``: a default ``kind()`` for None, ``options`` itself
    when it is one, else an error.

    Parameters
    ----------
    options : object or None
        The options given to a constructor.
    kind : type
        The options class (a dataclass whose fields all have defaults).
    where : str
        Function or component name, used in the message.

    Returns
    -------
    object
        An instance of ``kind``.

    Raises
    ------
    ParameterError
        ``"<where>: options must be a <kind>, got <type>"``.
    """
    options = kind() if options is None else options
    if not isinstance(options, kind):
        raise ParameterError(f"{where}: options must be a {kind.__name__}, got "
                             f"{type(options).__name__}")
    return options


def check_mapping(value: Any, name: str, where: str, what: str = "names") -> dict:
    """A dict (``None`` is an empty one), else a named error.

    Parameters
    ----------
    value : dict or None
        The argument.
    name : str
        Argument name, used in the message.
    where : str
        Function name, used in the message.
    what : str
        What the keys are (e.g. ``"input names"``), used in the message.

    Returns
    -------
    dict
        A shallow copy.

    Raises
    ------
    ParameterError
        ``"<where>: <name> must be a dict of <what> -> values, got list"``.
    """
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise ParameterError(f"{where}: {name} must be a dict of {what} -> values, got "
                             f"{type(value).__name__} {value!r:.60}")
    return dict(value)


def check_flag(value: Any, name: str, where: str, allow_none: bool = False) -> Any:
    """``True`` or ``False`` (or ``None`` when allowed), else a named error.

    Parameters
    ----------
    value : object
        The value to check.
    name : str
        Argument name, for the message.
    where : str
        The component or function, for the message.
    allow_none : bool
        Accept None.

    Returns
    -------
    bool or None
        ``value``, checked.

    Raises
    ------
    ParameterError
        For anything else (``"yes"``, 1, ...).
    """
    if isinstance(value, (bool, np.bool_)) or (allow_none and value is None):
        return value
    allowed = "True, False or None" if allow_none else "True or False"
    raise ParameterError(f"{where}: {name} must be {allowed}, got {value!r}")


def check_vector(value: Any, size: int, name: str, unit: str, where: str) -> np.ndarray:
    """A finite real vector of ``size`` entries.

    Parameters
    ----------
    value : object
        The value to check.
    size : int
        Required number of entries, >= 1.
    name : str
        Argument name, for the message.
    unit : str
        Unit of the value, for the message.
    where : str
        The component or function, for the message.

    Returns
    -------
    ndarray
        The vector, flattened, as floats [``unit``].

    Raises
    ------
    ParameterError
        For text, the wrong length, or entries that are not finite numbers.
    """
    if isinstance(value, (str, bytes, Mapping)):
        raise ParameterError(f"{where}: {name} must be {size} numbers [{unit}], got "
                             f"{type(value).__name__}")
    try:
        vec = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ParameterError(f"{where}: {name} must be {size} numbers [{unit}], got "
                             f"{value!r:.60}") from None
    if vec.size != size:
        raise ParameterError(f"{where}: {name} must have {size} entries [{unit}], got "
                             f"{vec.size}")
    check_range(vec, name, unit, where=where)
    return vec


def check_finite(where: str, unit: str, **values: Any) -> None:
    """Each of ``values`` (name -> number, array or SX) is a finite number [``unit``].

    Parameters
    ----------
    where : str
        The component or function, for the message.
    unit : str
        Unit of the values, for the message.
    **values
        Name -> number, array or SX (symbols pass unchecked).

    Raises
    ------
    ParameterError
        For the first that is not.
    """
    for name, value in values.items():
        check_range(value, name, unit, where=where)


def table_entry(table: Mapping[Any, Any], key: Any, what: str) -> Any:
    """The entry of a data table (catalogue constants by bearing type, series, method, ...).

    Parameters
    ----------
    table : Mapping
        The table.
    key : Any
        The key asked for.
    what : str
        What the keys are, used in the message (e.g. ``"bearing type"``).

    Returns
    -------
    The entry ``table[key]``.

    Raises
    ------
    CatalogError
        ``"unknown <what> <key>; known: ..."``, with a did-you-mean hint for a near-miss text key.
    """
    try:
        return table[key]
    except (KeyError, TypeError):
        known = sorted(map(str, table))
        close = difflib.get_close_matches(key, known, n=1) if isinstance(key, str) else []
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise CatalogError(f"unknown {what} {key!r}; known: {', '.join(known)}{hint}") from None
