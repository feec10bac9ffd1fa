"""Prepare a scene: choose the fidelity, assemble only what the outputs need.

``prepare`` builds and assembles the model (pruned to the requested outputs) and checks the
scene's names against it. Simulating a prepared scene is :mod:`bearingsim.scenes.scene_simulation`
(``run_simulation``, ``output_series``); running a whole scene and writing its files is
:func:`bearingsim.scenes.runner.run_scene`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.assembler import System, assemble_cached
from bearingsim.assemblies.spec import AssemblyPlot, AssemblySpec, PostQuantity
from bearingsim.errors import ModelError, ParameterError
from bearingsim.scenes import analysis_outputs
from bearingsim.scenes.registry import build_component
from bearingsim.scenes.scene import Scene, SceneError, line_of, scene_from_dict
from bearingsim.scenes.scene_input_checks import (
    input_range_problems,
    input_unit_mismatches,
    rest_problems,
    value_unit_mismatches,
)
from bearingsim.scenes.statics_table import STATICS_INPUTS, statics_of
from bearingsim.simulation import steady_state
from bearingsim.simulation.statics import static_stiffness
from bearingsim.simulation.steady import turning_angles

__all__ = [
    "Prepared",
    "choose_fidelity",
    "point_keys",
    "prepare",
    "reduced_args",
    "scene_inputs",
    "validate_scene",
]


@dataclass
class Prepared:
    """A scene with its assembled (pruned) system."""

    scene: Scene
    spec: AssemblySpec
    args: dict[str, Any]
    fidelity: str
    fidelity_reason: str
    system: System
    model_outputs: list[str]
    """Variables kept by pruning: the requested ones and those the post-processing reads."""
    post: dict[str, PostQuantity]
    """Requested quantities computed after the integration."""
    symmetry: list[str]
    assemble_s: float
    fidelity_attempts: list[str] = field(default_factory=list)
    fidelity_rejected: list[str] = field(default_factory=list)
    """Lower levels ``auto`` rejected because their measured error exceeds the tolerance."""
    plots: list[AssemblyPlot] = field(default_factory=list)
    """The assembly's figures at the chosen level (when the scene writes plots)."""
    plot_outputs: list[str] = field(default_factory=list)
    """Variables kept by pruning only for those figures (not in the CSV)."""

    def steady(self, inputs: dict[str, float], parameters: dict[str, float],
               x_guess: np.ndarray, t: float = 0.0, residual_tol: float = 1e-9) -> np.ndarray:
        """The steady state of the scene's system (:func:`~bearingsim.simulation.steady_state`)
        under ``inputs`` and ``parameters`` from ``x_guess``, inputs evaluated at ``t`` [s];
        raises :class:`~bearingsim.errors.BearingsimError` where none is found. For an
        assembly's figures, which may not import the runtime.

        Parameters
        ----------
        inputs : dict of str to float
            Input values by name (SI units).
        parameters : dict of str to float
            Parameter values by dotted name (SI units).
        x_guess : ndarray
            Start of the solve (states, SI units).
        t : float
            Time [s] at which inputs are evaluated.
        residual_tol : float
            Residual tolerance of the steady state, > 0.

        Returns
        -------
        ndarray
            The steady states (SI units).
        """
        return steady_state(self.system, inputs=inputs, parameters=parameters, x_guess=x_guess,
                            t=t, residual_tol=residual_tol)

    def observe(self, t: float, x: np.ndarray, inputs: dict[str, float],
                parameters: dict[str, float]) -> dict[str, float]:
        """The observed variables of the scene's system at time ``t`` [s], states ``x`` and the
        given ``inputs`` (the others at their defaults) and ``parameters``.

        Parameters
        ----------
        t : float
            Time [s].
        x : ndarray
            States (SI units).
        inputs : dict of str to float
            Input values by name (SI units).
        parameters : dict of str to float
            Parameter values by dotted name (SI units).

        Returns
        -------
        dict of str to float
            Observed values (SI units) by name.
        """
        system = self.system
        u = system.u_default()
        for name, value in inputs.items():
            u[system.input_names.index(name)] = value
        return system.observe(t, x, u, system.p0(parameters))

    def static_stiffness(self, x: np.ndarray, displacements: tuple[str, ...],
                         loads: tuple[str, ...], inputs: dict[str, float],
                         parameters: dict[str, float]) -> np.ndarray:
        """The exact static stiffness ``d loads / d displacements`` of the scene's system at the
        equilibrium ``x`` (:func:`~bearingsim.simulation.statics.static_stiffness`).

        Parameters
        ----------
        x : ndarray
            The equilibrium states (SI units).
        displacements : tuple of str
            Names of the displacement states.
        loads : tuple of str
            Names of the load inputs.
        inputs : dict of str to float
            Input values by name (SI units).
        parameters : dict of str to float
            Parameter values by dotted name (SI units).

        Returns
        -------
        ndarray
            Stiffness matrix, loads by displacements (SI units).
        """
        return static_stiffness(self.system, x, displacements, loads, inputs, parameters)

    @property
    def outputs(self) -> list[str]:
        """The requested outputs in order (model and post-processed); for a statics scene the
        columns of its assembly's statics solution.

        Returns
        -------
        list of str
            The output names.
        """
        if self.scene.analysis == "statics":
            return list(analysis_outputs.selected_columns(self, statics_of(self).columns))
        return (analysis_outputs.model_outputs_asked(self.scene)
                or [n for n in self.spec.default_outputs
                    if n in self.model_outputs or n in self.post])


