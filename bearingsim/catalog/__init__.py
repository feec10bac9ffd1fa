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
from bearingsim.catalog.rollers import (
    ROLLER_BEARINGS,
    RollerBearingGeometry,
    find_roller_bearing,
    register_roller_bearing,
)
from bearingsim.catalog.table_rows import row_to_geometry
from bearingsim.errors import CatalogError
from bearingsim.registry import Registry

__all__ = ["BEARINGS", "ENTRY_POINT_GROUP", "BearingGeometry", "PreloadClasses", "get_bearing",
           "list_bearings", "load_datasheet", "register_bearing", "resolve_bearing",
           "unregister_bearing"]

ENTRY_POINT_GROUP = "bearingsim.bearings"
"""Entry-point group of bearing plug-ins: each entry point loads a :class:`BearingGeometry`,
known by its designation."""


@lru_cache(maxsize=1)
def _catalogue() -> dict[str, BearingGeometry]:
    text = resources.files(__name__).joinpath("bearings.csv").read_text(encoding="utf-8")
    lines = [line for line in text.splitlines() if line.strip() and not line.startswith("#")]
    return {row["designation"]: row_to_geometry(row) for row in csv.DictReader(lines)}


def _designation(name: str) -> str:
    return str(name).strip().upper()


def _plugin_bearing(obj: object, entry_name: str) -> tuple[str, BearingGeometry]:
    """An entry point's geometry under its designation (TypeError: skipped, with why)."""
    if not isinstance(obj, BearingGeometry):
        raise TypeError(f"it loads {type(obj).__name__} {obj!r:.80}, not a BearingGeometry")
    return _designation(obj.designation), obj


BEARINGS = Registry("bearing", _catalogue, group=ENTRY_POINT_GROUP, convert=_plugin_bearing,
                    normalize=_designation, builtin_label="catalogue bearing",
                    replace_builtin=False)
"""Designation -> geometry: the catalogue (``bearings.csv``), the plug-ins of
:data:`ENTRY_POINT_GROUP` and the registered bearings (:func:`register_bearing`,
:func:`load_datasheet`, a scene's ``bearings`` key)."""
BEARINGS.sibling = (ROLLER_BEARINGS, "a cylindrical roller bearing")  # asked of the other
ROLLER_BEARINGS.sibling = (BEARINGS, "a ball bearing")


def list_bearings() -> list[str]:
    """Designations of all catalogued bearings, in table order, then the plug-ins' and the
    registered ones.

    Returns
    -------
    list of str
        The designations.
    """
    return list(BEARINGS)


def register_bearing(geometry: BearingGeometry | RollerBearingGeometry, *, replace: bool = False
                     ) -> BearingGeometry | RollerBearingGeometry:
    """Make a bearing known by its designation to every assembly, scene and ``bearingsim
    list``; returns it.

    Parameters
    ----------
    geometry : BearingGeometry or RollerBearingGeometry
        The bearing, known by its ``designation``.
    replace : bool
        Replace a bearing registered before under the same designation.

    Returns
    -------
    BearingGeometry or RollerBearingGeometry
        The registered geometry.

    Raises
    ------
    CatalogError
        For a designation already known (a catalogue bearing, or registered without
        ``replace``: :class:`~bearingsim.registry.NameTakenError`).
    """
    if isinstance(geometry, RollerBearingGeometry):  # the roller catalogue's registry
        return register_roller_bearing(geometry, replace=replace)
    if not isinstance(geometry, BearingGeometry):
        raise CatalogError(f"register_bearing: expected a BearingGeometry or a "
                           f"RollerBearingGeometry, got {type(geometry).__name__}")
    BEARINGS.register(_designation(geometry.designation), geometry, replace=replace)
    return geometry


def unregister_bearing(designation: str) -> None:
    """Forget a registered bearing (CatalogError for one that is not registered: unknown, or a
    catalogue bearing).

    Parameters
    ----------
    designation : str
        Designation of a registered bearing.
    """
    BEARINGS.unregister(designation)


def load_datasheet(path, *, replace: bool = False) -> list[str]:
    """Read a datasheet file (:func:`~bearingsim.catalog.datasheet.read_datasheet`, CSV or TOML
    in catalogue units) and register its bearings (:func:`register_bearing`: cylindrical roller
    bearings in the roller catalogue's registry); returns their designations.

    Parameters
    ----------
    path : str or os.PathLike
        The datasheet file (``.csv`` or ``.toml``).
    replace : bool
        Replace bearings registered before under the same designations.

    Returns
    -------
    list of str
        Designations of the registered bearings, in file order.
    """
    bearings = read_datasheet(path)
    for g in bearings:
        register_bearing(g, replace=replace)
    return [find_roller_bearing(g.designation) if isinstance(g, RollerBearingGeometry)
            else _designation(g.designation) for g in bearings]


def get_bearing(designation: str) -> BearingGeometry:
    """Geometry of a catalogued (or plug-in, or registered) bearing, in SI units.

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
        If the designation is unknown; the message lists the known designations and the close
        matches.
    """
    return BEARINGS[designation]


def resolve_bearing(bearing: str | BearingGeometry) -> BearingGeometry:
    """A catalogue designation or a user geometry, as a :class:`BearingGeometry`.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Catalogue (or registered) designation, or a geometry (returned as it is).

    Returns
    -------
    BearingGeometry
        The bearing's geometry.

    Raises
    ------
    CatalogError
        For an unknown designation.
    """
    return bearing if isinstance(bearing, BearingGeometry) else get_bearing(bearing)
