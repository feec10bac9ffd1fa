"""Parameter sweeps of a scene on dask.distributed.

A sweep runs one scene over a grid (``--grid key=v1,v2,...``, the Cartesian product of all
grids) or a quasi-random sample (``--sample key=low:high --samples N``, Latin hypercube or
Sobol from :mod:`scipy.stats.qmc`, :mod:`bearingsim.scenes.sampling`) of keys:

* ``inputs.<name>``: a number or an expression of ``t``;
* ``parameters.<name>``, ``initial.<state>``: numbers;
* ``simulation.<setting>``: ``t_end``, ``rtol``, ``atol``, ``method``, ``max_step``,
  ``n_points``, ``initial``;
* ``assembly.<argument>`` (also ``assembly.bearing.lubrication`` and ``assembly.fidelity``).

Every point is validated before anything runs. The model is prepared on the client once per
distinct structure (arguments that only change parameter values, such as the lubricant of a
Palmgren friction model, become parameter overrides) through the on-disk cache of assembled
systems (:mod:`bearingsim.assembler.cache`), and shipped to the workers as bytes; each worker
process loads it once (:mod:`bearingsim.scenes.sweep_worker`). The LocalCluster's workers are
forked from a process that imported bearingsim once, and points go out in chunks sized from
the measured time of the points finished so far, as the workers finish them
(:mod:`bearingsim.scenes.sweep_cluster`), so a task's scheduling cost is spread over ~0.25 s
of work; each point runs what
``bearingsim run`` runs for one operating point of that scene
(:func:`~bearingsim.scenes.analyses.run_operating_point`: a transient's final values with
``settled`` and ``time_constant``, a steady, modes or statics point's table row; an analysis
scene's own grid or cases are replaced by the sweep's points).

Files go through :class:`~bearingsim.scenes.outputs.OutputFolder` (one writer at a time, an
earlier sweep's files replaced only with ``overwrite``, the summary last). Rows are appended
to ``<scene>.sweep.csv`` as they arrive (:mod:`bearingsim.scenes.sweep_table`);
``resume=True`` skips the points already there; a point that fails or exceeds ``timeout`` is
recorded with its error and does not affect the others (``timeout`` defaults to the scene's
``simulation.timeout``); a worker lost mid-sweep has its chunks
re-run by the scheduler on the others.
"""

from __future__ import annotations

import concurrent.futures
import copy
import dataclasses
import functools
import hashlib
import importlib
import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from bearingsim.assembler import cache as system_cache
from bearingsim.errors import ParameterError
from bearingsim.scenes.analyses import point_model
from bearingsim.scenes.outputs import OutputFolder, command_line
from bearingsim.scenes.preparation import Prepared, choose_fidelity, prepare
from bearingsim.scenes.sampling import (
    SweepError,
    check_key,
    grid_points,
    parse_sample,
    sample_points,
)
from bearingsim.scenes.scene import Scene, SceneError, load_scene
from bearingsim.scenes.sweep_cluster import (
    CHUNK_SECONDS,
    ChunkFeeder,
    chunk_size,
    connect,
    distributed_module,
)
from bearingsim.scenes.sweep_table import SweepTable, cell, open_table
from bearingsim.scenes.sweep_worker import Job, ModelPayload, run_point
from bearingsim.units import display_unit
from bearingsim.validation import check_count

__all__ = ["SweepError", "SweepResult", "parse_grid", "parse_sample", "grid_points",
           "sample_points", "run_sweep", "describe_failures", "chunk_size", "CHUNK_SECONDS"]


@dataclass
class SweepResult:
    """Rows of the result table (one per point, in point order), failures and written files."""

    keys: list[str]
    rows: list[dict[str, Any]]
    failures: list[dict[str, Any]]
    models_built: int
    files: list[Path] = field(default_factory=list)
    wall_s: float = 0.0
    resumed: int = 0
    """Points taken from the table of an earlier run (``resume``)."""
    chunk_size: int = 1
    """Most points in one task."""
    point_s: float = math.nan
    """Median wall time of a point, which sized the chunks [s]."""
    phases: dict[str, float] = field(default_factory=dict)
    """Wall time [s] of the client's phases: ``plan`` (validate, prepare or load the models),
    ``cluster`` (waiting for the cluster after planning), ``ship`` (scatter the models),
    ``points`` (first chunk out to last row in), ``close`` (close the cluster), ``write``
    (sorted table, Parquet copy, plot, summary)."""

    @property
    def ok(self) -> list[dict[str, Any]]:
        """The rows of the points that succeeded.

        Returns
        -------
        list of dict
            The rows.
        """
        return [r for r in self.rows if r["status"] == "ok"]


