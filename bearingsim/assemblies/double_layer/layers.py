"""The double-layer bearing's layers: each layer's friction element, its lubrication method and
oil-bath level, and the middle ring's oil gap (Couette drag)."""

from __future__ import annotations

import copy
from typing import Any

from bearingsim.assemblies.double_layer.options import (
    _POSITIVE_OPTIONS,
    KINEMATIC_OPTIONS,
    layer_option_names,
)
from bearingsim.checks import check_arguments
from bearingsim.components.bearing_torque import (
    PalmgrenBearing,
    PureRollingLayer,
    SkfBearing,
)
from bearingsim.errors import ParameterError
from bearingsim.physics.drag import couette_damping
from bearingsim.physics.lubrication import LUBRICATION_METHODS
from bearingsim.validation import (
    check_choice,
    check_mapping,
    check_options,
    check_range,
    keyword_names,
)


def _layer(geometry, lubricant, fidelity: str, friction_model: str, options: dict):
    for key, unit in _POSITIVE_OPTIONS.items():
        if key in options:
            check_range(options[key], f"layer_options[{key!r}]", unit, 0.0, None,
                        low_inclusive=False, where="double_layer_bearing")
    if fidelity in ("kinematic", "kinematic_approx"):
        unused = sorted(set(options) - set(KINEMATIC_OPTIONS))
        if unused:
            raise ParameterError(
                f"double_layer_bearing: layer_options {', '.join(map(repr, unused))} not used at "
                f"fidelity {fidelity!r}; its only option is 'k' (pure-rolling drag coefficient "
                f"[N s/m], > 0)"
            )
        return PureRollingLayer(geometry, exact=fidelity == "kinematic", **options)
    check_options(options, layer_option_names(friction_model), "double_layer_bearing",
                  "layer_options", f"of the {friction_model!r} friction model (torque level)")
    layer = PalmgrenBearing if friction_model == "palmgren" else SkfBearing
    check_arguments(layer, (), {k: v for k, v in options.items()
                                if k in keyword_names(layer)},
                    "double_layer_bearing", "layer_options[{name!r}]")
    return layer(geometry, lubricant, **options)


def _with_method(lubricant, method: str):
    """A copy of ``lubricant`` lubricating by ``method``."""
    check_choice(method, "lubrication_method", LUBRICATION_METHODS, "double_layer_bearing")
    if not lubricant.is_viscous:
        raise ParameterError(f"double_layer_bearing: lubrication_method {method!r} needs an oil "
                             f"or grease, got {lubricant.describe()}")
    changed = copy.copy(lubricant)
    changed.method = method
    return changed


def _bath_options(gi, go, lubricants, oil_level, friction_model: str, fidelity: str,
                  options: dict) -> tuple[dict, dict]:
    """Each layer's layer options with its own oil level (see :class:`DoubleLayerBearing`)."""
    if oil_level is None:
        return options, options
    where = "double_layer_bearing"
    check_range(oil_level, "oil_level", "m", 0.0, None, where=where)
    if fidelity != "torque":  # checked, but the kinematic levels have no friction (as lubrication)
        return options, options
    if friction_model != "skf":
        raise ParameterError(f"{where}: oil_level is used by friction_model='skf' at the torque "
                             f"level (the drag of the immersed balls, the starvation factor); "
                             f"Palmgren's f0 has no published oil-level dependence here")
    if "oil_level" in options:
        raise ParameterError(f"{where}: give the oil level once, as oil_level (each layer sees "
                             f"it from its own lowest ball), not in layer_options")
    levels = (oil_level - 0.5 * (go.pitch_diameter - gi.pitch_diameter), oil_level)
    per_layer = []
    for g, lub, level in zip((gi, go), lubricants, levels, strict=True):
        layer = dict(options)
        if lub.method == "oil_bath" and level >= 0.0:
            layer.update(oil_level=level, Dw=g.ball_diameter, Z=g.ball_count)
        per_layer.append(layer)
    return per_layer[0], per_layer[1]


def _middle_ring_gap(options: Any, lubricant) -> tuple[float, ...]:
    """(radius, gap, length, wetted, eta, nu) of the middle ring's oil gap, checked."""
    where = "double_layer_bearing"
    opts = check_mapping(options, "middle_ring_drag", where, "keys")
    check_options(opts, ("radius", "gap", "length", "wetted"), where, "middle_ring_drag keys")
    missing = [k for k in ("radius", "gap", "length") if k not in opts]
    if missing:
        raise ParameterError(f"{where}: middle_ring_drag needs {', '.join(missing)} [m] (the "
                             f"turning cylinder's radius, the oil gap and the wetted length)")
    if not lubricant.is_viscous:
        raise ParameterError(f"{where}: middle_ring_drag needs an oil or grease in the outer "
                             f"layer, got {lubricant.describe()}")
    eta, nu = float(lubricant.dynamic_viscosity()), float(lubricant.kinematic_viscosity())
    wetted = opts.get("wetted", 1.0)
    couette_damping(opts["radius"], opts["gap"], opts["length"], eta, wetted)  # checks them
    return (float(opts["radius"]), float(opts["gap"]), float(opts["length"]), float(wetted),
            eta, nu)
