"""Parameter sweeps of a scene on dask.distributed.

A sweep runs one scene over a grid (``--grid key=v1,v2,...``, the Cartesian product of all
grids) or a quasi-random sample (``--sample key=low:high --samples N``, Latin hypercube or
Sobol from :mod:`scipy.stats.qmc`, :mod:`bearingsim.scenes.sampling`) of keys:

* ``inputs.<name>``: a number or an expression of ``t``;
* ``parameters.<name>``, ``initial.<state>``: numbers;
* ``simulation.<setting>``: ``t_end``, ``rtol``, ``atol``, ``method``, ``max_step``,
  ``n_points``, ``initial``;
* ``assembly.<argument>`` (also ``assembly.bearing.lubrication`` and ``assembly.fidelity``).

Every point is validated before anything runs (:mod:`bearingsim.scenes.sweep_grid` applies
a point to the scene), but for the limits an assembly sets on a parametric argument's value,
checked where the point runs (:func:`~bearingsim.scenes.sweep_plan.plan_sweep`). The model
is prepared on the client once per distinct structure (arguments that only change parameter
values, such as the lubricant of a Palmgren friction model, become parameter overrides,
:func:`~bearingsim.scenes.sweep_plan.plan_sweep`) through the on-disk cache of assembled
systems (:mod:`bearingsim.assembler.cache`), and shipped to the workers as bytes; each worker
process loads it once (:mod:`bearingsim.scenes.sweep_worker`). The LocalCluster's workers are
forked from a process that imported bearingsim once, started before anything else
(:mod:`bearingsim.sweep_server`), and points go out longest first by an estimate of their
time learned from the points finished so far (:mod:`bearingsim.scenes.sweep_order`), in
chunks sized from it, as the workers finish them (:mod:`bearingsim.scenes.sweep_cluster`), so
a task's scheduling cost is spread over about two seconds of work and the workers finish
together; each point runs what
``bearingsim run`` runs for one operating point of that scene
(:func:`~bearingsim.scenes.analyses.run_operating_point`: a transient's final values with
``settled`` and ``time_constant``, a steady, modes or statics point's table row; an analysis
scene's own grid or cases are replaced by the sweep's points).

Files go through :class:`~bearingsim.scenes.outputs.OutputFolder` (one writer at a time, an
earlier sweep's files replaced only with ``overwrite``, the summary last). Rows are appended
to ``<scene>.sweep.csv`` as they arrive (:mod:`bearingsim.scenes.sweep_table`; the
columns and the figure are :mod:`bearingsim.scenes.sweep_results`);
``resume=True`` skips the points already there; a point that fails or exceeds ``timeout`` is
recorded with its error and does not affect the others (``timeout`` defaults to the scene's
``simulation.timeout``); a worker lost mid-sweep has its chunks
re-run by the scheduler on the others. A transient point that ran but had not settled by
``t_end`` is kept with its values flagged (``settled`` False, the outputs in ``unsettled``),
counted apart from the settled ones (:func:`describe_points`), and the sweep warns
(:class:`~bearingsim.scenes.analyses.NotSettledWarning`) as ``bearingsim run`` does for one
point.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import dataclasses
import functools
import gc
import importlib
import json
import math
import os
import time
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from bearingsim.checks import checked
from bearingsim.scenes.analyses import NotSettledWarning
from bearingsim.scenes.outputs import OutputFolder, command_line
from bearingsim.scenes.sampling import (
    SweepError,
    crossed_points,
    grid_points,
    parse_sample,
    sample_points,
)
from bearingsim.scenes.scene import Scene, load_scene
from bearingsim.scenes.sweep_cluster import (
    CHUNK_SECONDS,
    ChunkFeeder,
    chunk_size,
    connect,
    distributed_module,
    ship,
)
from bearingsim.scenes.sweep_order import PointCosts, point_features
from bearingsim.scenes.sweep_plan import plan_sweep
from bearingsim.scenes.sweep_results import (
    SweepResult,
    column_units,
    describe_failures,
    describe_points,
    point_warnings,
    result_columns,
    sweep_figures,
    table_row,
)
from bearingsim.scenes.sweep_table import SweepTable, cell, from_cell, open_table
from bearingsim.scenes.sweep_worker import run_point
from bearingsim.sweep_preloads import learned_preloads, remember_preloads, scene_file
from bearingsim.sweep_server import PRELOADED, start_worker_server
from bearingsim.units import display_unit
from bearingsim.validation import check_count

__all__ = ["SweepError", "SweepResult", "parse_sample", "grid_points", "crossed_points",
           "sample_points", "run_sweep", "describe_failures", "describe_points", "chunk_size",
           "CHUNK_SECONDS"]


def _ready_to_write(units: dict[str, str]) -> None:
    """Import what writing the results takes (Parquet, the figure) and resolve the display
    units of the columns: the client does it in a thread from the end of its plan, while the
    cluster starts (the client waits for it, a core mostly idle) and then beside the points,
    instead of after the last point."""
    steps = [SweepTable.ready,
             *(functools.partial(importlib.import_module, name) for name in (
                 "matplotlib.figure", "matplotlib.backends.backend_agg",
                 "bearingsim.scenes.plots")),
             *(functools.partial(display_unit, unit) for unit in set(units.values()))]
    for step in steps:
        try:
            step()
        except Exception:  # noqa: BLE001, S112 - writing the results reports it, if it recurs
            continue


def _earlier_files(folder: Path, stem: str) -> list[str]:
    """Names of an earlier sweep's files of this scene in ``folder``."""
    names = [f"{stem}.{ext}" for ext in ("json", "csv", "parquet", "png")]
    return [n for n in names if (folder / n).exists()]


