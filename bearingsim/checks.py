"""The argument-checking layer of the public API: signature types, finite numbers in and out of
the physics functions, output sizes against memory, solver tolerances.

* :func:`checked` checks every argument of an entry point against its type hints (with
  `beartype <https://github.com/beartype/beartype>`_'s ``is_bearable``, the implicit numeric
  tower on: an ``int`` is a valid ``float``) and refuses integers beyond the float range, raising
  :class:`~bearingsim.errors.ParameterError` that names the function, the argument, what it
  accepts and what it got, instead of a ``TypeError``/``AttributeError``/``OverflowError``
  from deep inside.
* :func:`finite_io` wraps a physics function: a NaN argument, or a result that is NaN or
  infinite (an overflow at 1e308, inf - inf, 0/0), raises a named error. CasADi symbols pass
  unchecked (they are checked when numbers are bound), so the functions keep building models.
  :func:`guard_public_functions` applies it to every function in a module's ``__all__``.
* :func:`check_output_size` refuses an output (points x variables, grid products, samples)
  that would not fit in memory before it is allocated.
* :func:`check_tolerance` checks a relative or absolute solver tolerance against
  :data:`RTOL_RANGE`, :data:`ATOL_RANGE` and :data:`NEWTON_TOL_RANGE`.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import math
import numbers
import os
import re
import sys
import typing
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
from beartype import BeartypeConf
from beartype.door import is_bearable

from bearingsim.errors import ParameterError
from bearingsim.symbolic import is_symbolic

__all__ = [
    "ATOL_RANGE",
    "MAX_OUTPUT_FRACTION",
    "MAX_STATIC_LOAD_FACTOR",
    "NEWTON_TOL_RANGE",
    "RTOL_RANGE",
    "check_arguments",
    "check_identifier",
    "check_output_file",
    "check_output_size",
    "check_tolerance",
    "checked",
    "finite_io",
    "guard_public_functions",
]

RTOL_RANGE = (1e-14, 0.1)
"""Valid relative tolerance [-]: below 1e-14 it asks for more digits than a double carries
(about 16, less the round-off of a step); above 0.1 the answer has no correct digit."""
ATOL_RANGE = (1e-20, 1.0)
"""Valid absolute tolerance [state units]: the states are SI values (m, rad, m/s, rad/s);
1e-20 m is far below an atom, and an absolute error of 1 m or 1 rad/s is no answer."""
NEWTON_TOL_RANGE = (1e-16, 1e-2)
"""Valid residual or step tolerance of a Newton solve [residual units]: above 1e-2 a start
guess passes for a solution."""
MAX_STATIC_LOAD_FACTOR = 10.0
"""Largest plausible load as a multiple of the static load rating C0 [-]: at C0 the most loaded
contact reaches 4 200 MPa (ISO 76, permanent deformation begins); at 10 C0 it would be about
9 000 MPa, beyond the compressive strength of bearing steel: a load there is a unit slip (N
for kN, N for mN) or a typo, and is refused. Between C0 and this limit the models compute and
warn (:class:`~bearingsim.errors.PlasticDeformationWarning`)."""
MAX_OUTPUT_FRACTION = 0.5
"""Largest share of the machine's physical memory one output may take."""

_CONF = BeartypeConf(is_pep484_tower=True)


def _describe(hint: Any) -> str:
    """A type hint as text for a message (``float``, ``str | Path``, ``dict[str, float]``)."""
    if isinstance(hint, type):
        return hint.__name__
    # the modules named off (typing.Any, collections.abc.Sequence, bearingsim.scenes.scene.Scene)
    text = re.sub(r"(?<![\w'\"])(?:[a-z_]\w*\.)+(?=[A-Za-z_])", "", str(hint))
    return text.replace("NoneType", "None")


def _too_large_int(value: Any) -> bool:
    """An integer (or a container of them) beyond the float range (``10**400``)."""
    if isinstance(value, bool):
        return False
    if isinstance(value, int):
        return abs(value) > sys.float_info.max
    if isinstance(value, (list, tuple)):
        return any(_too_large_int(v) for v in value)
    if isinstance(value, dict):
        return any(_too_large_int(v) for v in value.values())
    return False


