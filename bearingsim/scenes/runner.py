"""Run a scene: choose the fidelity, assemble only what the outputs need, simulate, write.

``prepare`` builds and assembles the model (pruned to the requested outputs) and checks the
scene's names against it; ``run_scene`` simulates, computes the post-processed quantities and
writes CSV, a JSON summary (with everything that was skipped) and PNG plots.
"""

from __future__ import annotations

import contextlib
import glob
import json
import math
import re
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.assembler import System, assemble_cached
from bearingsim.assemblies.spec import AssemblyPlot, AssemblySpec, PostQuantity
from bearingsim.errors import ModelError, ParameterError
from bearingsim.files import atomic_path, column_name, write_series_csv
from bearingsim.plotting import set_value_scale
from bearingsim.scenes.analyses import (
    STATICS_INPUTS,
    NotSettledWarning,
    operating_points,
    point_label,
    point_units,
    run_points,
    settling_check,
    steady_values,
)
from bearingsim.scenes.expressions import compile_expression
from bearingsim.scenes.outputs import OutputFolder, command_line
from bearingsim.scenes.plots import BUILTIN_PLOTS, analysis_figures, render_report
from bearingsim.scenes.registry import build_component
from bearingsim.scenes.scene import Scene, SceneError, TableInput, line_of, scene_from_dict
from bearingsim.scenes.tables import scene_output_folder
from bearingsim.simulation import Result, simulate

