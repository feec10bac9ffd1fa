"""Fatigue life and load ratings of ball and cylindrical roller bearings, one module per
standard:

* :mod:`~bearingsim.physics.life.iso_281`: ISO 281:2007 basic dynamic load rating C (ball and
  roller), equivalent dynamic load P (X, Y factors) and basic rating life ``L10 = (C/P)^p``;
* :mod:`~bearingsim.physics.life.iso_76`: ISO 76:2006 basic static load rating C0 (ball and
  roller), static factors X0, Y0 and the static equivalent load P0;
* :mod:`~bearingsim.physics.life.lundberg_palmgren`: Lundberg-Palmgren lives of each
  ball-raceway contact (Harris & Kotzalas), combined as docs/studies.md, section C prescribes,
  and Sjovall's line-contact load integrals;
* :mod:`~bearingsim.physics.life.iso_ts_16281`: a basic reference rating life from the internal
  load distribution in the manner of ISO/TS 16281:2008 (ball and sliced roller form);
* :mod:`~bearingsim.physics.life.modified_life`: ISO 281:2007, clause 9: the reliability factor
  a1, the viscosity ratio kappa and the life modification factor a_ISO, applied to L10 and to
  the reference rating life L_10r (``L_nrm = a1 a_ISO L_10r``).

Every public name of these modules is importable from this package too
(``from bearingsim.physics.life import rating_life``).

SI units at the interface (m, N, rad, rad/s); the ISO formulas are evaluated in their own units
(mm, N) inside. Lives are in millions of revolutions of the rotating ring relative to the other.
Functions take floats, numpy arrays or CasADi SX; table look-ups are piecewise linear.
"""

from __future__ import annotations

from bearingsim.physics.life.iso_76 import (
    roller_static_load_rating,
    static_equivalent_load,
    static_factor,
    static_load_factors,
    static_load_rating,
)
from bearingsim.physics.life.iso_281 import (
    CYLINDRICAL_BM,
    LINE_LIFE_EXPONENT,
    basic_rating_life_hours,
    dynamic_load_rating,
    equivalent_dynamic_load,
    life_hours,
    rating_life,
    roller_dynamic_load_rating,
    roller_fc,
    xy_factors,
)
from bearingsim.physics.life.iso_ts_16281 import (
    raceway_dynamic_ratings,
    reference_rating_life,
    roller_raceway_ratings,
    roller_reference_rating_life,
    slice_equivalent_load,
)
from bearingsim.physics.life.lundberg_palmgren import (
    ball_contact_capacity,
    bearing_life,
    combined_contact_life,
    contact_life,
    line_load_integrals,
    raceway_contact_capacity,
    raceway_equivalent_load,
)
from bearingsim.physics.life.modified_life import (
    A_ISO_MAX,
    KAPPA_RANGE,
    RELIABILITY_FACTORS,
    life_modification_factor,
    modified_rating_life,
    rated_viscosity,
    reliability_factor,
    viscosity_ratio,
)

__all__ = [
    "dynamic_load_rating",
    "static_load_rating",
    "static_factor",
    "static_load_factors",
    "static_equivalent_load",
    "xy_factors",
    "equivalent_dynamic_load",
    "rating_life",
    "life_hours",
    "basic_rating_life_hours",
    "raceway_contact_capacity",
    "ball_contact_capacity",
    "contact_life",
    "combined_contact_life",
    "raceway_equivalent_load",
    "bearing_life",
    "raceway_dynamic_ratings",
    "reference_rating_life",
    "CYLINDRICAL_BM",
    "LINE_LIFE_EXPONENT",
    "roller_fc",
    "roller_dynamic_load_rating",
    "roller_static_load_rating",
    "line_load_integrals",
    "roller_raceway_ratings",
    "slice_equivalent_load",
    "roller_reference_rating_life",
    "A_ISO_MAX",
    "KAPPA_RANGE",
    "RELIABILITY_FACTORS",
    "reliability_factor",
    "rated_viscosity",
    "viscosity_ratio",
    "life_modification_factor",
    "modified_rating_life",
]
