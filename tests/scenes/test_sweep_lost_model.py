"""A sweep whose model is lost with the only worker holding it loses no point: the chunks in
flight, which the scheduler cancels with the model ("already forgotten"), are submitted again
with the model scattered anew to the worker that replaces it."""

from __future__ import annotations

import os
import signal
import time

import pytest

from bearingsim.scenes import load_scene
from bearingsim.scenes.sweep import grid_points
from bearingsim.scenes.sweep_cluster import TASKS_PER_WORKER, ChunkFeeder, connect
from bearingsim.scenes.sweep_grid import parse_grid
from bearingsim.scenes.sweep_plan import plan_sweep
from bearingsim.scenes.sweep_worker import load_model, run_point
from tests.scenes.sweep_scenes import torque_level_scene

distributed = pytest.importorskip("distributed")

SCENE = torque_level_scene()
N_POINTS = 8


def _kill_the_worker(client, model) -> int:
    """SIGKILL the one worker process and wait until the client hears that the model, whose
    only replica it held, is gone; returns its process id."""
    [pid] = client.run(os.getpid).values()
    os.kill(pid, signal.SIGKILL)
    deadline = time.monotonic() + 60
    while model.status == "finished" and time.monotonic() < deadline:
        time.sleep(0.02)
    assert model.status == "cancelled"  # the scheduler forgot it
    return pid


def test_chunks_of_a_model_lost_with_its_worker_are_run_again(tmp_path):
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    points = grid_points(parse_grid(
        [f"inputs.shaft_speed={','.join(str(100 + 50 * k) for k in range(N_POINTS))}"]))
    plan = plan_sweep(load_scene(path), points)
    [(key, payload)] = plan.payloads.items()
    client, cluster = connect(None, 1)  # a nanny starts a new worker when this one dies
    try:
        models = {key: client.scatter(payload, broadcast=True)}
        lost = models[key]
        feeder = ChunkFeeder(client, models, [(key, j) for j in plan.jobs], 1, None, chunk=1,
                             payloads=plan.payloads)
        rows, killed = {}, None
        for _part, chunk_rows in feeder:
            assert not isinstance(chunk_rows, BaseException), chunk_rows  # no chunk given up
            rows.update((r["index"], r) for r in chunk_rows)
            if killed is None:
                # chunks still in flight and to submit, all reading the model about to go
                assert len(feeder.running) == TASKS_PER_WORKER and feeder.todo
                killed = _kill_the_worker(client, lost)
        assert feeder.resubmitted >= TASKS_PER_WORKER  # at least the chunks in flight
        assert models[key] is not lost
    finally:
        client.close()
        cluster.close()
    assert sorted(rows) == list(range(N_POINTS))
    assert all(r["status"] == "ok" for r in rows.values()), rows
    assert {r["pid"] for r in rows.values()} - {killed}  # the others ran on the new worker
    prep = load_model(payload)  # every row as the point run here gives it
    for job in plan.jobs:
        assert rows[job.index]["final"]["Rs"] == pytest.approx(
            run_point(prep, job)["final"]["Rs"], rel=1e-12)
