"""The process that a sweep's LocalCluster workers are forked from, started early.

The workers of a sweep's LocalCluster (:mod:`bearingsim.scenes.sweep_cluster`) are forked from
one server process (:mod:`multiprocessing`'s ``forkserver``) that imports dask.distributed and
bearingsim's sweep worker module once; every worker starts with them imported. Importing them
takes the server about as long as it takes the client (seconds), so the sooner the server
starts the less the sweep waits for it: ``bearingsim sweep`` and
:func:`~bearingsim.scenes.sweep.run_sweep` call :func:`start_worker_server` before they import
or load anything, and the server imports on another core while the client imports, reads the
scene and plans the sweep. This module imports nothing else of bearingsim, so that it can.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.forkserver

__all__ = ["WORKER_MODULE", "WORKER_MODULES", "start_worker_server"]

WORKER_MODULE = "bearingsim.scenes.sweep_worker"
"""The sweep worker's module (also preloaded by every worker of a sweep's cluster)."""
WORKER_MODULES = ("distributed", WORKER_MODULE)
"""Imported by the server before it forks the first worker."""


def start_worker_server() -> None:
    """Start the fork server of the sweep workers of this process, importing
    :data:`WORKER_MODULES`; returns at once (the server imports them meanwhile). A server
    already running is kept (it lives as long as this process)."""
    multiprocessing.get_context("forkserver").set_forkserver_preload(list(WORKER_MODULES))
    multiprocessing.forkserver.ensure_running()
