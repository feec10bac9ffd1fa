"""What ``outputs`` selects in a scene: model variables and post-processed quantities for a run
in time or a steady scene; for a ``statics`` scene the columns of its assembly's statics
solution (``Q_max``, ``L10h``, ...); for a ``modes`` scene the assembly's named modes
(``axial``, ``radial x``, ...). Before, a statics or modes scene checked its ``outputs``
against the model's variables and then left them out of its table without a word.
"""

from __future__ import annotations

from typing import Any

from bearingsim.scenes.scene import Scene, SceneError, line_of
from bearingsim.scenes.statics_table import STATICS

__all__ = ["ANALYSIS_COLUMNS", "analysis_columns", "check_analysis_outputs", "model_outputs_asked",
           "requested_outputs", "selected_columns"]

ANALYSIS_COLUMNS = ("statics", "modes")
"""The analyses whose ``outputs`` name columns of their own solution, not model variables."""


def model_outputs_asked(scene: Scene) -> list[str]:
    """The scene's ``outputs`` that name model variables or post-processed quantities: all
    of them, or none for a statics or modes scene (:data:`ANALYSIS_COLUMNS`).

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    list of str
        The names (empty: the assembly's defaults apply).
    """
    return [] if scene.analysis in ANALYSIS_COLUMNS else list(scene.outputs)


def requested_outputs(scene: Scene, spec: Any) -> list[str]:
    """The outputs a scene's model is assembled for: its ``outputs`` of model variables and
    post-processed quantities, else the assembly's defaults; none for a statics scene, which
    solves its own equilibrium.

    Parameters
    ----------
    scene : Scene
        The scene.
    spec : AssemblySpec
        Its assembly's spec (:attr:`~bearingsim.assemblies.spec.AssemblySpec.default_outputs`).

    Returns
    -------
    list of str
        The names.
    """
    return model_outputs_asked(scene) or ([] if scene.analysis == "statics"
                                          else list(spec.default_outputs))


def analysis_columns(scene: Scene) -> dict[str, tuple[str, str]]:
    """What a statics or modes scene's ``outputs`` may name: the columns of its assembly's
    statics solution, or the assembly's named modes (natural frequencies); none for the other
    analyses.

    Parameters
    ----------
    scene : Scene
        The scene.

    Returns
    -------
    dict of str to (str, str)
        Column name -> (SI unit, description).
    """
    if scene.analysis == "statics" and scene.spec.name in STATICS:
        return dict(STATICS[scene.spec.name].columns)
    if scene.analysis == "modes":
        return {n: ("Hz", f"natural frequency of the {n} mode")
                for n in scene.spec.mode_names.values()}
    return {}


def check_analysis_outputs(prep: Any) -> None:
    """Refuse ``outputs`` of a statics or modes scene that are not columns of its solution.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).

    Raises
    ------
    SceneError
        Naming the unknown outputs and the columns there are (for modes of an assembly whose
        modes are named only when they are found, saying so).
    """
    scene = prep.scene
    if scene.analysis not in ANALYSIS_COLUMNS or not scene.outputs:
        return
    allowed = list(analysis_columns(scene))
    unknown = [n for n in scene.outputs if n not in allowed]
    if not unknown:
        return
    line = line_of(scene.text, "outputs")
    if not allowed:  # modes named after whichever state dominates them
        raise SceneError(f"a modes scene of {prep.spec.name} cannot select modes by name (its "
                         "modes are named after the state that dominates each, found with "
                         "them); leave outputs out: the table has every mode", "outputs", line,
                         "no outputs", scene.path)
    what = "statics column" if scene.analysis == "statics" else "mode"
    raise SceneError(f"a {scene.analysis} scene's outputs are its {what}s, not model variables: "
                     f"unknown {what} {', '.join(map(repr, unknown))}", "outputs", line,
                     ", ".join(allowed), scene.path)


def selected_columns(prep: Any, row: dict[str, Any]) -> dict[str, Any]:
    """The columns of a statics or modes row that the scene's ``outputs`` select, in their
    order (all of them, in the row's order, without ``outputs``).

    Parameters
    ----------
    prep : Prepared
        The prepared scene.
    row : dict
        The solution's columns by name.

    Returns
    -------
    dict
        The selected columns.
    """
    chosen = prep.scene.outputs
    return {n: row[n] for n in chosen if n in row} if chosen else dict(row)
