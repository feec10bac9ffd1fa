"""The duplex pair's catalogue limits: its static load rating by the ISO 76 rules for pairs (the
bounds of the shaft's load inputs, the check of constant loads) and its limiting speed.

* **Static load rating.** ISO 76 rates a DB, DF or DT pair of identical angular contact ball
  bearings as one bearing: ``C0`` twice one bearing's; DB/DF ``X0 = 1``, ``Y0`` twice the single
  row's; DT the single row's (:func:`bearingsim.physics.life.static_load_factors`, with the
  catalogue pages). A bearing without a catalogued C0 (the 7020 rows: the catalogues' ratings
  belong to other ball sets, ``bearings.csv``) is rated by the ISO 76 C0 of the ball set the
  model uses (``f0 Z Dw^2 cos a``, 4 200 MPa at the most loaded contact): 63.6 kN for 7020C.
* **Where the pair meets the shaft's loads.** The rule assumes that both bearings share the
  radial load equally, as they do for a load between the rows. The loads act at the shaft's
  centre of mass, so the rows (supports at their pressure centres ``z_k - s_k (dm/2) tan a``,
  ``l`` apart) carry ``R_k`` by statics; the pair is then rated on ``Fr = 2 max_k |R_k|``
  (equal shares give the pair's own ``Fr``). A radial force alone reaches C0 of the pair at
  ``C0 / max_k share_k`` (``2 C0`` when centred), a moment alone at ``C0 l``. Rows whose
  pressure centres cross (a DF pair closer than ``dm tan a``) carry a moment by their own tilt
  stiffness, which no catalogue rates: their moments are left unbounded, their forces rated as
  shared equally.
* **Limiting speed.** A pair runs slower than one bearing, the more so the higher its
  preload: SKF General Catalogue 6000 (Russian ed., 2006 data), p. 414, "speeds of paired
  bearings": the table's speeds reduced by about 20 %; NSK Super Precision Bearings (Russian
  ed.), p. 170, Table 5.1: a DB pair 0.80 x the single bearing's at light preload (0.85 extra
  light, 0.65 medium, 0.55 heavy). :data:`PAIR_SPEED_FACTORS` holds the light, medium and
  heavy factors; a preload between the bearing's class preloads is interpolated, one below
  the light class takes the light factor (SKF's 20 % for every pair), one above the heavy the
  heavy factor. NSK's table has rows DB, DBB and DBD, which its bearing-number key reads as
  sets of two, four (quadruplex: DBB, DFF, DBT, DFT, DTT) and three bearings (triplex: DBD,
  DFD, DTD), so its DB row stands for the pair; it is used for DF and DT as for DB.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from bearingsim.assemblies.duplex.preload import ARRANGEMENTS, preload_force
from bearingsim.catalog import BearingGeometry
from bearingsim.catalog.geometry import check_speed_limit
from bearingsim.components.rolling_element import (
    check_static_rating,
    load_input_bounds,
    static_load_bounds,
)
from bearingsim.errors import ParameterError
from bearingsim.physics.life import static_load_rating

__all__ = ["PAIR_SPEED_FACTORS", "check_pair_loads", "check_pair_speed", "pair_load_bounds",
           "pair_limiting_speed", "pair_speed_factor", "rated_geometry"]

PAIR_SPEED_FACTORS = {"light": 0.80, "medium": 0.65, "heavy": 0.55}
"""Limiting speed of a pair over one bearing's [-] by preload class (NSK Super Precision
Bearings p. 170, Table 5.1, row DB, the two-bearing set; the light one also SKF General
Catalogue 6000 p. 414)."""


def rated_geometry(geometry: BearingGeometry) -> BearingGeometry:
    """The bearing with a static load rating: as catalogued, else with the ISO 76 C0 of its ball
    set (listed in ``estimated`` as "C0").

    Parameters
    ----------
    geometry : BearingGeometry
        A bearing of the pair.

    Returns
    -------
    BearingGeometry
        The bearing, rated.
    """
    if geometry.static_load_rating is not None:
        return geometry
    c0 = float(static_load_rating(geometry.ball_diameter, geometry.pitch_diameter,
                                  geometry.ball_count, geometry.contact_angle))
    return dataclasses.replace(geometry, static_load_rating=c0,
                               estimated=(*geometry.estimated, "C0"))


def _supports(options: Any) -> tuple[float, float] | None:
    """Axial positions [m] of the rows' pressure centres from the shaft's centre of mass, or
    None where they cross (row 0's not beyond row 1's)."""
    g = options.geometry
    alpha = g.contact_angle if options.contact_angle is None else options.contact_angle
    h = 0.5 * g.pitch_diameter * math.tan(alpha)
    p0, p1 = (z - s * h for z, s in zip(options.shaft_spec.positions,
                                         ARRANGEMENTS[options.arrangement], strict=True))
    return (p0, p1) if p0 > p1 else None


def pair_load_bounds(options: Any, radial: bool = True) -> dict[str, dict[str, Any]]:
    """The bounds of the shaft's load inputs ``Fx``, ``Fy``, ``Fz`` [N], ``Mx``, ``My``
    [N m] as :class:`~bearingsim.language.Input` keywords: each warns above the load that alone
    brings the pair's ISO 76 static equivalent load to its rating (see the module) and is
    refused beyond 10 times it.

    Parameters
    ----------
    options : DuplexOptions
        The pair.
    radial : bool
        Bound the radial forces and moments too; False when further supports of the shaft
        share them (a spindle's rear bearing: statically indeterminate), so only ``Fz``.

    Returns
    -------
    dict
        Load name -> ``low``, ``high``, ``warn_above`` and ``limit``.
    """
    g = rated_geometry(options.geometry)
    bounds = load_input_bounds(g, arrangement=options.arrangement)
    if not radial:
        return {"Fz": bounds["Fz"]}
    supports = _supports(options)
    if supports is None:
        return bounds
    p0, p1 = supports
    c0, lever = g.static_load_rating, p0 - p1
    force = c0 * lever / max(abs(p0), abs(p1))
    return {**bounds, "Fx": static_load_bounds(force), "Fy": static_load_bounds(force),
            "Mx": static_load_bounds(c0 * lever), "My": static_load_bounds(c0 * lever)}


def check_pair_loads(options: Any, loads: dict[str, float], where: str) -> None:
    """Warn when constant loads at the shaft's centre of mass bring the pair's ISO 76 static
    equivalent load above its static load rating, refuse them beyond 10 times it
    (:func:`~bearingsim.components.rolling_element.check_static_rating` of the pair, on
    ``Fr = 2 max_k |R_k|``, see the module).

    Parameters
    ----------
    options : DuplexOptions
        The pair.
    loads : dict
        ``Fx``, ``Fy``, ``Fz`` [N], ``Mx``, ``My`` [N m] (missing ones 0).
    where : str
        The model, for messages.

    Raises
    ------
    ParameterError
        Beyond 10 x the pair's C0.

    Warns
    -----
    PlasticDeformationWarning
        Above the pair's C0.
    """
    fx, fy, fz, mx, my = (float(loads.get(k, 0.0)) for k in ("Fx", "Fy", "Fz", "Mx", "My"))
    supports = _supports(options)
    if supports is None:
        radial = math.hypot(fx, fy)
    else:
        p0, p1 = supports
        lever = p0 - p1
        rows = (((p1 * fx - my) / lever, (mx + p1 * fy) / lever),
                ((my - p0 * fx) / lever, (-mx - p0 * fy) / lever))
        radial = 2.0 * max(math.hypot(*r) for r in rows)
    check_static_rating(rated_geometry(options.geometry), (radial, 0.0, fz), where,
                        options.arrangement)


def pair_speed_factor(geometry: BearingGeometry, preload: float | None = None) -> float:
    """The pair's limiting speed over one bearing's [-] at an axial preload
    (:data:`PAIR_SPEED_FACTORS`, interpolated between the bearing's class preloads).

    Parameters
    ----------
    geometry : BearingGeometry
        A bearing of the pair.
    preload : float, optional
        Axial preload [N]; None: the light class.

    Returns
    -------
    float
        The factor, between the heavy and the light class's.
    """
    light = PAIR_SPEED_FACTORS["light"]
    if preload is None:
        return light
    try:
        forces = [preload_force(geometry, name) for name in PAIR_SPEED_FACTORS]
    except ParameterError:  # no preload classes (nor C to derive them): the light factor
        return light
    return float(np.interp(preload, forces, list(PAIR_SPEED_FACTORS.values())))


def pair_limiting_speed(geometry: BearingGeometry, preload: float | None = None
                        ) -> float | None:
    """Limiting speed of a pair of the bearing [rad/s]: :func:`pair_speed_factor` times the
    catalogue's (None without one).

    Parameters
    ----------
    geometry : BearingGeometry
        A bearing of the pair.
    preload : float, optional
        Axial preload [N]; None: the light class.

    Returns
    -------
    float or None
        The pair's limiting speed [rad/s].
    """
    limit = geometry.limiting_speed
    return None if limit is None else pair_speed_factor(geometry, preload) * limit


def check_pair_speed(geometry: BearingGeometry, speed: float, where: str,
                     preload: float | None = None) -> None:
    """Warn above the pair's limiting speed at its preload, refuse beyond twice it
    (:func:`~bearingsim.catalog.geometry.check_speed_limit`).

    Parameters
    ----------
    geometry : BearingGeometry
        A bearing of the pair.
    speed : float
        Shaft speed [rad/s], either sign.
    where : str
        The model, for messages.
    preload : float, optional
        Axial preload [N]; None: the light class.

    Raises
    ------
    ParameterError
        Beyond twice the pair's limiting speed.

    Warns
    -----
    SpeedLimitWarning
        Above it.
    """
    check_speed_limit(speed, pair_limiting_speed(geometry, preload), where,
                      f"the limiting speed of a pair of {geometry.designation} at "
                      + ("light preload" if preload is None else f"{preload:g} N preload")
                      + f" ({pair_speed_factor(geometry, preload):.3g} x the single "
                        "bearing's)")
