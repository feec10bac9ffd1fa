"""The double-layer bearing's options: fidelity levels, friction models and the layer options each
level takes."""

from __future__ import annotations

from typing import Any

from bearingsim.components.bearing_torque import (
    PalmgrenBearing,
    SkfBearing,
)
from bearingsim.errors import ParameterError
from bearingsim.physics.friction import skf_friction_components
from bearingsim.validation import (
    check_choice,
    keyword_names,
)

FIDELITIES = ("kinematic_approx", "kinematic", "torque", "quasi-static", "dynamic")
"""Fidelity levels; the first three (lowest first) are built by :class:`DoubleLayerBearing`."""
KINEMATIC_OPTIONS = ("k",)
"""``layer_options`` of the kinematic levels (the drag coefficient of PureRollingLayer)."""

FRICTION_MODELS = ("palmgren", "skf")
_LAYER_SETS = ("bearing", "lubricant", "name")
"""Arguments of the torque-level layer elements that :class:`DoubleLayerBearing` sets."""
_SKF_SETS = ("omega_rel", "dm", "lubricant", "series", "Fr", "Fa", "C0", "d", "D",
             "omega_reg")
"""Arguments of ``skf_friction_components`` that :class:`SkfBearing` sets itself."""


def layer_option_names(friction_model: str) -> tuple[str, ...]:
    """The ``layer_options`` a torque-level layer accepts (from the constructor signatures).

    Parameters
    ----------
    friction_model : {"palmgren", "skf"}
        Friction torque model.

    Returns
    -------
    tuple of str
        Keyword arguments of :class:`~bearingsim.components.bearing_torque.PalmgrenBearing`,
        or of :class:`~bearingsim.components.bearing_torque.SkfBearing` with the options it
        passes on to :func:`~bearingsim.physics.friction.skf_friction_components`.
    """
    if friction_model == "palmgren":
        return keyword_names(PalmgrenBearing, _LAYER_SETS)
    return keyword_names(SkfBearing, _LAYER_SETS) + keyword_names(skf_friction_components,
                                                                  _SKF_SETS)


_POSITIVE_OPTIONS = {"k": "N.s/m", "omega_reg": "rad/s"}
"""Numeric layer options (> 0), checked here so that the message names them."""


def _check_drive(drive: str) -> None:
    check_choice(drive, "drive", ("speed", "flange"), "double_layer_bearing")


def _pair(lubrication) -> tuple[Any, Any]:
    if isinstance(lubrication, (tuple, list)):
        if len(lubrication) != 2:
            raise ParameterError(f"double_layer_bearing: lubrication must be one lubricant or "
                                 f"an (inner, outer) pair, got {len(lubrication)} items")
        return lubrication[0], lubrication[1]
    return lubrication, lubrication
