"""The middle ring of a double-layer (nested) bearing: its parts, their mass properties and
its rotation (docs/studies.md, section A).

The inner bearing's outer ring, an intermediate sleeve and the outer bearing's inner ring form
the middle ring. I-type: both bearings in one radial plane, the sleeve a plain tube; Z-type:
the bearings offset axially, the sleeve a Z section.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from bearingsim.catalog import BearingGeometry
from bearingsim.components.connectors import Flange
from bearingsim.components.rotational import Inertia
from bearingsim.errors import ParameterError
from bearingsim.language import Assembly, Variable, connect
from bearingsim.physics.bearing_design import STEEL_DENSITY
from bearingsim.physics.fits import operating_clearance
from bearingsim.validation import check_choice, check_range

__all__ = ["STRUCTURES", "MiddleRing", "MiddleRingPart", "middle_ring_bodies",
           "middle_ring_structure", "mounted_geometries"]

STRUCTURES = ("I", "Z")
"""Middle ring types: I (both bearings in one radial plane) and Z (offset axially)."""


def middle_ring_structure(gi: BearingGeometry, go: BearingGeometry, structure: str | None) -> str:
    """Checked middle-ring type: "I" needs ``D1 <= d2``; None chooses "I" when it fits.

    Parameters
    ----------
    gi, go : BearingGeometry
        Inner (shaft-side) and outer (housing-side) bearing.
    structure : {"I", "Z"} or None
        Requested type.

    Returns
    -------
    str
        "I" or "Z".

    Raises
    ------
    ParameterError
        For another value, or "I" when the inner bearing does not fit in the outer one's bore.
    """
    if not (gi.pitch_diameter < go.pitch_diameter and gi.outside_diameter
            < go.outside_diameter and gi.bore < go.bore):
        raise ParameterError(
            f"double_layer_bearing: the inner bearing ({gi.designation}: d {gi.bore * 1e3:g}, D "
            f"{gi.outside_diameter * 1e3:g}, dm {gi.pitch_diameter * 1e3:g} mm) must be smaller "
            f"than the outer one ({go.designation}: d {go.bore * 1e3:g}, D "
            f"{go.outside_diameter * 1e3:g}, dm {go.pitch_diameter * 1e3:g} mm) in bore, "
            f"outside and pitch diameter: it sits inside it")
    fits = gi.outside_diameter <= go.bore
    structure = structure or ("I" if fits else "Z")
    check_choice(structure, "structure", STRUCTURES, "double_layer_bearing")
    if structure == "I" and not fits:
        raise ParameterError(
            f"double_layer_bearing: an I-type middle ring needs the inner bearing's outside "
            f"diameter ({gi.outside_diameter * 1e3:g} mm) <= the outer bearing's bore "
            f"({go.bore * 1e3:g} mm); use structure='Z'"
        )
    return structure



@dataclass(frozen=True)
class MiddleRingPart:
    """Mass properties of one part of the middle ring."""

    name: str
    mass: float
    """[kg]"""
    inertia: float
    """Polar moment of inertia [kg m^2]."""


def _tube(name: str, r_in: float, r_out: float, width: float, rho: float) -> MiddleRingPart:
    m = rho * math.pi * (r_out**2 - r_in**2) * width
    return MiddleRingPart(name, m, 0.5 * m * (r_out**2 + r_in**2))


def middle_ring_bodies(
    inner: BearingGeometry, outer: BearingGeometry, structure: str, wall: float = 2.5e-3,
    density: float = STEEL_DENSITY,
) -> list[MiddleRingPart]:
    """Mass and polar inertia of the three parts of the middle ring.

    The rings are hollow cylinders: the inner bearing's outer ring from the outer land radius
    ``dm/2 + 0.3 Dw`` to ``D/2``; the outer bearing's inner ring from ``d/2`` to the inner land
    radius ``dm/2 - 0.3 Dw`` (an estimate of the land heights of deep-groove rings). The sleeve
    is a plain tube between ``D1/2`` and ``d2/2`` (I-type), or a Z section (Z-type): a hub of
    thickness ``wall`` around the inner bearing, a hub of thickness ``wall`` inside the outer
    bearing's bore, joined by a radial web of thickness ``wall``.

    Parameters
    ----------
    inner, outer : BearingGeometry
        Inner (1) and outer (2) bearing.
    structure : {"I", "Z"}
        Middle ring type.
    wall : float
        Wall thickness of the Z-section sleeve [m].
    density : float
        Material density [kg/m^3].

    Returns
    -------
    list of MiddleRingPart
        Inner bearing's outer ring, sleeve, outer bearing's inner ring.
    """
    check_range(wall, "wall", "m", 0.0, None, low_inclusive=False, where="middle_ring_bodies")
    ring1 = _tube("inner bearing outer ring", inner.pitch_diameter / 2 + 0.3 * inner.ball_diameter,
                  inner.outside_diameter / 2, inner.width, density)
    ring2 = _tube("outer bearing inner ring", outer.bore / 2,
                  outer.pitch_diameter / 2 - 0.3 * outer.ball_diameter, outer.width, density)
    r1, r2 = inner.outside_diameter / 2, outer.bore / 2
    if structure == "I":
        sleeve = _tube("sleeve", r1, r2, max(inner.width, outer.width), density)
    else:
        hub1 = _tube("", r1, r1 + wall, inner.width, density)
        hub2 = _tube("", r2 - wall, r2, outer.width, density)
        web = _tube("", min(r2 - wall, r1), max(r1 + wall, r2), wall, density)
        sleeve = MiddleRingPart("sleeve", hub1.mass + hub2.mass + web.mass,
                          hub1.inertia + hub2.inertia + web.inertia)
    return [ring1, sleeve, ring2]


class MiddleRing(Assembly):
    """The middle ring: three rigid bodies joined by connections (not a hand-merged inertia).

    Parameters
    ----------
    bodies : list of MiddleRingPart
        Mass and polar inertia of its three parts, from the inner outward
        (:func:`middle_ring_bodies`).
    w0 : float
        Start speed [rad/s].
    name : str
        Instance name (the prefix of its variables' dotted names).

    Connectors
    ----------
    inner_side : Flange (the inner bearing's outer ring)
    outer_side : Flange (the outer bearing's inner ring)

    Variables
    ---------
    w [rad/s] : speed of the middle ring
    """

    def __init__(self, bodies: list[MiddleRingPart], w0: float = 0.0, name=None):
        super().__init__(name)
        ring1, sleeve, ring2 = bodies
        self.inner_ring_of_inner_bearing = Inertia(ring1.inertia, w0=w0)
        self.sleeve = Inertia(sleeve.inertia, w0=w0)
        self.outer_ring_of_outer_bearing = Inertia(ring2.inertia, w0=w0)
        self.J = sum(b.inertia for b in bodies)
        self.inner_side = Flange()
        self.outer_side = Flange()
        self.w = Variable(unit="rad/s", description="middle ring speed")
        self.mass = sum(b.mass for b in bodies)
        connect(self.inner_side, self.inner_ring_of_inner_bearing.flange_a)
        connect(self.inner_ring_of_inner_bearing.flange_b, self.sleeve.flange_a)
        connect(self.sleeve.flange_b, self.outer_ring_of_outer_bearing.flange_a)
        connect(self.outer_ring_of_outer_bearing.flange_b, self.outer_side)

    def equations(self):
        return [self.w == self.sleeve.w]


def mounted_geometries(inner: BearingGeometry, outer: BearingGeometry, structure: str,
                       wall: float = 2.5e-3, band: str = "mean"
                       ) -> tuple[BearingGeometry, BearingGeometry]:
    """The two layers with the operating clearance of the study's fits (docs/studies.md, section A:
    inner fits k6, outer fits H7).

    The inner bearing sits on the shaft with k6 (solid shaft) and in the middle ring with H7;
    the outer bearing sits on the middle ring with k6 and in the housing with H7 (rigid). The
    middle ring is the "shaft" of the outer bearing: an I-type sleeve has the inner bearing's
    outside diameter as its bore, a Z-type hub a wall of ``wall``; a thin seat gives way, so it
    takes up less clearance (:func:`~bearingsim.physics.fits.raceway_factor_inner`). The H7
    seats never have interference. Initial clearance: each geometry's own (the catalogue rows
    hold the CN mean; :func:`~bearingsim.physics.fits.operating_clearance` for the sources).

    Parameters
    ----------
    inner, outer : BearingGeometry
        Inner (shaft-side) and outer (housing-side) bearing.
    structure : {"I", "Z"}
        Middle ring type.
    wall : float
        Wall thickness of the Z-type hub under the outer bearing [m].
    band : {"mean", "smallest", "largest"}
        Interference of the probable band.

    Returns
    -------
    (BearingGeometry, BearingGeometry)
        Copies with ``diametral_clearance`` the operating clearance.

    A negative operating clearance is an internal preload: the quasi-static ball rows carry it
    (every ball loaded without an external load), the ball-level models refuse it by name.
    """
    check_choice(structure, "structure", STRUCTURES, "mounted_geometries")
    sleeve_bore = inner.outside_diameter if structure == "I" else outer.bore - 2.0 * wall
    clearances = (operating_clearance(inner, "k6", "H7", band=band),
                  operating_clearance(outer, "k6", "H7", shaft_bore=max(sleeve_bore, 0.0),
                                      band=band))
    return tuple(dataclasses.replace(g, diametral_clearance=c.operating)
                 for g, c in zip((inner, outer), clearances, strict=True))
