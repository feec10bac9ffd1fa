"""Units at every edge, with one units library (:mod:`pint`).

Models are SI inside (m, N, s, rad, Pa s). Values reach them in SI:

* numbers with a unit (``"10000 rpm"``, ``"500rpm"``, ``"2 kN"``, ``"25 µm"``, a
  :class:`pint.Quantity`) are converted by :func:`to_si` in scenes, sweep grids and the Python
  API alike (:mod:`bearingsim.units.registry`);
* a bare number is the SI value (rad/s, m, N m); where that differs from the customary
  engineering unit the value is echoed in both units and speeds are checked against the
  bearings' limiting speeds (docs/units.md);
* catalogue data in mm, r/min, mm^2/s or degrees is converted once, with the helpers below.

What a person reads is shown in one engineering unit per quantity kind
(:mod:`bearingsim.units.display`).
"""

from __future__ import annotations

import math
from typing import Any

from bearingsim.units.display import (
    DISPLAY_UNITS,
    describe,
    display_label,
    display_unit,
    engineering,
    to_display,
    unit_label,
)
from bearingsim.units.registry import (
    UnitError,
    is_quantity,
    pint_unit,
    quantity_to_si,
    registry,
    split_quantity,
)

__all__ = [
    "mm",
    "rpm_to_rad_s",
    "rad_s_to_rpm",
    "deg",
    "to_deg",
    "cst_to_m2_s",
    "m2_s_to_cst",
    "celsius_to_kelvin",
    "N_mm_to_N_m",
    "CUSTOMARY_DIFFERS",
    "DISPLAY_UNITS",
    "UnitError",
    "describe",
    "display_label",
    "display_unit",
    "engineering",
    "is_quantity",
    "parse_quantity",
    "pint_unit",
    "registry",
    "split_quantity",
    "to_display",
    "to_si",
    "unit_label",
]

RPM = 2.0 * math.pi / 60.0
"""One revolution per minute in rad/s."""

CUSTOMARY_DIFFERS = ("rad/s", "m", "N.m")
"""SI units whose customary engineering unit differs (r/min, µm or mm, N mm): a bare number
for such an input is taken as SI and echoed in both units (docs/units.md)."""


def mm(value):
    """Millimetres to metres.

    Parameters
    ----------
    value : float or array
        Length [mm].

    Returns
    -------
    float or array
        Length [m].
    """
    return value * 1e-3


def rpm_to_rad_s(n):
    """Speed in revolutions per minute to angular speed in rad/s.

    Parameters
    ----------
    n : float or array
        Speed [r/min].

    Returns
    -------
    float or array
        Angular speed [rad/s].
    """
    return n * RPM


def rad_s_to_rpm(w):
    """Angular speed in rad/s to revolutions per minute.

    Parameters
    ----------
    w : float or array
        Angular speed [rad/s].

    Returns
    -------
    float or array
        Speed [r/min].
    """
    return w / RPM


def deg(angle_deg):
    """Degrees to radians.

    Parameters
    ----------
    angle_deg : float or array
        Angle [deg].

    Returns
    -------
    float or array
        Angle [rad].
    """
    return angle_deg * math.pi / 180.0


def to_deg(angle_rad):
    """Radians to degrees.

    Parameters
    ----------
    angle_rad : float or array
        Angle [rad].

    Returns
    -------
    float or array
        Angle [deg].
    """
    return angle_rad * 180.0 / math.pi


def cst_to_m2_s(nu_cst):
    """Kinematic viscosity in mm^2/s (cSt) to m^2/s.

    Parameters
    ----------
    nu_cst : float or array
        Kinematic viscosity [mm^2/s].

    Returns
    -------
    float or array
        Kinematic viscosity [m^2/s].
    """
    return nu_cst * 1e-6


def m2_s_to_cst(nu):
    """Kinematic viscosity in m^2/s to mm^2/s (cSt).

    Parameters
    ----------
    nu : float or array
        Kinematic viscosity [m^2/s].

    Returns
    -------
    float or array
        Kinematic viscosity [mm^2/s].
    """
    return nu * 1e6


def celsius_to_kelvin(t_c):
    """Temperature in degrees Celsius to kelvin.

    Parameters
    ----------
    t_c : float or array
        Temperature [°C].

    Returns
    -------
    float or array
        Temperature [K].
    """
    return t_c + 273.15


def N_mm_to_N_m(m_nmm):  # noqa: N802 - unit names
    """Torque in N mm to N m.

    Parameters
    ----------
    m_nmm : float or array
        Torque [N mm].

    Returns
    -------
    float or array
        Torque [N m].
    """
    return m_nmm * 1e-3


_SI_UNITS = ("rad/s", "rad/s2", "rad", "m", "m/s", "N", "N.m", "s", "V", "A", "W", "K", "Pa",
             "N/m", "m2/s", "kg", "kg.m2", "Hz", "1")
"""SI units in the model's notation that :func:`parse_quantity` names a value's quantity by."""


def parse_quantity(text: str) -> tuple[float, str] | None:
    """``"10000 rpm"`` -> ``(1047.19..., "rad/s")``: a number with a unit converted to SI, and
    the SI unit (model notation) of its quantity; None when ``text`` is not of that form (it is
    then an expression, e.g. ``"rpm(10000) * min(t, 1)"``).

    Parameters
    ----------
    text : str

    Returns
    -------
    tuple or None

    A number with a unit that is not finite (``"nan N"``, ``"inf rpm"``, ``"1e999 N"``) is not
    a quantity either: :func:`bearingsim.scenes.expressions.compile_expression` then refuses it
    by name, and :func:`to_si` raises :class:`UnitError`.
    """
    parsed = split_quantity(text)
    if parsed is None or not math.isfinite(parsed[0]):
        return None
    from bearingsim.units.registry import base_exponents

    exps = base_exponents(parsed[1])[0]
    si = next((u for u in _SI_UNITS if base_exponents(u)[0] == exps), None)
    if si is None:
        return None
    try:
        return quantity_to_si(text, si, "value"), si
    except UnitError:  # overflows in SI
        return None


def to_si(value: Any, unit: str, name: str) -> Any:
    """A value given for an input or parameter of ``unit``, in ``unit``.

    Parameters
    ----------
    value : number, str or pint.Quantity
        A bare number (taken as ``unit``, returned unchanged), a number with a unit as text
        (``"10000 rpm"``) or a :class:`pint.Quantity`; anything else is returned unchanged for
        the caller to check (a function of time, a table).
    unit : str
        The SI unit of the input or parameter, model notation (``"rad/s"``).
    name : str
        Its name, for messages.

    Returns
    -------
    float or the value unchanged

    Raises
    ------
    UnitError
        For a unit of another quantity, or a value that is not finite.
    """
    if is_quantity(value) or (isinstance(value, str) and split_quantity(value) is not None):
        return quantity_to_si(value, unit, name)
    return value
