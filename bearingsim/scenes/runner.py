"""Run a scene: choose the fidelity, assemble only what the outputs need, simulate, write.

``prepare`` builds and assembles the model (pruned to the requested outputs) and checks the
scene's names against it; ``run_scene`` simulates, computes the post-processed quantities and
writes CSV, a JSON summary (with everything that was skipped) and PNG plots.
"""

from __future__ import annotations

import glob
import json
import math
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.assembler import System, assemble
from bearingsim.assemblies.spec import AssemblyPlot, AssemblySpec, PostQuantity
from bearingsim.errors import ModelError, ParameterError
from bearingsim.files import atomic_path, write_series_csv
from bearingsim.plotting import render, set_value_scale
from bearingsim.scenes.expressions import compile_expression
from bearingsim.scenes.plots import BUILTIN_PLOTS
from bearingsim.scenes.registry import build_component
from bearingsim.scenes.scene import Scene, SceneError, TableInput, line_of, scene_from_dict
from bearingsim.simulation import Result, simulate
from bearingsim.units import display_unit

__all__ = [
    "Prepared",
    "SceneRun",
    "choose_fidelity",
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
        """The requested outputs in order (model and post-processed)."""
        return self.scene.outputs or [n for n in self.spec.default_outputs
                                      if n in self.model_outputs or n in self.post]


@dataclass
class SceneRun:
    """The outcome of :func:`run_scene`."""

    prepared: Prepared
    result: Result
    series: dict[str, np.ndarray]
    """Requested outputs by name (post-processed ones included)."""
    summary: dict[str, Any]
    files: list[Path]


def _check(scene: Scene) -> Scene:
    """Re-validate a scene built in Python (dataclass) through the TOML validator."""
    if scene.text is not None:
        return scene
    return scene_from_dict(scene.to_dict(), path=scene.path)


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
    for n in list(scene.inputs) + list(scene.parameters) + list(scene.initial):
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
    args.update(spec.symmetric_args(args, scene.inputs))
    post_all = spec.post(args)
    requested = list(scene.outputs or spec.default_outputs)
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
        plots = assembly_plots(spec, args, fidelity) if scene.output.plots else []
        plot_outputs = list(dict.fromkeys(n for p in plots for n in p.needs
                                          if n not in model_outputs))
        try:
            system = assemble(component, outputs=model_outputs + plot_outputs)
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
    symmetry = spec.symmetry(args, scene.inputs)
    return Prepared(scene, spec, args, fidelity, reason, system, model_outputs, post,
                    symmetry, assemble_s, attempts, rejected, plots, plot_outputs)


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

    for n in scene.inputs:
        if n not in system.input_names:
            add(f"inputs.{n}", f"the model has no input {n!r}",
                ", ".join(system.input_names) or "none")
    units = {sig.name: sig.unit for sig in system.inputs}
    for n, si in scene.input_units.items():
        if n in units and units[n] != si:
            add(f"inputs.{n}", f"input {n} is in {units[n]}, but the value's unit is one of "
                f"{si}", f"a number with a unit of {units[n]}, or a number in {units[n]}")
    missing = [n for n in system.input_names
               if n not in scene.inputs and not scene.spec.is_optional_input(n)]
    if missing:
        add("inputs", "input(s) not given: " + ", ".join(f"{n} [{units[n]}]" for n in missing)
            + " (the run would hold them at their start value, e.g. a speed of 0)",
            "a number, an expression of t or a table for each; inputs that may be left out: "
            + (", ".join(scene.spec.optional_inputs) or "none"))
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


def validate_scene(scene: Scene | str | Path, assemble_model: bool = True) -> Prepared | Scene:
    """Check a scene without running it: the file, and (by default) its names against the
    assembled model. Returns the :class:`Prepared` scene (or the :class:`Scene`)."""
    from bearingsim.scenes.scene import load_scene

    if not isinstance(scene, Scene):
        scene = load_scene(scene)
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
            "n_points": s.n_points, "max_step": s.max_step, "initial": s.initial,
            "max_steps": s.max_steps, "timeout": s.timeout}
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


