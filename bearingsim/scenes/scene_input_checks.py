"""Checks of a scene's input values against its assembled model: the quantity of each value
given with a unit, and (for the preparation of every run and sweep point) the ranges.
"""

from __future__ import annotations

import re
import warnings

import numpy as np

from bearingsim.assembler import System
from bearingsim.errors import ParameterError
from bearingsim.scenes.scene import Scene
from bearingsim.scenes.scene_types import simulate_inputs
from bearingsim.simulation.input_ranges import check_input_ranges
from bearingsim.simulation.inputs import input_signal

__all__ = ["input_range_problems", "input_unit_mismatches"]


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


def input_range_problems(scene: Scene, system: System) -> dict[str, str]:
    """The inputs' values a run of the scene would refuse (out of the input's range, not
    finite; :func:`~bearingsim.simulation.input_ranges.check_input_ranges` over the run's time
    span), by the key that gives them: ``inputs.<name>``, or ``grid``/``cases`` for a point's value
    (each with the scene's other inputs). Warnings (a speed above the limiting speed) are the
    run's to give.

    Parameters
    ----------
    scene : Scene
        The scene, every input it gives named by the model.
    system : System
        The model.

    Returns
    -------
    dict of str to str
        Key -> the first message for it.
    """
    names = set(system.input_names)
    span = (scene.simulation.t_start, scene.simulation.t_end)
    times = np.array(span if scene.analysis == "transient" else span[:1])
    where = "grid" if scene.grid else "cases"
    swept = {key[len("inputs."):]: values for key, values in scene.grid.items()
             if key.startswith("inputs.")}
    first = {name: values[0] for name, values in swept.items()}
    # every grid value with the first of the others, or every case (a scene's own inputs
    # complete each)
    points = [{k[len("inputs."):]: v for k, v in case.items() if k.startswith("inputs.")}
              for case in scene.cases] or [first, *({**first, name: v} for name, values in
                                                      swept.items() for v in values[1:])]
    problems: dict[str, str] = {}
    for point in points:
        inputs = {n: v for n, v in {**scene.inputs, **point}.items() if n in names}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                check_input_ranges(system, input_signal(system, simulate_inputs(inputs)), times)
        except ParameterError as exc:
            named = re.match(r"input (\S+)", str(exc))
            name = named.group(1) if named else None
            problems.setdefault(where if name in point or name is None else f"inputs.{name}",
                                str(exc))
    return problems
