"""Where a sweep's points run, and how they are fed to the workers.

**The cluster.** Given a scheduler address, a sweep connects to it (``dask scheduler`` and
``dask worker`` processes started elsewhere). Otherwise it starts a LocalCluster whose worker
processes are forked from one server process that imported bearingsim once
(:mod:`bearingsim.sweep_server`, started before the sweep imports or plans anything, so that
it imports on another core meanwhile): N workers cost one import of bearingsim instead of N,
and little of it after the client is ready; a later sweep in the same Python
process forks its workers from the running server in a fraction of a second, and a forked
worker exits without the teardown of a spawned interpreter. One thread per worker (the
solvers hold the GIL), no dashboard.

**Feeding.** Chunks of points go out as the workers finish them, a few tasks per worker in
flight (one running and the next queued on the worker, so a worker never waits for the
client). The last points, no more than there are workers, go out one per worker that is free:
a point queued behind another on one worker while a second worker has nothing left to do
would leave that worker idle at the end of the sweep for up to a point's time. Given the
estimates of :class:`~bearingsim.scenes.sweep_order.PointCosts`, the points go out longest
first (the order is revised as the estimates improve), so the last points are the short ones
and the workers finish together; each chunk is sized from the estimated time of its first
point (:func:`chunk_size`: about :data:`CHUNK_SECONDS` of work per task, smaller towards the
end of the sweep); without estimates, in the given order, sized from the median wall time of
the points finished so far. Until the first point is back, chunks hold one point. The client
does nothing heavy while the workers run: it records rows and submits the next chunk.
"""

from __future__ import annotations

import logging
import math
import os
import statistics
import time
from collections.abc import Iterator
from typing import Any

from bearingsim.scenes.sampling import SweepError
from bearingsim.scenes.sweep_order import PointCosts
from bearingsim.scenes.sweep_worker import Job, run_chunk
from bearingsim.sweep_server import WORKER_MODULE, start_worker_server

__all__ = ["CHUNK_SECONDS", "CHUNKS_PER_WORKER", "TASKS_PER_WORKER", "QUIET_CLUSTER", "RESUBMITS",
           "distributed_module",
           "connect", "ship", "chunk_size", "ChunkFeeder"]

CHUNK_SECONDS = 2.0
"""Target wall time of one task [s]: a chunk holds about this much integration. A task costs
its worker a few milliseconds (messages, task state) on a quiet machine and more under load:
measured on 2 loaded cores, 64 ball-level points of 0.4-0.9 s on 2 workers, 5-7 ms between
two tasks on a worker, against none between two points of one task; 2 s chunks instead of 1 s
halved the client's CPU time per point and cut the mean gap between points from 5-7 ms to
1.4-5 ms. The balance bound of :func:`chunk_size` keeps the last chunks small whatever this
is."""
CHUNKS_PER_WORKER = 4
"""At least this many chunks per worker of the points still to go (balance at the end)."""
TASKS_PER_WORKER = 2
"""Tasks in flight per worker thread: one running, one queued on the worker (one per worker
for the last points, :meth:`ChunkFeeder._in_flight`)."""
WORKERS_RECOUNT_S = 2.0
"""How often the worker threads are counted again during a sweep [s] (on a cluster, workers
join and leave)."""
RESUBMITS = 100
"""Most chunks of one sweep submitted again after the scheduler cancelled them (their model
lost with a worker)."""
QUIET_CLUSTER = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "1s",
}
"""dask settings of a sweep's LocalCluster (scheduler, nannies and workers). dask's defaults
serve its dashboard: a statistical profiler sampling the task thread every 10 ms, an event-loop
tick every 20 ms, a system monitor every 0.5 s and each nanny's memory monitor every 0.1 s.
Measured beside an 8 s task, they cost the worker process 6-9 % of the task's CPU time in its
other threads and the client's process (scheduler and nanny) 5-11 %; with these settings about
1 % each (bench section 19, ``python -m bench.sweep_scaling``). On a machine whose cores all
run workers, that CPU comes out of the points. A worker still ends at its memory limit (checked
every second instead of every 0.1 s)."""


def distributed_module():
    """The ``distributed`` package, or a named error saying how to install it.

    Returns
    -------
    module
        The ``distributed`` package.
    """
    try:
        import distributed
    except ImportError:
        raise SweepError("sweeps run on dask.distributed, which is not installed: "
                         "pip install 'bearingsim[dask]'") from None
    return distributed


