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

from bearingsim.physics.life import iso_76, iso_281, iso_ts_16281, lundberg_palmgren, modified_life
from bearingsim.physics.life.iso_76 import (  # noqa: F401 (in __all__)
    PAIR_ARRANGEMENTS,
    pair_static_load_rating,
    roller_static_load_rating,
    static_equivalent_load,
    static_factor,
    static_load_factors,
    static_load_rating,
)
from bearingsim.physics.life.iso_281 import (  # noqa: F401 (in __all__)
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
from bearingsim.physics.life.iso_ts_16281 import (  # noqa: F401 (in __all__)
    raceway_dynamic_ratings,
    reference_rating_life,
    roller_raceway_ratings,
    roller_reference_rating_life,
    slice_equivalent_load,
)
from bearingsim.physics.life.lundberg_palmgren import (  # noqa: F401 (in __all__)
    ball_contact_capacity,
    bearing_life,
    combined_contact_life,
    contact_life,
    line_load_integrals,
    raceway_contact_capacity,
    raceway_equivalent_load,
)
from bearingsim.physics.life.modified_life import (  # noqa: F401 (in __all__)
    A_ISO_MAX,
    KAPPA_RANGE,
    RELIABILITY_FACTORS,
    life_modification_factor,
    modified_rating_life,
    rated_viscosity,
    reliability_factor,
    viscosity_ratio,
)

# the public names of the submodules, each imported above by name
__all__ = [
    *iso_281.__all__,
    *iso_76.__all__,
    *lundberg_palmgren.__all__,
    *iso_ts_16281.__all__,
    *modified_life.__all__,
]
