"""The units a person reads: one engineering unit per quantity kind, everywhere (console, plots,
HTML tables, scene and sweep figures). Files stay in SI with ``name [unit]`` headers.

=================  ============  ==========
quantity (SI)      shown in      e.g.
=================  ============  ==========
rad/s              r/min         10 000 r/min
m                  µm            12.5 µm
N.m                N mm          31.8 N mm
N                  kN            2.5 kN
K                  °C            80 °C
rad                deg           15 deg
Pa                 MPa           1 850 MPa
N/m                N/µm          120 N/µm
m2/s               mm²/s         32 mm²/s
=================  ============  ==========

Other units, and units the model already states in an engineering unit (a life in ``h``, a
time in ``s``), are shown as they are.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from bearingsim.units.registry import UnitError, base_exponents, si_factor, si_label

__all__ = ["DISPLAY_UNITS", "display_label", "to_display", "display_unit", "engineering",
           "unit_label", "describe"]

DISPLAY_UNITS: dict[str, str] = {
    "rad/s": "r/min",
    "m": "µm",
    "N.m": "N mm",
    "N": "kN",
    "K": "°C",
    "rad": "deg",
    "Pa": "MPa",
    "N/m": "N/µm",
    "m2/s": "mm²/s",
}
"""SI unit (model notation) -> the one unit it is shown in to a person."""

_PINT_SPELLING = {"mm²/s": "mm**2/s", "N/µm": "N/micrometer"}

_SHOWN_AS = {"Mrev": "10⁶ rev"}
"""Units a person reads under another name, the value unchanged: a life in millions of
revolutions as ISO 281 states it."""


def unit_label(unit: str) -> str:
    """A unit as shown to users: ``-`` for dimensionless (``"1"`` or ``""``), ``µm`` for
    ``um``, else itself.

    Parameters
    ----------
    unit : str

    Returns
    -------
    str
    """
    if unit in ("", "1"):
        return "-"
    return unit.replace("um", "µm") if unit in ("um", "um/s") else unit


@functools.lru_cache(maxsize=512)
def _display(unit: str) -> tuple[str, float, float]:
    """(label, factor, offset) to show values of ``unit``: ``shown = factor * x + offset``."""
    if unit in ("", "1", "-"):
        return "-", 1.0, 0.0
    if unit in _SHOWN_AS:
        return _SHOWN_AS[unit], 1.0, 0.0
    try:
        exps = base_exponents(unit)[0]
    except UnitError:
        return unit_label(unit), 1.0, 0.0
    for si, shown in DISPLAY_UNITS.items():
        if base_exponents(si)[0] == exps:
            factor, offset = si_factor(unit, _PINT_SPELLING.get(shown, shown))
            return shown, factor, offset
    return unit_label(unit), 1.0, 0.0


def display_label(unit: str) -> str:
    """The unit values of ``unit`` are shown in (``rad/s`` -> ``r/min``, ``m`` -> ``µm``).

    Parameters
    ----------
    unit : str
        Unit of the values, in the model's notation.

    Returns
    -------
    str
    """
    return _display(unit)[0]


def to_display(values, unit: str):
    """Values of ``unit`` in the unit a person reads them in (:data:`DISPLAY_UNITS`).

    Parameters
    ----------
    values : float or array_like
        In ``unit``.
    unit : str
        E.g. ``"rad/s"``, ``"N.m"``, ``"um"``.

    Returns
    -------
    tuple
        ``(converted values, label)``; a float for a float.
    """
    label, factor, offset = _display(unit)
    if isinstance(values, (int, float)):
        return float(values) * factor + offset, label
    return np.asarray(values, dtype=float) * factor + offset, label


def display_unit(unit: str, values=None) -> tuple[float, str]:
    """Factor and unit to show values of ``unit`` in (:data:`DISPLAY_UNITS`; ``values`` is
    accepted for compatibility and not used: the unit depends on the quantity, not on the
    magnitude). For a unit with an offset (K -> °C) use :func:`to_display`.

    Parameters
    ----------
    unit : str
    values : array_like, optional

    Returns
    -------
    tuple
        ``(factor, label)``.
    """
    label, factor, offset = _display(unit)
    if offset != 0.0:
        return 1.0, unit_label(unit)
    return factor, label


def _number(x: float) -> str:
    return f"{x:.5g}" if abs(x) < 1e5 else f"{x:.6g}"


def engineering(value: float, unit: str, *, both: bool = False,
                mark_dimensionless: bool = True) -> str:
    """A value of ``unit`` as a person reads it (:data:`DISPLAY_UNITS`), optionally followed by
    the value in ``unit`` itself.

    Parameters
    ----------
    value : float
    unit : str
    both : bool
        Also give the value in ``unit`` (used where a bare number was given in SI).
    mark_dimensionless : bool
        Write ``[-]`` after a dimensionless value (False: the number alone, ``Rs = 0.2095``).

    Returns
    -------
    str

    Examples
    --------
    >>> engineering(1047.2, "rad/s")
    '10000 r/min'
    >>> engineering(1047.2, "rad/s", both=True)
    '10000 r/min (1047.2 rad/s)'
    >>> engineering(12.5e-6, "m")
    '12.5 µm'
    """
    if not math.isfinite(value):
        return f"{value} {unit_label(unit)}"
    shown, label = to_display(float(value), unit)
    text = (f"{_number(shown)} {label}" if label != "-" else
            f"{_number(shown)} [-]" if mark_dimensionless else _number(shown))
    if both and label != unit_label(unit):
        text += f" ({value:.6g} {si_label(unit)})"
    return text


def describe(name: str, description: str, unit: str) -> str:
    """An axis or column label: the description (else the name) and the display unit,
    ``"cage speed [r/min]"``.

    Parameters
    ----------
    name, description, unit : str

    Returns
    -------
    str
    """
    return f"{description or name} [{display_label(unit)}]"
