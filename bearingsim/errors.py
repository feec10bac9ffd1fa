"""Exceptions of bearingsim.

Every error names what the user wrote: the component path, parameter or variable in dotted names,
its unit and the valid range. Structural errors list the equations and unknowns involved.
"""

from __future__ import annotations

import math
from typing import Any

from bearingsim.symbolic import is_symbolic

__all__ = [
    "BearingsimError",
    "ParameterError",
    "ModelError",
    "ConnectionError_",
    "StructuralError",
    "UnderdeterminedError",
    "OverdeterminedError",
    "SingularBlockError",
    "UnconnectedInputError",
    "SimulationError",
    "CatalogError",
    "check_choice",
    "check_count",
    "check_range",
]


class BearingsimError(Exception):
    """Base class of all bearingsim errors."""


class ParameterError(BearingsimError, ValueError):
    """A parameter or input value is of the wrong type or outside its valid range."""


class CatalogError(BearingsimError, KeyError):
    """An unknown bearing designation or lubricant name."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class ModelError(BearingsimError):
    """A model is built wrongly (bad declaration, bad equation, bad nesting)."""


class ConnectionError_(ModelError):
    """Two connectors of different types, or a connection that Modelica semantics forbid."""


class StructuralError(ModelError):
    """The flattened equations cannot be solved for the unknowns.

    Attributes
    ----------
    equations : list of str
        Descriptions of the equations involved (origin component and text).
    unknowns : list of str
        Dotted names of the unknowns involved.
    """

    def __init__(self, message: str, equations=(), unknowns=()):
        self.equations = list(equations)
        self.unknowns = list(unknowns)
        parts = [message]
        if self.equations:
            parts.append("equations:\n  " + "\n  ".join(self.equations))
        if self.unknowns:
            parts.append("unknowns:\n  " + "\n  ".join(self.unknowns))
        super().__init__("\n".join(parts))


class UnderdeterminedError(StructuralError):
    """Fewer equations than unknowns (or unknowns that no equation determines)."""


class OverdeterminedError(StructuralError):
    """More equations than unknowns (or equations that no unknown is left for)."""


class SingularBlockError(StructuralError):
    """A block of equations is structurally singular."""


class UnconnectedInputError(ModelError):
    """A required input of a sub-component is neither connected nor bound by an equation."""


class SimulationError(BearingsimError, RuntimeError):
    """The integrator failed; the message names the time reached and the diverging variables."""


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
    if is_symbolic(value):
        return value
    import numpy as np

    label = f"{where}: {name}" if where else name
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(
            f"{label} must be a number in {unit}, got {value!r} ({type(value).__name__})"
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
        raise ParameterError(
            f"{label} = {shown} [{unit}] is outside the valid range {lb}{lo}, {hi}{rb} [{unit}]"
        )
    if arr.ndim == 0 and not math.isfinite(float(arr)):
        raise ParameterError(f"{label} must be finite [{unit}]")
    return value


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
    if is_symbolic(value):
        return value
    import numpy as np

    label = f"{where}: {name}" if where else name
    arr = np.asarray(value)
    if arr.dtype == bool or arr.dtype.kind not in "iuf":
        raise ParameterError(f"{label} must be a whole number >= {low} [-], got {value!r}")
    check_range(value, name, "-", low, where=where)
    if np.any(arr != np.round(arr)):
        raise ParameterError(f"{label} must be a whole number >= {low} [-], got {value!r}")
    return value
