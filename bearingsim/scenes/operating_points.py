"""The operating points of a scene and the model that runs each.

A scene's points are every combination of its ``grid``, its load ``cases`` or its ``inputs``
alone (:func:`operating_points`); a point's keys become table columns (:func:`point_label`,
:func:`point_units`) and split into inputs, parameter values and assembly arguments
(:func:`split_point`). :func:`point_model` gives the model that runs a point: the prepared
one with parameter overrides when the point only changes parametric arguments, else one
assembled for its arguments. Running a point is
:func:`bearingsim.scenes.analyses.run_operating_point`.
"""

from __future__ import annotations

import itertools
import re
from typing import Any

from bearingsim.errors import BearingsimError
from bearingsim.scenes.preparation import point_keys, prepare
from bearingsim.scenes.scene import Scene, SceneError, line_of

__all__ = ["SIMULATION_UNITS", "filled_point", "key_unit", "operating_points", "point_label",
           "point_model", "point_units", "split_point"]


def operating_points(scene: Scene) -> list[dict[str, Any]]:
    """The operating points of a scene: every combination of its ``grid`` (the first key
    varying fastest), its ``cases`` in order, or one point of its ``inputs`` alone.

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Returns
    -------
    list of dict
        One ``{key: value}`` per operating point.
    """
    if scene.cases:
        return [dict(c) for c in scene.cases]
    if not scene.grid:
        return [{}]
    keys = list(scene.grid)
    combos = itertools.product(*(scene.grid[k] for k in reversed(keys)))
    return [dict(zip(keys, reversed(combo), strict=True)) for combo in combos]


def point_label(key: str) -> str:
    """The table column of a point key: ``inputs.shaft_speed`` -> ``shaft_speed``.

    Parameters
    ----------
    key : str
        A point key (``inputs.X``, ``parameters.X`` or an assembly argument).

    Returns
    -------
    str
        The column name.
    """
    return key.split(".", 1)[1] if key.split(".", 1)[0] in ("inputs", "parameters",
                                                              "assembly") else key


SIMULATION_UNITS = {"t_end": "s", "t_start": "s", "max_step": "s", "timeout": "s",
                    "rtol": "1", "n_points": "1"}
"""SI units of the numeric ``simulation.*`` settings a point may set (``atol`` is in each
state's own unit: none)."""


def key_unit(prep: Any, scene: Scene, key: str) -> str:
    """SI unit of the values of a point key: an input's, parameter's or state's from the model,
    an assembly argument's from the ``[unit]`` of its description, a simulation setting's
    (:data:`SIMULATION_UNITS`); ``""`` for text and for a key of no one unit.

    Parameters
    ----------
    prep : Prepared or None
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`; None: no model).
    scene : Scene
        The loaded scene.
    key : str
        The point key (``inputs.Fr``, ``assembly.preload_force``, ``simulation.t_end``, ...).

    Returns
    -------
    str
        The SI unit (``"1"``: dimensionless).
    """
    system = prep.system if prep is not None else None
    head, _, rest = key.partition(".")
    if head == "inputs" and system is not None and rest in system.input_names:
        return system.inputs[system.input_names.index(rest)].unit
    if head == "inputs":
        return scene.input_units.get(rest, "N" if re.search(r"\bF[xyzra]$", rest) else "")
    if head == "parameters" and system is not None and rest in system.parameter_names:
        return system.params[system.parameter_names.index(rest)].unit
    if head == "initial" and system is not None:
        return system.variable_units.get(rest, "")
    if head == "assembly":  # a number's unit, from its description (ArgSpec.unit)
        arg = scene.spec.args.get(rest)
        return arg.unit if arg is not None and arg.kind in ("float", "signal") else ""
    if head == "simulation":
        return SIMULATION_UNITS.get(rest, "")
    return ""


def point_units(prep: Any, scene: Scene, keys: list[str]) -> dict[str, str]:
    """SI unit of each point key's column (:func:`key_unit`).

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    scene : Scene
        The loaded scene.
    keys : list of str
        The point keys.

    Returns
    -------
    dict of str to str
        SI unit by column name.
    """
    return {point_label(key): key_unit(prep, scene, key) for key in keys}


def filled_point(prep: Any, point: dict[str, Any]) -> dict[str, Any]:
    """An operating point with every key the scene's grid or cases set, in their order: a key
    this point leaves out holds the value its run uses (the scene's own ``inputs`` or
    ``parameters``, the assembly's argument, else the model's default), so that a table of
    load cases has no blank cells.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    point : dict
        An operating point, ``{key: value}`` (``name`` is kept as it is).

    Returns
    -------
    dict
        ``{key: value}``; a key whose value no one states (an input the model does not have)
        is left out.
    """
    keys = dict.fromkeys([*point_keys(prep.scene), *(k for k in point if k != "name")])
    used = _used_values(prep, point, [k for k in keys if k not in point])
    filled = {k: v for k, v in point.items() if k == "name"}
    for key in keys:
        if key in point or key in used:
            filled[key] = point[key] if key in point else used[key]
    return filled