def summary(prep: Prepared, result: Result, series: dict[str, np.ndarray],
            files: list[Path] | None = None) -> dict[str, Any]:
    """The JSON summary of a run: sizes, timings, final values and every skip."""
    system = prep.system
    units = {**getattr(result, "units", {}), **{n: q.unit for n, q in prep.post.items()}}
    outs = {}
    for n, y in series.items():
        finite = y[np.isfinite(y)]
        outs[n] = {"unit": units.get(n, ""), "final": y[-1],
                   "min": finite.min() if finite.size else None,
                   "max": finite.max() if finite.size else None}
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
        "outputs": outs,
        "files": [str(f) for f in (files or [])],
    })


def time_figures(stem: str, t: np.ndarray, series: dict[str, np.ndarray],
                 units: dict[str, str], groups: list[list[str]], title: str
                 ) -> list[tuple[str, Any]]:
    """(file name, :class:`matplotlib.figure.Figure`) of the time traces: one panel per group
    (default: per output), at most 6 panels a figure (made without pyplot)."""
    from matplotlib.figure import Figure

    groups = groups or [[n] for n in series]
    figures = []
    for k in range(0, len(groups), 6):
        chunk = groups[k:k + 6]
        fig = Figure(figsize=(7, 1.9 * len(chunk) + 1))
        axes = np.atleast_1d(fig.subplots(len(chunk), 1, sharex=True, squeeze=False)[:, 0])
        for ax, group in zip(axes, chunk, strict=True):
            # engineering units for display (r/min, um, deg, N mm, -); SI in the CSV
            factor, unit = display_unit(units.get(group[0], ""),
                                        np.concatenate([series[n] for n in group]))
            for n in group:
                y = series[n] * factor
                ax.plot(t, np.where(np.isfinite(y), y, np.nan), label=n)
            set_value_scale(ax, [series[n] * factor for n in group])
            label = group[0] if len(group) == 1 else ", ".join(group)
            ax.set_ylabel(f"{label}\n[{unit}]", fontsize=8)
            if len(group) > 1:
                ax.legend(fontsize=7)
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time [s]")
        fig.suptitle(title, fontsize=10)
        fig.tight_layout()
        figures.append((f"{stem}.png" if k == 0 else f"{stem}_{k // 6 + 1}.png", fig))
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
            figures.append((f"{stem}.{plot.name}.png", render(spec, f"{prep.scene.title}\n"
                                                                    f"{spec.title}")))
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
    return (assembly_figures(prep, result, series, stem)
            + time_figures(stem, result.t, series, units, groups, prep.scene.title))


def write_plots(folder: Path, stem: str, t: np.ndarray, series: dict[str, np.ndarray],
                units: dict[str, str], groups: list[list[str]], title: str) -> list[Path]:
    """PNG figures of the time traces (:func:`time_figures`)."""
    return save_figures(folder, time_figures(stem, t, series, units, groups, title))


def save_figures(folder: Path, figures: list[tuple[str, Any]]) -> list[Path]:
    """Write (file name, Figure) pairs as PNG files into ``folder`` (atomically)."""
    files = []
    for name, fig in figures:
        path = folder / name
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=110)
        files.append(path)
    return files


def run_scene(scene: Scene | str | Path, out: str | Path | None = None, *, write: bool = True,
              overwrite: bool = False, progress: bool | None = None) -> SceneRun:
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
        scene = load_scene(scene)
    folder = Path(out if out is not None else scene.output.folder)
    stem = Path(scene.path).stem if scene.path else scene.assembly
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
    result = run_simulation(prep, progress=progress)
    series = output_series(prep, result)
    for n, y in series.items():
        if np.any(np.isnan(y)):
            raise ModelError(f"output {n} has NaN values; please report this scene")
    files: list[Path] = []
    units = {**getattr(result, "units", {}), **{n: q.unit for n, q in prep.post.items()}}
    if write:
        folder.mkdir(parents=True, exist_ok=True)
        if prep.scene.output.csv:
            files.append(write_series_csv(folder / f"{stem}.csv", result.t, series, units))
        if prep.scene.output.plots:
            files += save_figures(folder, scene_figures(prep, result, series, stem, units))
        summary_path = folder / f"{stem}.summary.json"
        files.append(summary_path)
        data = summary(prep, result, series, files)
        with atomic_path(summary_path) as tmp:
            tmp.write_text(json.dumps(data, indent=2))
    else:
        data = summary(prep, result, series, files)
    return SceneRun(prep, result, series, data, files)
