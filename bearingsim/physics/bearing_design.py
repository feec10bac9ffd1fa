"""Derived design data of a deep-groove ball bearing for the dynamic model (SI units).

Coordinates: z is the bearing axis (the study of docs/studies.md, section C writes x for the axial
direction; here its ``x`` is ``z`` and its radial ``y, z`` are ``x, y``). The outer ring is fixed
at the origin.

Groove geometry follows Harris & Kotzalas (*Rolling Bearing Analysis*, 5th ed., *Essential
Concepts*, ch. "Ball and roller bearings: internal geometry"): the groove bottoms are
``dm/2 + Dw/2 + Pd/4`` (outer) and ``dm/2 - Dw/2 - Pd/4`` (inner), so the outer groove curvature
centre lies *inside* the pitch circle, ``rho_o = dm/2 - (fo - 0.5) Dw + Pd/4``, and the inner one
*outside* it, ``rho_i = dm/2 + (fi - 0.5) Dw - Pd/4`` (the study of docs/studies.md, section C
prints these signs swapped).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from bearingsim.catalog import BearingGeometry, get_bearing
from bearingsim.errors import ParameterError
from bearingsim.physics.contact_curvature import raceway_radii
from bearingsim.physics.hertz import load_deflection_constant, semi_axes
from bearingsim.physics.materials import STEEL, Material, effective_modulus
from bearingsim.validation import check_range

__all__ = ["BRASS", "STEEL_DENSITY", "BRASS_DENSITY", "POSITION_REGULARIZATION", "CageDesign",
           "BearingDesign", "bearing_design"]

BRASS = Material("machined brass (CuZn39Pb3)", 100e9, 0.34)
"""Cage material of machined, outer-ring guided cages (E, nu of leaded brass)."""
STEEL_DENSITY = 7850.0
"""Bearing steel density [kg/m^3]."""
BRASS_DENSITY = 8500.0
"""Brass density [kg/m^3]."""

POSITION_REGULARIZATION = 1e3
"""Stiffness [N/m] of the weak spring that holds a quasi-static ball towards the pitch circle.

