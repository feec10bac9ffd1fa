"""The worker side of a sweep: a model loaded once per process, chunks of points run through
the scene runner's single-run functions, compact rows back.

A :class:`ModelPayload` carries one assembled model: the prepared scene of its structure
(everything :class:`~bearingsim.scenes.preparation.Prepared` holds but the system) and the
system as bytes (:func:`bearingsim.assembler.cache.dumps_system`, the format of the on-disk
cache). A worker loads it on first use and keeps it for the life of the process
(:data:`MODELS`), so a sweep of N points costs one load per worker and model, and a persistent
worker (``dask worker`` on a cluster) loads a model once across sweeps.

Each point runs exactly what ``bearingsim run`` runs for one operating point of that scene
(:func:`~bearingsim.scenes.analyses.run_operating_point`, whatever the scene's ``analysis``)
and returns its table row: a transient's final values with ``settled`` and
``time_constant``, a steady point's outputs, a modes point's natural frequencies or a statics
point's columns.
"""

from __future__ import annotations

import ctypes
import dataclasses
import os
import sys
import threading
import time
import uuid
import warnings
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from bearingsim.assembler.cache import loads_system
from bearingsim.scenes.analyses import run_operating_point
from bearingsim.scenes.preparation import Prepared
from bearingsim.scenes.scene import Scene
from bearingsim.sweep_preloads import imported_since

__all__ = ["MODELS", "LOADS", "ModelPayload", "Job", "PointTimeout", "dask_setup", "guard_time",
           "load_model", "process_token", "registrations", "restore_registrations", "run_chunk",
           "run_job", "run_point"]


@dataclass
class ModelPayload:
    """One assembled model for the workers (picklable; the system as bytes)."""

    token: str
    """Identifies the model: the SHA-256 (hex) of ``system``, the loaded system's
    ``content_key``."""
    prepared: Prepared
    """The prepared scene of the model's structure, ``system`` None."""
    system: bytes
    registered: bytes = b""
    """The bearings and lubricants registered in the client's process that the sweep names
    (a scene's ``bearings`` and ``[lubricants]``, or the API's ``register_bearing``),
    serialized: :func:`registrations`. A worker, another process, registers them before its
    points run (:func:`restore_registrations`): a statics point looks its bearing up by name,
    and a point of another lubricant builds the assembly to read its parameters."""


def _registries() -> tuple:
    """The registries of names a point may look up: ball and roller bearings, lubricants."""
    from bearingsim.catalog import BEARINGS
    from bearingsim.catalog.rollers import ROLLER_BEARINGS
    from bearingsim.physics.lubricant import LUBRICANTS

    return BEARINGS, ROLLER_BEARINGS, LUBRICANTS


_RESTORED: dict[str, dict[str, Any]] = {}
"""What :func:`restore_registrations` registered in this process for the last chunk, by
registry kind and name."""

_PROCESS: dict[int, str] = {}


def process_token() -> str:
    """A text that names this process among all (a worker on another machine may have the
    client's process id; a forked process gets a token of its own).

    Returns
    -------
    str
        The token.
    """
    pid = os.getpid()
    if pid not in _PROCESS:
        _PROCESS.clear()
        _PROCESS[pid] = f"{pid}-{uuid.uuid4().hex}"
    return _PROCESS[pid]


def registrations(names: Iterable[str]) -> bytes:
    """The registered bearings (ball and roller) and lubricants of this process that
    ``names`` name (:meth:`bearingsim.registry.Registry.registered`), serialized with
    cloudpickle (a scene's lubricant is a closure); empty when it names none. Only those:
    whatever else the process registered (a test's, another scene's) stays here, so an entry
    the workers could not load never reaches them.

    Parameters
    ----------
    names : iterable of str
        The texts a sweep's scene and points give (designations, lubricant names ...).

    Returns
    -------
    bytes
        ``{registry kind: {name: entry}, "process": process_token()}`` pickled, or ``b""``.
    """
    names = set(names)
    shipped = {}
    for registry in _registries():
        registered = registry.registered()
        used = {registry.find(n) for n in names} & set(registered)
        if used:
            shipped[registry.kind] = {n: registered[n] for n in sorted(used)}
    if not shipped:
        return b""
    import cloudpickle  # (a dependency of dask, which sweeps need)

    return cloudpickle.dumps({**shipped, "process": process_token()})


