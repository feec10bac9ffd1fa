"""The scene face of the deep-groove ball bearing: arguments and the build from scene arguments."""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.deep_groove.factory import deep_groove_ball_bearing
from bearingsim.assemblies.deep_groove.figures import deep_groove_plots
from bearingsim.assemblies.deep_groove.options import FIDELITIES
from bearingsim.assemblies.spec import ArgSpec, AssemblySpec, factory_default


# --------------------------------------------------------------------------- scene spec
def _deep_groove_from_scene(args: dict[str, Any], fidelity: str):
    """Build the bearing from the scene arguments of :data:`SCENE_SPEC` (defaults filled in)."""
    return deep_groove_ball_bearing(args["bearing"], fidelity=fidelity,
                                    lubricant=args["lubricant"])


_QUASI_STATIC, _DYNAMIC, _MASSIVE_BALLS = FIDELITIES

SCENE_SPEC = AssemblySpec(
    name="deep_groove_ball_bearing",
    description="single deep-groove ball bearing: quasi-static load distribution, or ball "
                "and cage dynamics (cage slip, pocket forces); inputs shaft_speed [rad/s] "
                "(dynamic levels), load.Fx, Fy, Fz [N]",
    build=_deep_groove_from_scene,
    args={
        "bearing": ArgSpec("bearing", factory_default(deep_groove_ball_bearing, "designation"),
                           "catalogue designation"),
        "lubricant": ArgSpec("lubricant", factory_default(deep_groove_ball_bearing, "lubricant"),
                             "lubricant name"),
    },
    fidelities=FIDELITIES,
    auto_fidelities=(_QUASI_STATIC, _MASSIVE_BALLS),
    output_fidelity=[("row.*", _QUASI_STATIC), ("load.*", _QUASI_STATIC),
                     *((pattern, _MASSIVE_BALLS) for pattern in
                       ("w_cage", "slip", "inner*", "outer*", "pocket*", "shaft_speed"))],
    default_outputs=["row.Q_i[0]", "row.alpha_i[0]"],
    optional_inputs=("load.*",),  # no load on the inner ring
    plots=deep_groove_plots,
)
"""The single deep-groove ball bearing as a scene assembly (:mod:`bearingsim.scenes`)."""
