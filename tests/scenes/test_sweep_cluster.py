"""Where a sweep's points run: the LocalCluster's workers forked from a server that imported
bearingsim, each with the environment of the sweep that started it; chunks fed as the workers
finish them, one point a task until a point's time is known, then sized from it."""

from __future__ import annotations

import os
import sys

import pytest

from bearingsim.scenes import load_scene
from bearingsim.scenes.sweep import grid_points
from bearingsim.scenes.sweep_cluster import (
    QUIET_CLUSTER,
    TASKS_PER_WORKER,
    ChunkFeeder,
    chunk_size,
    connect,
)
from bearingsim.scenes.sweep_grid import parse_grid
from bearingsim.scenes.sweep_plan import plan_sweep
from tests.scenes.sweep_scenes import torque_level_scene

distributed = pytest.importorskip("distributed")

SCENE = torque_level_scene()


def _worker_view() -> tuple[int, str | None, bool]:
    """(parent process id, BEARINGSIM_SWEEP_MARK, sweep worker module imported) in a worker."""
    return (os.getppid(), os.environ.get("BEARINGSIM_SWEEP_MARK"),
            "bearingsim.scenes.sweep_worker" in sys.modules)


def test_forked_workers_see_the_environment_of_their_sweep(monkeypatch):
    """The fork server keeps the environment it started with; a later sweep's workers still
    see the BEARINGSIM_ variables as they are when that sweep starts."""
    seen = []
    for mark in ("first", "second"):
        monkeypatch.setenv("BEARINGSIM_SWEEP_MARK", mark)
        client, cluster = connect(None, 1)
        try:
            [view] = client.run(_worker_view).values()
        finally:
            client.close()
            cluster.close()
        seen.append(view)
    assert [v[1] for v in seen] == ["first", "second"]
    # forked from the server (not spawned by this process), bearingsim already imported
    assert all(v[0] != os.getpid() and v[2] for v in seen)
    assert seen[0][0] == seen[1][0]  # one server for both sweeps


