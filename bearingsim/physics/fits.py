"""Mounting fits and the operating radial clearance they leave.

A ring pressed onto a shaft expands, a ring pressed into a housing contracts; both take up
radial internal clearance. This module turns ISO 286 tolerance zones of the seats and the normal
tolerance class of the bearing into interference (theoretical limits and the probable band),
the interference into the change of the raceway diameter (Lamé thick-ring solution for equal
materials), and that into the operating diametral clearance. A negative operating clearance is an
internal preload.

Sources (texts in the public repository ArtemFilin1990/Mar):

* ISO 286 zones k6 and H7 and the normal bearing tolerances: NSK *Rolling Bearings* CAT. No.
  E1102e, Appendix Tables 9 and 10 (pp. C18-C21) and Tables 15.2, 15.3 (pp. A130-A133); SKF
  General Catalogue 6000 (2006 data), Tables 7d and 8b (pp. 180, 186), deviations "according to
  ISO 286-2:1988". Both agree at every row used here.
* Probable interference: SKF GC 6000 p. 172, "covering 99 % of all combinations"; the band is the
  mean interference +- the root sum square of the two half tolerance widths, which reproduces
  every SKF probable value of the rows used (tests/physics/test_fits.py).
* Effective interference of ground seats, ``d / (d + 2)`` (turned: ``d / (d + 3)``), d in mm:
  NSK E1102e 9.1.2, eq. (9.4), (9.5), p. A83.
* Raceway diameter change, equal materials: NSK E1102e Table 15.1, p. A130: inner ring on a solid
  shaft ``dDi = dd k``, ``k = d / Di``; the hollow-shaft and finite-housing forms are the Lamé
  solutions ``k (1 - k0^2) / (1 - k^2 k0^2)`` and ``h (1 - h0^2) / (1 - h^2 h0^2)``. Rule-of-thumb
  checks: NSK 9.2 and NTN p. A-57, 70-90 % of the interference; KRW 2006 p. 95, 80 % (inner) and
  70 % (outer) for solid steel shafts and normal-wall steel housings.
* Radial internal clearance before mounting, deep groove ball bearings: NSK E1102e Table 9.9,
  p. A89 (classes C2 is not covered; CN and C3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from bearingsim.catalog.geometry import BearingGeometry
from bearingsim.checks import guard_public_functions
from bearingsim.errors import ParameterError
from bearingsim.validation import check_choice, check_range

__all__ = [
    "BEARING_BORE_TOLERANCE",
    "BEARING_OUTSIDE_TOLERANCE",
    "CLEARANCE_CLASSES",
    "ISO_286",
    "Fit",
    "OperatingClearance",
    "effective_interference",
    "fit",
    "initial_clearance",
    "operating_clearance",
    "raceway_factor_inner",
    "raceway_factor_outer",
]

_UM = 1e-6

ISO_286: dict[str, tuple[tuple[float, float, float, float], ...]] = {
    # zone: (over [mm], up to and including [mm], upper, lower deviation [um])
    "k6": ((18.0, 30.0, 15.0, 2.0), (30.0, 50.0, 18.0, 2.0)),
    "H7": ((30.0, 50.0, 25.0, 0.0), (50.0, 80.0, 30.0, 0.0)),
}
"""ISO 286 deviations of the shaft zone k6 and the hole zone H7 at the diameters of the
double-layer study (NSK E1102e App. Tables 9, 10; SKF GC 6000 Tables 7d, 8b). Other zones and
diameters are not entered (a named error asks for them)."""

BEARING_BORE_TOLERANCE: tuple[tuple[float, float, float, float], ...] = (
    (18.0, 30.0, 0.0, -10.0), (30.0, 50.0, 0.0, -12.0))
"""Normal tolerance class, mean bore diameter deviation (over, incl. [mm], upper, lower [um])."""
BEARING_OUTSIDE_TOLERANCE: tuple[tuple[float, float, float, float], ...] = (
    (30.0, 50.0, 0.0, -11.0), (50.0, 80.0, 0.0, -13.0))
"""Normal tolerance class, mean outside diameter deviation (over, incl. [mm], upper, lower
[um])."""

CLEARANCE_CLASSES: dict[str, tuple[tuple[float, float, float, float], ...]] = {
    "CN": ((24.0, 30.0, 5.0, 20.0), (30.0, 40.0, 6.0, 20.0), (40.0, 50.0, 6.0, 23.0)),
    "C3": ((24.0, 30.0, 13.0, 28.0), (30.0, 40.0, 15.0, 33.0), (40.0, 50.0, 18.0, 36.0)),
}
"""Radial internal clearance of deep groove ball bearings before mounting by bore diameter (over,
incl. [mm], min, max [um]), NSK E1102e Table 9.9, p. A89."""


def _row(table, diameter: float, what: str) -> tuple[float, float]:
    mm = diameter * 1e3
    for over, upto, first, second in table:
        if over < mm <= upto + 1e-9:
            return first, second
    spans = ", ".join(f"over {o:g} to {u:g} mm" for o, u, _, _ in table)
    raise ParameterError(f"{what}: no entry for {mm:g} mm (entered: {spans})")


@dataclass(frozen=True)
class Fit:
    """Interference of a ring seat [m] (positive: interference, negative: clearance).

    Attributes
    ----------
    smallest, largest : float
        Theoretical limits from the deviations.
    probable_smallest, probable_largest : float
        The probable band: mean +- root sum square of the half tolerance widths (SKF's
        "99 % of all combinations").
    """

    smallest: float
    largest: float
    probable_smallest: float
    probable_largest: float

    @property
    def mean(self) -> float:
        """Mean interference [m].

        Returns
        -------
        float
            Mean interference [m].
        """
        return 0.5 * (self.smallest + self.largest)


def fit(diameter: float, zone: str, seat: str) -> Fit:
    """Interference of a bearing ring on its seat.

    Parameters
    ----------
    diameter : float
        Nominal seat diameter [m]: the bore for ``seat="shaft"``, the outside diameter for
        ``seat="housing"``.
    zone : str
        ISO 286 zone of the seat (a key of :data:`ISO_286`).
    seat : {"shaft", "housing"}
        The inner ring on a shaft, or the outer ring in a housing.

    Returns
    -------
    Fit

    Raises
    ------
    ParameterError
        For an unknown zone or seat, or a diameter with no entered deviations.
    """
    check_choice(seat, "seat", ("shaft", "housing"), "fit")
    check_choice(zone, "zone", tuple(ISO_286), "fit")
    check_range(diameter, "diameter", "m", 0.0, 6.0, low_inclusive=False, where="fit")
    z_up, z_lo = _row(ISO_286[zone], diameter, f"fit: ISO 286 zone {zone}")
    if seat == "shaft":
        b_up, b_lo = _row(BEARING_BORE_TOLERANCE, diameter, "fit: bearing bore tolerance")
        largest, smallest = z_up - b_lo, z_lo - b_up
    else:
        b_up, b_lo = _row(BEARING_OUTSIDE_TOLERANCE, diameter,
                          "fit: bearing outside diameter tolerance")
        largest, smallest = b_up - z_lo, b_lo - z_up
    mean = 0.5 * (largest + smallest)
    spread = math.hypot(0.5 * (z_up - z_lo), 0.5 * (b_up - b_lo))
    return Fit(smallest * _UM, largest * _UM, (mean - spread) * _UM, (mean + spread) * _UM)


def effective_interference(interference: float, diameter: float, ground: bool = True) -> float:
    """Interference left after the seat surfaces are smoothed by pressing [m]: ``d / (d + 2)``
    of it for ground seats, ``d / (d + 3)`` for turned ones (d in mm; NSK E1102e eq. 9.4, 9.5).
    Clearance (a negative value) is returned unchanged.

    Parameters
    ----------
    interference : float
        Measured interference [m] (negative: clearance).
    diameter : float
        Fit diameter [m].
    ground : bool
        Ground (default) or turned seat surfaces.

    Returns
    -------
    float
        Effective interference [m].
    """
    check_range(interference, "interference", "m", -1e-3, 1e-3, where="effective_interference")
    check_range(diameter, "diameter", "m", 0.0, 6.0, low_inclusive=False,
                where="effective_interference")
    if interference <= 0.0:
        return interference
    mm = diameter * 1e3
    return interference * mm / (mm + (2.0 if ground else 3.0))


def raceway_factor_inner(bore: float, raceway: float, shaft_bore: float = 0.0) -> float:
    """Raceway expansion of an inner ring per unit interference [-] (Lamé, equal materials).

    ``k (1 - k0^2) / (1 - k^2 k0^2)`` with ``k = d / Di`` and ``k0 = d0 / d`` (``d0``: bore of a
    hollow shaft, 0 for a solid one; NSK E1102e Table 15.1 prints the solid case ``k``).

    Parameters
    ----------
    bore, raceway : float
        Ring bore d and raceway diameter Di [m], ``d < Di``.
    shaft_bore : float
        Bore of the hollow shaft d0 [m], ``0 <= d0 < d``.

    Returns
    -------
    float
        Raceway diameter change per unit interference [-].
    """
    check_range(bore, "bore", "m", 0.0, 6.0, low_inclusive=False, where="raceway_factor_inner")
    check_range(raceway, "raceway", "m", bore, None, low_inclusive=False,
                where="raceway_factor_inner")
    check_range(shaft_bore, "shaft_bore", "m", 0.0, bore, high_inclusive=False,
                where="raceway_factor_inner")
    k, k0 = bore / raceway, shaft_bore / bore
    return k * (1.0 - k0**2) / (1.0 - k**2 * k0**2)


def raceway_factor_outer(outside: float, raceway: float, housing_outside: float = math.inf
                         ) -> float:
    """Raceway contraction of an outer ring per unit interference [-] (Lamé, equal materials).

    ``h (1 - h0^2) / (1 - h^2 h0^2)`` with ``h = De / D`` and ``h0 = D / D0`` (``D0``: outside
    diameter of the housing, infinite for a rigid one; NSK E1102e Table 15.1).

    Parameters
    ----------
    outside, raceway : float
        Ring outside diameter D and raceway diameter De [m], ``De < D``.
    housing_outside : float
        Housing (or sleeve) outside diameter D0 [m], > D.

    Returns
    -------
    float
        Raceway diameter change per unit interference [-].
    """
    check_range(outside, "outside", "m", 0.0, 6.0, low_inclusive=False,
                where="raceway_factor_outer")
    check_range(raceway, "raceway", "m", 0.0, outside, low_inclusive=False,
                high_inclusive=False, where="raceway_factor_outer")
    if housing_outside != math.inf or not isinstance(housing_outside, float):
        check_range(housing_outside, "housing_outside", "m", outside, None,
                    low_inclusive=False, where="raceway_factor_outer")
    h, h0 = raceway / outside, outside / housing_outside
    return h * (1.0 - h0**2) / (1.0 - h**2 * h0**2)


def initial_clearance(geometry: BearingGeometry, clearance_class: str = "CN") -> tuple[float,
                                                                                       float]:
    """Radial internal clearance before mounting, (min, max) [m], of a deep groove ball bearing
    (:data:`CLEARANCE_CLASSES`, NSK E1102e Table 9.9).

    Parameters
    ----------
    geometry : BearingGeometry
        A deep groove ball bearing.
    clearance_class : str
        "C2", "CN", "C3", "C4" or "C5".

    Returns
    -------
    tuple of float
        Smallest and largest clearance [m].
    """
    check_choice(clearance_class, "clearance_class", tuple(CLEARANCE_CLASSES),
                 "initial_clearance")
    if not isinstance(geometry, BearingGeometry):
        raise ParameterError(f"initial_clearance: geometry must be a BearingGeometry, got "
                             f"{type(geometry).__name__}")
    low, high = _row(CLEARANCE_CLASSES[clearance_class], geometry.bore,
                     f"initial_clearance: class {clearance_class}")
    return low * _UM, high * _UM


@dataclass(frozen=True)
class OperatingClearance:
    """Diametral clearance of a mounted bearing [m] (negative: internal preload).

    Attributes
    ----------
    initial, inner_reduction, outer_reduction : float
        The clearance before mounting, and what the inner-ring and the outer-ring fit take up
        of it; :attr:`operating` is what is left.
    """

    initial: float
    inner_reduction: float
    outer_reduction: float

    @property
    def operating(self) -> float:
        """Mounted diametral clearance [m].

        Returns
        -------
        float
            Operating clearance [m].
        """
        return self.initial - self.inner_reduction - self.outer_reduction


def operating_clearance(geometry: BearingGeometry, shaft_zone: str | None = "k6",
                        housing_zone: str | None = "H7", *, initial: float | None = None,
                        shaft_bore: float = 0.0, housing_outside: float = math.inf,
                        band: str = "mean", ground: bool = True) -> OperatingClearance:
    """Operating diametral clearance of a deep groove ball bearing after mounting.

    Each seat's effective interference (``band``: the mean, or the smallest or largest of the
    probable band) times the Lamé raceway factor is taken from the clearance; a seat with
    clearance takes none.

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing (bore, outside diameter, pitch and ball diameter give the raceways
        ``Di = dm - Dw`` and ``De = dm + Dw``).
    shaft_zone, housing_zone : str or None
        ISO 286 zones of the shaft and housing seats (None: the ring is not pressed).
    initial : float, optional
        Diametral clearance before mounting [m]; default the geometry's own
        ``diametral_clearance`` (the catalogue rows hold the CN mean, :func:`initial_clearance`).
    shaft_bore : float
        Bore of a hollow shaft (or the inside of a sleeve the inner ring sits on) [m].
    housing_outside : float
        Outside diameter of the housing (or of a sleeve the outer ring sits in) [m].
    band : {"mean", "smallest", "largest"}
        Which interference of the probable band.
    ground : bool
        Ground (True) or turned seats.

    Returns
    -------
    OperatingClearance
    """
    check_choice(band, "band", ("mean", "smallest", "largest"), "operating_clearance")
    if not isinstance(geometry, BearingGeometry):
        raise ParameterError(f"operating_clearance: geometry must be a BearingGeometry, got "
                             f"{type(geometry).__name__}")
    if initial is None:
        initial = geometry.diametral_clearance
    check_range(initial, "initial", "m", 0.0, 1e-3, where="operating_clearance")
    inner_raceway = geometry.pitch_diameter - geometry.ball_diameter
    outer_raceway = geometry.pitch_diameter + geometry.ball_diameter

    def taken(zone, seat, diameter, factor):
        if zone is None:
            return 0.0
        f = fit(diameter, zone, seat)
        value = {"mean": f.mean, "smallest": f.probable_smallest,
                 "largest": f.probable_largest}[band]
        return max(effective_interference(value, diameter, ground), 0.0) * factor

    inner = taken(shaft_zone, "shaft", geometry.bore,
                  raceway_factor_inner(geometry.bore, inner_raceway, shaft_bore))
    outer = taken(housing_zone, "housing", geometry.outside_diameter,
                  raceway_factor_outer(geometry.outside_diameter, outer_raceway, housing_outside))
    return OperatingClearance(float(initial), inner, outer)


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
