"""The scene face of the double-layer bearing: arguments, the build from scene arguments and the
post-processed quantities (each layer's ISO 281 life, the total friction power)."""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.double_layer.factory import double_layer_bearing
from bearingsim.assemblies.double_layer.figures import double_layer_plots
from bearingsim.assemblies.double_layer.options import (
    FIDELITIES,
    FRICTION_MODELS,
    DoubleLayerOptions,
)
from bearingsim.assemblies.spec import (
    ArgSpec,
    AssemblySpec,
    PostQuantity,
    declared_errors,
    factory_default,
    given_args,
)
from bearingsim.catalog import resolve_bearing
from bearingsim.components.middle_ring import (
    STRUCTURES,
)
from bearingsim.language import Assembly
from bearingsim.physics.life import basic_rating_life_hours
from bearingsim.physics.lubrication import LUBRICATION_METHODS

# --------------------------------------------------------------------------- scene spec
_KINEMATIC_NAMES = ("Rs", "w_shaft", "w_middle", "shaft_speed", "middle.*", "shaft.phi",
                    "drive.*", "der(*phi)")
"""Names the kinematic (pure rolling) level provides. Its shaft torque is a numerical drag, not
a friction torque, so ``M_shaft``, the losses, the loads and every other name need ``torque``."""


def double_layer_from_scene(args: dict[str, Any], fidelity: str,
                            drive: str = "speed") -> Assembly:
    """Build the bearing from the scene arguments of :data:`SCENE_SPEC`.

    Parameters
    ----------
    args : dict
        Every argument of ``SCENE_SPEC.args`` (defaults filled in).
    fidelity : {"kinematic_approx", "kinematic", "torque", "quasi-static", "dynamic"}
        Fidelity level: ``quasi-static`` is the load sharing of
        :class:`.NestedQuasiStatic` (inputs ``shaft.Fx``, ``shaft.Fy``, ``shaft.Fz`` [N]),
        ``dynamic`` the ball and cage dynamics of both layers
        (:class:`DynamicDoubleLayerBearing`, inputs ``shaft_speed`` and
        ``inner_layer.load.Fx`` ... [N]); the friction-model arguments belong to the lower
        levels.
    drive : {"speed", "flange"}
        Imposed shaft speed (input ``shaft_speed`` [rad/s]) or a free shaft flange.

    Returns
    -------
    Assembly
        The double-layer bearing at that level.
    """
    if fidelity in ("quasi-static", "dynamic"):
        extra = {"drive": drive} if fidelity == "dynamic" else {}
        return double_layer_bearing(args["inner"], args["outer"], structure=args["structure"],
                                    fidelity=fidelity, lubrication=args["lubrication"], **extra)
    return double_layer_bearing(
        args["inner"], args["outer"], structure=args["structure"], fidelity=fidelity,
        lubrication=args["lubrication"], friction_model=args["friction_model"], drive=drive,
        lubrication_method=args["lubrication_method"], oil_level=args["oil_level"],
        middle_ring_drag=given_args(args["middle_ring_drag"]) or None,
        layer_options=given_args(args["layer_options"]) or None,
    )


def _layer_life(geometry, layer: str) -> PostQuantity:
    name = f"{layer}.L10h"
    needs = ("Fr", "Fa", f"{layer}.w_rel")

    def compute(series):
        return basic_rating_life_hours(geometry, *(series[n] for n in needs))

    return PostQuantity(name, "h", f"ISO 281 basic rating life of the {layer.replace('_', ' ')} "
                        f"({geometry.designation}) at the momentary load and relative speed "
                        f"(inf when unloaded or at rest)", needs, compute, "torque")


def _total_loss(series):
    return series["inner_layer.P_loss"] + series["outer_layer.P_loss"]