def _check(scene: Scene) -> Scene:
    """Re-validate a scene built in Python (dataclass) through the TOML validator."""
    if scene.text is not None:
        return scene
    return scene_from_dict(scene.to_dict(), path=scene.path, allow_paths=scene.allow_paths,
                           carried_units=scene.given_units)


def choose_fidelity(scene: Scene, spec: AssemblySpec, post: dict[str, PostQuantity]
                    ) -> tuple[str, str, list[str]]:
    """The fidelity to assemble, why, and the lower levels rejected for accuracy.

    ``auto`` takes the lowest level in ``spec.auto_fidelities`` that provides every requested
    output, every input and parameter the scene sets, and every post-processed quantity, and
    whose measured error (:meth:`~bearingsim.assemblies.spec.AssemblySpec.level_error`) on each
    requested output is within ``scene.tolerance``; a level that is too inaccurate for one
    output is rejected for the whole scene.

    Parameters
    ----------
    scene : Scene
        The loaded scene.
    spec : AssemblySpec
        The assembly's spec.
    post : dict of str to PostQuantity
        The post-processed quantities the scene requests.

    Returns
    -------
    tuple of (str, str, list of str)
        The level, the reason and the rejected levels.
    """
    if spec.fidelity_arg is None:
        return spec.fidelities[0], "the assembly has a single fidelity level", []
    if scene.fidelity != "auto":
        return scene.fidelity, "requested by the scene", []
    order = list(spec.auto_fidelities)
    need = {}
    names = analysis_outputs.model_outputs_asked(scene) or list(spec.default_outputs)
    for n in names:
        need[n] = post[n].fidelity if n in post else spec.min_fidelity(n)
    point_names = [k.split(".", 1)[1] for k in point_keys(scene)
                   if k.split(".", 1)[0] in ("inputs", "parameters")]
    for n in list(scene.inputs) + list(scene.parameters) + list(scene.initial) + point_names:
        need[n] = spec.min_fidelity(n)
    level = 0
    for fid in need.values():
        level = max(level, order.index(fid) if fid in order else len(order) - 1)
    provided = order[level]
    rejected = []
    for candidate in order[level:]:
        too_far = {n: e for n in names
                   if (e := spec.level_error(candidate, n)) is not None and e > scene.tolerance}
        if not too_far or candidate == order[-1]:
            break
        worst = max(too_far, key=too_far.get)
        rejected.append(
            f"{candidate}: {', '.join(sorted(too_far))} off by up to {too_far[worst]:.0%} "
            f"against '{spec.reference_fidelity}' (measured; tolerance {scene.tolerance:.0%})")
    chosen = candidate
    drivers = sorted(n for n, f in need.items() if f == provided)
    if chosen != provided:
        reason = (f"'{chosen}' is the lowest level whose measured error on the requested "
                  f"outputs is within the tolerance of {scene.tolerance:.0%}")
    elif level == 0:
        reason = (f"'{chosen}' (the lowest level) provides every requested name within the "
                  f"tolerance of {scene.tolerance:.0%}")
    else:
        reason = (f"'{chosen}' is the lowest level that provides "
                  + ", ".join(drivers[:8]) + (" ..." if len(drivers) > 8 else ""))
    return chosen, reason, rejected


def point_keys(scene: Scene) -> list[str]:
    """The keys an operating grid or the load cases set.

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Returns
    -------
    list of str
        The keys (``inputs.<name>``, ``parameters.<name>``, ...), each once, in order.
    """
    keys = list(scene.grid)
    for case in scene.cases:
        keys += [k for k in case if k != "name" and k not in keys]
    return keys


def _reducible(scene: Scene) -> bool:
    """Whether a scene may run the reduced model its loads allow (``symmetric_args``): a run
    in time only. The steady and modes analyses solve for every state and need each degree of
    freedom's load path, which the reduction leaves out (a duplex pair's representative balls
    carry no radial load or moment: its radial and tilt states would have no steady value and
    no stiffness)."""
    return scene.analysis == "transient"


