"""The one units library of bearingsim: a :mod:`pint` registry, unit strings in the model's
(Modelica) notation translated to pint's, and numbers with units read into SI.

The registry is made on first use (parsing pint's definitions takes ~0.6 s; their parsed form is
kept under the cache root, :data:`PINT_CACHE`), so importing bearingsim stays fast.
"""

from __future__ import annotations

import functools
import math
import re
import shutil
from typing import Any

from bearingsim.cache_paths import cache_root
from bearingsim.errors import ParameterError

__all__ = ["PINT_CACHE", "UnitError", "registry", "pint_unit", "si_factor", "base_exponents",
           "split_quantity", "quantity_to_si", "is_quantity", "same_quantity", "cycles_hint"]


class UnitError(ParameterError):
    """A unit that is unknown, or not one of the quantity the value is for."""


_MODELICA_NAMES = {"rev": "revolution", "Ohm": "ohm", "um": "micrometer", "µm": "micrometer",
                   "r/min": "rpm", "1/min": "rpm", "min^-1": "rpm", "min⁻¹": "rpm",
                   "min-1": "rpm", "degC": "degree_Celsius",
                   "°C": "degree_Celsius", "deg": "degree", "Nmm": "N*mm", "Nm": "N*m",
                   "cSt": "mm**2/s"}
"""Spellings of the model, catalogues and engineers that pint spells otherwise."""

_EXPRESSION_NAMES = {"t", "e", "pi"}
"""Names of the scene expressions (time, constants) that pint would read as units (tonne,
elementary charge, the number pi): text using them is never a number with a unit."""
_UNIT_TEXT = re.compile(r"[A-Za-zµ°²³⁻¹_0-9\s*/^().\-]+")
_SYMBOL_POWER = re.compile(r"([A-Za-zµ°]+)(-?\d+)(?![\w.])")
_NUMBER = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|[+-]?(?:nan|inf|infinity)"
_UNIT_START = r"1/\s*[A-Za-zµ°][^()]*?|[^\d\s+\-.(][^()]*?|\(.*\)"
"""A unit after a number: not a digit, sign, point or space first, except ``1/min``."""
_QUANTITY = re.compile(rf"^\s*({_NUMBER})\s*({_UNIT_START})\s*$", re.IGNORECASE)


PINT_CACHE = "pint"
"""Folder under the cache root (:func:`~bearingsim.cache_paths.cache_root`) of pint's parsed
unit definitions: the registry loads them in ~0.04 s instead of parsing its definition files
in ~0.6 s, in every process (a command, a sweep's client)."""


@functools.lru_cache(maxsize=1)
def registry():
    """The shared :class:`pint.UnitRegistry` (made on the first call, from the parsed
    definitions kept in :data:`PINT_CACHE` when they are there and sound).

    Returns
    -------
    pint.UnitRegistry
    """
    import pint

    folder = cache_root() / PINT_CACHE
    for _attempt in range(2):
        try:
            return pint.UnitRegistry(cache_folder=folder)
        except Exception:  # noqa: BLE001 - a corrupt or half-written entry: parse anew
            shutil.rmtree(folder, ignore_errors=True)
    return pint.UnitRegistry()  # a cache folder that cannot be used: no cache


def _translate(unit: str) -> str:
    """A unit string of the model (``N.m/rad``, ``kg.m2``, ``(rad/s)/s``, ``r/min``) in pint's
    syntax (``N*m/rad``, ``kg*m**2``)."""
    text = unit.strip()
    for name, pint_name in sorted(_MODELICA_NAMES.items(), key=lambda kv: -len(kv[0])):
        text = re.sub(rf"(?<![\w/]){re.escape(name)}(?![\w])", pint_name, text)
    text = _SYMBOL_POWER.sub(r"\1**\2", text)
    text = re.sub(r"(?<=[\w)])\s*\.\s*(?=[A-Za-zµ(])", "*", text)  # N.m -> N*m
    text = re.sub(r"(?<=[\w)])\s+(?=[A-Za-zµ(])", "*", text)  # N mm -> N*mm
    return text or "dimensionless"


@functools.lru_cache(maxsize=512)
def pint_unit(unit: str):
    """The :class:`pint.Unit` of a unit string of the model or of an engineer.

    Parameters
    ----------
    unit : str
        E.g. ``"rad/s"``, ``"N.m"``, ``"kg.m2"``, ``"rpm"``, ``"r/min"``, ``"µm"``, ``"kN"``,
        ``"1"`` or ``""`` (dimensionless).

    Returns
    -------
    pint.Unit

    Raises
    ------
    UnitError
        For a unit pint does not know.
    """
    if unit in ("", "1", "-"):
        return registry().dimensionless
    if not isinstance(unit, str) or not _UNIT_TEXT.fullmatch(unit) or len(unit) > 60:
        raise UnitError(f"unknown unit {unit!r:.70} (a unit is letters, digits, * / ^ . ( ) "
                        f"and spaces)")
    try:
        return registry().Unit(_translate(unit))
    except Exception as exc:  # noqa: BLE001 - pint's parser raises many types for bad text
        raise UnitError(f"unknown unit {unit!r} ({type(exc).__name__}: {exc})") from None