__all__ = [
    "Prepared",
    "SceneRun",
    "choose_fidelity",
    "console_lines",
    "prepare",
    "run_scene",
    "scene_figures",
    "simulate_inputs",
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

    @property
    def outputs(self) -> list[str]:
        """The requested outputs in order (model and post-processed); for a statics scene the
        columns of its assembly's statics solution."""
        if self.scene.analysis == "statics":
            from bearingsim.scenes.analyses import statics_of

            return list(statics_of(self).columns)
        return self.scene.outputs or [n for n in self.spec.default_outputs
                                      if n in self.model_outputs or n in self.post]


@dataclass
class SceneRun:
    """The outcome of :func:`run_scene`."""

    prepared: Prepared
    result: Result | None
    """The run in time (None for the analyses steady, modes and statics)."""
    series: dict[str, np.ndarray]
    """Requested outputs by name (post-processed ones included); for an analysis, the table's
    columns (one value per operating point)."""
    summary: dict[str, Any]
    files: list[Path]
    rows: list[dict[str, Any]] = field(default_factory=list)
    """An analysis's table: one row per operating point (plain names, SI values)."""


def _check(scene: Scene) -> Scene:
    """Re-validate a scene built in Python (dataclass) through the TOML validator."""
    if scene.text is not None:
        return scene
    return scene_from_dict(scene.to_dict(), path=scene.path, allow_paths=scene.allow_paths)


def choose_fidelity(scene: Scene, spec: AssemblySpec, post: dict[str, PostQuantity]
                    ) -> tuple[str, str, list[str]]:
    """The fidelity to assemble, why, and the lower levels rejected for accuracy.

    ``auto`` takes the lowest level in ``spec.auto_fidelities`` that provides every requested
    output, every input and parameter the scene sets, and every post-processed quantity, and
    whose measured error (:meth:`~bearingsim.assemblies.spec.AssemblySpec.level_error`) on each
    requested output is within ``scene.tolerance``; a level that is too inaccurate for one
    output is rejected for the whole scene.
    """
    if spec.fidelity_arg is None:
        return spec.fidelities[0], "the assembly has a single fidelity level", []
    if scene.fidelity != "auto":
        return scene.fidelity, "requested by the scene", []
    order = list(spec.auto_fidelities)
    need = {}
    names = list(scene.outputs or spec.default_outputs)
    for n in names:
        need[n] = post[n].fidelity if n in post else spec.min_fidelity(n)
    point_names = [k.split(".", 1)[1] for k in _point_keys(scene)
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


def _point_keys(scene: Scene) -> list[str]:
    """The keys an operating grid or the load cases set."""
    keys = list(scene.grid)
    for case in scene.cases:
        keys += [k for k in case if k != "name" and k not in keys]
    return keys


def scene_inputs(scene: Scene) -> dict[str, Any]:
    """The inputs a scene sets: its ``inputs`` and those of its grid or cases (the text
    ``"varies"`` for one that is not 0 at every point)."""
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

    Raises
    ------
    SceneError
        For names the model does not have (outputs, inputs, parameters, initial values) or
        parameter values outside their range, naming the key and line.
    """
    scene = _check(scene)
    spec = scene.spec
    args = spec.with_defaults(scene.args)
    if scene.analysis != "modes":  # modes need every degree of freedom
        args.update(spec.symmetric_args(args, scene_inputs(scene)))
    post_all = spec.post(args)
    # a statics scene solves its own equilibrium: no default outputs to keep
    requested = list(scene.outputs or ([] if scene.analysis == "statics"
                                       else spec.default_outputs))
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
                             "model variables (see the CSV of a run without 'outputs') or "
                             "post-processed: " + (", ".join(post_all) or "none"),
                             scene.path) from None
    assemble_s = time.perf_counter() - t0
    _check_names(scene, system)
    symmetry = spec.symmetry(args, scene_inputs(scene)) if scene.analysis != "modes" else []
    prep = Prepared(scene, spec, args, fidelity, reason, system, model_outputs, post,
                    symmetry, assemble_s, attempts, rejected, plots, plot_outputs)
    if scene.analysis == "statics":
        from bearingsim.scenes.analyses import statics_of

        statics_of(prep)  # an assembly without statics: an error before anything runs
    return prep


def assembly_plots(spec: AssemblySpec, args: dict[str, Any], fidelity: str
                   ) -> list[AssemblyPlot]:
    """The figures of an assembly at a level: those its spec declares
    (:attr:`~bearingsim.assemblies.spec.AssemblySpec.plots`) and, for a built-in assembly,
    those of :data:`bearingsim.scenes.plots.BUILTIN_PLOTS`."""
    builtin = BUILTIN_PLOTS.get(spec.name)
    return spec.plots(args, fidelity) + (builtin(args, fidelity) if builtin else [])


def _check_names(scene: Scene, system: System) -> None:
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
    for n, si in scene.input_units.items():
        if n in units and units[n] != si:
            add(f"inputs.{n}", f"input {n} is in {units[n]}, but the value's unit is one of "
                f"{si}", f"a number with a unit of {units[n]}, or a number in {units[n]}")
    missing = [n for n in system.input_names
               if n not in given and not scene.spec.is_optional_input(n)]
    if missing:
        add("inputs", "input(s) not given: " + ", ".join(f"{n} [{units[n]}]" for n in missing)
            + " (the run would hold them at their start value, e.g. a speed of 0)",
            "a number, an expression of t or a table for each; inputs that may be left out: "
            + (", ".join(scene.spec.optional_inputs) or "none"))
    for key in _point_keys(scene):
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
    if problems:
        first = problems[0]
        raise SceneError(first.reason, first.key, first.line, first.allowed, first.path,
                         problems=problems)


def simulate_inputs(inputs: dict[str, Any]) -> dict[str, Any]:
    """Scene inputs as accepted by ``simulate``: expressions compiled, tables as arrays."""
    out = {}
    for k, v in inputs.items():
        if isinstance(v, str):
            out[k] = compile_expression(v, f"inputs.{k}")
        elif isinstance(v, TableInput):
            out[k] = v.as_tuple()
        else:
            out[k] = v
    return out


def validate_scene(scene: Scene | str | Path, assemble_model: bool = True,
                   allow_paths: list[str | Path] | tuple = ()) -> Prepared | Scene:
    """Check a scene without running it: the file, and (by default) its names against the
    assembled model. Returns the :class:`Prepared` scene (or the :class:`Scene`);
    ``allow_paths`` as :func:`~bearingsim.scenes.scene.load_scene` takes it."""
    from bearingsim.scenes.scene import load_scene

    if not isinstance(scene, Scene):
        scene = load_scene(scene, allow_paths)
    scene = _check(scene)
    return prepare(scene) if assemble_model else scene


def _json_safe(v: Any) -> Any:
    if isinstance(v, dict):
        return {str(k): _json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_json_safe(x) for x in v]
    if isinstance(v, (np.floating, float)):
        return float(v) if math.isfinite(float(v)) else None
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.ndarray):
        return _json_safe(v.tolist())
    return v


def run_simulation(prep: Prepared, parameters: dict[str, float] | None = None,
                   inputs: dict[str, Any] | None = None, progress: bool | None = False,
                   **overrides) -> Result:
    """Simulate a prepared scene (optionally with other parameters, inputs or settings;
    ``progress`` as :func:`~bearingsim.simulation.simulate` takes it)."""
    s = prep.scene.simulation
    opts = {"t_start": s.t_start, "method": s.method, "rtol": s.rtol, "atol": s.atol,
            "n_points": s.n_points, "max_step": s.max_step, "initial": s.initial}
    opts.update(overrides)
    t_end = opts.pop("t_end", s.t_end)
    params = {**prep.scene.parameters, **(parameters or {})}
    ins = simulate_inputs({**prep.scene.inputs, **(inputs or {})})
    return simulate(prep.system, t_end, inputs=ins, parameters=params,
                    x0=prep.scene.initial or None, progress=progress, **opts)


def output_series(prep: Prepared, result: Result) -> dict[str, np.ndarray]:
    """The requested outputs: model series from the result, post-processed ones computed."""
    series = {n: np.asarray(result[n]) for n in prep.model_outputs}
    out = {}
    for n in prep.outputs:
        if n in prep.post:
            out[n] = np.asarray(prep.post[n].compute(series), dtype=float)
        else:
            out[n] = series[n]
    return out


def settling(prep: Prepared, result: Result, series: dict[str, np.ndarray]
             ) -> dict[str, Any]:
    """Whether a transient run's outputs settled (:func:`~bearingsim.scenes.analyses.
    settling_check`, the scene's criterion), with the steady values of the outputs under the
    final inputs where a steady state is found (started from the final state); warns
    (:class:`~bearingsim.scenes.analyses.NotSettledWarning`) naming the outputs that had not
    settled, unless the scene reports a transient on purpose."""
    scene = prep.scene
    if scene.transient_on_purpose:
        return {"transient_on_purpose": True, "settled": None, "time_constant": None,
                "criterion": "not checked: the scene reports a transient on purpose"}
    check = settling_check(result.t, series, scene.settling)
    check["transient_on_purpose"] = False
    check["steady"] = {}
    if check["settled"]:
        return check
    x_end = np.array([result.final(n) for n in prep.system.state_names])
    steady = steady_values(prep, dict(result.inputs), dict(result.parameters), x_end,
                           float(result.t[-1]))
    check["steady"] = {n: steady[n] for n in check["unsettled"]} if steady else {}
    units = _units(prep, result)
    from bearingsim.scenes.plots import display_text

    parts = []
    for n in check["unsettled"]:
        text = (f"{n} = {display_text(float(series[n][-1]), units.get(n, ''))} changed by "
                f"{check['outputs'][n]['change']:.2g} of its value")
        if n in check["steady"]:
            text += f" (steady value {display_text(check['steady'][n], units.get(n, ''))})"
        parts.append(text)
    tau = check["time_constant"]
    warnings.warn(
        f"{scene.title}: not settled at t_end = {result.t[-1]:g} s ({check['criterion']}): "
        + "; ".join(parts)
        + (f"; time constant about {tau:.3g} s" if math.isfinite(tau) else "")
        + ". Run longer (simulation.t_end), ask analysis = \"steady\" for the settled "
        "point, or set transient_on_purpose = true", NotSettledWarning, stacklevel=3)
    return check


def _units(prep: Prepared, result: Result) -> dict[str, str]:
    return {**getattr(result, "units", {}), **{n: q.unit for n, q in prep.post.items()}}


def summary(prep: Prepared, result: Result, series: dict[str, np.ndarray],
            files: list[Path] | None = None, settled: dict[str, Any] | None = None
            ) -> dict[str, Any]:
    """The JSON summary of a run: sizes, timings, final values, settling and every skip."""
    system = prep.system
    units = _units(prep, result)
    outs = {}
    checked = (settled or {}).get("outputs", {})
    for n, y in series.items():
        finite = y[np.isfinite(y)]
        outs[n] = {"unit": units.get(n, ""), "final": y[-1],
                   "min": finite.min() if finite.size else None,
                   "max": finite.max() if finite.size else None}
        if n in checked:
            outs[n].update(settled=checked[n]["settled"], change=checked[n]["change"],
                           time_constant=checked[n]["time_constant"])
        if n in (settled or {}).get("steady", {}):
            outs[n]["steady"] = settled["steady"][n]
    spec = prep.spec
    higher = []
    if prep.fidelity in spec.fidelities:
        higher = list(spec.fidelities[spec.fidelities.index(prep.fidelity) + 1:])
    return _json_safe({
        "title": prep.scene.title,
        "scene": prep.scene.path,
        "assembly": spec.name,
        "arguments": prep.args,
        "fidelity": {"requested": prep.scene.fidelity, "chosen": prep.fidelity,
                     "reason": prep.fidelity_reason, "attempts": prep.fidelity_attempts,
                     "tolerance": prep.scene.tolerance,
                     "rejected": prep.fidelity_rejected},
        "system": {"states": system.n_states, "inputs": system.input_names,
                   "parameters": len(system.params), "report": system.report},
        "skipped": {
            "pruned": list(system.skipped) or ["nothing: every equation is needed"],
            "fidelity_levels_not_used": higher,
            "post_processed": [
                {"name": q.name, "unit": q.unit, "needs": list(q.needs),
                 "note": f"{q.doc}; computed after the integration at the "
                         f"{result.t.size} save points, not in the right-hand side"}
                for q in prep.post.values()],
            "symmetry": prep.symmetry or ["none applicable to this assembly and load"],
        },
        "simulation": {"t_start": prep.scene.simulation.t_start,
                       "t_end": prep.scene.simulation.t_end,
                       "method": prep.scene.simulation.method,
                       "rtol": prep.scene.simulation.rtol,
                       "atol": prep.scene.simulation.atol, "points": int(result.t.size),
                       "stats": {k: v for k, v in result.stats.items()
                                 if isinstance(v, (int, float, str))}},
        "timings_s": {"assemble": round(prep.assemble_s, 4),
                      "simulate": round(float(result.stats.get("wall_time", 0.0)), 4)},
        "analysis": "transient",
        "settled": (settled or {}).get("settled"),
        "time_constant_s": (settled or {}).get("time_constant"),
        "settling": {k: v for k, v in (settled or {}).items() if k != "outputs"},
        "outputs": outs,
        "files": [str(f) for f in (files or [])],
    })


def _varying_inputs(prep: Prepared, result: Result
                    ) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """The inputs that change during the run, by name, and their units: the model's inputs
    and the assembly's signal arguments given as expressions of t (e.g. a load torque step);
    constant ones are left out."""
    out, units = {}, {}
    for name in prep.system.input_names:
        if name in result:
            out[name] = np.asarray(result[name], dtype=float)
            units[name] = prep.system.inputs[prep.system.input_names.index(name)].unit
    for name, arg in prep.spec.args.items():
        text = prep.args.get(name)
        if arg.kind == "signal" and isinstance(text, str):
            values = compile_expression(text, f"assembly.{name}")(result.t)
            out[name] = np.broadcast_to(np.asarray(values, dtype=float).ravel(), result.t.shape)
            m = re.search(r"\[([^\]]+)\]", arg.doc)
            units[name] = m.group(1).replace(" ", ".") if m else ""
    keep = {n: y for n, y in out.items()
            if y.size and np.ptp(y[np.isfinite(y)]) > 0.0}
    return keep, {n: units[n] for n in keep}


def time_figures(stem: str, t: np.ndarray, series: dict[str, np.ndarray],
                 units: dict[str, str], groups: list[list[str]], title: str,
                 inputs: dict[str, np.ndarray] | None = None, prep: Prepared | None = None
                 ) -> list[tuple[str, Any]]:
    """(file name, :class:`matplotlib.figure.Figure`) of the time traces, made without pyplot.

    The inputs that change during the run are drawn on top of every figure (one panel per
    unit), on the same time axis as the outputs they drive; then one panel per group
    (default: per output), at most 6 panels a figure. Axes are labelled with the variables'
    descriptions (``prep``) and display units (r/min, µm, N mm, kN, ...,
    :func:`bearingsim.scenes.plots.display`); loads, torques and powers on linear axes that
    show 0.
    """
    from matplotlib.figure import Figure

    from bearingsim.scenes.plots import axis_text, describe, display, include_zero

    inputs = inputs or {}
    by_unit: dict[str, list[str]] = {}
    for name in inputs:
        by_unit.setdefault(units.get(name, ""), []).append(name)
    input_groups = list(by_unit.values())
    data = {**inputs, **series}
    groups = groups or [[n] for n in series]
    per_figure = max(6 - len(input_groups), 2)
    figures = []
    for k in range(0, len(groups), per_figure):
        chunk = input_groups + groups[k:k + per_figure]
        fig = Figure(figsize=(7, 1.9 * len(chunk) + 1))
        axes = np.atleast_1d(fig.subplots(len(chunk), 1, sharex=True, squeeze=False)[:, 0])
        for row, (ax, group) in enumerate(zip(axes, chunk, strict=True)):
            unit = units.get(group[0], "")
            shown = []
            for n in group:
                y, label_unit = display(data[n], unit)
                shown.append(y)
                ax.plot(t, np.where(np.isfinite(y), y, np.nan), label=describe(n, prep),
                        color="0.35" if row < len(input_groups) else None)
            if not include_zero(ax, np.concatenate(shown), label_unit):
                set_value_scale(ax, shown)
            text = (axis_text(group[0], prep, label_unit) if len(group) == 1
                    else f"[{label_unit}]")
            ax.set_ylabel(("input: " if row < len(input_groups) else "") + text, fontsize=8)
            if len(group) > 1:
                ax.legend(fontsize=7)
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time [s]")
        fig.suptitle(title, fontsize=10)
        fig.tight_layout()
        figures.append((f"{stem}.png" if k == 0 else f"{stem}_{k // per_figure + 1}.png", fig))
    return figures


def assembly_figures(prep: Prepared, result: Result, series: dict[str, np.ndarray],
                     stem: str) -> list[tuple[str, Any]]:
    """(file name ``<stem>.<plot>.png``, Figure) of the assembly's own plots
    (:attr:`~bearingsim.assemblies.spec.AssemblySpec.plots`) for this run."""
    data = {**{n: np.asarray(result[n]) for n in prep.model_outputs + prep.plot_outputs},
            **series}
    figures = []
    for plot in prep.plots:
        spec = plot.make(prep, result, data)
        if spec is not None:
            figures.append((f"{stem}.{plot.name}.png",
                            render_report(spec, f"{prep.scene.title}\n{spec.title}")))
    return figures


def scene_figures(prep: Prepared, result: Result, series: dict[str, np.ndarray], stem: str,
                  units: dict[str, str]) -> list[tuple[str, Any]]:
    """Every figure of a run: the assembly's plots first, then the time traces.

    Raises
    ------
    SceneError
        When ``output.plot_groups`` names a series that is not an output.
    """
    groups = [g for g in prep.scene.output.plot_groups]
    missing = sorted({n for g in groups for n in g} - set(series))
    if missing:
        raise SceneError(f"plot group names {', '.join(missing)}, which are not "
                         "outputs", "output.plot_groups",
                         line_of(prep.scene.text, "output.plot_groups"),
                         ", ".join(series), prep.scene.path)
    inputs, input_units = _varying_inputs(prep, result)
    return (assembly_figures(prep, result, series, stem)
            + time_figures(stem, result.t, series, {**input_units, **units}, groups,
                           prep.scene.title, inputs, prep))


def run_scene(scene: Scene | str | Path, out: str | Path | None = None, *, write: bool = True,
              overwrite: bool = False, progress: bool | None = None,
              allow_paths: list[str | Path] | tuple = ()) -> SceneRun:
    """Run a scene and (by default) write CSV, JSON summary and plots to its output folder.

    Parameters
    ----------
    scene : Scene or path
        The scene, or a scene TOML file.
    out : path, optional
        Output folder (default: the scene's ``output.folder``).
    write : bool
        Write the files; otherwise only return the results.
    overwrite : bool
        Replace the files of an earlier run of the same scene in the folder; without it they
        are an error (checked before the run).
    progress : bool or None
        The solver's progress bar on standard error: always, never, or (None) when standard
        error is a terminal and the run takes longer than about 2 s.
    allow_paths : sequence of path
        Folders outside the scene file's folder its files may be in
        (:func:`~bearingsim.scenes.scene.load_scene`).

    Returns
    -------
    SceneRun

    Raises
    ------
    SceneError
        When the folder holds an earlier run's files and ``overwrite`` is False.
    """
    from bearingsim.scenes.scene import load_scene

    if not isinstance(scene, Scene):
        scene = load_scene(scene, allow_paths)
    folder = Path(out) if out is not None else scene_output_folder(scene)
    stem = Path(scene.path).stem if scene.path else scene.assembly
    # one writer per folder for the whole run (a second one is told who holds it)
    with OutputFolder(folder, command_line()) if write else contextlib.nullcontext() as lock:
        return _run_and_write(scene, folder, stem, lock, overwrite, progress)


def _run_and_write(scene: Scene, folder: Path, stem: str, lock: OutputFolder | None,
                   overwrite: bool, progress: bool | None) -> SceneRun:
    """:func:`run_scene` with the folder locked (``lock``; None: write nothing)."""
    write = lock is not None
    if write and not overwrite and folder.is_dir():
        earlier = sorted(p.name for p in folder.glob(f"{glob.escape(stem)}*")
                         if p.name in (f"{stem}.csv", f"{stem}.summary.json")
                         # time traces stem(_k).png, assembly plots stem.<plot>.png
                         or re.fullmatch(re.escape(stem) + r"(_\d+|\.(?!sweep\.)\w+)?\.png",
                                         p.name))
        if earlier:
            raise SceneError(f"{folder} holds the files of an earlier run ({', '.join(earlier)}); "
                             f"give --overwrite (run_scene(..., overwrite=True)) to replace "
                             f"them, or another output folder", "output.folder",
                             line_of(scene.text, "output.folder"), path=scene.path)
    prep = prepare(scene)
    if scene.analysis != "transient":
        return _run_analysis(prep, stem, lock)
    result = run_simulation(prep, progress=progress)
    series = output_series(prep, result)
    for n, y in series.items():
        if np.any(np.isnan(y)):
            raise ModelError(f"output {n} has NaN values; please report this scene")
    files: list[Path] = []
    units = _units(prep, result)
    settled = settling(prep, result, series)
    if write:
        # the earlier summary goes first, the new one comes last (naming its files)
        lock.retire(f"{stem}.summary.json")
        if prep.scene.output.csv:
            lock.add(write_series_csv(folder / f"{stem}.csv", result.t, series, units))
        if prep.scene.output.plots:
            lock.save_figures(lambda: scene_figures(prep, result, series, stem, units))
        summary_path = lock.write_summary(f"{stem}.summary.json",
                                          summary(prep, result, series, None, settled))
        data = json.loads(summary_path.read_text())
        files = lock.files
    else:
        data = summary(prep, result, series, files, settled)
    return SceneRun(prep, result, series, data, files)


def analysis_units(prep: Prepared, rows: list[dict[str, Any]]) -> dict[str, str]:
    """SI unit of each column of an analysis table."""
    from bearingsim.scenes.analyses import statics_of

    scene = prep.scene
    units = point_units(prep, scene, _point_keys(scene))
    if scene.analysis == "steady":
        units.update({n: u for n, u in {**prep.system.variable_units,
                                        **{n: q.unit for n, q in prep.post.items()}}.items()
                      if n in prep.outputs})
    elif scene.analysis == "statics":
        units.update({n: unit for n, (unit, _) in statics_of(prep).columns.items()})
    else:
        point = set(units) | {"name"}
        units.update({n: "Hz" for row in rows for n in row if n not in point})
    return units


def write_table(path: Path, rows: list[dict[str, Any]], units: dict[str, str]) -> Path:
    """An analysis table as CSV: one row per operating point, ``name [unit]`` headers (SI),
    written atomically."""
    import csv

    names = [n for n in (rows[0] if rows else {}) if not n.startswith("_")]
    for row in rows[1:]:
        names += [n for n in row if n not in names and not n.startswith("_")]
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([n if n == "name" else column_name(n, units.get(n, "")) for n in names])
        w.writerows([[row.get(n, "") for n in names] for row in rows])
    return path


def _run_analysis(prep: Prepared, stem: str, lock: OutputFolder | None) -> SceneRun:
    """Run a steady, modes or statics scene: one table row per operating point, the figures
    that answer it and the JSON summary (written into ``lock``'s folder, last; None: write
    nothing)."""
    scene = prep.scene
    t0 = time.perf_counter()
    points = operating_points(scene)
    rows = run_points(prep, points)
    solve_s = time.perf_counter() - t0
    units = analysis_units(prep, rows)
    columns = {n: np.array([row.get(n, math.nan) for row in rows])
               for n in rows[0] if n != "name"} if rows else {}
    keys = [point_label(k) for k in _point_keys(scene)]
    if lock is not None:
        lock.retire(f"{stem}.summary.json")
        if scene.output.csv:
            lock.add(write_table(lock.folder / f"{stem}.csv", rows, units))
        if scene.output.plots:
            lock.save_figures(lambda: [(f"{stem}.{name}.png", fig) for name, fig in
                                       analysis_figures(prep, rows, keys, units)])
    data = _json_safe({
        "title": scene.title,
        "scene": scene.path,
        "analysis": scene.analysis,
        "assembly": prep.spec.name,
        "arguments": prep.args,
        "fidelity": {"requested": scene.fidelity, "chosen": prep.fidelity,
                     "reason": prep.fidelity_reason, "attempts": prep.fidelity_attempts,
                     "tolerance": scene.tolerance, "rejected": prep.fidelity_rejected},
        "system": {"states": prep.system.n_states, "inputs": prep.system.input_names},
        "points": len(rows),
        "keys": keys,
        "units": units,
        "rows": rows,
        "timings_s": {"assemble": round(prep.assemble_s, 4), "solve": round(solve_s, 4)},
    })
    files: list[Path] = []
    if lock is not None:
        path = lock.write_summary(f"{stem}.summary.json", data)
        data = json.loads(path.read_text())
        files = lock.files
    return SceneRun(prep, None, columns, data, files, rows)


def console_lines(summary_data: dict[str, Any]) -> list[str]:
    """What ``bearingsim run`` prints of a run's results: a transient's final values with
    whether they settled, or an analysis's table in engineering units."""
    from bearingsim.scenes.plots import display_text

    s = summary_data
    if s.get("analysis", "transient") != "transient":
        units = s["units"]
        lines = [f"  {s['analysis']}: {s['points']} operating point(s)"]
        for row in s["rows"]:
            lines.append("  " + ", ".join(
                f"{n} = {v}" if isinstance(v, str) else
                f"{n} = {display_text(v, units.get(n, ''))}" for n, v in row.items()))
        return lines
    lines = []
    for name, o in s["outputs"].items():
        final = "inf/nan" if o["final"] is None else display_text(o["final"], o["unit"])
        note = ""
        if o.get("settled") is False:
            note = " (NOT settled" + (f"; steady {display_text(o['steady'], o['unit'])}"
                                      if o.get("steady") is not None else "") + ")"
        lines.append(f"  {name} = {final} at t_end{note}")
    st = s.get("settling", {})
    if st.get("transient_on_purpose"):
        lines.append("  transient on purpose: final values not checked for settling")
    elif s.get("settled") is not None:
        tau = s.get("time_constant_s")
        lines.append(f"  settled: {'yes' if s['settled'] else 'NO'} ({st.get('criterion')})"
                     + (f"; time constant {tau:.3g} s" if tau is not None else ""))
    return lines