def reduced_args(scene: Scene, args: dict[str, Any], inputs: dict[str, Any]
                 ) -> dict[str, Any]:
    """The assembly arguments of the reduced model a scene runs (empty: the full model).

    Parameters
    ----------
    scene : Scene
        The scene (its analysis and assembly).
    args : dict
        Its assembly arguments, defaults filled in.
    inputs : dict
        The inputs it sets (:func:`scene_inputs`, or a sweep point's).

    Returns
    -------
    dict
        Arguments to merge into ``args``: the assembly's ``symmetric_args`` for a run in time,
        else none.
    """
    return scene.spec.symmetric_args(args, inputs) if _reducible(scene) else {}


def scene_inputs(scene: Scene) -> dict[str, Any]:
    """The inputs a scene sets: its ``inputs`` and those of its grid or cases (the text
    ``"varies"`` for one that is not 0 at every point).

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Returns
    -------
    dict
        Input values by name (SI units, or ``"varies"``).
    """
    inputs = dict(scene.inputs)
    values: dict[str, list[Any]] = {}
    for key, vals in scene.grid.items():
        values.setdefault(key, []).extend(vals)
    for case in scene.cases:
        for key, v in case.items():
            values.setdefault(key, []).append(v)
    for key, vals in values.items():
        head, _, rest = key.partition(".")
        if head == "inputs":
            inputs[rest] = 0.0 if all(v == 0.0 for v in vals) else "varies"
    return inputs


def prepare(scene: Scene) -> Prepared:
    """Validate a scene, choose its fidelity and assemble the pruned model.

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Returns
    -------
    Prepared
        The prepared scene.

    Raises
    ------
    SceneError
        For names the model does not have (outputs, inputs, parameters, initial values) or
        parameter values outside their range, naming the key and line.
    """
    scene = _check(scene)
    scene.register_own()  # its bearings and lubricants, whatever scenes were read since
    spec = scene.spec
    args = spec.with_defaults(scene.args)
    args.update(reduced_args(scene, args, scene_inputs(scene)))
    post_all = spec.post(args)
    requested = analysis_outputs.requested_outputs(scene, spec)
    post = {n: post_all[n] for n in requested if n in post_all}
    model_outputs = [n for n in requested if n not in post]
    for q in post.values():
        model_outputs += [n for n in q.needs if n not in model_outputs]
    fidelity, reason, rejected = choose_fidelity(scene, spec, post)
    attempts = []
    t0 = time.perf_counter()
    while True:
        try:
            component = build_component(spec, args, fidelity)
        except ParameterError as exc:
            raise SceneError(str(exc), "assembly", line_of(scene.text, "assembly"),
                             path=scene.path) from None
        plots = (assembly_plots(spec, args, fidelity)
                 if scene.output.plots and scene.analysis == "transient" else [])
        plot_outputs = list(dict.fromkeys(n for p in plots for n in p.needs
                                          if n not in model_outputs))
        try:
            system = assemble_cached(component, outputs=model_outputs + plot_outputs)
            break
        except ModelError as exc:
            if "unknown output variable" not in str(exc):
                raise
            order = list(spec.auto_fidelities)
            if scene.fidelity == "auto" and fidelity in order and fidelity != order[-1]:
                attempts.append(f"{fidelity}: {exc}")
                fidelity = order[order.index(fidelity) + 1]
                reason += f"; raised to '{fidelity}' ({exc})"
                continue
            key = "outputs"
            raise SceneError(str(exc).replace("unknown output variable", "unknown output"),
                             key, line_of(scene.text, key),
                             "the model's variables (bearingsim validate --variables lists "
                             "them) or post-processed: " + (", ".join(post_all) or "none"),
                             scene.path) from None
    assemble_s = time.perf_counter() - t0
    _check_names(scene, system, requested)
    _check_fixed_point(scene, system, fidelity)
    symmetry = spec.symmetry(args, scene_inputs(scene)) if _reducible(scene) else []
    prep = Prepared(scene, spec, args, fidelity, reason, system, model_outputs, post,
                    symmetry, assemble_s, attempts, rejected, plots, plot_outputs)
    if scene.analysis == "statics":
        statics_of(prep)  # an assembly without statics: an error before anything runs
    analysis_outputs.check_analysis_outputs(prep)
    return prep


def assembly_plots(spec: AssemblySpec, args: dict[str, Any], fidelity: str
                   ) -> list[AssemblyPlot]:
    """The figures of an assembly at a level: those its spec declares
    (:attr:`~bearingsim.assemblies.spec.AssemblySpec.plots`).

    Parameters
    ----------
    spec : AssemblySpec
        The assembly's spec.
    args : dict
        The assembly arguments (defaults filled in).
    fidelity : str
        The fidelity level.

    Returns
    -------
    list of AssemblyPlot
        The figures.
    """
    return spec.plots(args, fidelity)


