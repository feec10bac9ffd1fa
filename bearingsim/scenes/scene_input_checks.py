"""Checks of a scene's input values against its assembled model: the quantity of each value
given with a unit, and (for the preparation of every run and sweep point) the ranges.
"""

from __future__ import annotations

from bearingsim.assembler import System
from bearingsim.scenes.scene import Scene

__all__ = ["input_unit_mismatches"]


def input_unit_mismatches(scene: Scene, system: System) -> dict[str, str]:
    """The inputs a scene gives as numbers with a unit of another quantity than the model's
    input (``"5 kN"`` for a speed), each with its message.

    Parameters
    ----------
    scene : Scene
        The scene (its :attr:`~bearingsim.scenes.scene.Scene.input_units`: the SI unit of each
        input given with a unit, in ``[inputs]``, a grid or cases).
    system : System
        The model.

    Returns
    -------
    dict of str to str
        Input name -> message.
    """
    units = {sig.name: sig.unit for sig in system.inputs}
    return {n: f"input {n} is in {units[n]}, but its value is given in {si}"
            for n, si in scene.input_units.items() if n in units and units[n] != si}
