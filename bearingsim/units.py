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