def _check_fixed_point(scene: Scene, system: System, fidelity: str) -> None:
    """A steady or modes scene needs a fixed point: a model whose angles turn with a speed
    input (balls and cage of a ball-level model) runs periodically (SceneError at
    ``analysis``, before any point is solved)."""
    if scene.analysis not in ("steady", "modes"):
        return
    units = system.variable_units
    speeds = [n for n, v in scene_inputs(scene).items()
              if units.get(n) == "rad/s" and v != 0.0]
    angles = turning_angles(system) if speeds else []
    if angles:
        shown = ", ".join(angles[:4]) + (f" and {len(angles) - 4} more" if len(angles) > 4
                                        else "")
        raise SceneError(
            f"{scene.assembly} at fidelity {fidelity} has no steady state "
            f"while {', '.join(speeds)} turns it: its angles turn with it ({shown}), so its "
            "steady running is periodic, not a fixed point", "analysis",
            line_of(scene.text, "analysis"), "a transient scene (analysis left out), or a "
            "level without these angles (fidelity)", scene.path)


def _check_names(scene: Scene, system: System, outputs: list[str]) -> None:
    problems = []

    def add(key, msg, allowed):
        problems.append(SceneError(msg, key, line_of(scene.text, key), allowed, scene.path))

    given = scene_inputs(scene)
    extra = STATICS_INPUTS if scene.analysis == "statics" else ()
    for n in given:
        if n not in system.input_names and n not in extra:
            key = f"inputs.{n}" if n in scene.inputs else ("grid" if scene.grid else "cases")
            add(key, f"the model has no input {n!r}", ", ".join(system.input_names) or "none")
    units = {sig.name: sig.unit for sig in system.inputs}
    swept = point_keys(scene)
    for n, message in input_unit_mismatches(scene, system).items():
        add(("grid" if scene.grid else "cases") if f"inputs.{n}" in swept else f"inputs.{n}",
            message, f"a number with a unit of {units[n]}, or a number in {units[n]}")
    for key, message in value_unit_mismatches(scene, system).items():
        add(("grid" if scene.grid else "cases") if key in swept else key, message,
            "a number with a unit of the model's quantity, or a number in its SI unit")
    missing = [n for n in system.input_names
               if n not in given and not scene.spec.is_optional_input(n)]
    if missing:
        add("inputs", "input(s) not given: " + ", ".join(f"{n} [{units[n]}]" for n in missing)
            + " (the run would hold them at their start value, e.g. a speed of 0)",
            "a number, an expression of t or a table for each; inputs that may be left out: "
            + (", ".join(scene.spec.optional_inputs) or "none"))
    for key in point_keys(scene):
        head, _, rest = key.partition(".")
        if head == "parameters" and rest not in system.parameter_names:
            add("grid" if scene.grid else "cases", f"the model has no parameter {rest!r}",
                ", ".join(system.parameter_names))
    for n, v in scene.parameters.items():
        try:
            system.p0({n: v})
        except ParameterError as exc:
            allowed = (", ".join(system.parameter_names) if n not in system.parameter_names
                       else "see the range in the message")
            add(f"parameters.{n}", str(exc), allowed)
    for n in scene.initial:
        if n not in system.state_names:
            add(f"initial.{n}", f"{n!r} is not a state of the (pruned) model",
                ", ".join(system.state_names) or "none")
    if not problems:  # every input named and given: their values within the inputs' ranges
        for key, message in input_range_problems(scene, system).items():
            add(key, message, "see the range in the message")
        for key, message in rest_problems(scene, outputs).items():
            add(key, message, "a shaft speed other than 0 (e.g. '1000 rpm', or an expression "
                "of t that starts at 0), or outputs without these")
    if problems:
        first = problems[0]
        raise SceneError(first.reason, first.key, first.line, first.allowed, first.path,
                         problems=problems)


def validate_scene(scene: Scene | str | Path, assemble_model: bool = True,
                   allow_paths: list[str | Path] | tuple = ()) -> Prepared | Scene:
    """Check a scene without running it: the file, and (by default) its names against the
    assembled model. Returns the :class:`Prepared` scene (or the :class:`Scene`);
    ``allow_paths`` as :func:`~bearingsim.scenes.scene.load_scene` takes it.

    Parameters
    ----------
    scene : Scene or str or Path
        The scene or its file.
    assemble_model : bool
        Also assemble the model and check the names against it.
    allow_paths : sequence of str or Path
        Further folders the scene may name files in.

    Returns
    -------
    Prepared or Scene
        The prepared scene, or the scene without ``assemble_model``.
    """
    from bearingsim.scenes.scene import load_scene

    if not isinstance(scene, Scene):
        scene = load_scene(scene, allow_paths)
    scene = _check(scene)
    return prepare(scene) if assemble_model else scene


