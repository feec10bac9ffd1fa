"""Catalogue of ball bearing geometries.

The table ``bearings.csv`` holds catalogue values in mm, degrees, um, kN and r/min; they are
converted to SI once, here. Each row names its ``source``. Internal geometry that manufacturers
do not publish is estimated and listed in the ``estimated`` column, by these rules:

* ``fi``, ``fo``: 0.52 / 0.53 for deep-groove bearings (typical values, Harris & Kotzalas,
  *Rolling Bearing Analysis*, 5th ed.); 0.525 / 0.515 for angular contact bearings (the values
  docs/studies.md, section B gives for the NSK 7020 series).
* ``Pd`` (deep-groove): the mean of the ISO 5753-1 Group N (CN) radial clearance range for the
  bore.
* ``dm``: (d + D) / 2.
* ``Z``, ``Dw`` (deep-groove): a standard ball size (ISO 3290) of 0.55 to 0.62 times the ring
  section (D - d) / 2, and the ball count for which the ISO 281 rating reproduces the catalogue C.

The angular contact rows carry published ball sets (docs/studies.md, section B for 7020, GMN's
precision catalogue for 7014), so only their groove curvature factors are estimated.

Catalogue ratings and speeds were transcribed from the named catalogues; check them against the
current catalogue before relying on them.
"""

from __future__ import annotations

import csv
from functools import lru_cache
from importlib import resources

from bearingsim.catalog.datasheet import read_datasheet
from bearingsim.catalog.geometry import BearingGeometry, PreloadClasses
from bearingsim.catalog.table_rows import row_to_geometry
from bearingsim.errors import CatalogError

__all__ = ["BearingGeometry", "PreloadClasses", "get_bearing", "list_bearings", "load_datasheet",
           "register_bearing", "resolve_bearing", "unregister_bearing"]

_USER: dict[str, BearingGeometry] = {}
"""Bearings registered by the user (:func:`register_bearing`, :func:`load_datasheet`)."""


@lru_cache(maxsize=1)
def _catalogue() -> dict[str, BearingGeometry]:
    text = resources.files(__name__).joinpath("bearings.csv").read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    return {row["designation"]: row_to_geometry(row) for row in csv.DictReader(lines)}


def list_bearings() -> list[str]:
    """Designations of all catalogued bearings, in table order, then the registered ones."""
    return list(_catalogue()) + [d for d in _USER if d not in _catalogue()]


def register_bearing(geometry: BearingGeometry, *, replace: bool = False) -> BearingGeometry:
    """Make a bearing known by its designation to every assembly, scene and ``bearingsim
    list``; returns it.

    Raises
    ------
    CatalogError
        For a designation already known (built in, or registered without ``replace``).
    """
    if not isinstance(geometry, BearingGeometry):
        raise CatalogError(f"register_bearing: expected a BearingGeometry, got "
                           f"{type(geometry).__name__}")
    key = geometry.designation.strip().upper()
    if key in _catalogue():
        raise CatalogError(f"register_bearing: {key} is a catalogue bearing; give yours "
                           f"another designation")
    if key in _USER and not replace:
        raise CatalogError(f"register_bearing: {key} is already registered; give replace=True")
    _USER[key] = geometry
    return geometry


def unregister_bearing(designation: str) -> None:
    """Forget a registered bearing (CatalogError for one that is not registered)."""
    key = str(designation).strip().upper()
    if key not in _USER:
        raise CatalogError(f"unregister_bearing: {designation!r} is not registered")
    del _USER[key]


def load_datasheet(path, *, replace: bool = False) -> list[str]:
    """Read a datasheet file (:func:`~bearingsim.catalog.datasheet.read_datasheet`, CSV or TOML
    in catalogue units) and register its bearings; returns their designations."""
    bearings = read_datasheet(path)
    for g in bearings:
        register_bearing(g, replace=replace)
    return [g.designation.strip().upper() for g in bearings]


def get_bearing(designation: str) -> BearingGeometry:
    """Geometry of a catalogued bearing, in SI units.

    Parameters
    ----------
    designation : str
        Bearing designation, e.g. "6204" or "7020C" (case-insensitive).

    Returns
    -------
    BearingGeometry

    Raises
    ------
    CatalogError
        If the designation is unknown; the message lists the known designations.
    """
    table = {**_USER, **_catalogue()}
    key = str(designation).strip().upper()
    if key not in table:
        raise CatalogError(
            f"unknown bearing designation {designation!r}; known designations: "
            + ", ".join(table)
        )
    return table[key]


def resolve_bearing(bearing: str | BearingGeometry) -> BearingGeometry:
    """A catalogue designation or a user geometry, as a :class:`BearingGeometry`.

    Raises
    ------
    CatalogError
        For an unknown designation.
    """
    return bearing if isinstance(bearing, BearingGeometry) else get_bearing(bearing)
