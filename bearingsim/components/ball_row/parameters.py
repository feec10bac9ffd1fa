"""A ball row's parameters: geometry, contact constants and options (:class:`RowParameters`,
:func:`row_parameters`)."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.physics.hertz import bearing_load_deflection_constants
from bearingsim.physics.materials import STEEL, Material
from bearingsim.validation import check_range

REFERENCES = ("touching", "centred")
_MAX_ALPHA = math.radians(45.0)
STEEL_DENSITY = 7850.0
"""Density of bearing steel balls [kg/m^3]."""


@dataclass(frozen=True)
class RowParameters:
    """Numeric parameters of a ball row (SI units); the component's parameters have these names.

    Attributes
    ----------
    Dw, dm : ball and pitch diameter [m]
    fi, fo : groove curvature factors [-]
    alpha0 : free contact angle [rad]
    K_i, K_o : Hertz load-deflection constants of the inner and outer contact [N/m^1.5]
    psi0 : ball position angle (azimuth of ball 0) [rad]
    smooth : regularization length of the contact law [m]
    interference : how much farther apart the groove centres are than ``A`` at zero
        displacement [m]: ``-Pd / 2`` for a negative diametral clearance (an internal preload
        of a mounted deep-groove bearing), else 0
    """

    Dw: float
    dm: float
    fi: float
    fo: float
    alpha0: float
    K_i: float
    K_o: float
    psi0: float = 0.0
    smooth: float = 1e-9
    interference: float = 0.0


def row_parameters(bearing: str | BearingGeometry, contact_angle: float | None = None,
                   ball_position_angle: float = 0.0, smooth: float = 1e-9,
                   ball: Material = STEEL, ring: Material = STEEL,
                   method: str = "exact") -> RowParameters:
    """Row parameters of a catalogue bearing.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Designation or geometry.
    contact_angle : float, optional
        Free contact angle [rad] in [0, 45 deg]; the bearing's free contact angle by default.
    ball_position_angle : float
        Azimuth of ball 0 [rad].
    smooth : float
        Regularization length [m], > 0.
    ball, ring : Material
        Materials (Hertz constants).
    method : {"exact", "hamrock_brewe"}
        Elliptic integrals of the Hertz constants.

    Returns
    -------
    RowParameters
        With the Hertz constants evaluated at the free contact angle.
    """
    g = resolve_bearing(bearing)
    alpha0 = g.free_contact_angle if contact_angle is None else contact_angle
    check_range(alpha0, "contact_angle", "rad", 0.0, _MAX_ALPHA,
                where=f"row_parameters({g.designation})")
    check_range(smooth, "smooth", "m", 0.0, low_inclusive=False, where="row_parameters")
    k_i, k_o = _contact_constants(g, ball, ring, float(alpha0), method)
    return RowParameters(g.ball_diameter, g.pitch_diameter, g.fi, g.fo, float(alpha0),
                         k_i, k_o, float(ball_position_angle), float(smooth),
                         max(-g.diametral_clearance, 0.0) / 2.0)


@functools.lru_cache(maxsize=64)
def _contact_constants(g: BearingGeometry, ball: Material, ring: Material, alpha0: float,
                       method: str) -> tuple[float, float]:
    """The inner and outer Hertz load-deflection constants of a row [N/m^1.5], once per
    bearing, materials, free contact angle and method (a few milliseconds each: a duplex
    pair's every operating point builds its two rows and solves its preload offset)."""
    k_i, k_o, _ = bearing_load_deflection_constants(g, ball, ring, alpha0, method)
    return float(k_i), float(k_o)