# --------------------------------------------------------------------------- specification
def _split_values(text: str) -> list[str]:
    """Split on ';' if present, else on commas outside parentheses, brackets and quotes (a
    TOML list such as ``["lithium grease", "ISO VG 32"]`` is one value)."""
    if ";" in text:
        return [v.strip() for v in text.split(";") if v.strip()]
    out, depth, cur, quote = [], 0, "", ""
    for ch in text:
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        if ch == "," and depth == 0 and not quote:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    if cur.strip():
        out.append(cur.strip())
    return out


def _value(text: str) -> Any:
    """A grid value: a TOML list or quoted string as TOML reads it, true/false, a number, or
    the text itself."""
    if text.strip()[:1] in ("[", "\"", "'"):
        try:
            return tomllib.loads(f"v = {text.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            raise SweepError(f"grid value {text!r} is not a TOML value (a list needs quoted "
                             f"text: [\"lithium grease\", \"ISO VG 32\"])") from None
    low = text.strip().lower()
    if low in ("true", "false"):
        return low == "true"
    try:
        v = float(text)
    except ValueError:
        return text.strip()
    return int(v) if v.is_integer() and "." not in text and "e" not in low else v


def parse_grid(items: list[str]) -> dict[str, list[Any]]:
    """``["inputs.shaft_speed=100,200", ...]`` -> ``{"inputs.shaft_speed": ["100", "200"]}``.

    Values stay text here; they are converted by the type the key expects when a point is
    applied to a scene (numbers for parameters, designations stay text).

    Parameters
    ----------
    items : list of str
        ``key=v1,v2,...`` each.

    Returns
    -------
    dict of str to list of str
        The values by key.
    """
    grid: dict[str, list[Any]] = {}
    for item in items:
        if "=" not in item:
            raise SweepError(f"--grid {item!r}: expected key=v1,v2,...")
        key, values = item.split("=", 1)
        key = key.strip()
        check_key(key)
        vals = _split_values(values)
        if not vals:
            raise SweepError(f"--grid {key}: no values")
        grid[key] = vals
    return grid


# --------------------------------------------------------------------------- planning
def _set_nested(d: dict, path: list[str], value: Any) -> None:
    for p in path[:-1]:
        d = d.setdefault(p, {})
    d[path[-1]] = value


def _coerce(scene: Scene, key: str, value: Any) -> Any:
    """A grid value converted to the type its key expects."""
    head, rest = key.split(".", 1)
    text_kinds = ("bearing", "lubricant", "choice")
    if head == "assembly":
        spec = scene.spec.args
        parts = rest.split(".")
        arg = None
        for part in parts:
            arg = spec.get(part) if spec else None
            spec = arg.table if arg is not None and arg.table else None
        if isinstance(value, str) and value.strip()[:1] in ("[", "\"", "'"):
            value = _value(value)
        if isinstance(value, list):
            return [str(v) for v in value]
        if rest == "fidelity" or (arg is not None and arg.kind in text_kinds):
            return str(value) if not isinstance(value, str) else value
        if arg is not None and arg.kind == "signal" and isinstance(value, str):
            v = _value(value)
            return v if not isinstance(v, bool) else value
    if head == "simulation" and rest in ("method", "initial"):
        return str(value)
    if isinstance(value, str):
        v = _value(value)
        return value if isinstance(v, bool) and head != "assembly" else v
    return value


def _point_scene(scene: Scene, point: dict[str, Any]) -> Scene:
    """The scene with the point's values applied, validated (errors name the sweep key); an
    analysis scene's own grid or cases are left out (the sweep's point is its one operating
    point)."""
    d = scene.to_dict()
    if scene.analysis != "transient":
        d.pop("grid", None)
        d.pop("cases", None)
    for key, value in point.items():
        value = _coerce(scene, key, value)
        head, rest = key.split(".", 1)
        if head == "assembly":
            _set_nested(d["assembly"], rest.split("."), value)
        else:
            d.setdefault(head, {})[rest] = value
    from bearingsim.scenes.scene import scene_from_dict

    try:
        return scene_from_dict(d, path=scene.path)
    except SceneError as exc:
        shown = ", ".join(f"{k}={v!r}" for k, v in point.items())
        why = "; ".join(p.key + ": " + p.reason + (f"; allowed: {p.allowed}" if p.allowed else "")
                        for p in exc.problems)
        raise SweepError(f"sweep point ({shown}): {why}") from None


def _check_operating_points(scene: Scene, points: list[dict[str, Any]]) -> None:
    """Raise :class:`SweepError` when an input the analysis scene takes from its own grid
    (which a sweep replaces) has no value at the sweep's points (a load case leaves out the
    inputs it does not set: those keep the scene's value or none)."""
    missing = sorted(k for k in scene.grid if k.startswith("inputs.") and k not in points[0]
                     and k.split(".", 1)[1] not in scene.inputs)
    if missing:
        raise SweepError(
            f"the sweep replaces the grid of this {scene.analysis} scene, and "
            f"{', '.join(missing)} then has no value: sweep it (--grid {missing[0]}=...) or "
            f"give it under [inputs]")


def _structure(sc: Scene) -> tuple[str, str]:
    """Key of the model structure of a point: fidelity and the non-parametric arguments (with
    the symmetry the point's inputs allow, as :func:`~bearingsim.scenes.preparation.prepare`
    uses)."""
    spec = sc.spec
    args = spec.with_defaults(sc.args)
    args.update(spec.symmetric_args(args, sc.inputs))
    post_all = spec.post(args)
    post = {n: post_all[n] for n in (sc.outputs or spec.default_outputs) if n in post_all}
    fidelity, _, _ = choose_fidelity(sc, spec, post)
    stripped = copy.deepcopy(args)
    for key, holds in spec.parametric_args.items():
        if holds(args):
            path, d = key.split("."), stripped
            for p in path[:-1]:
                d = d.get(p, {})
            d.pop(path[-1], None)
    return fidelity, json.dumps(stripped, sort_keys=True, default=str)


def _payload(prep: Prepared) -> ModelPayload:
    """The prepared model as bytes for the workers: the cache entry just used by ``prepare``
    (no second serialization), else the system serialized now."""
    last = system_cache.LAST
    data = system_cache.read_payload(last["path"], last["key"]) if last.get("path") else None
    if data is None:
        data = system_cache.dumps_system(prep.system)
    token = hashlib.sha256(data).hexdigest()
    return ModelPayload(token, dataclasses.replace(prep, system=None), data)


@dataclass
class _Plan:
    prepared: dict[tuple, Prepared]
    payloads: dict[tuple, ModelPayload]
    jobs: list[Job]
    structure: dict[int, tuple]
    """Point number -> structure key."""
    values: list[dict[str, Any]]
    """Point number -> swept values (converted)."""


def _plan(scene: Scene, points: list[dict[str, Any]]) -> _Plan:
    scenes = [_point_scene(scene, p) for p in points]
    if scene.analysis != "transient":
        _check_operating_points(scene, points)
    prepared: dict[tuple, Prepared] = {}
    payloads: dict[tuple, ModelPayload] = {}
    jobs, structure, values, converted = [], {}, [], {}
    for k, (raw, sc) in enumerate(zip(points, scenes, strict=True)):
        pt = {key: _coerce(scene, key, v) for key, v in raw.items()}
        key = _structure(sc)
        try:
            if key not in prepared:
                prepared[key] = prepare(sc)
                payloads[key] = _payload(prepared[key])
            prep = prepared[key]
            _, params = point_model(prep, sc.args)
            prep.system.p0({**sc.parameters, **params})
        except (SceneError, ParameterError) as exc:
            raise SweepError(f"sweep point {pt}: {exc}") from None
        for name in sc.inputs:  # (a statics load case also takes the speed, for the life)
            if sc.analysis != "statics" and name not in prep.system.input_names:
                raise SweepError(f"sweep point {pt}: the model has no input {name!r}; inputs: "
                                 + ", ".join(prep.system.input_names))
        jobs.append(Job(k, sc, params))
        structure[k] = key
        values.append(_si_values(pt, converted))
    return _Plan(prepared, payloads, jobs, structure, values)


# --------------------------------------------------------------------------- results
TRANSIENT_COLUMNS = ("settled", "time_constant", "unsettled")
"""The columns a transient point adds to its outputs' final values
(:func:`~bearingsim.scenes.analyses.run_operating_point`)."""


def _result_columns(prep: Prepared, probe: dict[str, Any] | None
                    ) -> tuple[list[str], dict[str, str]]:
    """The result columns of a sweep's rows and their SI units: those of the scene's own table
    row for its analysis (a transient's outputs with ``settled``, ``time_constant`` and
    ``unsettled``; a steady point's outputs; a statics point's columns; a modes point's mode
    names, read from the ``probe`` row of the first point)."""
    from bearingsim.scenes.runner import analysis_units
    from bearingsim.scenes.statics_table import statics_of

    kind = prep.scene.analysis
    if kind == "transient":
        system = prep.system
        units = {**system.variable_units, **{n: q.unit for n, q in prep.post.items()},
                 **{p.name: p.unit for p in system.params}}
        return ([*prep.outputs, *TRANSIENT_COLUMNS],
                {**{n: units[n] for n in prep.outputs if n in units}, "time_constant": "s"})
    if kind == "statics":
        names = list(statics_of(prep).columns)
    elif kind == "modes":
        names = [n for n in (probe or {}) if not n.startswith("_")]
    else:
        names = list(prep.outputs)
    units = analysis_units(prep, [probe] if probe else [])
    return names, {n: units[n] for n in names if units.get(n)}


def _column_units(prep: Prepared, keys: list[str], results: dict[str, str]
                  ) -> dict[str, str]:
    """Unit of every numeric sweep column: the swept inputs, parameters and initial values
    (from the first model; every model of a sweep has the same names), the results' and
    ``wall_s``."""
    system = prep.system
    units = {**system.variable_units, **{p.name: p.unit for p in system.params}}
    out = dict(results)
    for key in keys:
        head, _, name = key.partition(".")
        if head in ("inputs", "parameters", "initial") and name in units:
            out[key] = units[name]
    out["wall_s"] = "s"
    return out


def _table_row(index: int, values: dict[str, Any], results: list[str],
               r: dict[str, Any]) -> dict[str, Any]:
    row: dict[str, Any] = {"point": index, **values, "status": r["status"]}
    for name in results:
        row[name] = r["final"].get(name, float("nan")) if r["status"] == "ok" else float("nan")
    row["wall_s"] = round(float(r.get("wall_s", float("nan"))), 4)
    row["error"] = r["error"]
    return row


def _from_cell(text: str) -> Any:
    """A table cell read back: int, float, bool or text."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return {"True": True, "False": False}.get(text, text)


def _sweep_figures(prep: Prepared, rows: list[dict[str, Any]], keys: list[str],
                   results: list[str], units: dict[str, str], stem: str) -> list:
    """``<stem>.png``: each result against the first numeric swept key (engineering units);
    a transient's one panel per output, an analysis's one curve per value of the other keys
    (:func:`~bearingsim.scenes.plots.characteristic_figures`, natural frequencies in one
    panel); none when no swept key is numeric.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
    """
    from matplotlib.figure import Figure

    from bearingsim.scenes.plots import characteristic_figures

    ok = [r for r in rows if r["status"] == "ok"]
    numeric = [k for k in keys if ok and all(isinstance(r.get(k), (int, float))
                                             and not isinstance(r.get(k), bool) for r in ok)]
    outputs = [n for n in results if n in units and n not in TRANSIENT_COLUMNS]
    if not numeric or not outputs:
        return []
    kind = prep.scene.analysis
    if kind != "transient":
        order = [numeric[0], *(k for k in keys if k != numeric[0])]
        what = "modes" if kind == "modes" else "steady"
        figs = characteristic_figures(prep, ok, order, units, outputs, what)
        return [(f"{stem}.png", fig) for _, fig in figs[:1]]
    x_key = numeric[0]
    x = np.array([r[x_key] for r in ok], dtype=float)
    order = np.argsort(x)
    x_factor, x_unit = display_unit(units.get(x_key, ""), x)
    fig = Figure(figsize=(7, 1.9 * len(outputs) + 1))
    axes = np.atleast_1d(fig.subplots(len(outputs), 1, sharex=True))
    for ax, name in zip(axes, outputs, strict=True):
        y = np.array([r[name] for r in ok], dtype=float)
        factor, unit = display_unit(units[name], y)
        ax.plot(x[order] * x_factor, y[order] * factor, "o-")
        ax.set_ylabel(f"{name}\n[{unit}]", fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(f"{x_key} [{x_unit}]")
    fig.tight_layout()
    return [(f"{stem}.png", fig)]


def _ready_to_write(units: dict[str, str], cluster_up) -> None:
    """Import what writing the results takes (Parquet, the figure) and resolve the display
    units of the columns, a step at a time until ``cluster_up()``: the client does it while it
    would wait idle for the workers, instead of after the last point."""
    steps = [SweepTable.ready,
             *(functools.partial(importlib.import_module, name) for name in (
                 "matplotlib.figure", "matplotlib.backends.backend_agg",
                 "bearingsim.scenes.plots")),
             *(functools.partial(display_unit, unit) for unit in set(units.values()))]
    for step in steps:
        if cluster_up():
            return
        try:
            step()
        except Exception:  # noqa: BLE001, S112 - writing the results reports it, if it recurs
            continue


def _earlier_files(folder: Path, stem: str) -> list[str]:
    """Names of an earlier sweep's files of this scene in ``folder``."""
    names = [f"{stem}.{ext}" for ext in ("json", "csv", "parquet", "png")]
    return [n for n in names if (folder / n).exists()]


def run_sweep(scene: Scene | str | Path, points: list[dict[str, Any]], *,
              scheduler: str | None = None, n_workers: int = 2, out: str | Path | None = None,
              progress: bool = True, client=None, resume: bool = False,
              timeout: float | None = None, chunk: int | None = None,
              overwrite: bool = False) -> SweepResult:
    """Run a scene at every point on dask.distributed; one table, appended as points finish.

    Each point runs the scene's analysis for that operating point
    (:func:`~bearingsim.scenes.analyses.run_operating_point`, as ``bearingsim run`` does);
    an analysis scene's own grid or cases are replaced by the sweep's points.

    Parameters
    ----------
    scene : Scene or path
    points : list of dict
        From :func:`grid_points` or :func:`sample_points`.
    scheduler : str, optional
        Address of a running dask scheduler (``tcp://host:8786``); default: a LocalCluster.
    n_workers : int
        Workers of the LocalCluster.
    out : path, optional
        Folder for ``<scene>.sweep.csv`` (and ``.parquet``, ``.png``) and ``.sweep.json``,
        written through :class:`~bearingsim.scenes.outputs.OutputFolder` (locked for the
        sweep; the summary last); None: no files (and no ``resume``).
    progress : bool
        Show a progress bar.
    client : distributed.Client, optional
        Use this client (and leave it open).
    resume : bool
        Keep the rows of an earlier run of the same sweep in ``out`` and run only the others.
    timeout : float, optional
        Time budget of one point [s]: a point still running after it is recorded as failed.
        Default: the scene's ``simulation.timeout`` (None there: no budget).
    chunk : int, optional
        Points per task (default: :func:`chunk_size` of the median time of the points
        finished so far, one point a task until the first is back).
    overwrite : bool
        Replace an earlier sweep's files of this scene in ``out`` (without it, and without
        ``resume``, such files stop the sweep before anything runs).

    Returns
    -------
    SweepResult
        The rows of every point, with status and timings.

    Raises
    ------
    SweepError
        For an invalid key or point (before anything runs), an earlier sweep's files in
        ``out`` without ``overwrite`` or ``resume``, or a table that ``resume`` cannot
        continue.
    OutputFolderBusy
        When another run or sweep is writing into ``out``.
    KeyboardInterrupt
        On Ctrl-C, after the tasks are cancelled; the rows written so far stay in the table.
    """
    check_count(n_workers, "n_workers", 1, "run_sweep")
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    if not points:
        raise SweepError("a sweep needs at least one point")
    if timeout is None:
        timeout = scene.simulation.timeout
    if timeout is not None and not (math.isfinite(timeout) and timeout > 0):
        raise SweepError(f"--timeout must be a positive number of seconds, got {timeout!r}")
    if timeout != scene.simulation.timeout:  # the solver's own budget too (--timeout wins)
        scene = scene.replace(simulation=dataclasses.replace(scene.simulation, timeout=timeout))
    if resume and out is None:
        raise SweepError("resume needs the output folder of the earlier run (out=...)")
    stem = (Path(scene.path).stem if scene.path else scene.assembly) + ".sweep"
    if out is None:
        return _sweep(scene, points, None, stem, scheduler, n_workers, progress, client,
                      resume, timeout, chunk)
    with OutputFolder(out, command_line()) as folder:
        earlier = _earlier_files(folder.folder, stem)
        if earlier and not (overwrite or resume):
            raise SweepError(f"{folder.folder} holds an earlier sweep of this scene ("
                             + ", ".join(earlier) + "): add --overwrite to replace it, "
                             "--resume to continue it, or give another --out")
        return _sweep(scene, points, folder, stem, scheduler, n_workers, progress, client,
                      resume, timeout, chunk)


def _sweep(scene: Scene, points: list[dict[str, Any]], folder: OutputFolder | None, stem: str,
           scheduler: str | None, n_workers: int, progress: bool, client, resume: bool,
           timeout: float | None, chunk: int | None) -> SweepResult:
    """:func:`run_sweep` after its checks, writing into ``folder`` (None: nothing)."""
    distributed_module()  # a named error before anything starts when it is missing
    from tqdm import tqdm

    wall = time.perf_counter()
    phases: dict[str, float] = {}
    clock = [wall]

    def lap(name: str) -> None:
        now = time.perf_counter()
        phases[name] = now - clock[0]
        clock[0] = now

    own = client is None
    starting = (concurrent.futures.ThreadPoolExecutor(1).submit(connect, scheduler, n_workers)
                if own else None)  # the cluster starts while the client plans
    cluster = None
    try:
        plan = _plan(scene, points)
        keys = list(points[0])
        first = next(iter(plan.prepared.values()))
        probe = None
        if scene.analysis == "modes":  # the mode names (columns) come from a point
            job = plan.jobs[0]
            probe = run_point(plan.prepared[plan.structure[job.index]], job, timeout)
            if probe["status"] != "ok":
                raise SweepError(f"the first point of this modes sweep, which names the "
                                 f"columns, failed: {probe['error']}")
        results_names, result_units = _result_columns(first, probe and probe["final"])
        units = _column_units(first, keys, result_units)
        columns = ["point", *keys, "status", *results_names, "wall_s", "error"]
        table = done = None
        rows: dict[int, dict[str, Any]] = {}
        if folder is not None:
            if resume:  # the table stays; the summary is written anew when it is whole
                (folder.folder / f"{stem}.json").unlink(missing_ok=True)
            else:
                folder.retire(f"{stem}.json")
            table = SweepTable(folder.folder / f"{stem}.csv", columns, units)
            expected = {k: {key: cell(v) for key, v in values.items()}
                        for k, values in enumerate(plan.values)}
            done = open_table(table, resume, expected)
            rows = {k: {c: (_from_cell(v) if c not in keys else plan.values[k][c])
                        for c, v in r.items()} for k, r in done.items()}
        todo = [job for job in plan.jobs if job.index not in rows]
        results: dict[int, dict[str, Any]] = {}

        def record(r: dict[str, Any]) -> None:
            results[r["index"]] = r
            row = _table_row(r["index"], plan.values[r["index"]], results_names, r)
            rows[r["index"]] = row
            if table is not None:
                table.append(row)

        point_s = math.nan
        if probe is not None and todo and todo[0].index == probe["index"]:
            todo.pop(0)
            point_s = probe["wall_s"]
            record(probe)
        lap("plan")

        if own:
            if table is not None:
                _ready_to_write(units, starting.done)
            client, cluster = starting.result()
        client.wait_for_workers(1)
        lap("cluster")
        # every worker (scheduler_info may list a few); a LocalCluster's are all up
        n_threads = sum(client.nthreads().values())
        models = {key: client.scatter(payload, broadcast=True)
                  for key, payload in plan.payloads.items()
                  if any(plan.structure[j.index] == key for j in todo)}
        lap("ship")
        feeder = ChunkFeeder(client, models, [(plan.structure[j.index], j) for j in todo],
                             n_threads, timeout, chunk, point_s)
        bar = tqdm(total=len(points), initial=len(rows), unit="point", disable=not progress,
                   leave=False)
        try:
            for part, chunk_rows in feeder:
                if isinstance(chunk_rows, BaseException):  # a chunk lost for good
                    chunk_rows = [{"index": j.index, "status": "failed", "final": {},
                                   "error": f"{type(chunk_rows).__name__}: {chunk_rows}",
                                   "wall_s": float("nan")} for j in part]
                for r in chunk_rows:
                    record(r)
                bar.update(len(chunk_rows))
        except KeyboardInterrupt:
            feeder.cancel()
            raise
        finally:
            bar.close()
        point_s, size = feeder.point_s, feeder.largest
        lap("points")
    finally:
        if own:
            if client is None and starting is not None:
                try:
                    client, cluster = starting.result()
                except Exception:  # noqa: BLE001 - the planning error is the one to report
                    client = None
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()
    lap("close")
    ordered = [rows[k] for k in sorted(rows)]
    failures = [{"point": r["point"], "values": plan.values[r["point"]], "error": r["error"]}
                for r in ordered if r["status"] != "ok"]
    res = SweepResult(keys, ordered, failures, len(plan.prepared), resumed=len(done or {}),
                      chunk_size=size, point_s=point_s, phases=phases)
    if table is not None:
        for path in table.finish(ordered):
            folder.add(path)
        folder.save_figures(lambda: _sweep_figures(first, ordered, keys, results_names, units,
                                                   stem))
        summary = {
            "scene": scene.path, "analysis": scene.analysis, "points": len(ordered),
            "ok": len(res.ok), "failed": len(failures), "failures": failures,
            "models_built": res.models_built,
            "resumed": res.resumed, "chunk_size": size, "point_s": point_s,
            "structures": [{"fidelity": k[0], "arguments": json.loads(k[1])}
                           for k in plan.prepared],
            "model_loads_per_worker": sorted({(r.get("pid"), r.get("model_loads"))
                                              for r in results.values()
                                              if "model_loads" in r}),
            "scheduler": scheduler or f"LocalCluster({n_workers} workers)",
            "timeout_s": timeout, "phases_s": {k: round(v, 3) for k, v in phases.items()},
        }
        folder.write_summary(f"{stem}.json", json.loads(json.dumps(summary, default=str)))
        res.files = list(folder.files)
    lap("write")
    res.wall_s = time.perf_counter() - wall
    return res


def _si_values(point: dict[str, Any], memo: dict | None = None) -> dict[str, Any]:
    """The swept values as the table stores them: SI numbers for inputs that are constant
    (``"500 rpm"``, ``"rpm(500)"`` -> 52.36 under ``[rad/s]``), others as given. ``memo``
    keeps the converted values across the points of a sweep (a grid repeats each value)."""
    from bearingsim.scenes.expressions import constant_value

    memo = {} if memo is None else memo
    out = {}
    for key, value in point.items():
        if not key.startswith("inputs."):
            out[key] = value
            continue
        seen = (key, repr(value))
        if seen not in memo:
            si = constant_value(value, key)
            memo[seen] = value if si is None else si
        out[key] = memo[seen]
    return out


def describe_failures(res: SweepResult) -> str:
    """One line per failed point: its values and the error.

    Parameters
    ----------
    res : SweepResult
        A sweep's result.

    Returns
    -------
    str
        The lines (empty without failures).
    """
    lines = []
    for f in res.failures:
        values = ", ".join(f"{k}={v!r}" for k, v in f["values"].items())
        lines.append(f"point {f['point']} ({values}): {f['error']}")
    return "\n".join(lines)
