"""Unit strings of the model (Modelica syntax, e.g. ``N.m/rad``, ``kg.m2``, ``(rad/s)/s``) as FMI
unit definitions: exponents of the SI base units plus factor and offset, read with the package's
units library (:mod:`bearingsim.units.registry`)."""

from __future__ import annotations

import re
from dataclasses import dataclass

from bearingsim.units.registry import UnitError, base_exponents

__all__ = ["BASE_UNITS", "UnitDefinition", "derivative_unit", "normalize_unit", "parse_unit"]

BASE_UNITS = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")
"""The base units of an FMI ``BaseUnit`` element, in attribute order."""

_PINT_BASE = {"kilogram": "kg", "meter": "m", "second": "s", "ampere": "A", "kelvin": "K",
              "mole": "mol", "candela": "cd", "radian": "rad"}
"""pint's base units -> the FMI ``BaseUnit`` attributes."""


@dataclass(frozen=True)
class UnitDefinition:
    """A unit as exponents of :data:`BASE_UNITS`, ``factor`` and ``offset`` (SI = factor*x+offset).

    ``exponents`` is ``None`` when the unit string is not understood; it is then declared by
    name only.
    """

    name: str
    exponents: dict[str, int] | None
    factor: float = 1.0
    offset: float = 0.0


def parse_unit(text: str) -> UnitDefinition:
    """Read a unit string.

    Parameters
    ----------
    text : str
        Modelica unit syntax: factors joined by ``.``, integer exponents appended (``m2``,
        ``s-1``), parentheses for groups; ``/`` divides by the next factor or group.

    Returns
    -------
    UnitDefinition
        With ``exponents=None`` if a symbol is unknown.
    """
    try:
        exps, factor, offset = base_exponents(text)
    except UnitError:
        return UnitDefinition(text, None)
    out: dict[str, int] = {}
    for name, power in exps:
        if name not in _PINT_BASE or not float(power).is_integer():
            return UnitDefinition(text, None)
        out[_PINT_BASE[name]] = int(power)
    return UnitDefinition(text, out, factor, offset)


def derivative_unit(unit: str) -> str:
    """The unit of a time derivative, written simply: ``rad`` -> ``rad/s``, ``rad/s`` -> ``rad/s2``.

    Parameters
    ----------
    unit : str
        Unit of the differentiated variable.

    Returns
    -------
    str
    """
    if unit in ("", "1"):
        return "1/s"
    m = re.fullmatch(r"(.*)/s(\d*)", unit)
    if m and "(" not in m.group(1) and "/" not in m.group(1):
        return f"{m.group(1)}/s{int(m.group(2) or 1) + 1}"
    if "/" in unit:
        return f"({unit})/s"
    return f"{unit}/s"


def normalize_unit(unit: str) -> str:
    """Rewrite derivative units such as ``(rad/s)/s`` simply (``rad/s2``); others unchanged.

    Parameters
    ----------
    unit : str

    Returns
    -------
    str
    """
    m = re.fullmatch(r"\((.+)\)/s", unit)
    if m is None:
        return unit
    return derivative_unit(normalize_unit(m.group(1)))