@checked(skip=("n_workers", "chunk"))  # checked below, naming the flags
def run_sweep(scene: Scene | str | Path, points: Sequence[Mapping[str, Any]], *,
              scheduler: str | None = None, n_workers: int = 2, out: str | Path | None = None,
              progress: bool | None = None, client=None, resume: bool = False,
              timeout: float | None = None, chunk: int | None = None,
              overwrite: bool = False, longest_first: bool = True) -> SweepResult:
    """Run a scene at every point on dask.distributed; one table, appended as points finish.

    Each point runs the scene's analysis for that operating point
    (:func:`~bearingsim.scenes.analyses.run_operating_point`, as ``bearingsim run`` does);
    an analysis scene's own grid or cases are replaced by the sweep's points.

    Parameters
    ----------
    scene : Scene or path
    points : sequence of dict
        From :func:`grid_points` or :func:`sample_points` (a list or a tuple).
    scheduler : str, optional
        Address of a running dask scheduler (``tcp://host:8786``); default: a LocalCluster.
    n_workers : int
        Workers of the LocalCluster.
    out : path, optional
        Folder for ``<scene>.sweep.csv`` (and ``.parquet``, ``.png``) and ``.sweep.json``,
        written through :class:`~bearingsim.scenes.outputs.OutputFolder` (locked for the
        sweep; the summary last); None: no files (and no ``resume``).
    progress : bool, optional
        Show a progress bar of the points on standard error (``True``), never (``False``),
        or by default only when standard error is a terminal (a log file gets no bar).
    client : distributed.Client, optional
        Use this client (and leave it open).
    resume : bool
        Keep the rows of an earlier run of the same sweep in ``out`` and run only the others.
    timeout : float, optional
        Time budget of one point [s]: a point still running after it is recorded as failed.
        Default: the scene's ``simulation.timeout`` (None there: no budget).
    chunk : int, optional
        Points per task (default: :func:`chunk_size` of the estimated time of the chunk's
        first point, or with ``longest_first=False`` of the median time of the points
        finished so far; one point a task until the first is back).
    overwrite : bool
        Replace an earlier sweep's files of this scene in ``out`` (without it, and without
        ``resume``, such files stop the sweep before anything runs).
    longest_first : bool
        Run the points longest first, by an estimate of their wall time
        (:class:`~bearingsim.scenes.sweep_order.PointCosts`), so the workers finish together;
        False: in the given order. The rows are the same either way.

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
    check_count(n_workers, "n_workers (LocalCluster workers, --workers)", 1, "run_sweep")
    if chunk is not None:
        check_count(chunk, "chunk (points per task, --chunk)", 1, "run_sweep")
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    if scheduler is None and client is None:  # the workers' imports begin, on another core
        start_worker_server(learned_preloads(scene_file(scene.path)))
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
                      resume, timeout, chunk, longest_first)
    with OutputFolder(out, command_line()) as folder:
        earlier = _earlier_files(folder.folder, stem)
        if earlier and not (overwrite or resume):
            raise SweepError(f"{folder.folder} holds an earlier sweep of this scene ("
                             + ", ".join(earlier) + "): add --overwrite to replace it, "
                             "--resume to continue it, or give another --out")
        return _sweep(scene, points, folder, stem, scheduler, n_workers, progress, client,
                      resume, timeout, chunk, longest_first)


@contextlib.contextmanager
def _old_objects_frozen():
    """Keep the objects alive on entry (and those of each later :func:`gc.freeze`) out of
    Python's cyclic garbage collector until the exit (:func:`gc.unfreeze`): a sweep's client
    holds the model's, CasADi's and dask's objects (about 150 000), and each full collection
    scanned them all, about 0.1 s of its CPU two or three times a sweep."""
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


@_old_objects_frozen()
def _sweep(scene: Scene, points: list[dict[str, Any]], folder: OutputFolder | None, stem: str,
           scheduler: str | None, n_workers: int, progress: bool | None, client, resume: bool,
           timeout: float | None, chunk: int | None, longest_first: bool) -> SweepResult:
    """:func:`run_sweep` after its checks, writing into ``folder`` (None: nothing)."""
    wall = time.perf_counter()
    phases: dict[str, float] = {}
    clock = [wall]

    def lap(name: str) -> None:
        now = time.perf_counter()
        phases[name] = now - clock[0]
        clock[0] = now

    distributed_module()  # a named error before anything starts when it is missing
    from tqdm import tqdm

    lap("imports")
    own = client is None
    start = functools.partial(concurrent.futures.ThreadPoolExecutor(1).submit, connect,
                              scheduler, n_workers)
    resumed = resume and folder is not None and (folder.folder / f"{stem}.csv").is_file()
    # the cluster starts while the client plans; a resumed sweep's once points are left
    starting = start() if own and not resumed else None
    preparing = concurrent.futures.ThreadPoolExecutor(1)
    cluster = None
    try:
        plan = plan_sweep(scene, points)
        keys = list(points[0])
        first = next(iter(plan.prepared.values()))
        probe = None
        if scene.analysis == "modes":  # the mode names (columns) come from a point
            job = plan.jobs[0]
            probe = run_point(plan.prepared[plan.structure[job.index]], job, timeout)
            if probe["status"] != "ok":
                raise SweepError(f"the first point of this modes sweep, which names the "
                                 f"columns, failed: {probe['error']}")
        results_names, result_units = result_columns(first, probe and probe["final"])
        units = column_units(first, keys, result_units)
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
            rows = {k: {c: (from_cell(v) if c not in keys else plan.values[k][c])
                        for c, v in r.items()} for k, r in done.items()}
        todo = [job for job in plan.jobs if job.index not in rows]
        results: dict[int, dict[str, Any]] = {}

        def record(r: dict[str, Any]) -> None:
            results[r["index"]] = r
            row = table_row(r["index"], plan.values[r["index"]], results_names, r)
            rows[r["index"]] = row
            if table is not None:
                table.append(row)

        costs = PointCosts({j.index: point_features(
            j, plan.values[j.index], plan.prepared[plan.structure[j.index]].system.variable_units)
            for j in todo}) if longest_first else None
        point_s = math.nan
        if probe is not None and todo and todo[0].index == probe["index"]:
            todo.pop(0)
            point_s = probe["wall_s"]
            record(probe)
        gc.freeze()  # the model and the plan too
        lap("plan")

        if table is not None:  # while the cluster starts, then beside the points
            preparing.submit(_ready_to_write, units)
        if own and todo:
            starting = starting or start()
            try:
                client, cluster = starting.result()
            except OSError as exc:  # a scheduler that does not answer: no header-only table
                if table is not None and not rows:  # left to block the next sweep
                    table.path.unlink(missing_ok=True)
                raise SweepError(f"cannot reach the dask scheduler {scheduler}: {exc}"
                                 if scheduler else f"cannot start the LocalCluster: {exc}"
                                 ) from None
        if todo:  # (nothing left to run: no cluster)
            client.wait_for_workers(1)
        lap("cluster")
        # every worker (scheduler_info may list a few); a LocalCluster's are all up
        n_threads = sum(client.nthreads().values()) if todo else 1
        models = {key: ship(client, payload)
                  for key, payload in plan.payloads.items()
                  if any(plan.structure[j.index] == key for j in todo)}
        lap("ship")
        feeder = ChunkFeeder(client, models, [(plan.structure[j.index], j) for j in todo],
                             n_threads, timeout, chunk, point_s, plan.payloads,
                             costs) if todo else None
        bar = tqdm(total=len(points), initial=len(rows), unit="point", leave=False,
                   disable=None if progress is None else not progress)  # None: a terminal's
        try:
            for part, chunk_rows in feeder or ():
                if isinstance(chunk_rows, BaseException):  # a chunk lost for good
                    chunk_rows = [{"index": j.index, "status": "failed", "final": {},
                                   "error": f"{type(chunk_rows).__name__}: {chunk_rows}",
                                   "wall_s": float("nan")} for j in part]
                for r in chunk_rows:
                    record(r)
                bar.update(len(chunk_rows))
        except KeyboardInterrupt:
            if feeder:
                feeder.cancel()
            raise
        finally:
            bar.close()
        point_s, size = (feeder.point_s, feeder.largest) if feeder else (point_s, 0)
        lap("points")
    finally:
        preparing.shutdown()
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
    imported = sorted({m for r in results.values() if r.get("pid") != os.getpid()
                       for m in r.get("imported", ())})  # (an in-process worker: the client's)
    forked = own and scheduler is None  # a LocalCluster forked from this process's server
    if forked:  # what the workers' points imported, for the next sweep's server
        remember_preloads(scene_file(scene.path), imported)
    ordered = [rows[k] for k in sorted(rows)]
    failures = [{"point": r["point"], "values": plan.values[r["point"]], "error": r["error"]}
                for r in ordered if r["status"] != "ok"]
    res = SweepResult(keys, ordered, failures, len(plan.prepared), resumed=len(done or {}),
                      chunk_size=size, point_s=point_s, phases=phases,
                      spans={k: (r["pid"], r["started"], r["wall_s"])
                             for k, r in results.items() if "started" in r},
                      point_cpu={k: r["cpu_s"] for k, r in results.items() if "cpu_s" in r},
                      settling=("" if scene.analysis != "transient" else
                                "on purpose" if scene.transient_on_purpose else "checked"))
    res.warnings = point_warnings(results, len(points))
    for kind in res.warnings:
        warnings.warn(f"{scene.title or stem}: {kind['text']}", kind["category"], stacklevel=3)
    if res.unsettled:
        warnings.warn(f"{scene.title or stem}: {len(res.unsettled)} of {len(ordered)} point(s) "
                      "had not settled at t_end (their rows say settled False and name the "
                      "outputs in unsettled). Run longer (simulation.t_end), ask analysis = "
                      "\"steady\" for the settled points, or set transient_on_purpose = true",
                      NotSettledWarning, stacklevel=3)
    if table is not None:
        for path in table.finish(ordered):
            folder.add(path)
        folder.save_figures(lambda: sweep_figures(first, ordered, keys, results_names, units,
                                                   stem))
        summary = {
            "scene": scene.path, "analysis": scene.analysis, "points": len(ordered),
            "ok": len(res.ok), "not_settled": (len(res.unsettled)
                                               if res.settling == "checked" else None),
            "failed": len(failures), "failures": failures,
            "models_built": res.models_built,
            "resumed": res.resumed, "chunk_size": size, "point_s": point_s,
            "structures": [{"fidelity": k[0], "arguments": json.loads(k[1])}
                           for k in plan.prepared],
            "model_loads_per_worker": sorted({(r.get("pid"), r.get("model_loads"))
                                              for r in results.values()
                                              if "model_loads" in r}),
            "scheduler": scheduler or f"LocalCluster({n_workers} workers)",
            "timeout_s": timeout, "phases_s": {k: round(v, 3) for k, v in phases.items()},
            "worker_preloads": PRELOADED if forked else None, "worker_imports": imported,
            "warnings": [{"category": k["category"].__name__, "points": k["points"],
                          "message": k["message"]} for k in res.warnings],
        }
        folder.write_summary(f"{stem}.json", json.loads(json.dumps(summary, default=str)))
        res.files, res.plot_failures = list(folder.files), list(folder.plot_failures)
    lap("write")
    res.wall_s = time.perf_counter() - wall
    return res