_BLAS_THREADS = """
import ctypes, json, numpy
def blas_threads():
    paths = {line.split()[-1] for line in open("/proc/self/maps") if "openblas" in line.lower()}
    for path in sorted(paths):
        lib = ctypes.CDLL(path)
        for name in ("scipy_openblas_get_num_threads64_", "openblas_get_num_threads64_",
                     "openblas_get_num_threads"):
            if hasattr(lib, name):
                return getattr(lib, name)()
    return None
if __name__ == "__main__":
    from bearingsim.scenes.sweep_cluster import connect
    client, cluster = connect(None, 1)
    [worker] = client.run(blas_threads).values()
    client.close()
    cluster.close()
    print(json.dumps({"worker": worker, "client": blas_threads()}))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux") or len(os.sched_getaffinity(0)) < 2,
                    reason="/proc/self/maps is Linux's; on one core one BLAS thread anyway")
def test_forked_workers_run_their_linear_algebra_on_one_thread(tmp_path):
    """dask starts a worker with one BLAS thread, but a forked worker has its server's OpenBLAS
    pool, sized when the server imported numpy: one thread per core before (each worker's
    linear algebra on every core, beside the other workers). The client keeps its own."""
    import json
    import subprocess

    script = tmp_path / "blas_threads.py"
    script.write_text(_BLAS_THREADS)
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")}
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                         env=env, check=True, cwd=os.getcwd()).stdout
    seen = json.loads(out.strip().splitlines()[-1])
    if seen["worker"] is None:
        pytest.skip("numpy's BLAS is not OpenBLAS")
    assert seen["worker"] == 1
    assert seen["client"] > 1  # the client's own pool, as OpenBLAS sized it: untouched


def _worker_settings() -> dict:
    import dask

    return {key: dask.config.get(key) for key in QUIET_CLUSTER}


def test_the_sweep_cluster_runs_without_dasks_dashboard_machinery():
    """A sweep's workers have no statistical profiler and slow monitors (dask's defaults, made
    for its dashboard, cost them several % of each point's CPU time: bench section 19); the
    settings reach the forked worker processes, and the client's own settings stay dask's."""
    import dask

    before = {key: dask.config.get(key) for key in QUIET_CLUSTER}
    client, cluster = connect(None, 1)
    try:
        [seen] = client.run(_worker_settings).values()
    finally:
        client.close()
        cluster.close()
    assert seen["distributed.worker.profile.enabled"] is False
    assert seen == QUIET_CLUSTER
    assert {key: dask.config.get(key) for key in QUIET_CLUSTER} == before


def _feed(tmp_path, n_points: int, **kwargs) -> tuple[list[int], list[int]]:
    """(points per task in submission order, point numbers returned) of a ChunkFeeder on one
    in-process worker."""
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    points = grid_points(parse_grid(
        [f"inputs.shaft_speed={','.join(str(100 + 10 * k) for k in range(n_points))}"]))
    plan = plan_sweep(load_scene(path), points)
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as client:
        models = {key: client.scatter(p, broadcast=True) for key, p in plan.payloads.items()}
        feeder = ChunkFeeder(client, models, [(plan.structure[j.index], j) for j in plan.jobs],
                             1, None, **kwargs)
        sizes, returned = [], []
        for part, rows in feeder:
            sizes.append(len(part))
            assert [r["index"] for r in rows] == [j.index for j in part]
            assert all(r["status"] == "ok" for r in rows), rows
            returned += [r["index"] for r in rows]
    return sizes, returned


def test_chunks_hold_one_point_until_a_point_time_is_known(tmp_path):
    sizes, returned = _feed(tmp_path, 6)
    assert sorted(returned) == list(range(6))  # every point once
    assert sizes[:TASKS_PER_WORKER] == [1] * TASKS_PER_WORKER


def test_chunks_are_sized_from_a_measured_point_time(tmp_path):
    """A point of 1 ms: the first tasks take a quarter of what is left (the balance bound of
    chunk_size for one worker); together they hold every point once."""
    sizes, returned = _feed(tmp_path, 24, point_s=0.001)
    assert sorted(returned) == list(range(24))
    assert sizes[0] == chunk_size(0.001, 24, 1) == 6
    assert sizes[1] == chunk_size(0.001, 18, 1) == 5
    assert sum(sizes) == 24


def test_a_fixed_chunk_size_is_kept(tmp_path):
    sizes, _ = _feed(tmp_path, 7, chunk=3)
    assert sizes == [3, 3, 1]


def test_the_last_points_wait_for_a_free_worker(tmp_path):
    """Once no more points are left to submit than there are workers, none is queued behind a
    running task (it would idle another worker at the end of the sweep): with one worker, the
    last point goes out when the task before it is back."""
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    points = grid_points(parse_grid(["inputs.shaft_speed=100,150,200,250,300"]))
    plan = plan_sweep(load_scene(path), points)
    in_flight = []
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as client:
        models = {key: client.scatter(p, broadcast=True) for key, p in plan.payloads.items()}
        feeder = ChunkFeeder(client, models, [(plan.structure[j.index], j) for j in plan.jobs],
                             1, None, chunk=1)
        for _ in feeder:
            in_flight.append((len(feeder.todo), len(feeder.running)))
    # (points to submit, tasks in flight) after each chunk is back: two in flight while
    # more than one point is left to submit; the last goes out when the worker is free
    assert in_flight == [(2, 2), (1, 2), (1, 1), (0, 1), (0, 0)]


def test_a_sweeps_results_are_tracked_on_its_own_clients_loop(tmp_path):
    """A sweep started while another client is the current one (the test suite's fixture, a
    notebook's ``with Client():``) tracked its chunks on that client's event loop, because
    dask's ``as_completed`` takes the default client's loop: the chunks' events were set from
    one loop's thread and awaited on another's, and their results fetched through the sweep
    client's connections from the wrong thread. A CLI sweep inside a test once hung there
    with both chunks finished. The feeder now tracks them on its own client's loop."""
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    plan = plan_sweep(load_scene(path),
                      grid_points(parse_grid(["inputs.shaft_speed=100,150,200"])))
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as current:
        sweep_client = distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                                          dashboard_address=":0")
        try:
            assert sweep_client.loop is not current.loop
            models = {key: sweep_client.scatter(p, broadcast=True)
                      for key, p in plan.payloads.items()}
            feeder = ChunkFeeder(sweep_client, models,
                                 [(plan.structure[j.index], j) for j in plan.jobs], 1, None)
            assert feeder.done.loop is sweep_client.loop
            returned = sorted(r["index"] for _, rows in feeder for r in rows)
        finally:
            sweep_client.close()
    assert returned == [0, 1, 2]
