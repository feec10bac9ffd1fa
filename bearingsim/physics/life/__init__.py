"""Fatigue life and load ratings of ball bearings, one module per standard:

* :mod:`~bearingsim.physics.life.iso_281`: ISO 281:2007 basic dynamic load rating C,
  equivalent dynamic load P (X, Y factors) and basic rating life ``L10 = (C/P)^3``;
* :mod:`~bearingsim.physics.life.iso_76`: ISO 76:2006 basic static load rating C0, static
  factors X0, Y0 and the static equivalent load P0;
* :mod:`~bearingsim.physics.life.lundberg_palmgren`: Lundberg-Palmgren lives of each
  ball-raceway contact (Harris & Kotzalas), combined as docs/studies.md, section C prescribes;
* :mod:`~bearingsim.physics.life.iso_ts_16281`: a basic reference rating life from the internal
  load distribution in the manner of ISO/TS 16281:2008.

Every public name of these modules is importable from this package too
(``from bearingsim.physics.life import rating_life``).

SI units at the interface (m, N, rad, rad/s); the ISO formulas are evaluated in their own units
(mm, N) inside. Lives are in millions of revolutions of the rotating ring relative to the other.
Functions take floats, numpy arrays or CasADi SX; table look-ups are piecewise linear.
"""

from __future__ import annotations

from bearingsim.physics.life.iso_76 import (
    static_equivalent_load,
    static_factor,
    static_load_factors,
    static_load_rating,
)
from bearingsim.physics.life.iso_281 import (
    basic_rating_life_hours,
    dynamic_load_rating,
    equivalent_dynamic_load,
    life_hours,
    rating_life,
    xy_factors,
)
from bearingsim.physics.life.iso_ts_16281 import raceway_dynamic_ratings, reference_rating_life
from bearingsim.physics.life.lundberg_palmgren import (
    ball_contact_capacity,
    bearing_life,
    combined_contact_life,
    contact_life,
    raceway_contact_capacity,
    raceway_equivalent_load,
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
]