def _scene_post(args: dict[str, Any]) -> dict[str, PostQuantity]:
    """ISO 281 basic rating life [h] of each layer with catalogue ratings, and the total friction
    power [W]."""
    out = {}
    for layer in ("inner", "outer"):
        geometry = resolve_bearing(args[layer])
        if geometry.dynamic_load_rating is not None and geometry.static_load_rating is not None:
            quantity = _layer_life(geometry, f"{layer}_layer")
            out[quantity.name] = quantity
    out["P_loss_total"] = PostQuantity("P_loss_total", "W", "friction power of both layers",
                                       ("inner_layer.P_loss", "outer_layer.P_loss"), _total_loss,
                                       "torque")
    return out


def _palmgren(args: dict[str, Any]) -> bool:
    """The lubricant only changes parameter values (the viscosity) under Palmgren friction."""
    return args["friction_model"] == "palmgren"


SCENE_SPEC = AssemblySpec(
    name="double_layer_bearing",
    description="I/Z-type double-layer (nested) ball bearing driven at an imposed shaft speed "
                "(input shaft_speed [rad/s]; torque level adds the loads Fr, Fa [N])",
    build=double_layer_from_scene,
    args={
        "inner": ArgSpec("bearing", factory_default(double_layer_bearing, "inner"),
                         "inner (shaft-side) deep-groove bearing"),
        "outer": ArgSpec("bearing", factory_default(double_layer_bearing, "outer"),
                         "outer (housing-side) deep-groove bearing"),
        "structure": ArgSpec("choice", factory_default(double_layer_bearing, "structure"),
                             "middle ring type (default: I if it fits, else Z)",
                             choices=STRUCTURES),
        "lubrication": ArgSpec("lubricant", factory_default(double_layer_bearing, "lubrication"),
                               "lubricant of both layers, or [inner, outer]"),
        "friction_model": ArgSpec("choice", factory_default(DoubleLayerOptions, "friction_model"),
                                  "friction torque model (torque level)",
                                  choices=FRICTION_MODELS),
        "lubrication_method": ArgSpec("choice", None, "lubrication method of both layers "
                                      "(default: the lubricant's own)",
                                      choices=LUBRICATION_METHODS),
        "oil_level": ArgSpec("float", None, "oil bath level above the outer layer's lowest ball "
                             "centre [m] (SKF friction model)", low=0.0,
                             low_inclusive=True),
        "middle_ring_drag": ArgSpec("table", None, "the middle ring's laminar drag in the oil "
                                    "(torque level)", table={
            "radius": ArgSpec("float", None, "radius of the turning cylinder [m]", low=0.0),
            "gap": ArgSpec("float", None, "oil gap to the fixed bore [m]", low=0.0),
            "length": ArgSpec("float", None, "wetted length [m]", low=0.0),
            "wetted": ArgSpec("float", None, "wetted fraction of the circumference", low=0.0),
        }),
        "layer_options": ArgSpec("table", None, "options of the friction elements", table={
            "smooth": ArgSpec("bool", None, "smooth blend of the Palmgren M0 branches"),
            "load_dependent": ArgSpec("bool", None, "include the load-dependent torque M1"),
            "omega_reg": ArgSpec("float", None, "friction sign regularization speed [rad/s]",
                                 low=0.0),
        }),
    },
    fidelities=FIDELITIES,
    auto_fidelities=("kinematic", "torque"),
    output_fidelity=[(pattern, "kinematic") for pattern in _KINEMATIC_NAMES],
    default_outputs=["w_shaft", "w_middle", "Rs", "M_shaft"],
    post=_scene_post,
    parametric_args={"lubrication": _palmgren},
    optional_inputs=("Fr", "Fa", "shaft.F*", "middle.F*", "inner_layer.load.*"),  # no load
    reference_fidelity=declared_errors("double_layer_bearing")[0],
    level_errors=declared_errors("double_layer_bearing")[1],
    plots=double_layer_plots,
    undefined_at_rest={
        "Rs": "the speed ratio Rs = w_middle / w_shaft is 0/0 (the model's regularized Rs "
              "is 0 there, no answer)",
        "*.L10h": "a life in hours is not defined (the model's value is inf)"},
)
"""The double-layer bearing as a scene assembly (:mod:`bearingsim.scenes`)."""