An unloaded ball in the clearance has no stiffness; this spring keeps the Newton iteration
regular. Loaded balls move some 10 um from the pitch circle, so the force error is about 0.01 N.
"""


@dataclass(frozen=True)
class CageDesign:
    """Cage geometry (outer-ring land guided, stadium pockets), SI units.

    Attributes
    ----------
    pocket_clearance : float
        Pocket end radius minus ball radius ``Rp - Rb`` [m].
    pocket_straight : float
        Straight length ``Sp`` of the stadium pocket, along the bearing axis [m].
    web : float
        Radial thickness of the cage bars (pocket length along the pocket axis) [m].
    guide_clearance : float
        Radial clearance ``Cg`` between cage rail and outer-ring land [m].
    guide_width : float
        Land width ``Bg`` [m] (both rails together).
    mass : float
        Cage mass [kg].
    inertia : float
        Polar moment of inertia [kg m^2].
    guide_radius : float
        Land radius ``Rg`` [m].
    """

    pocket_clearance: float
    pocket_straight: float
    web: float
    guide_clearance: float
    guide_width: float
    mass: float
    inertia: float
    guide_radius: float


@dataclass(frozen=True)
class BearingDesign:
    """Everything the dynamic components need, derived once from a catalogue geometry.

    Attributes
    ----------
    geometry : BearingGeometry
        Catalogue geometry (Dw, dm, fi, fo, Z).
    clearance : float
        Diametral clearance Pd [m].
    rho_inner, rho_outer : float
        Radii of the inner and outer groove curvature-centre circles [m] (see module doc).
    k_inner, k_outer : float
        Hertz load-deflection constants at the free contact angle [N/m^1.5].
    a1_inner, a1_outer : float
        Semi-major axes at 1 N [m]; ``a = a1 Q^(1/3)``.
    rx_inner, ry_inner, rx_outer, ry_outer : float
        Effective radii along and across rolling [m] (film thickness after the run).
    e_eff : float
        Effective modulus E' (Hamrock, = 2 E*) of ball and rings [Pa].
    ball_mass, ball_inertia : float
        [kg], [kg m^2].
    ring_mass, ring_tilt_inertia, ring_polar_inertia : float
        Inner ring [kg], [kg m^2].
    cage : CageDesign
    free_contact_angle : float
        [rad].
    """

    geometry: BearingGeometry
    clearance: float
    rho_inner: float
    rho_outer: float
    k_inner: float
    k_outer: float
    a1_inner: float
    a1_outer: float
    rx_inner: float
    ry_inner: float
    rx_outer: float
    ry_outer: float
    e_eff: float
    ball_mass: float
    ball_inertia: float
    ring_mass: float
    ring_tilt_inertia: float
    ring_polar_inertia: float
    cage: CageDesign
    free_contact_angle: float

    @property
    def ball_radius(self) -> float:
        """Dw / 2 [m].

        Returns
        -------
        float
            Ball radius [m].
        """
        return 0.5 * self.geometry.ball_diameter

    @property
    def gamma(self) -> float:
        """Dw cos(a0) / dm [-] at the free contact angle.

        Returns
        -------
        float
            Pitch ratio [-].
        """
        g = self.geometry
        return g.ball_diameter * math.cos(self.free_contact_angle) / g.pitch_diameter

    @property
    def epicyclic_ratio(self) -> float:
        """Cage speed over inner-ring speed in pure rolling, ``(1 - gamma) / 2`` [-].

        Returns
        -------
        float
            Cage over inner-ring speed [-].
        """
        return 0.5 * (1.0 - self.gamma)


def _cage_design(g: BearingGeometry, pocket_clearance, guide_clearance) -> CageDesign:
    dw, dm = g.ball_diameter, g.pitch_diameter
    web = 0.35 * dw
    width = 0.6 * g.width
    r_in, r_out = 0.5 * dm - 0.5 * web, 0.5 * dm + 0.5 * web
    ring_volume = math.pi * (r_out**2 - r_in**2) * width
    pocket_volume = g.ball_count * math.pi * (0.5 * dw + pocket_clearance) ** 2 * web
    mass = BRASS_DENSITY * (ring_volume - pocket_volume)
    inertia = 0.5 * mass * (r_out**2 + r_in**2)
    return CageDesign(
        pocket_clearance=pocket_clearance,
        pocket_straight=0.05 * dw,
        web=web,
        guide_clearance=guide_clearance,
        guide_width=0.4 * width,
        mass=mass,
        inertia=inertia,
        guide_radius=r_out,
    )


def bearing_design(
    designation: str | BearingGeometry = "6304",
    clearance: float | None = None,
    ball: Material = STEEL,
    ring: Material = STEEL,
    pocket_clearance: float | None = None,
    guide_clearance: float | None = None,
) -> BearingDesign:
    """Derive the dynamic model's constants from a catalogue bearing.

    Hertz constants and ellipse sizes are evaluated at the free contact angle with the exact
    Hertz solution (:mod:`bearingsim.physics.hertz`; Harris & Kotzalas, ch. "Contact stress and
    deformation"). Cage dimensions are not catalogued; the defaults are typical of machined brass
    cages: pocket clearance ``0.03 Dw``, guide clearance ``0.015 Dw`` (smaller than the pocket
    clearance, so the land guides the cage), bar thickness ``0.35 Dw``, width ``0.6 B``.

    Parameters
    ----------
    designation : str or BearingGeometry
        Catalogue designation (``"6304"``) or a geometry.
    clearance : float, optional
        Diametral clearance Pd [m], >= 0; default: the catalogue value.
    ball, ring : Material
        Ball and ring materials.
    pocket_clearance, guide_clearance : float, optional
        Cage clearances [m], > 0 and below ``0.2 Dw``; the guide clearance must be smaller than
        the pocket clearance.

    Raises
    ------
    ParameterError
        For a clearance out of range or a guide clearance not below the pocket clearance.

    Returns
    -------
    BearingDesign
    """
    g = designation if isinstance(designation, BearingGeometry) else get_bearing(designation)
    where = f"bearing_design({g.designation})"
    if g.contact_angle != 0.0:
        raise ParameterError(f"{where}: the dynamic model is for deep-groove bearings (contact "
                             f"angle 0), got {g.contact_angle:g} rad")
    pd = g.diametral_clearance if clearance is None else clearance
    if pd < 0.0:
        raise ParameterError(f"{where}: diametral clearance {pd * 1e6:.2f} um < 0 (an internal "
                             f"preload, e.g. from the mounting fits): the ball-level models need "
                             f"a clearance >= 0 [m]; the quasi-static ball rows model the preload")
    check_range(pd, "clearance", "m", 0.0, 0.2 * g.groove_centre_distance, where=where)
    dw, dm = g.ball_diameter, g.pitch_diameter
    pocket_clearance = 0.03 * dw if pocket_clearance is None else pocket_clearance
    guide_clearance = 0.015 * dw if guide_clearance is None else guide_clearance
    check_range(pocket_clearance, "pocket_clearance", "m", 0.0, 0.2 * dw, low_inclusive=False,
                where=where)
    check_range(guide_clearance, "guide_clearance", "m", 0.0, 0.2 * dw, low_inclusive=False,
                where=where)
    if guide_clearance >= pocket_clearance:
        raise ParameterError(f"{where}: guide_clearance = {guide_clearance:g} m must be smaller "
                             f"than pocket_clearance = {pocket_clearance:g} m (the land, not the "
                             f"pockets, guides the cage; defaults 0.015 Dw = {0.015 * dw:g} m "
                             f"and 0.03 Dw = {0.03 * dw:g} m)")
    alpha0 = math.acos(1.0 - pd / (2.0 * g.groove_centre_distance))
    e_eff = effective_modulus(ball, ring)
    rxi, ryi = raceway_radii(dw, dm, g.fi, alpha0, "inner")
    rxo, ryo = raceway_radii(dw, dm, g.fo, alpha0, "outer")
    a1i, _ = semi_axes(1.0, rxi, ryi, e_eff)
    a1o, _ = semi_axes(1.0, rxo, ryo, e_eff)
    ball_mass = STEEL_DENSITY * math.pi * dw**3 / 6.0
    r_bore, r_land = 0.5 * g.bore, 0.5 * dm - 0.3 * dw
    ring_mass = STEEL_DENSITY * math.pi * (r_land**2 - r_bore**2) * g.width
    return BearingDesign(
        geometry=g,
        clearance=pd,
        rho_inner=0.5 * dm + (g.fi - 0.5) * dw - 0.25 * pd,
        rho_outer=0.5 * dm - (g.fo - 0.5) * dw + 0.25 * pd,
        k_inner=float(load_deflection_constant(rxi, ryi, e_eff)),
        k_outer=float(load_deflection_constant(rxo, ryo, e_eff)),
        a1_inner=float(a1i),
        a1_outer=float(a1o),
        rx_inner=float(rxi), ry_inner=float(ryi), rx_outer=float(rxo), ry_outer=float(ryo),
        e_eff=e_eff,
        ball_mass=ball_mass,
        ball_inertia=0.1 * ball_mass * dw**2,
        ring_mass=ring_mass,
        ring_tilt_inertia=ring_mass * ((r_land**2 + r_bore**2) / 4.0 + g.width**2 / 12.0),
        ring_polar_inertia=0.5 * ring_mass * (r_land**2 + r_bore**2),
        cage=_cage_design(g, pocket_clearance, guide_clearance),
        free_contact_angle=alpha0,
    )
