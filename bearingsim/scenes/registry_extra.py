"""Registry entries of assemblies that live in modules written after the scene layer.

Each entry is added only when its module imports (``duplex_pair`` from
``bearingsim.assemblies.duplex``).
"""

from __future__ import annotations

from typing import Any

from bearingsim.scenes.registry import ArgSpec, AssemblySpec

__all__ = ["register_extra"]


def _build_duplex(args: dict[str, Any], fidelity: str):
    from bearingsim.assemblies.duplex import duplex_pair

    kwargs = {k: v for k, v in args.items() if v is not None and k not in ("bearing",)}
    return duplex_pair(args["bearing"], **kwargs)


def _build_deep_groove(args: dict[str, Any], fidelity: str):
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing

    return deep_groove_ball_bearing(args["bearing"], fidelity=fidelity,
                                    lubricant=args["lubricant"])


def _pure_axial(inputs: dict[str, Any]) -> bool:
    radial = [inputs.get(n, 0.0) for n in ("shaft.Fx", "shaft.Fy", "shaft.Mx", "shaft.My")]
    return all(isinstance(v, (int, float)) and v == 0.0 for v in radial)


def _duplex_symmetry(args: dict[str, Any], inputs: dict[str, Any]) -> list[str]:
    if args.get("axisymmetric"):
        return ["pure axial load: one representative ball per row is solved (axisymmetric "
                "rows); the other balls equal it and the rows carry no radial load or moment"]
    return []


def _duplex_symmetric_args(args: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    return {"axisymmetric": True} if _pure_axial(inputs) else {}


def register_extra(register) -> None:
    """Register the optional assemblies whose modules exist."""
    try:
        from bearingsim.assemblies import deep_groove, duplex
    except ImportError:
        return
    register(AssemblySpec(
        name="deep_groove_ball_bearing",
        description="single deep-groove ball bearing: quasi-static load distribution, or ball "
                    "and cage dynamics (cage slip, pocket forces); inputs shaft_speed [rad/s] "
                    "(dynamic levels), load.Fx, Fy, Fz [N]",
        build=_build_deep_groove,
        args={
            "bearing": ArgSpec("bearing", "6304", "catalogue designation"),
            "lubricant": ArgSpec("lubricant", "ISO VG 32", "lubricant name"),
        },
        fidelities=deep_groove.FIDELITIES,
        auto_fidelities=("quasi-static", "dynamic_massive_balls"),
        output_fidelity=[("row.*", "quasi-static"), ("load.*", "quasi-static"),
                         ("w_cage", "dynamic_massive_balls"),
                         ("slip", "dynamic_massive_balls"), ("inner*", "dynamic_massive_balls"),
                         ("outer*", "dynamic_massive_balls"), ("pocket*", "dynamic_massive_balls"),
                         ("shaft_speed", "dynamic_massive_balls")],
        default_outputs=["row.Q_i[0]", "row.alpha_i[0]"],
    ))
    register(AssemblySpec(
        name="duplex_pair",
        description="DF/DB/DT duplex pair of angular contact ball bearings on a rigid shaft "
                    "(quasi-static ball rows); inputs shaft.Fx, Fy, Fz [N], Mx, My [N m]",
        build=_build_duplex,
        args={
            "bearing": ArgSpec("bearing", "7020C", "bearing of both rows"),
            "arrangement": ArgSpec("choice", "DF", "arrangement",
                                   choices=tuple(duplex.ARRANGEMENTS)),
            "preload": ArgSpec("choice", "light", "catalogue preload class",
                               choices=duplex.PRELOAD_CLASSES),
            "speed": ArgSpec("float", None, "shaft speed [rad/s]", low=-1e9),
            "speed_effects": ArgSpec("bool", None, "centrifugal and gyroscopic ball loads"),
        },
        fidelities=("quasi-static",),
        auto_fidelities=("quasi-static",),
        output_fidelity=[],
        default_outputs=["shaft.x", "shaft.z", "shaft.ty"],
        symmetry=_duplex_symmetry,
        symmetric_args=_duplex_symmetric_args,
        fidelity_arg=None,
    ))