@functools.lru_cache(maxsize=512)
def base_exponents(unit: str) -> tuple[tuple[tuple[str, float], ...], float, float]:
    """Exponents of the SI base units (radian counted as a base unit), factor and offset:
    ``SI value = factor * value + offset``; kept on disk for later processes, which then need
    not import pint (:mod:`~bearingsim.units.conversion_memo`).

    Parameters
    ----------
    unit : str

    Returns
    -------
    tuple
        ``((("kilogram", 1.0), ...), factor, offset)``.

    Raises
    ------
    UnitError
        For a unit pint does not know, or one without a finite SI factor.
    """
    from bearingsim.units.conversion_memo import memo

    if not isinstance(unit, str):
        return _base_exponents(unit)  # refused by pint_unit; nothing to keep
    kept = memo().get(unit)
    if isinstance(kept, dict) and isinstance(kept.get("error"), str):
        raise UnitError(kept["error"])
    if isinstance(kept, list) and len(kept) == 3:
        exps, factor, offset = kept
        return tuple((str(name), float(power)) for name, power in exps), factor, offset
    try:
        result = _base_exponents(unit)
    except UnitError as exc:
        memo().put(unit, {"error": str(exc)})
        raise
    memo().put(unit, [[list(e) for e in result[0]], result[1], result[2]])
    return result


def _base_exponents(unit: str) -> tuple[tuple[tuple[str, float], ...], float, float]:
    """:func:`base_exponents` computed by pint."""
    ureg = registry()
    u = pint_unit(unit)
    try:
        zero = ureg.Quantity(0.0, u).to_base_units()
        one = ureg.Quantity(1.0, u).to_base_units()
        exps = tuple(sorted((str(k), float(v)) for k, v in one._units.items()))
        factor, offset = float(one.magnitude - zero.magnitude), float(zero.magnitude)
    except (OverflowError, ArithmeticError) as exc:
        raise UnitError(f"unit {unit!r} cannot be converted to SI ({exc})") from None
    if not (math.isfinite(factor) and factor != 0.0 and math.isfinite(offset)):
        raise UnitError(f"unit {unit!r} has no finite SI factor")
    return exps, factor, offset


def si_factor(unit: str, si_unit: str) -> tuple[float, float]:
    """Factor and offset from ``unit`` to ``si_unit`` (``si = factor * x + offset``).

    Parameters
    ----------
    unit : str
        The unit of the value.
    si_unit : str
        The SI unit to convert to.

    Returns
    -------
    tuple of float
        ``(factor, offset)``.

    Raises
    ------
    UnitError
        When the two are not units of the same quantity (radians counted).
    """
    e1, f1, o1 = base_exponents(unit)
    e2, f2, o2 = base_exponents(si_unit)
    if e1 != e2:
        hint = cycles_hint(unit, si_unit)  # "1000 Hz" for a speed in rad/s
        if hint:
            raise UnitError(f"{unit!r} is not a unit of {si_label(si_unit)} quantities (it is "
                            f"{_dimension_text(unit)}){hint}")
        if not e2:  # was "not a unit of - quantities (..., '1' is dimensionless)"
            raise UnitError(f"{unit!r} is not a unit of dimensionless quantities (it is "
                            f"{_dimension_text(unit)}); give a pure number")
        raise UnitError(f"{unit!r} is not a unit of {si_label(si_unit)} quantities "
                        f"(it is {_dimension_text(unit)}, {si_unit!r} is "
                        f"{_dimension_text(si_unit)})")
    return f1 / f2, (o1 - o2) / f2


def cycles_hint(unit: str, si_unit: str) -> str:
    """For a unit of cycles per time given where an angle per time is wanted (``Hz``, ``1/s``
    for ``rad/s``): what to write instead; else empty.

    Parameters
    ----------
    unit : str
        The unit given.
    si_unit : str
        The unit wanted.

    Returns
    -------
    str
        ``"; Hz counts cycles, not their angle: ..."`` or ``""``.
    """
    try:
        given, wanted = base_exponents(unit)[0], base_exponents(si_unit)[0]
    except UnitError:
        return ""
    if ("radian", 1.0) not in wanted or tuple(e for e in wanted if e[0] != "radian") != given:
        return ""
    return (f"; {unit} counts cycles, not their angle: give a rotational speed in r/min, rpm, "
            "1/min or rev/s (revolutions carry the angle), or in rad/s")


