"""The options of a cylindrical roller bearing product, validated once."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from bearingsim.catalog.rollers import RollerBearingGeometry, resolve_roller_bearing
from bearingsim.components.dynamic.ring import check_loads
from bearingsim.errors import ParameterError
from bearingsim.physics.lubricant import Lubricant, as_lubricant
from bearingsim.validation import check_choice, check_count, check_quantity

__all__ = ["FIDELITIES", "FRICTION_MODELS", "MAX_TILT", "CylindricalRollerOptions"]

FIDELITIES = ("torque", "quasi-static")
"""Levels, lowest first: the friction torque between the rings (no rollers resolved), and the
rollers' load distribution (sliced line contacts)."""
FRICTION_MODELS = ("palmgren", "skf")
"""Friction torque models of the torque level."""
MAX_TILT = 0.01
"""Largest misalignment about either axis [rad]."""


@dataclass(frozen=True)
class CylindricalRollerOptions:
    """Everything a cylindrical roller bearing is built from; checked at construction.

    Attributes
    ----------
    bearing : str or RollerBearingGeometry
        Catalogue designation (e.g. "NU206") or geometry; resolved to ``geometry``.
    fidelity : {"torque", "quasi-static"}
    clearance : float, optional
        Diametral clearance Pd [m], in [0, 0.1 Dw] (default: the catalogue's, the middle of the
        normal group).
    misalignment : (float, float)
        Tilt ``(tx, ty)`` of the inner ring against the outer ring [rad], each in
        [-0.01, 0.01] (quasi-static level).
    n_slices : int
        Slices per roller, >= 1 (quasi-static level).
    lubricant : str or Lubricant
        Torque level: the lubricant of the friction model; resolved to ``lubricant``.
    friction_model : {"palmgren", "skf"}
        Torque level: Palmgren's ``M0 + M1`` or SKF's four-component model.
    loads : dict
        Quasi-static level: ``Fx, Fy`` on the inner ring [N], constants, functions of time or
        None (inputs ``load.Fx``, ``load.Fy``; missing keys are inputs).

    Raises
    ------
    ParameterError
        For a value outside its range (naming it, with unit and range), an unknown choice or
        designation (:class:`~bearingsim.errors.CatalogError`).
    """

    bearing: str | RollerBearingGeometry = "NU206"
    fidelity: str = "quasi-static"
    clearance: float | None = None
    misalignment: tuple[float, float] = (0.0, 0.0)
    n_slices: int = 10
    lubricant: str | Lubricant = "ISO VG 32"
    friction_model: str = "palmgren"
    loads: dict[str, Any] = field(default_factory=dict)
    geometry: RollerBearingGeometry = field(init=False)

    def __post_init__(self) -> None:
        where = "cylindrical_roller_bearing"
        object.__setattr__(self, "geometry", resolve_roller_bearing(self.bearing))
        check_choice(self.fidelity, "fidelity", FIDELITIES, where)
        check_choice(self.friction_model, "friction_model", FRICTION_MODELS, where)
        if self.clearance is not None:  # "20 um" -> 2e-05
            object.__setattr__(self, "clearance", float(check_quantity(
                self.clearance, "clearance", "m", 0.0, 0.1 * self.geometry.roller_diameter,
                where=where)))
        tilt = tuple(self.misalignment) if isinstance(self.misalignment, (tuple, list)) else ()
        if len(tilt) != 2:
            raise ParameterError(f"{where}: misalignment must be (tx, ty) [rad], got "
                                 f"{self.misalignment!r}")
        object.__setattr__(self, "misalignment", tuple(
            float(check_quantity(value, f"misalignment[{k}]", "rad", -MAX_TILT, MAX_TILT,
                                 where=where)) for k, value in enumerate(tilt)))
        check_count(self.n_slices, "n_slices", 1, where=where)
        object.__setattr__(self, "lubricant", as_lubricant(self.lubricant, where))
        loads = dict(self.loads or {})
        unknown = sorted(set(loads) - {"Fx", "Fy"})
        if unknown:
            raise ParameterError(f"{where}: loads may have the keys Fx, Fy [N] (the bearing "
                                 f"carries no axial load; the misalignment sets the tilt), got "
                                 f"{', '.join(unknown)}")
        object.__setattr__(self, "loads", check_loads(loads, where))  # "2 kN" -> 2000.0

    @property
    def clearance_value(self) -> float:
        """The diametral clearance used [m].

        Returns
        -------
        float
            The given ``clearance`` [m], else the geometry's ``diametral_clearance`` [m].
        """
        return self.geometry.diametral_clearance if self.clearance is None else \
            float(self.clearance)
