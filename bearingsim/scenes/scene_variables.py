"""The variables a scene may ask for as outputs: every variable of its model, unpruned, with
unit and description (``bearingsim validate --variables``), its assembly's post-processed
quantities, and the parameters its ``[parameters]`` may set.
"""

from __future__ import annotations

from dataclasses import dataclass

from bearingsim.errors import ParameterError
from bearingsim.scenes.analysis_outputs import analysis_columns
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
    parameters : list of (str, str, float, str, str)
        Name, SI unit, value (with the scene's ``[parameters]``), allowed range (``"> 0"``,
        ``"0 to 0.01"``, ``""`` for any number) and description of each parameter of the
        model: what ``[parameters]`` may set and a sweep may vary as ``parameters.<name>``.
    columns : list of (str, str, str)
        Name, SI unit and description of what a statics scene's ``outputs`` name (the columns
        of its assembly's statics solution) or a modes scene's (the assembly's named modes);
        empty for the other analyses.
    """

    fidelity: str
    variables: list[tuple[str, str, str]]
    post: list[tuple[str, str, str]]
    parameters: list[tuple[str, str, float, str, str]]
    columns: list[tuple[str, str, str]] = ()


def _range_text(declaration) -> str:
    """A parameter's allowed range as ``bearingsim list`` states an argument's."""
    low, high = getattr(declaration, "low", None), getattr(declaration, "high", None)
    inclusive = getattr(declaration, "low_inclusive", True)
    if low is not None and high is not None:
        return f"{low:g} to {high:g}" if inclusive else f"> {low:g}, <= {high:g}"
    if low is not None:
        return f"{'>=' if inclusive else '>'} {low:g}"
    return f"<= {high:g}" if high is not None else ""


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
    try:
        values = system.p0(scene.parameters)
    except ParameterError as exc:
        raise SceneError(str(exc), "parameters", line_of(scene.text, "parameters"),
                         path=scene.path) from None
    return ModelVariables(
        fidelity,
        [(n, units.get(n, ""), descriptions.get(n, "")) for n in system.observed_names],
        [(n, q.unit, q.doc) for n, q in spec.post(args).items()],
        [(q.name, q.unit, float(v), _range_text(q.declaration), q.description)
         for q, v in zip(system.params, values, strict=True)],
        [(n, unit, text) for n, (unit, text) in analysis_columns(scene).items()])
