"""Checks of a scene's input values against its assembled model: the quantity of each value
given with a unit, (for the preparation of every run and sweep point) the ranges, and outputs
asked for at a shaft speed held at 0 that have no value at rest.
"""

from __future__ import annotations

import fnmatch
import re
import warnings
from typing import Any

import numpy as np

from bearingsim.assembler import System
from bearingsim.errors import ParameterError
from bearingsim.scenes.expressions import constant_value
from bearingsim.scenes.scene import Scene
from bearingsim.scenes.scene_types import simulate_inputs
from bearingsim.simulation.input_ranges import check_input_ranges
from bearingsim.simulation.inputs import input_signal
from bearingsim.units.registry import cycles_hint

__all__ = ["input_range_problems", "input_unit_mismatches", "rest_problems",
           "value_unit_mismatches"]


def input_unit_mismatches(scene: Scene, system: System) -> dict[str, str]:
    """The inputs a scene gives as numbers with a unit of another quantity than the model's
    input (``"5 kN"`` for a speed, or an expression whose ``rpm()`` or ``deg()`` give another
    unit: ``"rpm(100)"`` for a force), each with its message.

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
            + cycles_hint(si, units[n])
            + (f" (the expression {scene.inputs[n]!r}: rpm() converts r/min to rad/s, deg() "
               "degrees to rad)" if isinstance(scene.inputs.get(n), str) else "")
            for n, si in scene.input_units.items() if n in units and units[n] != si}


def value_unit_mismatches(scene: Scene, system: System) -> dict[str, str]:
    """The parameters and initial values a scene gives as numbers with a unit of another
    quantity than the model's (``"5 kg"`` for a force), each with its message.

    Parameters
    ----------
    scene : Scene
        The scene (its :attr:`~bearingsim.scenes.scene.Scene.value_units`).
    system : System
        The model.

    Returns
    -------
    dict of str to str
        Key (``parameters.<name>``, ``initial.<state>``) -> message.
    """
    units = {"parameters": {p.name: p.unit for p in system.params},
             "initial": {x.name: x.unit for x in system.states}}
    out = {}
    for key, si in scene.value_units.items():
        section, name = key.split(".", 1)
        unit = units.get(section, {}).get(name)
        if unit is not None and unit != si:
            what = "parameter" if section == "parameters" else "state"
            out[key] = (f"{what} {name} is in {unit}, but its value is given in {si}"
                        + cycles_hint(si, unit))
    return out


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
    problems: dict[str, str] = {}
    for point in _points(scene):
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


def _points(scene: Scene) -> list[dict[str, Any]]:
    """The inputs each operating point gives beyond the scene's own ``[inputs]``: every grid
    value with the first of the others, or every case."""
    swept = {key[len("inputs."):]: values for key, values in scene.grid.items()
             if key.startswith("inputs.")}
    first = {name: values[0] for name, values in swept.items()}
    return [{k[len("inputs."):]: v for k, v in case.items() if k.startswith("inputs.")}
            for case in scene.cases] or [first, *({**first, name: v} for name, values in
                                                    swept.items() for v in values[1:])]


def rest_problems(scene: Scene, outputs: list[str]) -> dict[str, str]:
    """The outputs asked for that have no value at rest
    (:attr:`~bearingsim.assemblies.spec.AssemblySpec.undefined_at_rest`) while a point holds
    the input ``shaft_speed`` at 0, by the key that gives that speed (``inputs.shaft_speed``,
    ``grid`` or ``cases``).

    Parameters
    ----------
    scene : Scene
        The scene.
    outputs : list of str
        The outputs it asks for (its own or the assembly's defaults).

    Returns
    -------
    dict of str to str
        Key -> the message for it.
    """
    undefined = scene.spec.undefined_at_rest
    why = {n: next(r for p, r in undefined.items() if fnmatch.fnmatchcase(n, p))
           for n in outputs if any(fnmatch.fnmatchcase(n, p) for p in undefined)}
    problems: dict[str, str] = {}
    for point in _points(scene) if why else ():
        speed = {**scene.inputs, **point}.get("shaft_speed")
        if speed is None or constant_value(speed, "inputs.shaft_speed") != 0.0:
            continue
        key = ("grid" if scene.grid else "cases") if "shaft_speed" in point else \
            "inputs.shaft_speed"
        problems.setdefault(key, (
            f"input shaft_speed = 0 rad/s holds the shaft at rest, where the outputs "
            f"{', '.join(why)} have no value: " + "; ".join(dict.fromkeys(why.values()))
            + "; valid range of shaft_speed: other than 0 [rad/s]"))
    return problems
