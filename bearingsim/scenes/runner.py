"""Run a scene: simulate or analyse its prepared model, write its files.

``run_scene`` prepares the scene (:func:`bearingsim.scenes.preparation.prepare`: the fidelity,
the model assembled and pruned to the requested outputs, the names checked), simulates,
computes the post-processed quantities and writes CSV, a JSON summary (with everything that was
skipped) and PNG plots (:mod:`bearingsim.scenes.run_figures`); an analysis scene's table is
:mod:`bearingsim.scenes.analysis_table`.
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

from bearingsim.checks import checked
from bearingsim.errors import ModelError, SimulationError
from bearingsim.scenes.analyses import (
    NoModesWarning,
    NotSettledWarning,
    PointFailedWarning,
    output_resolution,
    run_points,
    settling_check,
    steady_values,
)
from bearingsim.scenes.analysis_figures import analysis_figures
from bearingsim.scenes.analysis_table import analysis_units, write_table
from bearingsim.scenes.operating_points import operating_points, point_label
from bearingsim.scenes.outputs import OutputFolder, command_line
from bearingsim.scenes.preparation import Prepared, point_keys, prepare
from bearingsim.scenes.run_figures import scene_figures
from bearingsim.scenes.scene import Scene, SceneError, line_of
from bearingsim.scenes.scene_simulation import output_series, run_simulation
from bearingsim.scenes.tables import scene_output_folder
from bearingsim.series_csv import write_series_csv
from bearingsim.simulation import Result

__all__ = [
    "SceneRun",
    "console_lines",
    "run_scene",
]


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


def settling(prep: Prepared, result: Result, series: dict[str, np.ndarray]
             ) -> dict[str, Any]:
    """Whether a transient run's outputs settled (:func:`~bearingsim.scenes.analyses.
    settling_check`, the scene's criterion), with the steady values of the outputs under the
    final inputs where a steady state is found (started from the final state); warns
    (:class:`~bearingsim.scenes.analyses.NotSettledWarning`) naming the outputs that had not
    settled, unless the scene reports a transient on purpose.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    result : Result
        The run's result.
    series : dict of str to ndarray
        The requested outputs' series by name (SI units).

    Returns
    -------
    dict
        The settling check and the steady values.
    """
    scene = prep.scene
    if scene.transient_on_purpose:
        return {"transient_on_purpose": True, "settled": None, "time_constant": None,
                "criterion": "not checked: the scene reports a transient on purpose"}
    check = settling_check(result.t, series, scene.settling, output_resolution(prep, series))
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
        + (". Run longer (simulation.t_end), ask analysis = \"steady\" for the settled "
           "point, or set transient_on_purpose = true" if steady else
           ". Run longer (simulation.t_end) or set transient_on_purpose = true (no steady "
           "state was found from the final state under the final inputs, so analysis = "
           "\"steady\" is no way round: a ball-level model at speed runs periodically)"),
        NotSettledWarning, stacklevel=3)
    return check


def _units(prep: Prepared, result: Result) -> dict[str, str]:
    return {**getattr(result, "units", {}), **{n: q.unit for n, q in prep.post.items()}}


def summary(prep: Prepared, result: Result, series: dict[str, np.ndarray],
            files: list[Path] | None = None, settled: dict[str, Any] | None = None
            ) -> dict[str, Any]:
    """The JSON summary of a run: sizes, timings, final values, settling and every skip.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    result : Result
        The run's result.
    series : dict of str to ndarray
        The requested outputs' series by name (SI units).
    files : list of Path, optional
        The run's files.
    settled : dict, optional
        The settling check (:func:`settling`).

    Returns
    -------
    dict
        The summary (JSON-serializable).
    """
    system = prep.system
    units = _units(prep, result)
    outs = {}
    checked = (settled or {}).get("outputs", {})
    resolution = output_resolution(prep, series)
    for n, y in series.items():
        finite = y[np.isfinite(y)]
        outs[n] = {"unit": units.get(n, ""), "final": y[-1],
                   "min": finite.min() if finite.size else None,
                   "max": finite.max() if finite.size else None}
        if n in resolution:
            outs[n]["resolution"] = resolution[n]
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
                       "method": result.stats.get("method", prep.scene.simulation.method),
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


@checked
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


def _run_analysis(prep: Prepared, stem: str, lock: OutputFolder | None) -> SceneRun:
    """Run a steady, modes or statics scene: one table row per operating point, the figures
    that answer it and the JSON summary (written into ``lock``'s folder, last; None: write
    nothing)."""
    scene = prep.scene
    t0 = time.perf_counter()
    points = operating_points(scene)
    rows = run_points(prep, points)
    solve_s = time.perf_counter() - t0
    solved = [row for row in rows if "error" not in row]
    failed = [{"point": k, "error": row["error"]} for k, row in enumerate(rows) if "error" in row]
    units = analysis_units(prep, rows)
    if rows and not solved:  # nothing answered (e.g. a model whose steady running is periodic)
        first = _point_text(rows[0], units)  # (empty for a scene of [inputs] alone)
        head = (f"no operating point found an answer; the first, {first}" if len(rows) > 1
                else "the operating point" + (f" ({first})" if first else "")
                + " found no answer")
        raise SimulationError(f"{head}: {rows[0]['error']}")
    if failed:
        warnings.warn(f"{len(failed)} of {len(rows)} operating point(s) found no solution; "
                      f"their rows say why (column error), the others are answered. First: "
                      f"{_point_text(rows[failed[0]['point']], units)}: {failed[0]['error']}",
                      PointFailedWarning, stacklevel=3)
    names = list(dict.fromkeys(n for row in rows for n in row))
    columns = {n: np.array([row.get(n, math.nan) for row in rows])
               for n in names if n not in ("name", "error")}
    keys = [point_label(k) for k in point_keys(scene)]
    if scene.analysis == "modes" and not any(set(row) - {*keys, "name"} for row in solved):
        warnings.warn(f"{scene.title or stem}: no oscillating mode at any operating point: every "
                      f"eigenvalue of the linearized model is real (its {prep.system.n_states} "
                      "state(s) settle without oscillating), so there is no natural "
                      "frequency to report", NoModesWarning, stacklevel=3)
    if lock is not None:
        lock.retire(f"{stem}.summary.json")
        if scene.output.csv:
            lock.add(write_table(lock.folder / f"{stem}.csv", rows, units))
        if scene.output.plots and solved:
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
        "failed": failed,
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


def _point_text(row: dict[str, Any], units: dict[str, str]) -> str:
    """A point's row as a message names it, in display units (``Fr = 0.5 kN``), its error
    left out."""
    from bearingsim.scenes.plots import curve_label

    return curve_label({n: v for n, v in row.items() if n != "error"}, units)


def console_lines(summary_data: dict[str, Any]) -> list[str]:
    """What ``bearingsim run`` prints of a run's results: a transient's final values with
    whether they settled, or an analysis's table in engineering units.

    Parameters
    ----------
    summary_data : dict
        The run's summary (:func:`summary`).

    Returns
    -------
    list of str
        The lines.
    """
    from bearingsim.scenes.plots import display_text

    s = summary_data
    if s.get("analysis", "transient") != "transient":
        units = s["units"]
        lines = [f"  {s['analysis']}: {s['points']} operating point(s)"]
        keys = {*s["keys"], "name"}
        for row in s["rows"]:
            lines.append(f"  {_point_text(row, units)}"
                         + (f": FAILED: {row['error']}" if "error" in row else
                            ": no oscillating mode" if set(row) <= keys else ""))
        return lines
    stats = s.get("simulation", {}).get("stats", {})
    reason, backend_reason = stats.get("method_reason", ""), stats.get("backend_reason", "")
    lines = [f"  solver: {stats.get('method', '?')}" + (f" ({reason})" if reason else "")
             + (f"; evaluator {stats['backend']}" if backend_reason else "")
             + (f" ({backend_reason})" if backend_reason and backend_reason not in reason
                else "")]
    for name, o in s["outputs"].items():
        final = "inf/nan" if o["final"] is None else display_text(o["final"], o["unit"])
        note = ""
        if o.get("settled") is False:
            note = " (NOT settled" + (f"; steady {display_text(o['steady'], o['unit'])}"
                                      if o.get("steady") is not None else "") + ")"
        if o["final"] and abs(o["final"]) <= o.get("resolution", 0.0):
            note += (f" (zero to the run's resolution, atol = "
                     f"{display_text(o['resolution'], o['unit'])})")
        lines.append(f"  {name} = {final} at t_end{note}")
    st = s.get("settling", {})
    if st.get("transient_on_purpose"):
        lines.append("  transient on purpose: final values not checked for settling")
    elif s.get("settled") is not None:
        tau = s.get("time_constant_s")
        lines.append(f"  settled: {'yes' if s['settled'] else 'NO'} ({st.get('criterion')})"
                     + (f"; time constant {tau:.3g} s" if tau is not None else ""))
    return lines
