"""Catalogue of cylindrical roller bearings (NU type) and their geometry, in SI units.

The table ``cylindrical_rollers.csv`` holds catalogue values in mm, kN, r/min and um (its header
names the source, pages and the rules for the internal geometry no catalogue publishes); they are
converted to SI once, here. :class:`RollerBearingGeometry` is the roller counterpart of the ball
:class:`~bearingsim.catalog.geometry.BearingGeometry`: it answers the rolling-element seam's
geometry questions (:class:`~bearingsim.components.rolling_element.ElementGeometry`).
"""

from __future__ import annotations

import csv
import re
from dataclasses import KW_ONLY, dataclass
from functools import lru_cache
from importlib import resources

from bearingsim.catalog.geometry import CatalogueBearing, check_elements_fit
from bearingsim.catalog.table_rows import optional_value, shared_columns
from bearingsim.errors import CatalogError, ParameterError
from bearingsim.physical_checks import check_diameter
from bearingsim.registry import Registry
from bearingsim.units import mm
from bearingsim.validation import check_count, check_range

__all__ = ["ROLLER_BEARINGS", "RollerBearingGeometry", "find_roller_bearing",
           "get_roller_bearing", "list_roller_bearings", "register_roller_bearing",
           "resolve_roller_bearing", "roller_row_to_geometry", "unregister_roller_bearing"]

_SPECIFIC_RATING = (10.0, 200.0)
"""Valid range of a roller bearing's C and C0 per projected roller area, C / (Z Lwe Dw) [N/mm^2]
(NU 206 ECP: 42.8 and 35.5; a rating given in kN is 1000 times below)."""


@dataclass(frozen=True)
class RollerBearingGeometry(CatalogueBearing):
    """Geometry of a single-row cylindrical roller bearing (NU type), SI units.

    Attributes
    ----------
    designation, bore, outside_diameter, width, pitch_diameter
        As :class:`~bearingsim.catalog.geometry.CatalogueBearing` ("NU206", d, D, B, dm [m]);
        also its ratings C, C0 [N], speeds [rad/s], ``estimated`` (the fields derived by the
        catalogue's stated rules) and ``source``.
    roller_count : int
        Rollers Z [-], >= 3 (keyword only, as the fields below).
    roller_diameter : float
        Dw [m].
    roller_length : float
        Effective roller length Lwe [m] (the contact length of a straight roller).
    diametral_clearance : float
        Radial internal clearance Pd [m] (total play of one ring against the other), >= 0.
    fatigue_load_limit : float or None
        Pu [N].
    explorer : bool
        An SKF Explorer bearing (its C lies above the ISO 281 value of its roller set).

    Raises
    ------
    ParameterError
        For a value out of range, rollers that do not fit the ring section or the pitch circle,
        or ratings that are not of this roller set (e.g. given in kN).
    """

    _: KW_ONLY
    roller_count: int
    roller_diameter: float
    roller_length: float
    fatigue_load_limit: float | None = None
    explorer: bool = False

    bearing_type = "cylindrical_roller"
    """Key of the friction and life tables."""
    rolling_element = "roller"
    """The rolling element of the seam (:mod:`bearingsim.components.rolling_element`)."""
    contact = "line"
    """Contact law of the element."""
    contact_angle = 0.0
    """Nominal contact angle [rad] (radial bearing)."""

    def __post_init__(self) -> None:
        where = f"RollerBearingGeometry({self.designation})"
        check_count(self.roller_count, "roller_count", 3, where=where)
        self._check_section(where)
        for name in ("roller_diameter", "roller_length"):
            check_diameter(getattr(self, name), name, where)
        check_range(self.diametral_clearance, "diametral_clearance", "m", 0.0,
                    0.1 * self.roller_diameter, where=where)
        self._check_catalogue_values(where, ("fatigue_load_limit",))
        check_elements_fit(where, "rollers", self.roller_count, self.bore, self.outside_diameter,
                           self.roller_diameter, self.pitch_diameter)
        dw = self.roller_diameter
        if self.roller_length >= self.width:
            raise ParameterError(
                f"{where}: roller_length = {self.roller_length:g} m must be below the width "
                f"{self.width:g} m")
        self._check_specific_ratings(
            where, self.roller_count * self.roller_length * 1e3 * dw * 1e3, _SPECIFIC_RATING,
            "roller",
            f"{self.roller_count} rollers of {dw * 1e3:g} x {self.roller_length * 1e3:g} mm",
            "Z Lwe Dw")

    @property
    def gamma(self) -> float:
        """``Dw / dm`` [-].

        Returns
        -------
        float
            gamma [-].
        """
        return self.roller_diameter / self.pitch_diameter

    @property
    def element_count(self) -> int:
        """Number of rolling elements (the seam's name for Z).

        Returns
        -------
        int
            Z.
        """
        return self.roller_count

    @property
    def element_diameter(self) -> float:
        """Rolling element diameter [m] (the seam's name for Dw).

        Returns
        -------
        float
            Dw [m].
        """
        return self.roller_diameter

    @property
    def series(self) -> str | None:
        """Dimension series of the designation ("2" for NU206, "3" for NU306, "22" for
        NU2206), or None for a designation that does not follow it.

        Returns
        -------
        str or None
            The dimension series, or None.
        """
        digits = re.search(r"\d+", self.designation)
        if digits is None or len(digits.group()) < 3:
            return None
        number = digits.group()
        return number[:-2]


