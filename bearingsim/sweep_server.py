"""The process that a sweep's LocalCluster workers are forked from, started early.

The workers of a sweep's LocalCluster (:mod:`bearingsim.scenes.sweep_cluster`) are forked from
one server process (:mod:`multiprocessing`'s ``forkserver``) that imports dask.distributed and
bearingsim's sweep worker module once; every worker starts with them imported. Importing them
takes the server about as long as it takes the client (seconds), so the sooner the server
starts the less the sweep waits for it: ``bearingsim sweep`` and
:func:`~bearingsim.scenes.sweep.run_sweep` call :func:`start_worker_server` before they import
or load anything, and the server imports on another core while the client imports, reads the
scene and plans the sweep. This module imports nothing else of bearingsim, so that it can. The
server also imports the modules the swept scene's workers imported at their first point in
its earlier sweeps (:mod:`bearingsim.sweep_preloads`), so that every worker starts with them.

**Ctrl-C.** A terminal sends SIGINT to every process of the foreground process group: the
client, the fork server and every worker forked from it. The client answers it (it cancels the
chunks in flight, closes the cluster and keeps the rows that finished); a worker must not, or
each one dies of its own ``KeyboardInterrupt`` and prints a traceback of dask's nanny and
asyncio (dask.distributed leaves this to the application: dask/distributed#1925). So the server
is spawned with SIGINT ignored (an ignored signal stays ignored across ``exec``, and Python
leaves it so), which keeps the server quiet while it imports; the server hands its original
handler, "ignore", to every process it forks, so the workers ignore SIGINT from their first
instruction and end when the client closes the cluster.

**One thread per worker.** A worker runs one point at a time (``threads_per_worker=1``), and
dask's nannies start the workers they spawn with one thread for BLAS and OpenMP
(``distributed.nanny.pre-spawn-environ``). A forked worker keeps the thread pool of its server,
though: numpy's OpenBLAS sizes its pool when the server imports numpy, one thread per core. So
the server is spawned with :data:`SINGLE_THREADED` set to 1 (each one the user has not set):
otherwise every worker's linear algebra runs on as many threads as the machine has cores,
beside the other workers.
"""

from __future__ import annotations

import importlib
import multiprocessing
import multiprocessing.forkserver
import os
import signal
import threading
from collections.abc import Sequence

__all__ = ["PRELOADED", "PRELOAD_VARIABLE", "SINGLE_THREADED", "WORKER_MODULE",
           "WORKER_MODULES", "import_learned", "start_worker_server"]

WORKER_MODULE = "bearingsim.scenes.sweep_worker"
"""The sweep worker's module (also preloaded by every worker of a sweep's cluster)."""
WORKER_MODULES = ("distributed", WORKER_MODULE)
"""Imported by the server before it forks the first worker."""


SINGLE_THREADED = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")
"""The thread-pool sizes the server starts with: 1 unless this process's environment sets
them (see the module's docstring)."""

PRELOADED: list[str] = []
"""The modules this process's fork server imports (set by the first
:func:`start_worker_server`; empty before)."""
PRELOAD_VARIABLE = "BEARINGSIM_SWEEP_PRELOAD"
"""The environment variable that hands the server the learned modules (:func:`import_learned`):
multiprocessing's server skips a preload that raises ImportError but dies of any other error,
and a learned module is imported under the server's own guard instead."""


def import_learned() -> None:
    """Import the modules named in :data:`PRELOAD_VARIABLE` (separated by spaces), each on its
    own: one that fails (a module gone, or one that raises as it is imported) is left to the
    workers, which import it on use and report its error. The variable is removed, so that
    the workers forked from the server do not see it. Run by the server as it imports this
    module, its last preload."""
    for name in os.environ.pop(PRELOAD_VARIABLE, "").split():
        try:
            importlib.import_module(name)
        except Exception:  # noqa: BLE001, S112 - the workers meet it again on use, and say so
            continue


def start_worker_server(preload: Sequence[str] = ()) -> None:
    """Start the fork server of the sweep workers of this process, importing
    :data:`WORKER_MODULES` and then ``preload``; returns at once (the server imports them
    meanwhile). A server already running is kept (it lives as long as this process), with what
    it imported (:data:`PRELOADED`).

    Called from the main thread, the server starts with SIGINT ignored, and so do the
    workers forked from it (see the module's docstring); this process ignores SIGINT only
    while it spawns the server.

    Parameters
    ----------
    preload : sequence of str
        More modules for the server to import: those the workers of the swept scene imported
        at their first point in its earlier sweeps
        (:func:`bearingsim.sweep_preloads.learned_preloads`; one that fails to import is
        skipped)."""
    if not PRELOADED:  # the first call of this process chooses what the server imports
        PRELOADED.extend(dict.fromkeys([*WORKER_MODULES, *preload]))
        multiprocessing.get_context("forkserver").set_forkserver_preload(
            [*WORKER_MODULES, __name__])  # this module last: it imports the learned ones
    handler = signal.getsignal(signal.SIGINT)
    if handler is None or threading.current_thread() is not threading.main_thread():
        # only the main thread sets handlers; one set outside Python cannot be put back
        _ensure_running()
        return
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        _ensure_running()
    finally:
        signal.signal(signal.SIGINT, handler)


def _ensure_running() -> None:
    """Start the server if it is not running, handing it the learned modules
    (:data:`PRELOAD_VARIABLE`) and one thread per pool (:data:`SINGLE_THREADED`), set only
    while it is spawned."""
    added = {name: "1" for name in SINGLE_THREADED if name not in os.environ}
    os.environ.update(added)
    os.environ[PRELOAD_VARIABLE] = " ".join(PRELOADED[len(WORKER_MODULES):])
    try:
        multiprocessing.forkserver.ensure_running()
    finally:
        os.environ.pop(PRELOAD_VARIABLE, None)
        for name in added:
            os.environ.pop(name, None)


if os.environ.get(PRELOAD_VARIABLE):  # in the fork server, as its last preload
    import_learned()
