"""Unit conversions at the model boundary.

Models are SI inside (m, N, s, rad, Pa s). Catalogue data in mm, r/min, mm^2/s or degrees is
converted once, with these helpers.
"""

from __future__ import annotations

import math

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
    "QUANTITY_UNITS",
    "parse_quantity",
    "engineering",
    "display_unit",
    "unit_label",
]

RPM = 2.0 * math.pi / 60.0
"""One revolution per minute in rad/s."""


def mm(value):
    """Millimetres to metres."""
    return value * 1e-3


def rpm_to_rad_s(n):
    """Speed in revolutions per minute to angular speed in rad/s."""
    return n * RPM


def rad_s_to_rpm(w):
    """Angular speed in rad/s to revolutions per minute."""
    return w / RPM


def deg(angle_deg):
    """Degrees to radians."""
    return angle_deg * math.pi / 180.0


def to_deg(angle_rad):
    """Radians to degrees."""
    return angle_rad * 180.0 / math.pi


def cst_to_m2_s(nu_cst):
    """Kinematic viscosity in mm^2/s (cSt) to m^2/s."""
    return nu_cst * 1e-6


def m2_s_to_cst(nu):
    """Kinematic viscosity in m^2/s to mm^2/s (cSt)."""
    return nu * 1e6


def celsius_to_kelvin(t_c):
    """Temperature in degrees Celsius to kelvin."""
    return t_c + 273.15


def N_mm_to_N_m(m_nmm):  # noqa: N802 - unit names
    """Torque in N mm to N m."""
    return m_nmm * 1e-3


QUANTITY_UNITS: dict[str, tuple[str, float]] = {
    "rad/s": ("rad/s", 1.0), "rpm": ("rad/s", RPM), "r/min": ("rad/s", RPM),
    "m": ("m", 1.0), "mm": ("m", 1e-3), "um": ("m", 1e-6), "µm": ("m", 1e-6),
    "N": ("N", 1.0), "kN": ("N", 1e3),
    "N.m": ("N.m", 1.0), "N m": ("N.m", 1.0), "Nm": ("N.m", 1.0), "N.mm": ("N.m", 1e-3),
    "N mm": ("N.m", 1e-3), "Nmm": ("N.m", 1e-3),
    "rad": ("rad", 1.0), "deg": ("rad", math.pi / 180.0),
    "s": ("s", 1.0), "ms": ("s", 1e-3),
    "V": ("V", 1.0), "A": ("A", 1.0), "W": ("W", 1.0), "kW": ("W", 1e3),
}
"""Engineering units a scene value may carry (``"10000 rpm"``): unit -> (SI unit, factor)."""


def parse_quantity(text: str) -> tuple[float, str] | None:
    """``"10000 rpm"`` -> ``(1047.19..., "rad/s")``: a number and a unit of
    :data:`QUANTITY_UNITS`, converted to SI; None when ``text`` is not of that form (it is then
    an expression, e.g. ``"rpm(10000) * min(t, 1)"``)."""
    parts = text.strip().split(maxsplit=1)
    if len(parts) != 2 or parts[1].strip() not in QUANTITY_UNITS:
        return None
    try:
        value = float(parts[0])
    except ValueError:
        return None
    si, factor = QUANTITY_UNITS[parts[1].strip()]
    return value * factor, si


def unit_label(unit: str) -> str:
    """A unit as shown to users: ``-`` for dimensionless (``"1"`` or ``""``), else itself."""
    return "-" if unit in ("", "1") else unit


def engineering(value: float, unit: str) -> str:
    """A value in SI shown in the unit an engineer reads it in: the units of
    :func:`display_unit`, with rad/s also in r/min and N in kN above 1 kN.

    Examples
    --------
    >>> engineering(1047.2, "rad/s")
    '1047.2 rad/s (10000 r/min)'
    >>> engineering(12.5e-6, "m")
    '12.5 um'
    """
    if not math.isfinite(value):
        return f"{value} [{unit_label(unit)}]"
    if unit == "rad/s":
        return f"{value:.6g} rad/s ({rad_s_to_rpm(value):.5g} r/min)"
    factor, shown = display_unit(unit, [value])
    if shown == "-":
        return f"{value:.6g} [-]"
    return f"{value:.6g} {shown}" if factor == 1.0 else f"{value * factor:.5g} {shown}"


def display_unit(unit: str, values) -> tuple[float, str]:
    """Factor and unit to plot SI ``values`` of ``unit`` in: r/min for rad/s, um or mm for
    small lengths, deg for rad, N mm for small torques and N m for others, kN for forces from
    1 kN, MPa for pressures (contact pressures, ``Pa``), ``-`` for dimensionless; else SI."""
    import numpy as np

    finite = np.asarray(values, dtype=float)
    finite = finite[np.isfinite(finite)]
    peak = float(np.max(np.abs(finite))) if finite.size else 0.0
    if unit_label(unit) == "-":
        return 1.0, "-"
    if unit == "rad/s":
        return 1.0 / RPM, "r/min"
    if unit == "rad":
        return 180.0 / math.pi, "deg"
    if unit == "m" and peak < 1e-3:
        return 1e6, "um"
    if unit == "m" and peak < 1.0:
        return 1e3, "mm"
    if unit == "N.m" and peak < 1.0:
        return 1e3, "N mm"
    if unit == "N.m":
        return 1.0, "N m"
    if unit == "N" and peak >= 1e3:
        return 1e-3, "kN"
    if unit == "Pa":
        return 1e-6, "MPa"
    return 1.0, unit
