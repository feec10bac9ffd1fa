"""The plan of a sweep: every point validated, one model per distinct structure, the jobs.

Points that differ only in parameter values (a parametric assembly argument such as a
Palmgren model's lubricant) share a model structure (:func:`plan_sweep` keys them by fidelity
and the non-parametric arguments); each structure is prepared once on the client and shipped
to the workers as bytes (:class:`~bearingsim.scenes.sweep_worker.ModelPayload`, the cache entry
of :mod:`bearingsim.assembler.cache` when there is one).
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import json
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from bearingsim.assembler import cache as system_cache
from bearingsim.errors import ParameterError
from bearingsim.scenes.analysis_outputs import model_outputs_asked
from bearingsim.scenes.preparation import Prepared, choose_fidelity, prepare, reduced_args
from bearingsim.scenes.sampling import SweepError
from bearingsim.scenes.scene import Scene, SceneError
from bearingsim.scenes.scene_input_checks import (
    input_range_problems,
    input_unit_mismatches,
    value_unit_mismatches,
)
from bearingsim.scenes.sweep_grid import (
    check_operating_points,
    check_point_keys,
    coerce,
    point_scene,
    si_values,
)
from bearingsim.scenes.sweep_worker import Job, ModelPayload, registrations

__all__ = ["SweepPlan", "plan_sweep"]


def _structure(sc: Scene) -> tuple[str, str]:
    """Key of the model structure of a point: fidelity and the non-parametric arguments (with
    the symmetry the point's inputs allow, as :func:`~bearingsim.scenes.preparation.prepare`
    uses)."""
    spec = sc.spec
    args = spec.with_defaults(sc.args)
    args.update(reduced_args(sc, args, sc.inputs))
    post_all = spec.post(args)
    post = {n: post_all[n] for n in (model_outputs_asked(sc) or spec.default_outputs)
            if n in post_all}
    fidelity, _, _ = choose_fidelity(sc, spec, post)
    stripped = copy.deepcopy(args)
    for key, holds in spec.parametric_args.items():
        if holds(args):
            path, d = key.split("."), stripped
            for p in path[:-1]:
                d = d.get(p, {})
            d.pop(path[-1], None)
    return fidelity, json.dumps(stripped, sort_keys=True, default=str)


def _texts(value: Any) -> Iterator[str]:
    """Every text in a scene's value, nested tables and lists included (the names a sweep's
    points may look up: designations, lubricants)."""
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for item in value.values():
            yield from _texts(item)
    elif isinstance(value, (list, tuple)):
        for item in value:
            yield from _texts(item)


def _payload(prep: Prepared, names: set[str]) -> ModelPayload:
    """The prepared model as bytes for the workers: the cache entry just used by ``prepare``
    (no second serialization), else the system serialized now; with the client's registered
    bearings and lubricants that ``names`` name."""
    last = system_cache.LAST
    data = system_cache.read_payload(last["path"], last["key"]) if last.get("path") else None
    if data is None:
        data = system_cache.dumps_system(prep.system)
    token = hashlib.sha256(data).hexdigest()
    return ModelPayload(token, dataclasses.replace(prep, system=None), data,
                        registrations(names))


@dataclass
class SweepPlan:
    """The prepared models of a sweep (one per structure), their payloads and the jobs."""

    prepared: dict[tuple, Prepared]
    payloads: dict[tuple, ModelPayload]
    jobs: list[Job]
    structure: dict[int, tuple]
    """Point number -> structure key."""
    values: list[dict[str, Any]]
    """Point number -> swept values (converted)."""


def plan_sweep(scene: Scene, points: list[dict[str, Any]]) -> SweepPlan:
    """Validate every point of a sweep, prepare one model per distinct structure and make
    the jobs.

    Each point's scene, inputs, parameters and assembly arguments (kind, choices, range) are
    checked here, and the first point of each structure builds its model. The parameter
    overrides of an assembly's parametric arguments (a duplex pair's preload: the assembly
    built to read them, tens of milliseconds) are derived where each point runs
    (:func:`~bearingsim.scenes.operating_points.point_model`), in parallel; a value the
    assembly refuses there (a preload no row can carry) fails that point, named in its row,
    while the others run.

    Parameters
    ----------
    scene : Scene
        The swept scene.
    points : list of dict
        The sweep's points (values by sweep key).

    Returns
    -------
    SweepPlan
        The models, their payloads, the jobs and each point's structure and swept values.

    Raises
    ------
    SweepError
        For a point whose values make an invalid scene or model, or that sets other keys than
        the first point, naming the point.
    """
    check_point_keys(points)
    scenes = [point_scene(scene, p) for p in points]
    names = {text for sc in scenes for text in _texts(sc.args)}  # what points look up
    if scene.analysis != "transient":
        check_operating_points(scene, points)
    prepared: dict[tuple, Prepared] = {}
    payloads: dict[tuple, ModelPayload] = {}
    jobs, structure, values, converted = [], {}, [], {}
    for k, (raw, sc) in enumerate(zip(points, scenes, strict=True)):
        pt = {key: coerce(scene, key, v) for key, v in raw.items()}
        key = _structure(sc)
        try:
            if key not in prepared:
                prepared[key] = prepare(sc)
                payloads[key] = _payload(prepared[key], names)
            prep = prepared[key]
            # not the overrides of parametric arguments (point_model builds the assembly to
            # read them, tens of ms a point): each point derives them where it runs
            prep.system.p0(sc.parameters)
        except (SceneError, ParameterError) as exc:
            raise SweepError(f"sweep point {pt}: {exc}") from None
        problems = [*input_unit_mismatches(sc, prep.system).values(),
                    *value_unit_mismatches(sc, prep.system).values(),
                    *input_range_problems(sc, prep.system).values()]
        if problems:
            raise SweepError(f"sweep point {pt}: {problems[0]}")
        for name in sc.inputs:  # (a statics load case also takes the speed, for the life)
            if sc.analysis != "statics" and name not in prep.system.input_names:
                raise SweepError(f"sweep point {pt}: the model has no input {name!r}; inputs: "
                                 + ", ".join(prep.system.input_names))
        jobs.append(Job(k, sc))
        structure[k] = key
        values.append(si_values(pt, converted, sc))
    return SweepPlan(prepared, payloads, jobs, structure, values)
