"""Unit strings of the model (Modelica syntax, e.g. ``N.m/rad``, ``kg.m2``, ``(rad/s)/s``) as FMI
unit definitions: exponents of the SI base units plus factor and offset."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

__all__ = ["BASE_UNITS", "UnitDefinition", "derivative_unit", "normalize_unit", "parse_unit"]

BASE_UNITS = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")
"""The base units of an FMI ``BaseUnit`` element, in attribute order."""

# symbol -> (exponents by base unit, factor, offset)
_SYMBOLS: dict[str, tuple[dict[str, int], float, float]] = {
    "1": ({}, 1.0, 0.0),
    "kg": ({"kg": 1}, 1.0, 0.0),
    "g": ({"kg": 1}, 1e-3, 0.0),
    "m": ({"m": 1}, 1.0, 0.0),
    "mm": ({"m": 1}, 1e-3, 0.0),
    "um": ({"m": 1}, 1e-6, 0.0),
    "s": ({"s": 1}, 1.0, 0.0),
    "ms": ({"s": 1}, 1e-3, 0.0),
    "min": ({"s": 1}, 60.0, 0.0),
    "h": ({"s": 1}, 3600.0, 0.0),
    "A": ({"A": 1}, 1.0, 0.0),
    "K": ({"K": 1}, 1.0, 0.0),
    "degC": ({"K": 1}, 1.0, 273.15),
    "mol": ({"mol": 1}, 1.0, 0.0),
    "cd": ({"cd": 1}, 1.0, 0.0),
    "rad": ({"rad": 1}, 1.0, 0.0),
    "deg": ({"rad": 1}, math.pi / 180.0, 0.0),
    "rev": ({"rad": 1}, 2.0 * math.pi, 0.0),
    "Hz": ({"s": -1}, 1.0, 0.0),
    "N": ({"kg": 1, "m": 1, "s": -2}, 1.0, 0.0),
    "Pa": ({"kg": 1, "m": -1, "s": -2}, 1.0, 0.0),
    "MPa": ({"kg": 1, "m": -1, "s": -2}, 1e6, 0.0),
    "GPa": ({"kg": 1, "m": -1, "s": -2}, 1e9, 0.0),
    "J": ({"kg": 1, "m": 2, "s": -2}, 1.0, 0.0),
    "W": ({"kg": 1, "m": 2, "s": -3}, 1.0, 0.0),
    "V": ({"kg": 1, "m": 2, "s": -3, "A": -1}, 1.0, 0.0),
    "Ohm": ({"kg": 1, "m": 2, "s": -3, "A": -2}, 1.0, 0.0),
    "H": ({"kg": 1, "m": 2, "s": -2, "A": -2}, 1.0, 0.0),
    "Wb": ({"kg": 1, "m": 2, "s": -2, "A": -1}, 1.0, 0.0),
    "T": ({"kg": 1, "s": -2, "A": -1}, 1.0, 0.0),
    "F": ({"kg": -1, "m": -2, "s": 4, "A": 2}, 1.0, 0.0),
    "C": ({"s": 1, "A": 1}, 1.0, 0.0),
    "L": ({"m": 3}, 1e-3, 0.0),
}

_TOKEN = re.compile(r"\s*(\(|\)|/|\.|[A-Za-z]+-?\d*|1)")
_FACTOR = re.compile(r"([A-Za-z]+)(-?\d+)?$")


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


def _tokens(text: str) -> list[str]:
    pos, out = 0, []
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            raise ValueError(f"cannot read unit {text!r} at {text[pos:]!r}")
        out.append(m.group(1))
        pos = m.end()
    return out


def _parse(tokens: list[str], k: int) -> tuple[dict[str, int], float, float, int]:
    """Factors up to a closing parenthesis; ``/`` divides by the next factor only.

    Returns exponents, factor, offset and the index of the next token.
    """
    exps: dict[str, int] = {}
    factor, offset, sign = 1.0, 0.0, 1
    while k < len(tokens) and tokens[k] != ")":
        tok = tokens[k]
        if tok in "./":
            sign = -1 if tok == "/" else 1
            k += 1
            continue
        n = 1
        if tok == "(":
            sub, f, _, k = _parse(tokens, k + 1)
        elif tok == "1":
            sub, f = {}, 1.0
        else:
            m = _FACTOR.match(tok)
            if m is None or m.group(1) not in _SYMBOLS:
                raise ValueError(f"unknown unit symbol {tok!r}")
            sub, f, off = _SYMBOLS[m.group(1)]
            n = int(m.group(2)) if m.group(2) else 1
            offset = off if len(tokens) == 1 else 0.0
        k += 1
        for base, e in sub.items():
            exps[base] = exps.get(base, 0) + sign * n * e
        factor *= f ** (sign * n)
        sign = 1
    return {b: e for b, e in exps.items() if e}, factor, offset, k


def parse_unit(text: str) -> UnitDefinition:
    """Read a unit string.

    Parameters
    ----------
    text : str
        Modelica unit syntax: factors joined by ``.``, divided by ``/`` (everything after a ``/``
        integer exponents appended
        (``m2``, ``s-1``), parentheses for groups; ``/`` divides by the next factor or group.

    Returns
    -------
    UnitDefinition
        With ``exponents=None`` if a symbol is unknown.
    """
    try:
        exps, factor, offset, _ = _parse(_tokens(text), 0)
    except ValueError:
        return UnitDefinition(text, None)
    return UnitDefinition(text, exps, factor, offset)


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