def check_identifier(value: Any, name: str, where: str) -> str:
    """A name usable in dotted variable paths: a Python identifier (letters, digits and ``_``,
    not starting with a digit, no dots).

    Parameters
    ----------
    value : object
        The value to check.
    name : str
        Argument name, for the message.
    where : str
        The component or function, for the message.

    Returns
    -------
    str
        ``value``, checked.

    Raises
    ------
    ParameterError
        For anything else (``''``, ``'a.b'``, ``'1abc'``, a number).
    """
    if not (isinstance(value, str) and value.isidentifier()):
        raise ParameterError(
            f"{where}: {name} must be an identifier (letters, digits and _, not starting with "
            f"a digit; it becomes part of dotted variable names such as {name}.w), got "
            f"{value!r:.40}")
    return value


def _hints(func: Callable) -> dict[str, Any]:
    """The resolved type hints of ``func`` (or of a class's constructor), without the return;
    empty when a hint names a class imported only for type checking."""
    target = func.__init__ if isinstance(func, type) else func
    try:
        hints = typing.get_type_hints(target)
    except (NameError, TypeError):
        return {}
    hints.pop("return", None)
    return hints


def check_arguments(func: Callable, args: tuple, kwargs: dict[str, Any], where: str,
                    label: str = "{name}", skip: tuple[str, ...] = ()) -> None:
    """Check a call's arguments against ``func``'s signature and type hints (see
    :func:`checked`); ``label`` formats an argument's name in messages (e.g.
    ``"layer_options[{name!r}]"``).

    Parameters
    ----------
    func : callable
        The function or class whose signature and hints apply.
    args : tuple
        The call's positional arguments.
    kwargs : dict
        The call's keyword arguments.
    where : str
        The function, for the messages.
    label : str
        Format of an argument's name in messages, with a ``{name}`` field.
    skip : tuple of str
        Arguments whose type is not checked here.

    Raises
    ------
    ParameterError
        For unknown or missing arguments, a value that does not match its hint, or an integer
        beyond the float range.
    """
    signature = inspect.signature(func)
    hints = _hints(func)
    try:
        bound = signature.bind_partial(*args, **kwargs) if isinstance(func, type) else \
            signature.bind(*args, **kwargs)
    except TypeError as exc:
        names = [n for n in signature.parameters if n != "self"]
        raise ParameterError(f"{where}: {exc}; its arguments are {', '.join(names)}") from None
    for name, value in bound.arguments.items():
        shown = label.format(name=name)
        if _too_large_int(value):
            raise ParameterError(f"{where}: {shown} = {str(value)[:20]}... is beyond the range "
                                 f"of a float (about 1.8e308)")
        hint = hints.get(name)
        if name in skip or hint is None or hint is Any or signature.parameters[name].kind in (
                inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD):
            continue
        if not is_bearable(value, hint, conf=_CONF):
            raise ParameterError(f"{where}: {shown} must be {_describe(hint)}, got "
                                 f"{value!r:.60} ({type(value).__name__})")


def checked(func: Callable | None = None, *, skip: tuple[str, ...] = ()) -> Callable:
    """Decorator of a public entry point: each argument is checked against its type hint.

    Hints that cannot be resolved (classes imported only for type checking) and ``Any`` are
    not checked; integers beyond the float range (``10**400``) are refused whatever the hint.
    ``skip`` names arguments whose type the function checks itself (with a better message).

    Parameters
    ----------
    func : callable, optional
        The function or class (None: ``checked(skip=...)`` returns the decorator).
    skip : tuple of str
        Arguments whose type the function checks itself.

    Returns
    -------
    callable
        The wrapped function, or the decorator when ``func`` is None.

    Raises
    ------
    ParameterError
        ``"<function>: <argument> must be <hint>, got <value> (<type>)"``; for unknown or
        missing arguments the signature's complaint and the accepted names.
    """
    if func is None:
        return functools.partial(checked, skip=skip)
    where = func.__qualname__.replace(".__init__", "")

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        check_arguments(func, args, kwargs, where, skip=skip)
        return func(*args, **kwargs)

    return wrapper


def _numbers(value: Any) -> np.ndarray | None:
    """The value as a float array if it is numeric (a number, array, sequence of numbers or
    sequence of such sequences, flattened), else None (text, objects, CasADi symbols)."""
    if isinstance(value, (bool, str, bytes)) or is_symbolic(value):
        return None
    if isinstance(value, numbers.Number) or isinstance(value, np.ndarray):
        try:
            return np.asarray(value, dtype=float)
        except (TypeError, ValueError, OverflowError):
            return None
    if isinstance(value, (list, tuple)) and value and all(
            isinstance(v, numbers.Real) and not isinstance(v, bool) for v in value):
        return np.asarray(value, dtype=float)
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, (list, tuple))
                                                          for v in value):
        rows = [_numbers(v) for v in value]  # e.g. the slice loads of every roller
        if all(r is not None for r in rows):
            return np.concatenate([r.ravel() for r in rows])
    return None