def _dimension_text(unit: str) -> str:
    exps = base_exponents(unit)[0]
    if not exps:
        return "dimensionless"
    return " ".join(f"{k}^{v:g}" if v != 1 else k for k, v in exps)


def si_label(unit: str) -> str:
    """``-`` for a dimensionless unit, else the unit itself.

    Parameters
    ----------
    unit : str
        An SI unit.

    Returns
    -------
    str
        The label shown to users.
    """
    return "-" if unit in ("", "1") else unit


def split_quantity(text: str) -> tuple[float, str] | None:
    """``"10000 rpm"`` -> ``(10000.0, "rpm")``; ``"500rpm"``, ``"2 kN"``, ``"25 µm"``,
    ``"80 °C"`` alike. None when the text is not one number followed by a unit known to the
    units library (it may then be an expression such as ``"rpm(1000) * t"``).

    Parameters
    ----------
    text : str

    Returns
    -------
    tuple or None
        The number as written (it may be non-finite: the caller refuses it) and the unit.
    """
    m = _QUANTITY.match(text)
    if m is None:
        return None
    number, unit = m.group(1), m.group(2).strip()
    if _EXPRESSION_NAMES & set(re.findall(r"[A-Za-zµ°_]+", unit)):
        return None  # "1000 rpm * t" is an expression of time, not rpm times tonnes
    try:
        base_exponents(unit)
    except UnitError:
        return None
    try:
        value = float(number)
    except (ValueError, OverflowError):
        return None
    return value, unit


def same_quantity(a: str, b: str) -> bool:
    """Whether two units measure the same quantity (the same powers of the SI base units,
    radian counted as one: ``rad/s`` and ``r/min`` do, ``rad/s`` and ``N`` do not).

    Parameters
    ----------
    a, b : str
        Units (model notation or pint's).

    Returns
    -------
    bool
        For units pint does not know: whether they are spelt alike.
    """
    try:
        return base_exponents(a)[0] == base_exponents(b)[0]
    except UnitError:
        return a == b


def is_quantity(value: Any) -> bool:
    """Whether ``value`` is a :class:`pint.Quantity` (without importing pint for others).

    Parameters
    ----------
    value : object
        Anything.

    Returns
    -------
    bool
        Whether it is a pint quantity.
    """
    return type(value).__module__.startswith("pint") and hasattr(value, "magnitude")


def quantity_to_si(value: Any, si_unit: str, name: str) -> float:
    """A number with a unit in the SI unit of the quantity it is for.

    Parameters
    ----------
    value : str or pint.Quantity
        ``"10000 rpm"``, ``"2 kN"``, ``"25 µm"``, or a :class:`pint.Quantity` of any registry.
    si_unit : str
        The unit of the model's input or parameter (``"rad/s"``, ``"N"``, ``"m"``).
    name : str
        The input or parameter, for messages.

    Returns
    -------
    float
        The value in ``si_unit``.

    Raises
    ------
    UnitError
        For text that is not a number with a unit, a unit of another quantity, or a value that
        is not finite.
    """
    if is_quantity(value):
        magnitude, unit = value.magnitude, str(value.units)
        try:
            magnitude = float(magnitude)
        except (TypeError, ValueError):
            raise UnitError(f"{name}: a quantity must be one number with a unit, got "
                            f"{value!r:.80}") from None
    elif isinstance(value, str):
        parsed = split_quantity(value)
        if parsed is None:
            raise UnitError(f"{name}: {value!r:.80} is not a number with a unit; write e.g. "
                            f"'{_example(si_unit)}' or a number in {si_label(si_unit)}")
        magnitude, unit = parsed
    else:
        raise UnitError(f"{name}: expected a number with a unit, got {type(value).__name__}")
    if not math.isfinite(magnitude):
        raise UnitError(f"{name}: {value!s:.80} is not a finite number; give a finite value in "
                        f"{unit}")
    try:
        factor, offset = si_factor(unit, si_unit)
    except UnitError as exc:
        raise UnitError(f"{name}: {exc}") from None
    si = magnitude * factor + offset
    if not math.isfinite(si):
        raise UnitError(f"{name}: {value!s:.80} overflows in {si_label(si_unit)}")
    return si


def _example(si_unit: str) -> str:
    return {"rad/s": "10000 rpm", "N": "2 kN", "m": "25 µm", "N.m": "30 N mm"}.get(
        si_unit, f"10 {si_label(si_unit)}")