def restore_registrations(data: bytes) -> None:
    """Register in this process what :func:`registrations` serialized in another, replacing
    entries of the same names; what it registered for an earlier sweep's chunks and this one
    does not name is forgotten first (a persistent worker; an entry that replaced a built-in
    one gives it back). In the client's own process (a worker thread there) nothing is done:
    its registries are the client's.

    Parameters
    ----------
    data : bytes
        From :func:`registrations`.

    Raises
    ------
    RuntimeError
        When they cannot be loaded here (each point of the chunk then fails with why).
    """
    import pickle

    try:
        shipped = pickle.loads(data) if data else {}  # noqa: S301 - the sweep's own client's
    except Exception as exc:  # noqa: BLE001 - named for every point of the chunk
        raise RuntimeError(f"the client's registered bearings and lubricants cannot be loaded "
                           f"in this worker: {type(exc).__name__}: {exc}") from None
    if shipped.get("process") == process_token():
        return
    for registry in _registries():
        entries = shipped.get(registry.kind, {})
        for name, entry in _RESTORED.pop(registry.kind, {}).items():
            if name not in entries:
                registry.forget(name, entry)
        for name, entry in entries.items():
            registry.register(name, entry, replace=True)
        registered = registry.registered()
        _RESTORED[registry.kind] = {n: registered[n] for n in entries}


@dataclass
class Job:
    """One sweep point."""

    index: int
    scene: Scene
    """The scene with the point's values applied (inputs, parameters, initial values,
    simulation settings, assembly arguments: the run derives the parameter overrides of
    parametric ones, :func:`~bearingsim.scenes.operating_points.point_model`)."""


MODELS: dict[str, Prepared] = {}
"""Models loaded in this process, by token."""
LOADS: dict[str, int] = {}
"""How often each model was loaded in this process (for tests and the sweep summary)."""
_LOCK = threading.Lock()


def load_model(payload: ModelPayload) -> Prepared:
    """The prepared model of ``payload``, loaded on first use in this process.

    Parameters
    ----------
    payload : ModelPayload
        The model.

    Returns
    -------
    Prepared
        The prepared model.
    """
    with _LOCK:
        prep = MODELS.get(payload.token)
        if prep is None:
            system = loads_system(payload.system, content_key=payload.token)
            prep = dataclasses.replace(payload.prepared, system=system)
            MODELS[payload.token] = prep
            LOADS[payload.token] = LOADS.get(payload.token, 0) + 1
        return prep


def run_job(prep: Prepared, job: Job) -> dict[str, Any]:
    """Run one point; returns ``index``, ``status`` ("ok"/"failed"), ``final`` (the table
    row of :func:`~bearingsim.scenes.analyses.run_operating_point`, columns starting with
    ``_`` left out), ``error``, ``wall_s``, ``cpu_s`` (the CPU time of the thread that ran
    it [s]: below ``wall_s`` by the time it waited for a core), ``pid`` and ``started`` (the
    epoch time [s] the point started, for a timeline of the workers) and ``warnings``, the
    warnings the point gave, each once (category, message), for the client to report
    (:func:`~bearingsim.scenes.sweep_results.point_warnings`) instead of the worker's
    standard error. Never raises for a failing point.

    Parameters
    ----------
    prep : Prepared
        The prepared model.
    job : Job
        The point.

    Returns
    -------
    dict
        The point's row.
    """
    t0, cpu0 = time.perf_counter(), time.thread_time()
    row: dict[str, Any] = {"index": job.index, "pid": os.getpid(), "started": time.time()}
    with warnings.catch_warnings(record=True) as caught:  # one point at a time per process
        warnings.simplefilter("always")
        try:
            values = run_operating_point(dataclasses.replace(prep, scene=job.scene))
            final = {k: v for k, v in values.items() if not k.startswith("_")}
            for name in prep.outputs:
                if isinstance(final.get(name), float) and np.isnan(final[name]):
                    raise ValueError(f"output {name} is NaN")
            row.update(status="ok", final=final, error="")
        except Exception as exc:  # noqa: BLE001 - a failed point is reported, never fatal
            row.update(status="failed", final={}, error=f"{type(exc).__name__}: {exc}")
    row["warnings"] = list(dict.fromkeys((w.category, str(w.message)) for w in caught))
    row["wall_s"] = time.perf_counter() - t0
    row["cpu_s"] = time.thread_time() - cpu0
    return row


