"""Single deep-groove ball bearing as a product: quasi-static and dynamic fidelity
(docs/studies.md, section C).

Coordinates: z is the bearing axis (the study of docs/studies.md, section C uses x): its axial
force ``Fx`` is our ``Fz``, its radial ``Fy, Fz`` are our ``Fx, Fy`` and its moments ``My, Mz``
our ``Mx, My``.

Dynamic fidelities build, for every ball j, a :class:`~bearingsim.components.dynamic.Ball`, its
inner and outer :class:`~bearingsim.components.dynamic.RaceContact`, a
:class:`~bearingsim.components.dynamic.PocketContact` with the cage and (with a viscous
lubricant) a :class:`~bearingsim.components.dynamic.BallDrag`; the cage is guided by the outer
ring land. The inner ring is a 5-DOF :class:`~bearingsim.components.dynamic.RingBody` (its mass,
not a quasi-static balance as in the study, so the ring mode is resolved rather than eliminated)
loaded by a :class:`~bearingsim.components.dynamic.RingLoad`, and turned through a rotational
flange by a speed source (or by whatever the user connects to ``shaft``). The outer ring is
fixed to the housing. For a nested bearing either ring's translations can instead be left to an
enclosing assembly through a ring-frame connector (``inner_ring="frame"``,
``outer_support="frame"``).

* :mod:`.options`: fidelity levels, shared constants and the dynamic levels' options
  (:class:`DeepGrooveOptions` with its groups :class:`RingOptions`, :class:`FilmOptions`,
  :class:`CageOptions`), checked once;
* :mod:`.quasi_static`: :class:`QuasiStaticDeepGroove`;
* :mod:`.dynamic`: :class:`DeepGrooveBallBearing`;
* :mod:`.factory`: :func:`deep_groove_ball_bearing`;
* :mod:`.figures`: ball load against azimuth with Stribeck's distribution;
* :mod:`.scene`: :data:`SCENE_SPEC`.
"""

from bearingsim.assemblies.deep_groove.dynamic import DeepGrooveBallBearing
from bearingsim.assemblies.deep_groove.factory import deep_groove_ball_bearing
from bearingsim.assemblies.deep_groove.options import (
    FIDELITIES,
    FILM_DAMPING,
    CageOptions,
    DeepGrooveOptions,
    FilmOptions,
    RingOptions,
)
from bearingsim.assemblies.deep_groove.quasi_static import QuasiStaticDeepGroove
from bearingsim.assemblies.deep_groove.scene import SCENE_SPEC

__all__ = ["FIDELITIES", "FILM_DAMPING", "SCENE_SPEC", "CageOptions", "DeepGrooveBallBearing",
           "DeepGrooveOptions", "FilmOptions", "QuasiStaticDeepGroove", "RingOptions",
           "deep_groove_ball_bearing"]
