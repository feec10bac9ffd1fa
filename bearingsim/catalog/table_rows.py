"""Bearing table rows: the catalogue tables ``bearings.csv`` (ball bearings, also the format of
user datasheets) and ``cylindrical_rollers.csv`` hold catalogue units (mm, degrees, um, kN,
r/min) under the same column names where they share a quantity; converted to SI here once."""

from __future__ import annotations

from typing import Any

from bearingsim.catalog.geometry import BearingGeometry, PreloadClasses
from bearingsim.units import deg, mm, rpm_to_rad_s

__all__ = ["optional_value", "row_to_geometry", "shared_columns"]


def optional_value(text: str, scale: float) -> float | None:
    """A number of an optional column in SI units, or None for a blank cell.

    Parameters
    ----------
    text : str
        The cell.
    scale : float
        Its unit in SI (e.g. 1e3 for kN).

    Returns
    -------
    float or None
        ``float(text) * scale``, or None.
    """
    return float(text) * scale if text.strip() else None


def shared_columns(row: dict[str, str]) -> dict[str, Any]:
    """The geometry fields of the columns every bearing table has, in SI units.

    Parameters
    ----------
    row : dict of str to str
        Column name -> text: ``designation``, ``d_mm``, ``D_mm``, ``B_mm``, ``dm_mm``,
        ``Pd_um`` [um], ``C_kN``, ``C0_kN``, ``ref_speed_rpm``, ``lim_speed_rpm`` (the ratings
        and speeds may be blank), ``estimated`` (``;``-separated field names) and ``source``.

    Returns
    -------
    dict
        ``designation``, ``bore``, ``outside_diameter``, ``width``, ``pitch_diameter``,
        ``diametral_clearance``, ``dynamic_load_rating``, ``static_load_rating``,
        ``reference_speed``, ``limiting_speed``, ``estimated``, ``source``.
    """
    return {
        "designation": row["designation"],
        "bore": mm(float(row["d_mm"])),
        "outside_diameter": mm(float(row["D_mm"])),
        "width": mm(float(row["B_mm"])),
        "pitch_diameter": mm(float(row["dm_mm"])),
        "diametral_clearance": float(row["Pd_um"]) * 1e-6,
        "dynamic_load_rating": optional_value(row["C_kN"], 1e3),
        "static_load_rating": optional_value(row["C0_kN"], 1e3),
        "reference_speed": optional_value(row["ref_speed_rpm"], rpm_to_rad_s(1.0)),
        "limiting_speed": optional_value(row["lim_speed_rpm"], rpm_to_rad_s(1.0)),
        "estimated": tuple(f for f in row["estimated"].split(";") if f),
        "source": row["source"],
    }


def row_to_geometry(row: dict[str, str]) -> BearingGeometry:
    """A ball bearing from one table row in catalogue units (the columns of ``bearings.csv``).

    Parameters
    ----------
    row : dict of str to str
        Column name -> text: ``designation``, ``d_mm``, ``D_mm``, ``B_mm``, ``Z``, ``Dw_mm``,
        ``dm_mm``, ``fi``, ``fo``, ``alpha_deg``, ``Pd_um`` [um], ``C_kN``, ``C0_kN``,
        ``ref_speed_rpm``, ``lim_speed_rpm``, ``preload_light_N``, ``preload_medium_N``,
        ``preload_heavy_N`` (the optional ones may be blank), ``estimated`` (``;``-separated
        field names) and ``source``.

    Returns
    -------
    BearingGeometry
        In SI units.

    Raises
    ------
    ParameterError
        For a value the geometry checks refuse (naming the parameter, unit and valid range).
    ValueError
        For a number that does not parse.
    """
    preload = None
    if row["preload_light_N"].strip():
        preload = PreloadClasses(
            float(row["preload_light_N"]),
            float(row["preload_medium_N"]),
            float(row["preload_heavy_N"]),
        )
    return BearingGeometry(
        **shared_columns(row),
        ball_count=int(row["Z"]),
        ball_diameter=mm(float(row["Dw_mm"])),
        fi=float(row["fi"]),
        fo=float(row["fo"]),
        contact_angle=deg(float(row["alpha_deg"])),
        preload=preload,
    )
