"""The variables a scene may ask for as outputs: every variable of its model, unpruned, with
unit and description (``bearingsim validate --variables``), and its assembly's post-processed
quantities.
"""

from __future__ import annotations

from dataclasses import dataclass

from bearingsim.errors import ParameterError
from bearingsim.scenes.preparation import reduced_args, scene_inputs
from bearingsim.scenes.scene import Scene, SceneError, line_of

__all__ = ["ModelVariables", "model_variables"]


@dataclass(frozen=True)
class ModelVariables:
    """The variables of a scene's model.

    Attributes
    ----------
    fidelity : str
        The level whose model is listed.
    variables : list of (str, str, str)
        Name, SI unit and description of each variable (states, their derivatives, the
        connectors' fields, the algebraic variables), in the model's order.
    post : list of (str, str, str)
        The same of the assembly's post-processed quantities.
    """

    fidelity: str
    variables: list[tuple[str, str, str]]
    post: list[tuple[str, str, str]]


def model_variables(scene: Scene) -> ModelVariables:
    """Every variable of the model a scene runs, for choosing its ``outputs``: at the scene's
    fidelity (``auto``: the highest level ``auto`` may use, whose model has the most), with
    the scene's assembly arguments, and without its ``outputs`` (unknown names in them, the
    reason to look, are no error here).

    Parameters
    ----------
    scene : Scene
        The loaded scene (its file checked).

    Returns
    -------
    ModelVariables
        The level, the variables and the post-processed quantities.

    Raises
    ------
    SceneError
        For assembly arguments the assembly refuses (naming the ``assembly`` table's line).
    """
    from bearingsim.assembler.cache import assemble_cached
    from bearingsim.scenes.registry import build_component

    spec = scene.spec
    args = spec.with_defaults(scene.args)
    args.update(reduced_args(scene, args, scene_inputs(scene)))
    fidelity = scene.fidelity if scene.fidelity != "auto" else spec.auto_fidelities[-1]
    try:
        system = assemble_cached(build_component(spec, args, fidelity))
    except ParameterError as exc:
        raise SceneError(str(exc), "assembly", line_of(scene.text, "assembly"),
                         path=scene.path) from None
    units, descriptions = system.variable_units, dict(system.observed_descriptions)
    return ModelVariables(
        fidelity,
        [(n, units.get(n, ""), descriptions.get(n, "")) for n in system.observed_names],
        [(n, q.unit, q.doc) for n, q in spec.post(args).items()])
