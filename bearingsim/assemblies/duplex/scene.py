"""The scene face of the duplex pair: arguments, the build from scene arguments and the symmetry
reductions (pure axial load: one ball per row)."""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.duplex.figures import MODE_NAMES_BY_STATE, duplex_plots
from bearingsim.assemblies.duplex.options import DuplexOptions
from bearingsim.assemblies.duplex.pair import DuplexPair, duplex_pair
from bearingsim.assemblies.duplex.preload import ARRANGEMENTS, PRELOAD_CLASSES
from bearingsim.assemblies.spec import (
    ArgSpec,
    AssemblySpec,
    factory_default,
    given_args,
    single_level,
)
from bearingsim.errors import ParameterError
from bearingsim.validation import check_quantity

# --------------------------------------------------------------------------- scene spec
_RADIAL_INPUTS = ("shaft.Fx", "shaft.Fy", "shaft.Mx", "shaft.My")


def _duplex_from_scene(args: dict[str, Any], fidelity: str) -> DuplexPair:
    """Build the pair from the scene arguments of :data:`SCENE_SPEC` (defaults filled in;
    ``fidelity`` is unused: the pair has one level)."""
    keywords = given_args(args, leave_out=("bearing", "preload_force"))
    if args.get("preload_force") is not None:
        if args.get("preload") is not None:
            raise ParameterError(
                f"duplex_pair: give either preload ({args['preload']!r}, a class) or "
                f"preload_force ({args['preload_force']!r} N), not both")
        keywords["preload"] = float(check_quantity(  # "1 kN" from export-fmu --arg
            args["preload_force"], "preload_force", "N", 0.0, low_inclusive=False,
            where="duplex_pair"))
    return duplex_pair(args["bearing"], **keywords)


def _pure_axial(inputs: dict[str, Any]) -> bool:
    """Every radial force and moment input absent or the constant 0."""
    radial = [inputs.get(name, 0.0) for name in _RADIAL_INPUTS]
    return all(isinstance(v, (int, float)) and v == 0.0 for v in radial)


def _symmetry(args: dict[str, Any], inputs: dict[str, Any]) -> list[str]:
    if args.get("axisymmetric"):
        return ["pure axial load: one representative ball per row is solved (axisymmetric "
                "rows); the other balls equal it and the rows carry no radial load or moment"]
    return []


def _symmetric_args(args: dict[str, Any], inputs: dict[str, Any]) -> dict[str, Any]:
    return {"axisymmetric": True} if _pure_axial(inputs) else {}


SCENE_SPEC = AssemblySpec(
    name="duplex_pair",
    description="DF/DB/DT duplex pair of angular contact ball bearings on a rigid shaft "
                "(quasi-static ball rows); inputs shaft.Fx, Fy, Fz [N], Mx, My [N m]",
    build=_duplex_from_scene,
    args={
        "bearing": ArgSpec("bearing", factory_default(duplex_pair, "designation"),
                           "bearing of both rows"),
        "arrangement": ArgSpec("choice", factory_default(duplex_pair, "arrangement"),
                               "arrangement", choices=tuple(ARRANGEMENTS)),
        "preload": ArgSpec("choice", factory_default(duplex_pair, "preload"),
                           "preload class: catalogued, else a fraction of C (default: light)",
                           choices=PRELOAD_CLASSES),
        "preload_force": ArgSpec("float", None, "axial preload [N] instead of a class",
                                 low=0.0),
        "speed": ArgSpec("float", factory_default(duplex_pair, "speed"), "shaft speed [rad/s]"),
        "speed_effects": ArgSpec("bool", factory_default(DuplexOptions, "speed_effects"),
                                 "centrifugal and gyroscopic ball loads"),
        "damping_ratio": ArgSpec("float", factory_default(DuplexOptions, "damping_ratio"),
                                 "damping ratio of the shaft against the housing [-] "
                                 "(default: none, a load step rings for ever)", low=0.0,
                                 high=1.0, low_inclusive=True),
    },
    **single_level("quasi-static"),
    default_outputs=["shaft.x", "shaft.z", "shaft.ty"],
    symmetry=_symmetry,
    symmetric_args=_symmetric_args,
    # the preload (spacer width difference, DT spring force) and the speed (with speed effects
    # built in) are parameters of the assembled pair: a grid over them needs no re-assembly
    parametric_args={"preload": lambda args: True, "preload_force": lambda args: True,
                     "speed": lambda args: bool(args.get("speed_effects"))},
    optional_inputs=("shaft.*",),  # no external load (the preload alone)
    plots=duplex_plots,
    mode_names=MODE_NAMES_BY_STATE,
)
"""The duplex pair as a scene assembly (:mod:`bearingsim.scenes`)."""
