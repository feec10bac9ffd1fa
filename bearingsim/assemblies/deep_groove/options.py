"""The deep-groove ball bearing's fidelity levels and the constants its levels share."""

from __future__ import annotations

FIDELITIES = ("quasi-static", "dynamic", "dynamic_massive_balls")
"""Fidelity levels, lowest first."""
_W_REG = 1e-2  # rad/s, regularization of the slip ratio at standstill
FILM_DAMPING = 1e-5
"""Damping of a lubricated race contact over its tangent stiffness [s] (Kramer 1993: rolling
bearings damp 0.25e-5 .. 2.5e-5 times their stiffness; see
:class:`~bearingsim.components.dynamic.RaceContact`)."""


_SET_BY_FACTORY = ("design", "lubricant", "massive_balls", "speed", "loads")
"""Arguments of :class:`DeepGrooveBallBearing` that :func:`deep_groove_ball_bearing` sets."""