def _forked_local_cluster(n_workers: int):
    """A LocalCluster of ``n_workers`` single-thread worker processes forked from a server
    that imported bearingsim (started on first use, kept for the life of this process);
    returns when every worker is up."""
    import dask
    import distributed.utils
    from distributed import LocalCluster

    # distributed's first forkserver context would import its optional packages (pandas, ...)
    # into this process to preload them in the server (while the client plans); the workers
    # need bearingsim's modules instead, which the server imports (started by now, usually)
    distributed.utils._forkserver_preload_set = True
    start_worker_server()
    # the variables bearingsim reads at run time go to every worker as they are now (the
    # fork server keeps the environment it started with)
    env = {k: v for k, v in os.environ.items() if k.startswith("BEARINGSIM_")}
    with dask.config.set({"distributed.worker.multiprocessing-method": "forkserver",
                          **QUIET_CLUSTER}):
        return LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                            preload=[WORKER_MODULE], env=env, dashboard_address=None,
                            # no dashboard; the scheduler's HTTP server on a free port
                            scheduler_kwargs={"dashboard_address": ":0"},
                            silence_logs=logging.CRITICAL)


def connect(scheduler: str | None, n_workers: int) -> tuple[Any, Any]:
    """``(client, cluster)``: a client of the scheduler at ``scheduler`` (cluster None), or of
    a new LocalCluster of ``n_workers`` forked workers (see the module's docstring).

    Parameters
    ----------
    scheduler : str or None
        Scheduler address (None: a new LocalCluster).
    n_workers : int
        Workers of a new LocalCluster, >= 1.

    Returns
    -------
    tuple
        ``(client, cluster)``.
    """
    distributed = distributed_module()
    if scheduler:
        return distributed.Client(scheduler), None
    cluster = _forked_local_cluster(n_workers)
    return distributed.Client(cluster), cluster


def ship(client: Any, payload: Any) -> Any:
    """Send a model's payload to every worker (``Client.scatter``, broadcast); its future.

    The payload is scattered under a random key (``hash=False``): dask would otherwise hash
    its megabytes to name it, about 0.1 s per model of the client's time (the payload carries
    its own token already).

    Parameters
    ----------
    client : distributed.Client
        The sweep's client.
    payload : ModelPayload
        The model (:mod:`~bearingsim.scenes.sweep_plan`).

    Returns
    -------
    distributed.Future
        The scattered payload.
    """
    return client.scatter(payload, broadcast=True, hash=False)


def chunk_size(point_s: float, n_points: int, n_workers: int) -> int:
    """Points per task: about :data:`CHUNK_SECONDS` of work, and at least
    :data:`CHUNKS_PER_WORKER` tasks per worker.

    Parameters
    ----------
    point_s : float
        Measured wall time of one point [s] (NaN: not known yet, one point a task).
    n_points, n_workers : int
        Points still to run and workers to run them.

    Returns
    -------
    int
        Points per task, >= 1.
    """
    by_time = CHUNK_SECONDS / max(point_s, 1e-4) if math.isfinite(point_s) else 1.0
    by_balance = n_points / (CHUNKS_PER_WORKER * max(n_workers, 1))
    return max(1, min(int(by_time), math.ceil(by_balance)))