class PointTimeout(Exception):
    """Raised inside a point's thread when it exceeds its time budget."""


def guard_time(timeout: float) -> float:
    """Wall time [s] after which a point's thread is given up for a point budget of
    ``timeout`` seconds: the budget plus a quarter and a second.

    The point's run has the budget itself (``simulation.timeout``: every integrator,
    SUNDIALS included, stops in a :class:`~bearingsim.errors.BudgetExceededError` once its
    integration used it up, and the point is recorded with that error); the guard, later by
    the set-up's share, ends what does not integrate (a statics or steady point's solve, a
    set-up that hangs).

    Parameters
    ----------
    timeout : float
        The point's time budget [s].

    Returns
    -------
    float
        The guard's wall time [s].
    """
    return 1.25 * timeout + 1.0


def _run_with_budget(prep: Prepared, job: Job, timeout: float) -> dict[str, Any]:
    """:func:`run_job` in a thread; a point still running after :func:`guard_time` is
    returned as failed, and :class:`PointTimeout` is raised in its thread, which stops it at
    its next return to Python (the sweep goes on either way)."""
    box: dict[str, Any] = {}
    thread = threading.Thread(target=lambda: box.update(run_job(prep, job)), daemon=True,
                              name=f"sweep-point-{job.index}")
    thread.start()
    thread.join(guard_time(timeout))
    if thread.is_alive():
        ctypes.pythonapi.PyThreadState_SetAsyncExc(ctypes.c_ulong(thread.ident),
                                                   ctypes.py_object(PointTimeout))
        return {"index": job.index, "pid": os.getpid(), "status": "failed", "final": {},
                "error": f"TimeoutError: the point exceeded its time budget of {timeout:g} s",
                "wall_s": guard_time(timeout)}
    return box


def run_point(prep: Prepared, job: Job, timeout: float | None = None) -> dict[str, Any]:
    """:func:`run_job`, within a time budget of ``timeout`` seconds when given.

    Parameters
    ----------
    prep : Prepared
        The prepared model.
    job : Job
        The point.
    timeout : float, optional
        Time budget [s], > 0 (None: none).

    Returns
    -------
    dict
        The point's row (:func:`run_job`).
    """
    return run_job(prep, job) if timeout is None else _run_with_budget(prep, job, timeout)


def run_chunk(payload: ModelPayload, jobs: list[Job], timeout: float | None = None
              ) -> list[dict[str, Any]]:
    """Run a chunk of points of one model (a dask task); one row per point.

    Parameters
    ----------
    payload : ModelPayload
        The model (loaded once per process).
    jobs : list of Job
        The points.
    timeout : float, optional
        Time budget of each point [s] (None: none).

    Returns
    -------
    list of dict
        The rows (:func:`run_point`), in ``jobs`` order; the last also has ``imported``, the
        modules this process imported since its last report (the first: since the worker
        started, :func:`dask_setup`), when there are any.
    """
    restore_registrations(payload.registered)
    prep = load_model(payload)
    rows = []
    for job in jobs:
        row = run_point(prep, job, timeout)
        row["model_loads"] = LOADS.get(payload.token, 0)
        rows.append(row)
    imported = imported_since(_REPORTED[0])  # the modules the points needed, once each
    if imported and rows:
        _REPORTED[0] = frozenset(sys.modules)
        rows[-1]["imported"] = imported
    return rows


_REPORTED = [frozenset(sys.modules)]
"""The modules of this process when they were last reported (:mod:`bearingsim.sweep_preloads`),
first those of its start (:func:`dask_setup`), so that a worker reports what its points
imported."""


def dask_setup(worker: Any) -> None:
    """Called by dask in every worker process that preloads this module (a sweep's LocalCluster,
    ``dask worker --preload``) when it starts: the modules it has then (the fork server's
    and dask's) are not the points' (:data:`_REPORTED`).

    Parameters
    ----------
    worker : distributed.Worker
        The worker (unused).
    """
    _REPORTED[0] = frozenset(sys.modules)