def _result_numbers(result: Any) -> list[tuple[str, np.ndarray]]:
    """The numeric parts of a result: itself, the items of a tuple, the fields of a
    dataclass."""
    parts: list[tuple[str, Any]]
    if dataclasses.is_dataclass(result) and not isinstance(result, type):
        parts = [(f.name, getattr(result, f.name)) for f in dataclasses.fields(result)]
    elif isinstance(result, tuple):
        parts = [(f"[{k}]", v) for k, v in enumerate(result)]
    else:
        parts = [("", result)]
    out = []
    for label, value in parts:
        arr = _numbers(value)
        if arr is not None:
            out.append((label, arr))
    return out


def finite_io(func: Callable, infinite_results: bool = False) -> Callable:
    """Decorator of a physics function: no NaN in, no NaN or infinity out.

    With ``infinite_results`` an infinite result is a valid answer where an argument is 0 or
    infinite (the life of an unloaded contact); from finite non-zero arguments it is an
    overflow and raises, and a NaN result always does.

    The function runs first, so its own checks (naming unit and valid range) speak first. Then
    a NaN or infinite result (an overflow for arguments near 1e308, inf - inf) raises, naming
    the arguments that are not ordinary numbers, and so does a NaN argument the function let
    through. An infinite argument is allowed where the function turns it into a finite answer
    (a housing of infinite outside diameter). Calls with a CasADi symbol among the arguments
    are passed through.

    Parameters
    ----------
    func : callable
        The physics function.
    infinite_results : bool
        Accept an infinite result where an argument is 0 or infinite.

    Returns
    -------
    callable
        The wrapped function.

    Raises
    ------
    ParameterError
        ``"<function>: <argument> must not be NaN"`` or ``"<function>: the result <field> is
        not finite (nan) for <argument> = <value>, ...: the arguments are beyond the range
        the formula can represent"``.
    """
    signature = inspect.signature(func)
    where = func.__name__

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        values = list(args) + list(kwargs.values())
        if any(is_symbolic(v) for v in values):
            return func(*args, **kwargs)
        try:
            bound = signature.bind(*args, **kwargs)
        except TypeError:
            return func(*args, **kwargs)  # the function's own argument error
        given = [(name, arr) for name, value in bound.arguments.items()
                 if (arr := _numbers(value)) is not None and arr.size]
        nan_args = [name for name, arr in given if np.isnan(arr).any()]

        def extreme() -> str:  # the arguments that are not ordinary numbers, for a message
            with np.errstate(all="ignore"):
                named = [f"{name} = {bound.arguments[name]!r:.40}" for name, arr in given
                         if not np.isfinite(arr).all() or np.nanmax(np.abs(arr)) > 1e150
                         or ((arr != 0) & (np.abs(arr) < 1e-150)).any()]
            return ", ".join(named)

        with np.errstate(all="ignore"):
            try:
                result = func(*args, **kwargs)  # its own checks name unit and range first
            except (OverflowError, ZeroDivisionError, FloatingPointError) as exc:
                raise ParameterError(
                    f"{where}: {type(exc).__name__} ({exc}) for "
                    f"{extreme() or 'these arguments'}: the arguments are beyond "
                    f"the range the formula can represent") from None
        for label, arr in _result_numbers(result):
            if np.isfinite(arr).all():
                continue
            nan = bool(np.isnan(arr).any())
            # an infinite answer is a limit (zero load, infinite capacity), not an overflow
            if not nan and infinite_results and any(((a == 0) | np.isinf(a)).any()
                                                    for _, a in given):
                continue
            what = f"the result {label}".rstrip()
            raise ParameterError(
                f"{where}: {what} is not finite ({'nan' if nan else 'inf'}) for "
                f"{extreme() or 'these arguments'}: the arguments are beyond the "
                f"range the formula can represent; give each in its SI unit and plausible "
                f"range (docs/physics.md, 'Valid ranges')")
        if nan_args:
            raise ParameterError(f"{where}: {', '.join(nan_args)} must not be NaN")
        return result

    wrapper.__wrapped_finite__ = True
    return wrapper


