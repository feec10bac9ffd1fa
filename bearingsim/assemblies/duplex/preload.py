"""The duplex pair's arrangements and preload: catalogue preload classes, the spacer offset that
gives a preload and the preload an offset gives, the preload stiffness."""

from __future__ import annotations

import math

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.ball_row import axial_approach, row_loads, row_parameters
from bearingsim.errors import ParameterError
from bearingsim.units import to_si
from bearingsim.validation import check_range

ARRANGEMENTS = {"DF": (1, -1), "DB": (-1, 1), "DT": (1, 1)}
"""Axial loading direction ``s`` of (row 0, row 1) for each arrangement."""
PRELOAD_CLASSES = ("light", "medium", "heavy")


PRELOAD_FRACTIONS = {15.0: (0.0085, 0.020, 0.040), 25.0: (0.014, 0.033, 0.065),
                     30.0: (0.015, 0.048, 0.075)}
"""Preload rule for bearings without catalogued classes: free contact angle [deg] -> axial
preload of the light, medium and heavy class as a fraction of the basic dynamic load rating C
[-]; linear in the contact angle between the entries, the end entries outside them.

No published rule was found (catalogues tabulate preload classes per bearing, not as a
fraction of C), so the fractions are the ones the catalogue's own classes imply: the NSK
precision 7020 series of docs/studies.md, section B (7020C 15 deg: 540/1270/2550 N, 7020A5 25 deg:
830/1960/3920 N, 7020A 30 deg: 840/2750/4310 N) divided by the ISO 281 C of their ball set
(63.5, 59.9 and 57.5 kN), rounded to two digits; ``tests/assemblies/test_duplex.py``
recomputes them. For
a 15 deg bearing that is about 1 %, 2 % and 4 % of C."""


def _class_fraction(level: str, contact_angle: float) -> float:
    """Fraction of C of a preload class at a contact angle [rad] (:data:`PRELOAD_FRACTIONS`)."""
    angles = sorted(PRELOAD_FRACTIONS)
    column = PRELOAD_CLASSES.index(level)
    alpha = min(max(math.degrees(contact_angle), angles[0]), angles[-1])
    for lo, hi in zip(angles, angles[1:], strict=False):
        if alpha <= hi:
            w = (alpha - lo) / (hi - lo)
            return (1.0 - w) * PRELOAD_FRACTIONS[lo][column] + w * PRELOAD_FRACTIONS[hi][column]
    return PRELOAD_FRACTIONS[angles[-1]][column]  # pragma: no cover - alpha is clamped


def preload_force(geometry: BearingGeometry, preload: str | float) -> float:
    """Axial preload [N] of a class name ("light", "medium", "heavy") or a number.

    A class is the bearing's catalogued preload of that class; for an angular contact bearing
    without catalogued classes but with a basic dynamic load rating C, it is the fraction
    :data:`PRELOAD_FRACTIONS` of C at the bearing's contact angle (e.g. 7014C, C = 48.5 kN:
    light 412 N, medium 970 N, heavy 1940 N).

    Parameters
    ----------
    geometry : BearingGeometry
        The bearing of the pair.
    preload : str or float
        Preload class ("light", "medium", "heavy") or axial preload [N], > 0, or a number
        with a unit ("500 N", "0.5 kN").

    Returns
    -------
    float
        Axial preload [N].

    Raises
    ------
    ParameterError
        For an unknown class, a class of a bearing with neither catalogued classes nor (angular
        contact with) C, or a preload <= 0.
    """
    preload = to_si(preload, "N", "duplex_pair: preload")  # "500 N"; a class stays a name
    if isinstance(preload, str):
        if preload not in PRELOAD_CLASSES:
            raise ParameterError(f"duplex_pair: preload class must be 'light', 'medium' or "
                                 f"'heavy', or the preload an axial force in N (a number > 0, "
                                 f"or e.g. '500 N'), got {preload!r}")
        if geometry.preload is not None:
            return geometry.preload[preload]
        if geometry.dynamic_load_rating is None or geometry.bearing_type != "angular_contact":
            missing = ("no dynamic load rating C" if geometry.bearing_type == "angular_contact"
                       else "a contact angle of 0 (the rule of C is for angular contact bearings)")
            raise ParameterError(
                f"duplex_pair: bearing {geometry.designation} has no catalogued preload classes "
                f"and {missing}, so preload {preload!r} is undefined; give the preload in N "
                "(a number > 0), or an angular contact bearing with preload classes or C "
                "(e.g. C_kN in its datasheet)")
        return _class_fraction(preload, geometry.contact_angle) * geometry.dynamic_load_rating
    check_range(preload, "preload", "N", 0.0, low_inclusive=False, where="duplex_pair")
    return float(preload)


def _spacer_arrangement(arrangement: str, where: str) -> tuple[float, float]:
    """The row directions of a DF or DB pair (those a spacer width difference preloads)."""
    if arrangement not in ("DF", "DB"):
        raise ParameterError(f"{where}: arrangement must be 'DF' or 'DB', got "
                             f"{arrangement!r} (a DT pair is preloaded by an axial force)")
    return ARRANGEMENTS[arrangement]


