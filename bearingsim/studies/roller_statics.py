"""Quasi-static cylindrical roller bearing (NU) under a radial load at a misalignment.

The inner ring moves radially against the fixed outer ring until the sliced line contacts of
the rollers balance the radial load
(:func:`~bearingsim.components.roller_row.roller_row_equilibrium`, the equations of the scenes'
quasi-static level); the tilt is imposed (a misalignment), and the moment the shaft must apply
to hold it follows. The result carries the roller loads, the largest
contact pressure, the radial stiffness (exact Jacobian) and the ISO/TS 16281 roller-form
reference rating life.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from bearingsim.assemblies.cylindrical_roller.options import CylindricalRollerOptions
from bearingsim.catalog.rollers import RollerBearingGeometry
from bearingsim.components.dynamic.ring import load_value
from bearingsim.components.roller_row import (
    roller_row_equilibrium,
    roller_row_lives,
    roller_row_parameters,
)
from bearingsim.physical_checks import check_static_pressure
from bearingsim.validation import check_mapping

__all__ = ["LOAD_NAMES", "ROLLER_PRESSURE_LIMIT", "RollerStatics", "roller_statics"]

LOAD_NAMES = ("Fx", "Fy")
"""External loads on the inner ring [N]: radial (an NU bearing carries no axial load; the
product's options refuse any other)."""
ROLLER_PRESSURE_LIMIT = 4.0e9
"""Contact pressure [Pa] at which ISO 76 sets the basic static radial load rating of roller
bearings (4 000 MPa; 4 200 MPa for ball bearings); above it a warning is given."""



@dataclass(frozen=True)
class RollerStatics:
    """Result of :func:`roller_statics`.

    Attributes
    ----------
    roller_loads : numpy.ndarray
        Load of each roller [N].
    max_pressure : float
        Largest contact pressure of any slice (inner raceway) [Pa].
    displacement : numpy.ndarray
        Inner ring displacement (x, y) against the outer ring [m].
    moment : numpy.ndarray
        Moment (Mx, My) [N m] the shaft applies to hold the misalignment.
    stiffness : numpy.ndarray
        Radial stiffness ``-d(row load on the inner ring) / d(x, y)``, 2x2 [N/m].
    reference_life : float
        ISO/TS 16281 roller-form reference rating life L10r [10^6 rev] (rotating inner
        ring; inf without load).
    state : numpy.ndarray
        The solved inner ring position (x, y) [m], a start for a nearby load case.
    """

    roller_loads: np.ndarray
    max_pressure: float
    displacement: np.ndarray
    moment: np.ndarray
    stiffness: np.ndarray
    reference_life: float
    state: np.ndarray


def roller_statics(bearing: str | RollerBearingGeometry = "NU206",
                   loads: Mapping[str, float | str] | None = None,
                   misalignment: tuple = (0.0, 0.0), clearance: float | str | None = None,
                   n_slices: int = 10) -> RollerStatics:
    """Roller loads, contact pressure, stiffness and life of a cylindrical roller bearing.

    Parameters
    ----------
    bearing : str or RollerBearingGeometry
        Catalogue designation ("NU206", "NU 206") or geometry.
    loads : dict, optional
        ``Fx``, ``Fy`` on the inner ring [N] (numbers, or with a unit: ``"5 kN"``).
    misalignment : (float, float)
        Tilt (tx, ty) of the inner ring against the outer ring [rad], each in [-0.01, 0.01]
        (or with a unit: ``"0.5 mrad"``).
    clearance : float or str, optional
        Diametral clearance [m] (default: the catalogue's, the middle of the normal group).
    n_slices : int
        Slices per roller, >= 1.

    Returns
    -------
    RollerStatics

    Raises
    ------
    ParameterError
        For an unknown load name, a value outside its range (naming it, with its unit), or
        loads whose contact pressure exceeds that of 10 x C0
        (:func:`~bearingsim.physical_checks.check_static_pressure`).
    SimulationError
        If no equilibrium is found.

    Warns
    -----
    PlasticDeformationWarning
        Above :data:`ROLLER_PRESSURE_LIMIT`.
    """
    where = "roller_statics"
    # checked (units converted) as the product's quasi-static level checks them
    opts = CylindricalRollerOptions(bearing, "quasi-static", clearance=clearance,
                                    misalignment=misalignment, n_slices=n_slices,
                                    loads=check_mapping(loads, "loads", where,
                                                        "load names (Fx, Fy)"))
    g, clearance, tilt = opts.geometry, opts.clearance, list(opts.misalignment)
    force = [load_value(opts.loads.get(k, 0.0), k, where) for k in LOAD_NAMES]  # constants
    p = roller_row_parameters(g, clearance)
    eq = roller_row_equilibrium(p, g.roller_count, n_slices, force, tilt)
    p_max = float(max(eq.contacts.p_max))
    check_static_pressure(p_max, ROLLER_PRESSURE_LIMIT, "1/2", f"{where}({g.designation})",
                          f"{dict(zip(LOAD_NAMES, force, strict=True))} [N]")
    moment = np.asarray(eq.moment, dtype=float)
    # a moment that symmetry makes 0 comes out as round-off of the slice sums (1e-16 N m):
    # below 1e-9 of the load's moment over the pitch diameter it is 0
    moment[np.abs(moment) < 1e-9 * np.hypot(*force) * g.pitch_diameter] = 0.0
    return RollerStatics(np.asarray(eq.contacts.Q), p_max,
                         eq.inner[:2].copy(), moment, eq.stiffness[:2, :2],
                         float(roller_row_lives(g, clearance, [eq.inner], n_slices)[0]),
                         eq.inner[:2].copy())
