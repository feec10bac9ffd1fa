"""The motor drive's figure: its double-layer bearing's steady speed ratio against shaft speed
(:func:`bearingsim.assemblies.double_layer.figures.rs_figure`).
"""

from __future__ import annotations

from typing import Any

from bearingsim.assemblies.double_layer.figures import rs_figure
from bearingsim.assemblies.spec import AssemblyPlot

__all__ = ["motor_drive_plots"]


def motor_drive_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Rs of the bearing against shaft speed.

    Parameters
    ----------
    args : dict
        Every argument of the assembly's ``SCENE_SPEC.args`` (defaults filled in).
    fidelity : str
        Fidelity level of the scene, one of the spec's levels.

    Returns
    -------
    list of AssemblyPlot
        The bearing's Rs figure where its level has one.
    """
    return [AssemblyPlot("rs_speed", ("bearing.w_shaft", "bearing.Rs"),
                         rs_figure("bearing.", args["bearing"], "motor.w_ref"))]
