"""The catalogue limits an input may carry: ``Input(..., warn_above=LIMIT, limit=KIND)``.

Between the limit and the input's hard bounds (``low``, ``high``) a run warns with the kind's
warning, naming the limit and what happens beyond it; outside the bounds it is refused
(:func:`~bearingsim.simulation.input_ranges.check_input_ranges`). Each kind says what its limit is,
so that the same check serves speeds and loads.
"""

from __future__ import annotations

from dataclasses import dataclass

from bearingsim.errors import PlasticDeformationWarning, SpeedLimitWarning

__all__ = ["INPUT_LIMITS", "InputLimit"]


@dataclass(frozen=True)
class InputLimit:
    """What an input's limit is and what exceeding it means."""

    name: str
    """The limit, as a message names it ("the bearing's limiting speed")."""
    effect: str
    """What happens beyond it."""
    warning: type[UserWarning]
    """The warning a run above it gives."""


INPUT_LIMITS = {
    "speed": InputLimit("the bearing's limiting speed",
                        "the catalogue no longer vouches for the bearing there",
                        SpeedLimitWarning),
    "static load": InputLimit(
        "the load at which this component alone brings the static equivalent load to the "
        "static load rating C0",
        "the raceways deform permanently (ISO 76)", PlasticDeformationWarning),
}
"""Kinds of input limits: a speed above a limiting speed
(:func:`~bearingsim.catalog.geometry.speed_input_bounds`), a load component above the one that
alone makes the static equivalent load reach C0
(:func:`~bearingsim.components.rolling_element.load_input_bounds`)."""