def guard_public_functions(namespace: dict[str, Any], infinite_results: bool = False) -> None:
    """Wrap every function named in ``namespace["__all__"]`` (a module's globals) with
    :func:`finite_io` (``infinite_results`` passed on); classes, constants and already
    wrapped functions are left alone.

    Parameters
    ----------
    namespace : dict
        A module's globals, with ``__all__``; changed in place.
    infinite_results : bool
        Passed on to :func:`finite_io`.
    """
    for name in namespace.get("__all__", ()):
        obj = namespace.get(name)
        if inspect.isfunction(obj) and not getattr(obj, "__wrapped_finite__", False):
            namespace[name] = finite_io(obj, infinite_results)


def _physical_memory() -> float:
    """Physical memory of the machine [bytes] (8 GiB where the system does not say)."""
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return 8.0 * 1024**3


def check_output_size(count: float, bytes_each: float, what: str, where: str) -> None:
    """Refuse an output of ``count`` items of ``bytes_each`` bytes that would take more than
    :data:`MAX_OUTPUT_FRACTION` of physical memory, before it is allocated.

    ``count`` may be a product far beyond any integer a list could hold (a grid of 10^12
    points): it is compared as a float.

    Parameters
    ----------
    count : float
        Number of items, >= 0.
    bytes_each : float
        Size of one item [bytes], >= 0.
    what : str
        What is counted, for the message.
    where : str
        The component or function, for the message.

    Raises
    ------
    ParameterError
        ``"<where>: <what> = <count> would take <size> GiB, more than <limit> GiB (half the
        memory of this machine)"``.
    """
    size = float(count) * float(bytes_each)
    limit = MAX_OUTPUT_FRACTION * _physical_memory()
    if not math.isfinite(size) or size > limit:
        raise ParameterError(
            f"{where}: {what} = {float(count):.4g} would take {size / 1024**3:.3g} GiB, more "
            f"than {limit / 1024**3:.3g} GiB (half the memory of this machine); ask for fewer")


def check_output_file(path: Any, suffix: str, name: str, where: str) -> Path:
    """A path to write one file to: text or path-like, not an existing folder, ending in
    ``suffix``.

    Parameters
    ----------
    path : str or os.PathLike
        The path to check.
    suffix : str
        Required file suffix, lower case with the dot (e.g. ``".csv"``).
    name : str
        Argument name, for the message.
    where : str
        The component or function, for the message.

    Returns
    -------
    Path
        The path.

    Raises
    ------
    ParameterError
        Naming the argument and what it accepts.
    """
    if not isinstance(path, (str, os.PathLike)) or not str(path):
        raise ParameterError(f"{where}: {name} must be a file path ending in {suffix}, got "
                             f"{path!r:.60} ({type(path).__name__})")
    out = Path(path)
    if out.is_dir() or out.suffix.lower() != suffix:
        raise ParameterError(f"{where}: {name} must be a file path ending in {suffix} (not a "
                             f"folder), got {str(path)!r:.80}")
    return out


def check_tolerance(value: Any, name: str, kind: str, where: str) -> float:
    """A solver tolerance within its sane range.

    Parameters
    ----------
    value : float
        The tolerance.
    name : str
        Argument name, used in the message.
    kind : {"rtol", "atol", "newton"}
        Which range applies (:data:`RTOL_RANGE`, :data:`ATOL_RANGE`,
        :data:`NEWTON_TOL_RANGE`).
    where : str
        Function name, used in the message.

    Returns
    -------
    float

    Raises
    ------
    ParameterError
        Outside the range, naming it.
    """
    low, high = {"rtol": RTOL_RANGE, "atol": ATOL_RANGE, "newton": NEWTON_TOL_RANGE}[kind]
    unit = "-" if kind == "rtol" else "state units" if kind == "atol" else "residual units"
    if isinstance(value, (bool, str, bytes)) or not isinstance(value, numbers.Real):
        raise ParameterError(f"{where}: {name} must be a number in [{low:g}, {high:g}] "
                             f"[{unit}], got {value!r:.40} ({type(value).__name__})")
    if not (math.isfinite(value) and low <= value <= high):
        raise ParameterError(
            f"{where}: {name} = {value!r} [{unit}] is outside the valid range [{low:g}, "
            f"{high:g}] [{unit}]: a tolerance outside it is no tolerance (too loose: a start "
            f"guess passes; too tight: below the round-off of doubles)")
    return float(value)


