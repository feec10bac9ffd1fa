"""A scene's assembly as an FMU: ``bearingsim export-fmu scene.toml model.fmu``.

The FMU holds the model the scene runs: its assembly with the scene's arguments, at the level
the scene's fidelity chooses (``auto``: the cheapest within the scene's tolerance for its
outputs), the scene's own bearings and lubricants (registered when the scene is read), its
outputs (those of the model; post-processed quantities such as a life are computed after a
run, so they are no FMU output; a statics scene's columns come from its statics solver, and
its FMU outputs the assembly's own) and its ``[parameters]`` and constant inputs as start
values. An input the scene gives as an expression of ``t`` or a table stays an FMU input
without a start value: the importer drives it. The axisymmetric reduction of a transient
scene is not applied (it holds only for the scene's own loads, and the FMU's inputs are
free).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from bearingsim.fmu.cli import scene_outputs
from bearingsim.scenes.expressions import constant_value
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.scenes.preparation import point_keys, prepare
from bearingsim.scenes.registry import build_component
from bearingsim.scenes.scene import load_scene

__all__ = ["SceneFMU", "scene_fmu"]


@dataclass(frozen=True)
class SceneFMU:
    """What :func:`~bearingsim.fmu.export.export_fmu` is given for a scene.

    Attributes
    ----------
    model : Component
        The scene's assembly at its level.
    fidelity : str
        That level.
    outputs : list of str
        The scene's outputs the model has.
    inputs : dict of str to float
        Start values [SI] of the inputs the scene holds constant.
    parameters : dict of str to float
        The scene's ``[parameters]`` [SI].
    notes : list of str
        What the FMU leaves out of the scene (post-processed outputs, inputs that vary in
        time), one line each.
    """

    model: Any
    fidelity: str
    outputs: list[str]
    inputs: dict[str, float]
    parameters: dict[str, float]
    notes: list[str] = field(default_factory=list)


def scene_fmu(name: str) -> SceneFMU | None:
    """The FMU arguments of a scene file (``*.toml``) or built-in scene, or None when ``name``
    names neither (an assembly name, a factory).

    Parameters
    ----------
    name : str
        A scene file or the name of a built-in scene (``bearingsim list``).

    Returns
    -------
    SceneFMU or None
        The model, its outputs, start values and notes.

    Raises
    ------
    SceneError
        For an invalid scene, naming its key and line.
    """
    if not name.endswith(".toml") and builtin_scene_path(name) is None:
        return None
    scene = load_scene(name)  # its bearings and lubricants registered, for the build below
    prep = prepare(scene)
    model = build_component(prep.spec, prep.spec.with_defaults(scene.args), prep.fidelity)
    post = [n for n in prep.outputs if n in prep.post]
    inputs, varying = {}, []
    for n, value in scene.inputs.items():
        constant = constant_value(value, f"inputs.{n}")  # (None: of t, or a table)
        if constant is None:
            varying.append(n)
        else:
            inputs[n] = constant
    notes = []
    if post:
        needs = list(dict.fromkeys(n for q in post for n in prep.post[q].needs))
        shown = ", ".join(needs[:4]) + (f" and {len(needs) - 4} more" if len(needs) > 4 else "")
        notes.append(f"post-processed after a run, not FMU outputs: {', '.join(post)} "
                     f"(computed from {shown}: --outputs exports those)")
    if varying:
        notes.append(f"inputs the scene varies in time, left to the importer (no start "
                     f"value): {', '.join(varying)}")
    keys = point_keys(scene)
    if keys:
        notes.append(f"the scene's {'grid' if scene.grid else 'load cases'} ({', '.join(keys)}) "
                     "are operating points of its runs, not of the FMU: one model with the "
                     "scene's own [assembly] (its inputs and parameters set by the importer)")
    known = set(prep.system.observed_names)
    outputs = [n for n in prep.outputs if n in known]
    if scene.analysis == "statics":  # its columns come from the statics solver
        notes.append(f"the statics columns ({', '.join(prep.outputs)}) are solved after the "
                     "model, not FMU outputs: the FMU outputs the model's own")
        outputs = scene_outputs(prep.spec, model, prep.fidelity)
    return SceneFMU(model, prep.fidelity, outputs, inputs, dict(scene.parameters), notes)