def _used_values(prep: Any, point: dict[str, Any], keys: list[str]) -> dict[str, Any]:
    """The values a run of ``point`` uses for ``keys`` it does not give: the scene's own, else
    the model's or the assembly's default (none for a key without one). A grid point gives
    every key: nothing is looked up."""
    if not keys:
        return {}
    system = prep.system
    inputs, parameters, args = split_point(prep.scene, point)
    heads = {key.partition(".")[0] for key in keys}
    sources = {"inputs": [inputs], "parameters": [parameters], "assembly": [args]}
    if "inputs" in heads:
        sources["inputs"].append(dict(zip(system.input_names, system.u_default().tolist(),
                                          strict=True)))
    if "parameters" in heads:
        sources["parameters"].append(dict(zip(system.parameter_names, system.p0().tolist(),
                                              strict=True)))
    if "assembly" in heads:
        sources["assembly"].append(prep.spec.with_defaults(args))
    used = {}
    for key in keys:
        head, _, rest = key.partition(".")
        found = [source[rest] for source in sources.get(head, ()) if rest in source]
        if found:
            used[key] = found[0]
    return used


def split_point(scene: Scene, point: dict[str, Any]
                ) -> tuple[dict[str, float], dict[str, float], dict[str, Any]]:
    """The inputs, parameter values and assembly arguments of an operating point (the scene's
    own merged with the point's).

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    point : dict
        An operating point, ``{key: value}``.

    Returns
    -------
    tuple of (dict, dict, dict)
        Inputs [SI], parameter values [SI] and assembly arguments.
    """
    inputs = {k: v for k, v in scene.inputs.items()}
    parameters = dict(scene.parameters)
    args = dict(scene.args)
    for key, value in point.items():
        head, _, rest = key.partition(".")
        if head == "inputs":
            inputs[rest] = value
        elif head == "parameters":
            parameters[rest] = value
        elif head == "assembly":
            args[rest] = value
    return inputs, parameters, args


def _parameter_values(component) -> dict[str, float]:
    from bearingsim.language.declarations import Parameter

    return {decl.path: float(decl.value) for comp in component.walk()
            for decl in comp.declarations.values()
            if isinstance(decl, Parameter) and decl.value is not None}


def _is_parametric(spec: Any, key: str, args: dict[str, Any]) -> bool:
    holds = spec.parametric_args.get(key)
    return holds is not None and bool(holds(args))


def point_model(prep: Any, args: dict[str, Any]) -> tuple[Any, dict[str, float]]:
    """The prepared model that runs an operating point with the assembly arguments ``args``,
    and the parameter overrides it needs.

    Arguments the assembly declares parametric
    (:attr:`~bearingsim.assemblies.spec.AssemblySpec.parametric_args`, e.g. a duplex pair's
    preload) become parameter overrides of the assembled model of ``prep``; any other changed
    argument (an arrangement, a bearing) assembles the model for those arguments, once per
    distinct set (cached on ``prep``).

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    args : dict
        The point's assembly arguments.

    Returns
    -------
    tuple of (Prepared, dict of str to float)
        The prepared model and its parameter overrides (SI units).

    Raises
    ------
    SceneError
        When an argument declared parametric changes the model's parameters (please report),
        or the arguments are invalid.
    """
    from bearingsim.scenes.registry import build_component

    spec = prep.spec
    full = spec.with_defaults(args)
    full.update({k: v for k, v in prep.args.items() if k not in spec.args})  # symmetry
    changed = [k for k in spec.args if full.get(k) != prep.args.get(k)]
    if not changed:
        return prep, {}
    cache = prep.__dict__.setdefault("_point_models", {})
    structural = [k for k in changed if not _is_parametric(spec, k, full)]
    if structural:
        key = repr(sorted((k, repr(full[k])) for k in structural))
        if key not in cache:
            scene = prep.scene
            base = {k: v for k, v in scene.args.items()}
            base.update({k: full[k] for k in structural})
            cache[key] = prepare(scene.replace(args=base))
        return point_model(cache[key], args)
    if "base" not in cache:
        cache["base"] = _parameter_values(build_component(spec, prep.args, prep.fidelity))
    base_values = cache["base"]
    try:
        new = _parameter_values(build_component(spec, full, prep.fidelity))
    except BearingsimError as exc:
        raise SceneError(str(exc), "grid", line_of(prep.scene.text, "grid"),
                         path=prep.scene.path) from None
    if set(new) != set(base_values):
        raise SceneError(f"the assembly argument(s) {', '.join(changed)}, declared parametric, "
                         "change the model's structure; please report", "grid",
                         line_of(prep.scene.text, "grid"), path=prep.scene.path)
    names = set(prep.system.parameter_names)
    return prep, {n: v for n, v in new.items() if n in names and v != base_values[n]}