class ChunkFeeder:
    """Chunks of points submitted as the workers finish them; iterate for the results.

    Parameters
    ----------
    client : distributed.Client
    models : dict
        Structure key -> future of the model's :class:`~bearingsim.scenes.sweep_worker.
        ModelPayload` on the workers.
    jobs : list of (structure key, Job)
        The points to run, in order.
    n_workers : int
        Worker threads to keep busy.
    timeout : float, optional
        Time budget of one point [s].
    chunk : int, optional
        Fixed points per task (None: sized from the measured point times).
    point_s : float
        A point's wall time measured beforehand [s] (NaN: none).
    payloads : dict, optional
        Structure key -> the model's payload, scattered again when a dying worker took the
        model with it (None: such chunks fail).
    costs : PointCosts, optional
        Estimates of the points' wall times: the points go out longest first and a chunk is
        sized from the estimate of its first point (None: in the given order, chunks sized
        from the median time of the points finished so far).
    """

    def __init__(self, client, models: dict[tuple, Any], jobs: list[tuple[tuple, Job]],
                 n_workers: int, timeout: float | None, chunk: int | None = None,
                 point_s: float = math.nan, payloads: dict[tuple, Any] | None = None,
                 costs: PointCosts | None = None):
        self.client = client
        self.models = models
        self.payloads = payloads or {}
        self.resubmitted = 0
        """Chunks submitted again after the scheduler cancelled them (their model lost with a
        worker)."""
        self._model_of: dict[Any, tuple[tuple, Any]] = {}
        """Chunk future -> (structure key, the model future it reads)."""
        self._cancelled = False
        self.todo = list(jobs)
        self.n_workers = max(1, n_workers)
        self.timeout = timeout
        self.chunk = chunk
        self.times: list[float] = [] if math.isnan(point_s) else [point_s]
        self.largest = 0
        """Most points in one task so far."""
        self.running: dict[Any, list[Job]] = {}
        self.costs = costs
        self._ordered = -1
        """:attr:`PointCosts.version` the points still to go were last ordered by."""
        self._workers_seen: set[Any] = set()
        self._counted = time.monotonic()
        # results come with the futures (fetched by the client's event loop, not one
        # round trip per chunk after it is reported done); tracked on this client's loop, not
        # the default client's (dask's default), which may be another one's
        self.done = distributed_module().as_completed(loop=client.loop, with_results=True,
                                                      raise_errors=False)

    @property
    def point_s(self) -> float:
        """Median wall time of the points finished so far [s] (NaN: none yet).

        Returns
        -------
        float
            Median wall time [s] or NaN.
        """
        return statistics.median(self.times) if self.times else math.nan

    def _size(self) -> int:
        if self.chunk is not None:
            return self.chunk
        head = self.costs.estimate(self.todo[0][1].index) if self.costs else math.nan
        return chunk_size(head if math.isfinite(head) else self.point_s, len(self.todo),
                          self.n_workers)

    def _order(self) -> None:
        """Put the points still to go longest first when the estimates changed."""
        if self.costs is None or self.costs.version == self._ordered:
            return
        by_index = {job.index: (key, job) for key, job in self.todo}
        self.todo = [by_index[k] for k in self.costs.longest_first(list(by_index))]
        self._ordered = self.costs.version

    def _measured(self, rows: list[dict[str, Any]]) -> None:
        """Note the wall times of a chunk's finished points."""
        for r in rows:
            if r["status"] != "ok":
                continue
            self.times.append(r["wall_s"])
            if self.costs is not None:
                worker = r.get("pid")
                self.costs.add(r["index"], r["wall_s"], worker not in self._workers_seen)
                self._workers_seen.add(worker)

    def _in_flight(self) -> int:
        """Most tasks in flight: :data:`TASKS_PER_WORKER` per worker, one per worker once no
        more points are left to submit than there are workers."""
        per_worker = TASKS_PER_WORKER if len(self.todo) > self.n_workers else 1
        return per_worker * self.n_workers

    def _fill(self) -> None:
        """Submit chunks until :meth:`_in_flight` tasks are in flight."""
        if time.monotonic() - self._counted > WORKERS_RECOUNT_S:  # workers joined or left
            self.n_workers = max(1, sum(self.client.nthreads().values()))
            self._counted = time.monotonic()
        self._order()
        while self.todo and len(self.running) < self._in_flight():
            key = self.todo[0][0]
            size = self._size()
            part, rest = [], []
            for item in self.todo:  # the next points of the first one's model, in order
                (part if item[0] == key and len(part) < size else rest).append(item)
            self.todo = rest
            part = [job for _, job in part]
            self._submit(key, part)
            self.largest = max(self.largest, len(part))

    def _submit(self, key: tuple, part: list[Job]) -> None:
        """Submit one chunk of the model ``key``."""
        model = self.models[key]
        task = self.client.submit(run_chunk, model, part, self.timeout, pure=False,
                                  key=f"sweep-chunk-{part[0].index}-{time.time_ns()}")
        self.running[task] = part
        self._model_of[task] = (key, model)
        self.done.add(task)

    def __iter__(self) -> Iterator[tuple[list[Job], list[dict[str, Any]] | BaseException]]:
        """``(jobs, rows)`` of each finished chunk, or ``(jobs, exception)`` of a chunk lost
        for good."""
        self._fill()
        for task, result in self.done:
            part = self.running.pop(task)
            key, model = self._model_of.pop(task)
            if task.status == "cancelled" and self._run_again(key, model, part):
                continue
            # an error comes as (type, exception, traceback), a cancelled task as its error
            rows = result[1] if task.status == "error" else result
            if not isinstance(rows, BaseException):
                self._measured(rows)
            self._fill()
            yield part, rows

    def _run_again(self, key: tuple, model: Any, part: list[Job]) -> bool:
        """Submit a chunk cancelled by the scheduler again, at most :data:`RESUBMITS` times a
        sweep; True when it was.

        The scheduler cancels a chunk when the model it reads is lost: it forgets scattered
        data whose last replica goes with a dying worker, and cancels the chunks in flight
        that read it ("already forgotten") and any submitted after ("lost dependencies"). The
        first such chunk back scatters the model anew to the workers there are (waiting for
        one); the chunk goes out again with it. Chunks that :meth:`cancel` cancelled are not
        run again."""
        if self._cancelled or not self.payloads or self.resubmitted >= RESUBMITS:
            return False
        if self.models[key] is model and model.status != "finished":
            self.models[key] = ship(self.client, self.payloads[key])
        self.resubmitted += 1
        self._submit(key, part)
        return True

    def cancel(self) -> None:
        """Cancel the chunks in flight; submit no more."""
        self._cancelled = True
        self.todo.clear()
        self.client.cancel(list(self.running))
