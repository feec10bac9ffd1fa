"""The duplex pair's shaft: mass properties and row positions (:class:`ShaftSpec`)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from bearingsim.catalog import BearingGeometry
from bearingsim.errors import ParameterError
from bearingsim.validation import check_range

STEEL_DENSITY = 7850.0


@dataclass(frozen=True)
class ShaftSpec:
    """Shaft of a duplex pair: mass properties and row positions.

    The source study does not give them; the defaults describe a solid steel shaft of 100 mm
    diameter (the 7020 bore) and 400 mm length with the rows 300 mm apart, centred on the centre
    of mass. The tilt stiffness goes with ``(L -+ (dm/2) tan a)^2`` (pressure centres), so the
    study's finding that the contact angle changes the axial mode most holds only for rows far
    apart compared with ``(dm/2) tan a`` (17 to 36 mm for the 7020 series); with rows 100 mm
    apart the DF tilt modes change more.

    Attributes
    ----------
    diameter, length : float
        Of the solid cylinder that gives the default mass properties [m].
    row_spacing : float
        Axial distance between the two rows' centres [m], > 0.
    centre_offset : float
        Axial position of the midpoint between the rows from the centre of mass [m].
    mass, transverse_inertia, polar_inertia : float, optional
        Override the solid-cylinder values [kg, kg m^2, kg m^2]; include the inner rings.
    density : float
        Material density [kg/m^3].
    """

    diameter: float = 0.100
    length: float = 0.400
    row_spacing: float = 0.300
    centre_offset: float = 0.0
    mass: float | None = None
    transverse_inertia: float | None = None
    polar_inertia: float | None = None
    density: float = STEEL_DENSITY

    def __post_init__(self) -> None:
        for name in ("diameter", "length", "row_spacing", "density"):
            check_range(getattr(self, name), name, "m" if name != "density" else "kg/m3", 0.0,
                        low_inclusive=False, where="ShaftSpec")
        check_range(self.centre_offset, "centre_offset", "m", where="ShaftSpec")
        for name in ("mass", "transverse_inertia", "polar_inertia"):
            if getattr(self, name) is not None:
                check_range(getattr(self, name), name, "kg" if name == "mass" else "kg.m2", 0.0,
                            low_inclusive=False, where="ShaftSpec")

    @property
    def solid_mass(self) -> float:
        """Mass of the solid cylinder [kg].

        Returns
        -------
        float
            ``rho pi r^2 l`` [kg].
        """
        return self.density * math.pi * self.diameter**2 / 4.0 * self.length

    @property
    def m(self) -> float:
        """Shaft mass [kg].

        Returns
        -------
        float
            The given mass [kg], else the solid cylinder's.
        """
        return self.solid_mass if self.mass is None else self.mass

    @property
    def jt(self) -> float:
        """Transverse moment of inertia about the centre of mass, ``m (3 r^2 + l^2) / 12``.

        Returns
        -------
        float
            Transverse moment of inertia [kg m^2].
        """
        if self.transverse_inertia is not None:
            return self.transverse_inertia
        return self.m * (0.75 * self.diameter**2 + self.length**2) / 12.0

    @property
    def jp(self) -> float:
        """Polar moment of inertia, ``m r^2 / 2`` [kg m^2].

        Returns
        -------
        float
            Polar moment of inertia [kg m^2].
        """
        return self.m * self.diameter**2 / 8.0 if self.polar_inertia is None else \
            self.polar_inertia

    @property
    def positions(self) -> tuple[float, float]:
        """Axial positions (L1, -L2) of row 0 and row 1 from the centre of mass [m].

        Returns
        -------
        tuple of (float, float)
            Axial positions of row 0 and row 1 [m].
        """
        half = 0.5 * self.row_spacing
        return (self.centre_offset + half, self.centre_offset - half)


def _shaft_spec(shaft: ShaftSpec | dict | None, geometry: BearingGeometry) -> ShaftSpec:
    """The shaft: by default a solid steel shaft of the bearing's bore, four bores long, with
    the rows three bores apart (the 7020 default: 100 mm x 400 mm, rows 300 mm apart); a given
    shaft whose diameter is not the bore warns (its inner rings would not fit)."""
    if shaft is None:
        bore = geometry.bore
        return ShaftSpec(diameter=bore, length=4.0 * bore, row_spacing=3.0 * bore)
    if isinstance(shaft, dict):
        try:
            shaft = ShaftSpec(**shaft)
        except TypeError as exc:
            raise ParameterError(f"duplex_pair: bad shaft specification: {exc}") from None
    if not isinstance(shaft, ShaftSpec):
        raise ParameterError(f"duplex_pair: shaft must be a ShaftSpec or a dict, got {shaft!r}")
    if not math.isclose(shaft.diameter, geometry.bore, rel_tol=1e-6):
        warnings.warn(f"duplex_pair: the shaft diameter {shaft.diameter * 1e3:g} mm is not the "
                      f"bore of {geometry.designation} ({geometry.bore * 1e3:g} mm); its mass "
                      f"properties are those of the shaft given", UserWarning, stacklevel=4)
    return shaft
