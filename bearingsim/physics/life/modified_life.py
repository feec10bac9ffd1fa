"""ISO 281:2007, clause 9: the modified rating life ``L_nm = a1 a_ISO L10``, applied to the basic
rating life of ISO 281 and to the basic reference rating life ``L_10r`` of ISO/TS 16281
(``L_nrm = a1 a_ISO L_10r``).

* **Reliability factor a1** (Table 12): 1 at 90 % reliability down to 0.077 at 99.95 %.
* **Rated viscosity** ``nu1`` (eqs. 28, 29): ``nu1 = 45000 n^-0.83 Dpw^-0.5`` for
  ``n < 1000 r/min`` and ``nu1 = 4500 n^-0.5 Dpw^-0.5`` above [mm^2/s, r/min, mm]; the
  viscosity ratio is ``kappa = nu / nu1`` (eq. 27), ``nu`` the lubricant's (a grease's base
  oil's) kinematic viscosity at the operating temperature.
* **Life modification factor** ``a_ISO`` (eqs. 31-36), of ``kappa`` and ``x = e_C Cu / P``
  (contamination factor ``e_C``, fatigue load limit ``Cu``, equivalent dynamic load ``P``):
  radial ball bearings ``a_ISO = 0.1 [1 - (2.5671 - b / kappa^c)^0.83 x^(1/3)]^-9.3`` and
  radial roller bearings ``a_ISO = 0.1 [1 - (1.5859 - b / kappa^c) x^0.4]^-9.185``, with
  ``(b, c)`` = (2.2649, 0.054381) ball / (1.3993, 0.054381) roller for ``0.1 <= kappa < 0.4``,
  (1.9987, 0.19087) / (1.2348, 0.19087) for ``0.4 <= kappa < 1`` and (1.9987, 0.071739) /
  (1.2348, 0.071739) for ``1 <= kappa <= 4``. ``a_ISO <= 50`` (clause 9.3.3.4, also for
  ``x > 5``), ``kappa > 4`` counts as 4, ``kappa < 0.1`` is outside the method.

Source: GOST 18855-2013 (ISO 281:2007, MOD), clause 9, pp. 20-28 (a scanned standard, read from
the page images): Table 12 (p. 21), Table 13 (the ``e_C`` guide values, p. 24), eqs. (27)-(29)
and Figure 2 (p. 25), clause 9.3.3.4 (p. 26), eqs. (31)-(36) with Figures 3 and 4 (pp. 27-29).
The scan renders several coefficients illegibly (the roller eq. 34); every coefficient above
agrees with two independent public implementations (GitHub code index; one of them prints
0.019087 for 0.19087, which would break the continuity) and makes ``a_ISO`` continuous at
``kappa = 0.4`` and 1 (to 0.1 %; tests/physics/test_modified_life.py), and the curves
reproduce the values read from the standard's Figures 3 and 4 within 3 %. The ISO/TS 16281 life is
modified with the bearing's ``a_ISO`` (its ``P`` the equivalent load that gives ``L_10r``); the
standard's own per-raceway stress form of ``a_ISO`` is not included.

The functions take floats or numpy arrays (the formula is piecewise in ``kappa``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.checks import guard_public_functions
from bearingsim.physics.life.tables import check_life
from bearingsim.validation import check_choice, check_range

__all__ = [
    "A_ISO_MAX",
    "KAPPA_RANGE",
    "RELIABILITY_FACTORS",
    "reliability_factor",
    "rated_viscosity",
    "viscosity_ratio",
    "life_modification_factor",
    "modified_rating_life",
]

A_ISO_MAX = 50.0
"""Upper limit of the life modification factor a_ISO [-] (ISO 281:2007, clause 9.3.3.4)."""
KAPPA_RANGE = (0.1, 4.0)
"""Viscosity ratios [-] the a_ISO formulas cover: below 0.1 the method does not apply, above 4
kappa counts as 4 (clause 9.3.3.4)."""
RELIABILITY_FACTORS: dict[float, float] = {
    90.0: 1.0, 95.0: 0.64, 96.0: 0.55, 97.0: 0.47, 98.0: 0.37, 99.0: 0.25, 99.2: 0.22,
    99.4: 0.19, 99.6: 0.16, 99.8: 0.12, 99.9: 0.093, 99.92: 0.087, 99.94: 0.080, 99.95: 0.077,
}
"""Reliability [%] -> life modification factor a1 [-] (ISO 281:2007, Table 12)."""

# (b, c) of (2.5671 - b / kappa^c) for balls and (1.5859 - b / kappa^c) for rollers, by the
# kappa ranges [0.1, 0.4), [0.4, 1), [1, 4]; then the load exponent, the outer exponent.
_A_ISO = {
    "ball": (2.5671, ((2.2649, 0.054381), (1.9987, 0.19087), (1.9987, 0.071739)), 0.83,
             1.0 / 3.0, -9.3),
    "roller": (1.5859, ((1.3993, 0.054381), (1.2348, 0.19087), (1.2348, 0.071739)), 1.0, 0.4,
               -9.185),
}
_ELEMENTS = tuple(_A_ISO)
_RPM_PER_RAD_S = 30.0 / np.pi


def reliability_factor(reliability: float) -> float:
    """Reliability factor a1 [-] of ISO 281:2007, Table 12.

    Parameters
    ----------
    reliability : float
        Reliability [%], one of the rows of :data:`RELIABILITY_FACTORS` (90 to 99.95).

    Returns
    -------
    float
        a1 [-].

    Raises
    ------
    ParameterError
        For a reliability that is not a row of the table.
    """
    key = float(check_range(reliability, "reliability", "%", 90.0, 99.95,
                            where="reliability_factor"))
    check_choice(key, "reliability", tuple(RELIABILITY_FACTORS), "reliability_factor")
    return RELIABILITY_FACTORS[key]


def rated_viscosity(speed: Any, pitch_diameter: Any) -> Any:
    """Rated kinematic viscosity ``nu1`` [m^2/s] (ISO 281:2007, eqs. 28 and 29).

    Parameters
    ----------
    speed : float or array
        Speed of the rotating ring relative to the other [rad/s], > 0.
    pitch_diameter : float or array
        Pitch diameter Dpw [m], in (0, 6] (``(d + D)/2`` where it is not known).

    Returns
    -------
    float or array
        nu1 [m^2/s].
    """
    where = "rated_viscosity"
    check_range(speed, "speed", "rad/s", 0.0, low_inclusive=False, where=where)
    check_range(pitch_diameter, "pitch_diameter", "m", 0.0, 6.0, low_inclusive=False,
                where=where)
    n = np.asarray(speed, dtype=float) * _RPM_PER_RAD_S
    d_mm = np.asarray(pitch_diameter, dtype=float) * 1e3
    nu1_mm2_s = np.where(n < 1000.0, 45000.0 * n ** -0.83, 4500.0 * n ** -0.5) / np.sqrt(d_mm)
    return (nu1_mm2_s * 1e-6)[()]


def viscosity_ratio(kinematic_viscosity: Any, speed: Any, pitch_diameter: Any) -> Any:
    """Viscosity ratio ``kappa = nu / nu1`` [-] (ISO 281:2007, eq. 27).

    Parameters
    ----------
    kinematic_viscosity : float or array
        Kinematic viscosity of the lubricant (a grease's base oil) at the operating temperature
        [m^2/s], > 0 (:meth:`~bearingsim.physics.lubricant.Lubricant.kinematic_viscosity`).
    speed, pitch_diameter
        As in :func:`rated_viscosity`.

    Returns
    -------
    float or array
        kappa [-].
    """
    check_range(kinematic_viscosity, "kinematic_viscosity", "m^2/s", 1e-7, 1e-2,
                where="viscosity_ratio")
    return np.asarray(kinematic_viscosity, dtype=float) / rated_viscosity(speed, pitch_diameter)


def life_modification_factor(kappa: Any, contamination_load_ratio: Any,
                             rolling_element: str = "ball") -> Any:
    """Life modification factor ``a_ISO`` [-] of radial bearings (ISO 281:2007, eqs. 31-36).

    Parameters
    ----------
    kappa : float or array
        Viscosity ratio [-], >= 0.1 (:func:`viscosity_ratio`); values above 4 count as 4.
    contamination_load_ratio : float or array
        ``e_C Cu / P`` [-], >= 0: contamination factor e_C (0 to 1, ISO 281 Table 13) times the
        fatigue load limit Cu [N] over the equivalent dynamic load P [N].
    rolling_element : {"ball", "roller"}
        Radial ball (eqs. 31-33) or radial roller bearings (eqs. 34-36).

    Returns
    -------
    float or array
        a_ISO [-], in [0.1, 50].

    Raises
    ------
    ParameterError
        For kappa below 0.1, a negative or non-finite load ratio, or another element.
    """
    where = "life_modification_factor"
    check_choice(rolling_element, "rolling_element", _ELEMENTS, where)
    check_range(kappa, "kappa", "-", KAPPA_RANGE[0], where=where)
    check_range(contamination_load_ratio, "contamination_load_ratio (e_C Cu/P)", "-", 0.0,
                where=where)
    base, pieces, base_exponent, load_exponent, exponent = _A_ISO[rolling_element]
    k = np.minimum(np.asarray(kappa, dtype=float), KAPPA_RANGE[1])
    (b1, c1), (b2, c2), (b3, c3) = pieces
    reduction = np.where(k < 0.4, b1 / k**c1, np.where(k < 1.0, b2 / k**c2, b3 / k**c3))
    lubrication = np.maximum(base - reduction, 0.0) ** base_exponent
    bracket = 1.0 - lubrication * np.asarray(contamination_load_ratio, dtype=float) ** load_exponent
    with np.errstate(divide="ignore"):
        a_iso = np.where(bracket > 0.0, 0.1 * np.maximum(bracket, 1e-300) ** exponent, A_ISO_MAX)
    return np.minimum(a_iso, A_ISO_MAX)[()]


def modified_rating_life(life: Any, kappa: Any, contamination_factor: Any,
                         fatigue_load_limit: Any, load: Any, rolling_element: str = "ball",
                         reliability: float = 90.0) -> Any:
    """Modified rating life ``L_nm = a1 a_ISO L`` [10^6 rev] (ISO 281:2007, eq. 23).

    With ``L`` the basic rating life L10 of ISO 281 this is ISO 281's ``L_nm``; with the basic
    reference rating life ``L_10r`` of ISO/TS 16281 (:func:`~bearingsim.physics.life.
    iso_ts_16281.reference_rating_life`, :func:`~bearingsim.physics.life.iso_ts_16281.
    roller_reference_rating_life`) it is the modified reference rating life ``L_nrm``.

    Parameters
    ----------
    life : float or array
        L10 or L_10r [10^6 rev], >= 0 (infinite for an unloaded bearing).
    kappa : float or array
        Viscosity ratio [-], >= 0.1.
    contamination_factor : float or array
        e_C [-], in [0, 1] (ISO 281 Table 13: 1 extreme cleanliness ... 0 very heavy
        contamination).
    fatigue_load_limit : float or array
        Cu [N], > 0 (catalogue; SKF prints it as Pu).
    load : float or array
        Equivalent dynamic load P [N], > 0.
    rolling_element : {"ball", "roller"}
    reliability : float
        Reliability [%], a row of :data:`RELIABILITY_FACTORS`.

    Returns
    -------
    float or array
        L_nm or L_nrm [10^6 rev].
    """
    where = "modified_rating_life"
    check_life(life, "life", where)
    check_range(contamination_factor, "contamination_factor", "-", 0.0, 1.0, where=where)
    check_range(fatigue_load_limit, "fatigue_load_limit", "N", 0.0, low_inclusive=False,
                where=where)
    check_range(load, "load", "N", 0.0, low_inclusive=False, where=where)
    ratio = (np.asarray(contamination_factor, dtype=float)
             * np.asarray(fatigue_load_limit, dtype=float) / np.asarray(load, dtype=float))
    a_iso = life_modification_factor(kappa, ratio, rolling_element)
    return reliability_factor(reliability) * a_iso * np.asarray(life, dtype=float)[()]


# no NaN in or out (bearingsim.checks); an unloaded bearing's life is infinite
guard_public_functions(globals(), infinite_results=True)
