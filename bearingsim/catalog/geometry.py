"""Internal geometry of a single-row ball bearing, in SI units.

Relations from Harris & Kotzalas, *Rolling Bearing Analysis*, 5th ed., *Essential Concepts of
Bearing Technology*, chapter "Rolling bearing macrogeometry" (groove curvature, clearance, free
contact angle, groove curvature centre loci).
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import KW_ONLY, dataclass
from typing import Any

from bearingsim.errors import ParameterError, SpeedLimitWarning
from bearingsim.physical_checks import MAX_BALL_DIAMETER, check_diameter
from bearingsim.validation import check_range

__all__ = ["BearingGeometry", "CatalogueBearing", "PreloadClasses", "SPEED_LIMIT_MULTIPLE",
           "check_catalogue_values", "check_elements_fit", "check_speed_limit",
           "speed_input_bounds"]

SPEED_LIMIT_MULTIPLE = 2.0
"""Multiple of a limiting speed above which a speed is refused (between 1x and this multiple a
run warns): catalogues allow running above the limiting speed only with special cages,
lubrication and precision, and not by a factor of two."""


def check_speed_limit(speed: float, limit: float | None, where: str, what: str) -> None:
    """Warn above a limiting speed, refuse above :data:`SPEED_LIMIT_MULTIPLE` times it.

    Parameters
    ----------
    speed : float
        Ring (or shaft) speed [rad/s], either sign.
    limit : float or None
        The limiting speed [rad/s]; None checks nothing.
    where : str
        The model, for messages.
    what : str
        What the limit is, e.g. ``"the limiting speed of 61905"``.

    Raises
    ------
    ParameterError
        Above ``SPEED_LIMIT_MULTIPLE * limit``.

    Warns
    -----
    SpeedLimitWarning
        Above ``limit``.
    """
    if limit is None:
        return
    s = abs(float(speed))
    shown = f"{s:g} rad/s ({s * 30 / math.pi:.0f} r/min)"
    if s > SPEED_LIMIT_MULTIPLE * limit:
        raise ParameterError(
            f"{where}: speed {shown} is more than {SPEED_LIMIT_MULTIPLE:g} x {what}, "
            f"{limit * 30 / math.pi:.0f} r/min; valid range [0, "
            f"{SPEED_LIMIT_MULTIPLE * limit * 30 / math.pi:.0f}] r/min (a bare number is rad/s: "
            f"write e.g. '10000 rpm' for r/min, docs/units.md)")
    if s > limit:
        warnings.warn(f"{where}: {shown} exceeds {what}, {limit * 30 / math.pi:.0f} r/min",
                      SpeedLimitWarning, stacklevel=4)


def check_catalogue_values(geometry: Any, names: tuple[str, ...], where: str) -> None:
    """Refuse a catalogue value of ``geometry`` that is given (not None) but not positive.

    Parameters
    ----------
    geometry : object
        A bearing geometry (its attributes ``names``).
    names : tuple of str
        Attribute names: loads and ratings [N], and speeds (names ending in ``speed``) [rad/s].
    where : str
        The geometry, for messages.

    Raises
    ------
    ParameterError
        For a value that is not finite and positive.
    """
    for name in names:
        value = getattr(geometry, name)
        if value is not None:
            check_range(value, name, "rad/s" if name.endswith("speed") else "N", 0.0,
                        low_inclusive=False, where=where)


def check_elements_fit(where: str, elements: str, count: int, bore: float,
                       outside_diameter: float, element_diameter: float,
                       pitch_diameter: float) -> None:
    """Refuse rolling elements that do not fit the ring section or the pitch circle.

    Parameters
    ----------
    where : str
        The geometry, for messages.
    elements : str
        What the elements are called, plural (``"balls"``, ``"rollers"``).
    count : int
        Number of elements Z [-].
    bore, outside_diameter : float
        d, D [m].
    element_diameter : float
        Dw [m].
    pitch_diameter : float
        dm [m].

    Raises
    ------
    ParameterError
        Unless ``bore < dm - Dw``, ``dm + Dw < outside_diameter`` and ``Dw < dm sin(pi/Z)``.
    """
    d, big_d, dw, dm = bore, outside_diameter, element_diameter, pitch_diameter
    if not (d < dm - dw and dm + dw < big_d):
        raise ParameterError(
            f"{where}: the {elements} do not fit the ring section: need bore < dm - Dw and "
            f"dm + Dw < outside_diameter, got bore = {d:g}, dm = {dm:g}, Dw = {dw:g}, "
            f"outside_diameter = {big_d:g} [m]")
    if dw >= dm * math.sin(math.pi / count):
        raise ParameterError(
            f"{where}: {count} {elements} of Dw = {dw:g} m do not fit on the pitch "
            f"circle dm = {dm:g} m (need Dw < dm sin(pi/Z) = "
            f"{dm * math.sin(math.pi / count):g} m)")


def speed_input_bounds(limit: float | None) -> dict[str, Any]:
    """``low``, ``high`` and ``warn_above`` [rad/s] and ``limit`` (``"speed"``) of a speed input
    (:class:`~bearingsim.language.Input`) under a limiting speed: the run warns above ``limit``
    and refuses above :data:`SPEED_LIMIT_MULTIPLE` times it; nothing without a limit.

    Parameters
    ----------
    limit : float or None
        Limiting speed [rad/s].

    Returns
    -------
    dict
    """
    if limit is None:
        return {}
    return {"low": -SPEED_LIMIT_MULTIPLE * limit, "high": SPEED_LIMIT_MULTIPLE * limit,
            "warn_above": limit, "limit": "speed"}

_MAX_CONTACT_ANGLE = math.radians(45.0)
_SPECIFIC_RATING = (1.0, 100.0)
"""Valid range of a ball bearing's load rating per ball area, C / (Z Dw^2) [N/mm^2]: about 25
for small deep-groove bearings, 3 for a slewing ring of 100 balls of 100 mm (ISO 281's
fc Dw^1.4 / Z^(1/3)); a rating in kN is 1000 times below."""
_RATING_RATIO = (0.2, 5.0)
"""Valid range of C0 / C of a ball bearing [-] (deep groove about 0.5, angular contact 0.6 to
1.3, large slewing rings up to about 4)."""


@dataclass(frozen=True)
class PreloadClasses:
    """Axial preload of the light, medium and heavy classes of a duplex pair.

    Attributes
    ----------
    light, medium, heavy : float
        Axial preload [N].
    """

    light: float
    medium: float
    heavy: float

    def __post_init__(self) -> None:
        for name in ("light", "medium", "heavy"):
            check_range(getattr(self, name), name, "N", 0.0, where="PreloadClasses")
        if not self.light <= self.medium <= self.heavy:
            raise ParameterError(
                f"PreloadClasses: preloads must satisfy light <= medium <= heavy, got "
                f"{self.light:g}, {self.medium:g}, {self.heavy:g} [N]"
            )

    def __getitem__(self, level: str) -> float:
        """Preload of the class named ``level`` ("light", "medium" or "heavy") [N]."""
        if level not in ("light", "medium", "heavy"):
            raise ParameterError(
                f"preload class must be 'light', 'medium' or 'heavy', got {level!r}"
            )
        return getattr(self, level)


@dataclass(frozen=True)
class CatalogueBearing:
    """What every catalogued bearing has, whatever its rolling elements: the fields of the
    columns all bearing tables share (:func:`~bearingsim.catalog.table_rows.shared_columns`),
    SI units, and their checks. A subclass declares its elements' fields after ``KW_ONLY``.

    Attributes
    ----------
    designation : str
        Bearing designation, e.g. "6204".
    bore, outside_diameter, width : float
        d, D, B [m].
    pitch_diameter : float
        dm [m].
    diametral_clearance : float
        Radial internal clearance Pd [m] (the subclass states its valid range).
    dynamic_load_rating, static_load_rating : float or None
        Catalogue basic dynamic and static radial load ratings C, C0 [N].
    reference_speed, limiting_speed : float or None
        Catalogue reference (thermal) and limiting speeds [rad/s].
    estimated : tuple of str
        Names of the fields that were estimated because no catalogue publishes them.
    source : str
        Where the values come from.
    """

    designation: str
    bore: float
    outside_diameter: float
    width: float
    pitch_diameter: float
    diametral_clearance: float = 0.0
    dynamic_load_rating: float | None = None
    static_load_rating: float | None = None
    reference_speed: float | None = None
    limiting_speed: float | None = None
    estimated: tuple[str, ...] = ()
    source: str = "user"

    def _check_section(self, where: str) -> None:
        """Refuse a d, D, B or dm out of range."""
        for name in ("bore", "outside_diameter", "width", "pitch_diameter"):
            check_diameter(getattr(self, name), name, where)

    def _check_catalogue_values(self, where: str, loads: tuple[str, ...] = ()) -> None:
        """Refuse a given rating, further catalogue load ``loads`` [N] or speed that is not
        positive (:func:`check_catalogue_values`)."""
        check_catalogue_values(self, ("dynamic_load_rating", "static_load_rating", *loads,
                                      "reference_speed", "limiting_speed"), where)

    def _check_specific_ratings(self, where: str, area: float, valid: tuple[float, float],
                                element: str, elements: str, formula: str) -> None:
        """Refuse a C or C0 [N] whose rating per element area ``area`` [mm^2] (``formula``) is
        outside ``valid`` [N/mm^2]: in kN, mistyped or of another set of ``elements``."""
        low, high = valid
        for name in ("dynamic_load_rating", "static_load_rating"):
            value = getattr(self, name)
            if value is not None and not low <= value / area <= high:
                hint = ("did you pass kN?" if value / area < low else
                        f"mistyped, or not this {element} set's rating?")
                raise ParameterError(
                    f"{where}: {name} = {value:g} N is not a rating of {elements}: {name} / "
                    f"({formula}) = {value / area:.3g} N/mm^2, valid range [{low:g}, "
                    f"{high:g}] N/mm^2 ({hint})")

    def check_speed(self, speed: float, where: str) -> None:
        """Warn when a constant ring speed [rad/s] exceeds the catalogue limiting speed (the
        bearing's kinematic and thermal safe operation: cage, lubricant), refuse it above
        :data:`SPEED_LIMIT_MULTIPLE` times that (:func:`check_speed_limit`); nothing is checked
        without a limiting speed.

        Parameters
        ----------
        speed : float
            Constant ring speed [rad/s] (its magnitude is checked).
        where : str
            What is checked, for the messages (component or assembly and parameter).

        Raises
        ------
        ParameterError

        Warns
        -----
        SpeedLimitWarning
        """
        check_speed_limit(speed, self.limiting_speed, where,
                          f"the limiting speed of {self.designation}")


@dataclass(frozen=True)
class BearingGeometry(CatalogueBearing):
    """Geometry of a single-row ball bearing (deep-groove or angular contact), SI units.

    Attributes
    ----------
    designation, bore, outside_diameter, width, pitch_diameter
        As :class:`CatalogueBearing`; also its ratings, speeds, ``estimated`` and ``source``.
    ball_count : int
        Number of balls Z [-], at least 3 (keyword only, as the fields below).
    ball_diameter : float
        Ball diameter Dw [m].
    fi, fo : float
        Inner and outer groove curvature factors (groove radius / Dw) [-], each in (0.5, 1).
    contact_angle : float
        Nominal contact angle [rad], 0 for a deep-groove bearing, at most 45 deg.
    diametral_clearance : float
        Diametral clearance Pd [m]: the total radial play of one ring against the other (ISO
        5753's radial internal clearance), twice the clearance per side. Negative: an internal
        preload (the operating clearance of a bearing mounted with more interference than
        clearance, :func:`~bearingsim.physics.fits.operating_clearance`), down to
        ``-0.2 A``; the quasi-static ball rows and the ISO/TS 16281 form model it, the
        ball-level (dynamic) models refuse it by name.
    preload : PreloadClasses or None
        Preload classes of a duplex pair, where published.

    Raises
    ------
    ParameterError
        If a value is out of range or the balls do not fit the ring section.
    """

    _: KW_ONLY
    ball_count: int
    ball_diameter: float
    fi: float
    fo: float
    contact_angle: float = 0.0
    preload: PreloadClasses | None = None

    def __post_init__(self) -> None:
        where = f"BearingGeometry({self.designation})"
        if isinstance(self.ball_count, bool) or not isinstance(self.ball_count, int):
            raise ParameterError(
                f"{where}: ball_count must be an integer >= 3 [-], got {self.ball_count!r}"
            )
        check_range(self.ball_count, "ball_count", "-", 3, where=where)
        self._check_section(where)
        check_diameter(self.ball_diameter, "ball_diameter", where, MAX_BALL_DIAMETER)
        check_range(self.fi, "fi", "-", 0.5, 1.0, low_inclusive=False, where=where)
        check_range(self.fo, "fo", "-", 0.5, 1.0, low_inclusive=False, where=where)
        check_range(self.contact_angle, "contact_angle", "rad", 0.0, _MAX_CONTACT_ANGLE,
                    where=where)
        check_range(self.diametral_clearance, "diametral_clearance", "m",
                    -0.2 * (self.fi + self.fo - 1.0) * self.ball_diameter, where=where)
        self._check_catalogue_values(where)
        self._check_rating_units(where)
        check_elements_fit(where, "balls", self.ball_count, self.bore, self.outside_diameter,
                           self.ball_diameter, self.pitch_diameter)
        cos_free = 1.0 - self.diametral_clearance / (2.0 * self.groove_centre_distance)
        if cos_free < math.cos(_MAX_CONTACT_ANGLE):
            raise ParameterError(
                f"{where}: diametral_clearance = {self.diametral_clearance:g} m gives a free "
                f"contact angle above 45 deg; valid range [0, "
                f"{2.0 * self.groove_centre_distance * (1 - math.cos(_MAX_CONTACT_ANGLE)):g}] [m]"
            )

    def _check_rating_units(self, where: str) -> None:
        """Catch ratings in kN and swapped or mistyped ratings: a ball bearing's C and C0 per
        unit ball area, ``C / (Z Dw^2)`` and ``C0 / (Z Dw^2)`` with Dw in mm, lie within
        :data:`_SPECIFIC_RATING` (6304: 25.1 and 12.5 N/mm^2), and C0 / C within
        :data:`_RATING_RATIO`."""
        self._check_specific_ratings(
            where, self.ball_count * (self.ball_diameter * 1e3) ** 2, _SPECIFIC_RATING, "ball",
            f"{self.ball_count} balls of {self.ball_diameter * 1e3:g} mm", "Z Dw^2")
        c, c0 = self.dynamic_load_rating, self.static_load_rating
        if c is not None and c0 is not None and not _RATING_RATIO[0] <= c0 / c \
                <= _RATING_RATIO[1]:
            raise ParameterError(
                f"{where}: static_load_rating / dynamic_load_rating = {c0 / c:.3g}, valid range "
                f"[{_RATING_RATIO[0]:g}, {_RATING_RATIO[1]:g}] for ball bearings (swapped or "
                f"mistyped ratings?)")

    @property
    def series(self) -> str | None:
        """The catalogue series of the designation (``"619"`` for 61905, ``"63"`` for 6304,
        ``"160"`` for 16004, ``"70"`` for 7014C), or None when the designation does not follow
        the ISO numbering (a user geometry).

        Returns
        -------
        str or None
            The series, or None.
        """
        digits = re.match(r"\d+", self.designation.strip())
        if digits is None or len(digits.group()) < 4:
            return None
        number = digits.group()
        if len(number) == 5 and number[:3] in ("618", "619", "160"):
            return number[:3]
        return number[:2] if len(number) == 4 else None

    @property
    def bearing_type(self) -> str:
        """"deep_groove" for a zero nominal contact angle, else "angular_contact".

        Returns
        -------
        str
            ``"deep_groove"`` or ``"angular_contact"``.
        """
        return "deep_groove" if self.contact_angle == 0.0 else "angular_contact"

    @property
    def inner_groove_radius(self) -> float:
        """Inner raceway groove radius ri = fi Dw [m].

        Returns
        -------
        float
            Inner groove radius [m].
        """
        return self.fi * self.ball_diameter

    @property
    def outer_groove_radius(self) -> float:
        """Outer raceway groove radius ro = fo Dw [m].

        Returns
        -------
        float
            Outer groove radius [m].
        """
        return self.fo * self.ball_diameter

    @property
    def total_curvature(self) -> float:
        """Total curvature B = fi + fo - 1 [-] (Harris & Kotzalas).

        Returns
        -------
        float
            Total curvature [-].
        """
        return self.fi + self.fo - 1.0

    @property
    def groove_centre_distance(self) -> float:
        """Distance between the groove curvature centres A = B Dw [m] (Harris & Kotzalas).

        Returns
        -------
        float
            Groove centre distance [m].
        """
        return self.total_curvature * self.ball_diameter

    @property
    def free_contact_angle(self) -> float:
        """Free (unloaded) contact angle [rad].

        For a deep-groove bearing, from the radial clearance: cos a0 = 1 - Pd / (2 A)
        (Harris & Kotzalas), 0 without clearance or with a preload (Pd <= 0). For an angular
        contact bearing, the nominal contact angle.

        Returns
        -------
        float
            Free contact angle [rad], in [0, pi/2).
        """
        if self.bearing_type == "angular_contact":
            return self.contact_angle
        if self.diametral_clearance <= 0.0:  # no clearance or an internal preload
            return 0.0
        return math.acos(1.0 - self.diametral_clearance / (2.0 * self.groove_centre_distance))

    @property
    def inner_groove_centre_radius(self) -> float:
        """Radius of the locus of the inner groove curvature centre [m].

        ``dm/2 + (fi - 0.5) Dw cos a0`` with the ball centre on the pitch circle and the free
        contact angle a0 (Harris & Kotzalas): the inner groove centre lies beyond the ball centre,
        outside the pitch circle.

        Returns
        -------
        float
            Radius [m].
        """
        return 0.5 * self.pitch_diameter + (self.fi - 0.5) * self.ball_diameter * math.cos(
            self.free_contact_angle
        )

    @property
    def outer_groove_centre_radius(self) -> float:
        """Radius of the locus of the outer groove curvature centre [m].

        ``dm/2 - (fo - 0.5) Dw cos a0`` (Harris & Kotzalas): inside the pitch circle.

        Returns
        -------
        float
            Radius [m].
        """
        return 0.5 * self.pitch_diameter - (self.fo - 0.5) * self.ball_diameter * math.cos(
            self.free_contact_angle
        )

    @property
    def gamma(self) -> float:
        """Dimensionless ball size gamma = Dw cos(a) / dm [-] at the nominal contact angle.

        Returns
        -------
        float
            gamma [-].
        """
        return self.ball_diameter * math.cos(self.contact_angle) / self.pitch_diameter