def roller_row_to_geometry(row: dict[str, str]) -> RollerBearingGeometry:
    """A cylindrical roller bearing from one table row in catalogue units (the columns of
    ``cylindrical_rollers.csv``, also those of a roller in a user's datasheet).

    Parameters
    ----------
    row : dict of str to str
        Column name -> text: those of
        :func:`~bearingsim.catalog.table_rows.shared_columns` and ``Z``, ``Dw_mm``,
        ``Lwe_mm``, ``Pu_kN`` (may be blank), ``explorer`` (``1`` for an SKF Explorer
        bearing).

    Returns
    -------
    RollerBearingGeometry
        The bearing in SI units.

    Raises
    ------
    ParameterError
        For a value its geometry checks refuse.
    """
    return RollerBearingGeometry(
        **shared_columns(row),
        roller_count=int(row["Z"]),
        roller_diameter=mm(float(row["Dw_mm"])),
        roller_length=mm(float(row["Lwe_mm"])),
        fatigue_load_limit=optional_value(row["Pu_kN"], 1e3),
        explorer=row["explorer"].strip() == "1",
    )


@lru_cache(maxsize=1)
def _catalogue() -> dict[str, RollerBearingGeometry]:
    text = resources.files("bearingsim.catalog").joinpath("cylindrical_rollers.csv").read_text(
        encoding="utf-8")
    lines = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    return {row["designation"]: roller_row_to_geometry(row) for row in csv.DictReader(lines)}


def _key(designation: str) -> str:
    return re.sub(r"\s+", "", str(designation)).upper()


ROLLER_BEARINGS = Registry("cylindrical roller bearing", _catalogue, normalize=_key,
                           builtin_label="catalogue bearing", replace_builtin=False)
"""Designation -> geometry: the catalogue (``cylindrical_rollers.csv``) and the registered
bearings (:func:`register_roller_bearing`, a datasheet's rollers:
:func:`~bearingsim.catalog.load_datasheet`, a scene's ``bearings`` key)."""


def list_roller_bearings() -> list[str]:
    """Designations of the catalogued cylindrical roller bearings, in table order, then the
    registered ones.

    Returns
    -------
    list of str
    """
    return list(ROLLER_BEARINGS)


def register_roller_bearing(geometry: RollerBearingGeometry, *, replace: bool = False
                            ) -> RollerBearingGeometry:
    """Make a cylindrical roller bearing known by its designation to the roller assemblies,
    scenes and ``bearingsim list``; returns it.

    Parameters
    ----------
    geometry : RollerBearingGeometry
        The bearing, known by its ``designation`` (spaces and case ignored).
    replace : bool
        Replace a bearing registered before under the same designation.

    Returns
    -------
    RollerBearingGeometry
        The registered geometry.

    Raises
    ------
    CatalogError
        For a designation already known (a catalogue bearing, or registered without
        ``replace``).
    """
    if not isinstance(geometry, RollerBearingGeometry):
        raise CatalogError(f"register_roller_bearing: expected a RollerBearingGeometry, got "
                           f"{type(geometry).__name__}")
    ROLLER_BEARINGS.register(_key(geometry.designation), geometry, replace=replace)
    return geometry


def unregister_roller_bearing(designation: str) -> None:
    """Forget a registered cylindrical roller bearing.

    Parameters
    ----------
    designation : str
        As registered (spaces and case ignored).

    Raises
    ------
    CatalogError
        For a designation not registered (a catalogue bearing cannot be removed).
    """
    ROLLER_BEARINGS.unregister(designation)


def find_roller_bearing(name: object) -> str | None:
    """The catalogue designation that ``name`` stands for (case and spaces ignored), or None.

    Parameters
    ----------
    name : object
        A designation as written ("NU 206", "nu206"); anything but text stands for none.

    Returns
    -------
    str or None
        The designation as the catalogue spells it ("NU206"), or None.
    """
    return ROLLER_BEARINGS.find(name) if isinstance(name, str) else None


def get_roller_bearing(designation: str) -> RollerBearingGeometry:
    """Geometry of a catalogued cylindrical roller bearing.

    Parameters
    ----------
    designation : str
        E.g. "NU206" or "NU 206" (case- and space-insensitive).

    Returns
    -------
    RollerBearingGeometry

    Raises
    ------
    CatalogError
        For an unknown designation (the message lists the known ones).
    """
    return ROLLER_BEARINGS[designation]


def resolve_roller_bearing(bearing: str | RollerBearingGeometry) -> RollerBearingGeometry:
    """A designation or a geometry, as a :class:`RollerBearingGeometry`.

    Parameters
    ----------
    bearing : str or RollerBearingGeometry

    Returns
    -------
    RollerBearingGeometry

    Raises
    ------
    CatalogError
        For an unknown designation.
    """
    return bearing if isinstance(bearing, RollerBearingGeometry) else get_roller_bearing(bearing)