def preload_offset(bearing: str | BearingGeometry, preload: float, arrangement: str = "DF",
                   contact_angle: float | None = None) -> float:
    """Spacer width difference that preloads a DF or DB pair of identical rows [m].

    Each row must carry the axial ``preload``: its inner ring moves by the row's axial approach
    ``delta_a`` (:func:`~bearingsim.components.ball_row.axial_approach`, Jones's relation) along
    its loading direction, so the offset is ``s1 delta_a - s0 delta_a``.

    Parameters
    ----------
    bearing : str or BearingGeometry
    preload : float
        Axial preload [N], > 0.
    arrangement : {"DF", "DB"}
    contact_angle : float, optional
        Free contact angle [rad] (default: the bearing's).

    Returns
    -------
    float
        The width difference [m] (negative for DF, positive for DB).
    """
    s0, s1 = _spacer_arrangement(arrangement, "preload_offset")
    g = resolve_bearing(bearing)
    delta = axial_approach(row_parameters(g, contact_angle), g.ball_count, preload)
    return (s1 - s0) * delta


def offset_preload(bearing: str | BearingGeometry, offset: float, arrangement: str = "DF",
                   contact_angle: float | None = None) -> float:
    """Axial preload [N] that a spacer width difference gives a DF or DB pair of identical rows.

    The inverse of :func:`preload_offset`: each row's inner ring moves by ``|offset| / 2``
    along its loading direction and the row carries the axial load of that approach (classic
    row, rigid rings and housing, no speed effects).

    Parameters
    ----------
    bearing : str or BearingGeometry
    offset : float
        Spacer width difference [m]: < 0 for DF, > 0 for DB.
    arrangement : {"DF", "DB"}
    contact_angle : float, optional
        Free contact angle [rad] (default: the bearing's).

    Returns
    -------
    float
        Axial preload of each row [N], > 0.

    Raises
    ------
    ParameterError
        For a DT arrangement or an offset of the wrong sign (axial play).
    """
    s0, s1 = _spacer_arrangement(arrangement, "offset_preload")
    if not offset * (s1 - s0) > 0.0:
        raise ParameterError(
            f"duplex_pair: a spacer width difference of {offset:g} m leaves both rows of the "
            f"{arrangement} pair unloaded (axial play); valid range: "
            f"{'> 0' if s1 > s0 else '< 0'} m"
        )
    g = resolve_bearing(bearing)
    loads = row_loads(row_parameters(g, contact_angle), [0.0, 0.0, 0.5 * abs(offset), 0.0, 0.0],
                      [0.0] * 5, g.ball_count, 1)
    return -float(loads.inner_load[2])


def preload_stiffness(bearing: str | BearingGeometry, directions: tuple[int, int],
                      positions: tuple[float, float], approach: tuple[float, float],
                      contact_angle: float | None = None) -> list[float]:
    """Diagonal of the 5x5 stiffness of a shaft on two ball rows at rest, about its centre of
    mass [N/m, N/m, N/m, N m/rad, N m/rad].

    Each row's ``5 x 5`` stiffness is the central difference of its ring loads
    (:func:`~bearingsim.components.ball_row.row_loads`, classic rows: no speed effects) at the
    inner ring's axial ``approach`` along the row's loading direction; the rows are moved to
    the centre of mass with the levers of their ``positions`` (rigid housing).

    Parameters
    ----------
    bearing : str or BearingGeometry
    directions : (int, int)
        Loading direction of each row.
    positions : (float, float)
        Axial position of each row from the centre of mass [m].
    approach : (float, float)
        Axial approach of each row's inner ring along its loading direction [m], > 0.
    contact_angle : float, optional
        Free contact angle [rad] (default: the bearing's).

    Returns
    -------
    list of 5 float
    """
    g = resolve_bearing(bearing)
    rp = row_parameters(g, contact_angle)
    total = [[0.0] * 5 for _ in range(5)]
    for s, z_k, delta in zip(directions, positions, approach, strict=True):
        lever = [[1.0, 0.0, 0.0, 0.0, z_k], [0.0, 1.0, 0.0, -z_k, 0.0], [0.0, 0.0, 1.0, 0.0, 0.0],
                 [0.0, 0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 0.0, 1.0]]
        steps = (1e-3 * delta,) * 3 + (2e-3 * delta / g.pitch_diameter,) * 2
        row = [[0.0] * 5 for _ in range(5)]
        for j, h in enumerate(steps):
            loads = []
            for sign in (1.0, -1.0):
                u = [0.0, 0.0, s * delta, 0.0, 0.0]
                u[j] += sign * h
                loads.append(row_loads(rp, u, [0.0] * 5, g.ball_count, s).inner_load)
            for i in range(5):
                row[i][j] = -(float(loads[0][i]) - float(loads[1][i])) / (2.0 * h)
        for a in range(5):
            for b in range(5):
                total[a][b] += sum(lever[i][a] * row[i][j] * lever[j][b]
                                   for i in range(5) for j in range(5))
    return [total[k][k] for k in range(5)]
