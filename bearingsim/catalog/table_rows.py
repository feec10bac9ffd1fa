"""Ball-bearing table rows: the catalogue table ``bearings.csv`` and user datasheets share one
row format in catalogue units (mm, degrees, um, kN, r/min), converted to SI here once for
both."""

from __future__ import annotations

from bearingsim.catalog.geometry import BearingGeometry, PreloadClasses
from bearingsim.units import deg, mm, rpm_to_rad_s

__all__ = ["row_to_geometry"]


def _optional(text: str, scale: float) -> float | None:
    return float(text) * scale if text.strip() else None


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
        designation=row["designation"],
        bore=mm(float(row["d_mm"])),
        outside_diameter=mm(float(row["D_mm"])),
        width=mm(float(row["B_mm"])),
        ball_count=int(row["Z"]),
        ball_diameter=mm(float(row["Dw_mm"])),
        pitch_diameter=mm(float(row["dm_mm"])),
        fi=float(row["fi"]),
        fo=float(row["fo"]),
        contact_angle=deg(float(row["alpha_deg"])),
        diametral_clearance=float(row["Pd_um"]) * 1e-6,
        dynamic_load_rating=_optional(row["C_kN"], 1e3),
        static_load_rating=_optional(row["C0_kN"], 1e3),
        reference_speed=_optional(row["ref_speed_rpm"], rpm_to_rad_s(1.0)),
        limiting_speed=_optional(row["lim_speed_rpm"], rpm_to_rad_s(1.0)),
        preload=preload,
        estimated=tuple(f for f in row["estimated"].split(";") if f),
        source=row["source"],
    )
