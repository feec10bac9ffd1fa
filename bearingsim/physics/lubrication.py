"""Lubrication methods and the Palmgren f0 table that depends on them.

The data every lubricant refers to (:mod:`bearingsim.physics.lubricant` checks a lubricant's
``method`` against :data:`LUBRICATION_METHODS` and takes its load-independent friction factor
from :func:`palmgren_f0`); the friction models of :mod:`bearingsim.physics.friction` use them
through the lubricant. This module imports neither of the two.
"""

from __future__ import annotations

from bearingsim.checks import guard_public_functions
from bearingsim.validation import table_entry

__all__ = ["LUBRICATION_METHODS", "PALMGREN_F0", "PALMGREN_F0_BY_SERIES", "palmgren_f0"]

LUBRICATION_METHODS = ("grease", "oil_mist", "oil_bath", "oil_jet", "vertical_shaft")
"""Lubrication methods distinguished by the Palmgren f0 table."""

# Palmgren f0 by bearing type and lubrication method. Source: Harris & Kotzalas, Rolling Bearing
# Analysis, 5th ed., Essential Concepts, table "f0 versus bearing type and method of lubrication"
# (after Palmgren, Ball and Roller Bearing Engineering, 1959). Where the table gives a range the
# middle is used. "vertical_shaft" and "oil_jet" share the table's "oil bath (vertical shaft) or
# oil jet" column.
# Verification status: unverified against the cited table. None of the catalogues retrieved (NSK
# E1102e, SKF 6000 (2006), NTN CAT. No. 2202, Koyo CAT. NO. 203E-1, GMN 4000 0813 EN, the FAG/INA
# document found was a price list) prints a Palmgren f0 table or f1 formula; NTN and Koyo give
# friction coefficients mu instead, SKF only its four-component model.
_F0_ROWS = {
    #                          grease, oil_mist, oil_bath, oil_jet / vertical_shaft
    "deep_groove_ball": (1.35, 1.0, 2.0, 4.0),
    "self_aligning_ball": (1.75, 0.85, 1.75, 3.5),
    "angular_contact_ball": (2.0, 1.7, 3.3, 6.6),
    "angular_contact_ball_pair": (4.0, 3.4, 6.6, 13.2),
    "thrust_ball": (5.5, 0.8, 1.5, 3.0),
    "cylindrical_roller": (0.8, 2.15, 3.1, 3.1),
    "spherical_roller": (5.25, 2.6, 5.25, 10.5),
    "tapered_roller": (6.0, 3.0, 6.0, 9.0),
}
PALMGREN_F0: dict[str, dict[str, float]] = {
    btype: dict(zip(LUBRICATION_METHODS, (*row, row[3]), strict=True))
    for btype, row in _F0_ROWS.items()
}
"""Palmgren load-independent friction factor f0 [-] by bearing type and lubrication method."""


PALMGREN_F0_BY_SERIES: dict[tuple[str, str], tuple[float, float]] = {
    # (bearing type, series): (grease or oil mist, oil bath or recirculating oil)
    ("deep_groove_ball", "618"): (1.1, 1.7),
    ("deep_groove_ball", "160"): (1.1, 1.7),
    ("deep_groove_ball", "60"): (1.1, 1.7),
    ("deep_groove_ball", "619"): (1.1, 1.7),
    ("deep_groove_ball", "62"): (1.3, 2.0),
    ("deep_groove_ball", "63"): (1.5, 2.3),
    ("deep_groove_ball", "64"): (1.5, 2.3),
    ("angular_contact_ball", "70"): (1.3, 2.0),
    ("angular_contact_ball", "72"): (1.3, 2.0),
    ("angular_contact_ball", "73"): (2.0, 3.0),
}
"""Palmgren f0 [-] by bearing type and series: Schaeffler *Rolling Bearings* HR 1 (2006) p. 58
"Bearing factors for deep groove ball bearings" and p. 59 "... angular contact ball bearings",
columns "Grease, oil mist" and "Oil bath, recirculating oil" (merged table cells read as
belonging to every row of their block, as the f1 column shows). The oil column agrees with
Timken Engineering Manual Table 114 p. 184 (series 39/00: 1.7, 02: 2, 03: 2.3; angular contact
02: 2, 03: 3) and KRW catalogue 2006 p. 117 (619/160/60: 1.75, 62-64: 2) within 3 %; the grease
column with KRW's (1.17, 1.34) within 6 %. Where a series is listed, :func:`palmgren_f0` uses
these values (oil jet: HR 1's recirculating oil); the per-type table :data:`PALMGREN_F0` covers
other series, the vertical shaft and the other bearing types."""

_SERIES_COLUMN = {"grease": 0, "oil_mist": 0, "oil_bath": 1, "oil_jet": 1}


def palmgren_f0(bearing_type: str, method: str, series: str | None = None) -> float:
    """Palmgren load-independent friction factor f0 [-].

    Parameters
    ----------
    bearing_type : str
        One of the keys of :data:`PALMGREN_F0`, e.g. ``"deep_groove_ball"``.
    method : str
        Lubrication method, one of :data:`LUBRICATION_METHODS`.
    series : str, optional
        Catalogue series (:attr:`~bearingsim.catalog.geometry.BearingGeometry.series`, e.g.
        ``"619"``): for the series of :data:`PALMGREN_F0_BY_SERIES` (Schaeffler HR 1) and every
        method but ``vertical_shaft``, f0 comes from there.

    Returns
    -------
    float
        f0 [-].

    Raises
    ------
    CatalogError
        For an unknown bearing type or lubrication method; the message lists the known ones.
    """
    row = table_entry(PALMGREN_F0, bearing_type, "bearing type")
    value = table_entry(row, method, "lubrication method")
    by_series = PALMGREN_F0_BY_SERIES.get((bearing_type, series))
    if by_series is not None and method in _SERIES_COLUMN:
        return by_series[_SERIES_COLUMN[method]]
    return value


guard_public_functions(globals())  # no NaN in, no NaN or inf out (bearingsim.checks)
