"""A sweep on a real dask deployment: ``dask scheduler`` and two ``dask worker`` processes
started from the command line, talking TCP on 127.0.0.1 as on a cluster; the sweep reaches them
with ``--scheduler tcp://...``. A worker killed mid-sweep loses nothing: the scheduler re-runs
its chunks on the other worker."""

from __future__ import annotations

import csv
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from bearingsim.scenes import load_scene, run_scene
from bearingsim.scenes.sweep import grid_points, run_sweep
from bearingsim.scenes.sweep_grid import parse_grid
from tests.catalog.datasheets import NU206_AS_MINE
from tests.scenes.sweep_scenes import torque_level_scene

distributed = pytest.importorskip("distributed")

WORKTREE = Path(__file__).resolve().parents[2]
DASK = Path(sys.executable).parent / "dask"
SCENE = torque_level_scene(("Rs", "M_shaft"), t_end=0.05)


def _start(args: list[str]) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": str(WORKTREE)}
    return subprocess.Popen([str(DASK), *args], env=env, start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def _stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()


def _scheduler_address(info: Path, deadline: float) -> str:
    """The address in the scheduler's file, once the file is written whole (the scheduler
    creates it, then writes it)."""
    while True:
        try:
            return json.loads(info.read_text())["address"]
        except (OSError, ValueError, KeyError):
            if time.monotonic() > deadline:
                raise
            time.sleep(0.1)


@pytest.fixture()
def deployment(tmp_path):
    """(scheduler address, worker processes): one scheduler and two single-thread workers,
    each its own ``dask`` command, preloading bearingsim's sweep worker module."""
    if not DASK.is_file():
        pytest.skip("the dask command line is not installed")
    info = tmp_path / "scheduler.json"
    procs = [_start(["scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                     "--scheduler-file", str(info)])]
    try:
        address = _scheduler_address(info, time.monotonic() + 90)
        workers = [_start(["worker", address, "--nthreads", "1", "--nworkers", "1",
                           "--no-dashboard", "--host", "127.0.0.1",
                           "--preload", "bearingsim.scenes.sweep_worker"]) for _ in range(2)]
        procs += workers
        with distributed.Client(address) as client:
            client.wait_for_workers(2, timeout=120)
        yield address, workers
    finally:
        for proc in reversed(procs):
            _stop(proc)


def test_sweep_through_the_command_line_on_a_tcp_scheduler(deployment, tmp_path):
    address, _ = deployment
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    out = tmp_path / "out"
    done = subprocess.run(
        [sys.executable, "-m", "bearingsim.cli", "sweep", str(path), "--grid",
         "inputs.shaft_speed=100,200,300,400", "--scheduler", address, "--out", str(out),
         "--no-progress"], env={**os.environ, "PYTHONPATH": str(WORKTREE)},
        capture_output=True, text=True, timeout=240)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "4 point(s): 4 settled, 0 not settled, 0 failed" in done.stdout
    rows = list(csv.DictReader((out / "bearing.sweep.csv").open()))
    assert [r["status"] for r in rows] == ["ok"] * 4
    summary = json.loads((out / "bearing.sweep.json").read_text())
    assert summary["scheduler"] == address
    single = run_scene(load_scene(path).replace(inputs={"shaft_speed": 400.0}), write=False)
    assert float(rows[3]["Rs [-]"]) == pytest.approx(float(single.series["Rs"][-1]),
                                                     rel=1e-12)


def test_a_worker_killed_mid_sweep_loses_nothing(deployment, tmp_path):
    address, workers = deployment
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    points = grid_points(parse_grid(["inputs.shaft_speed=" + ",".join(
        str(100 + 25 * k) for k in range(24))]))
    out = tmp_path / "out"
    box: dict = {}
    sweep = threading.Thread(target=lambda: box.update(res=run_sweep(
        path, points, scheduler=address, out=out, progress=False, chunk=1)))
    sweep.start()
    table = out / "bearing.sweep.csv"
    deadline = time.monotonic() + 180
    while time.monotonic() < deadline and sweep.is_alive():
        if table.is_file() and table.read_text().count("\n") >= 3:
            break
        time.sleep(0.05)
    before = table.read_text().count("\n") - 1
    _stop(workers[0])  # SIGKILL to the worker and its nanny: gone for good
    sweep.join(300)
    assert not sweep.is_alive()
    res = box["res"]
    assert before < len(points), "the worker must be killed mid-sweep"
    assert len(res.rows) == len(points) and len(res.ok) == len(points), res.failures
    assert [r["point"] for r in res.rows] == list(range(len(points)))


_DATASHEET = """
[[bearing]]
designation = "MY6304"
d_mm = 20.0
D_mm = 52.0
B_mm = 15.0
Z = 7
Dw_mm = 9.52
dm_mm = 36.0
C_kN = 15.9
C0_kN = 7.9
"""




@pytest.fixture()
def scene_bearings_forgotten():
    """The bearings the test's scenes register (process-wide) are forgotten after it, so that
    a later test in this process may register the same designations."""
    from bearingsim.catalog import BEARINGS
    from bearingsim.catalog.rollers import ROLLER_BEARINGS

    before = {r.kind: set(r.registered()) for r in (BEARINGS, ROLLER_BEARINGS)}
    yield
    for registry in (BEARINGS, ROLLER_BEARINGS):
        for name in set(registry.registered()) - before[registry.kind]:
            registry.unregister(name)


def test_workers_know_the_scenes_own_bearings_and_lubricants(deployment, tmp_path,
                                                              scene_bearings_forgotten):
    """A scene's ``bearings`` and ``[lubricants]`` are registered in the process that reads it;
    the workers, other processes, did not know them. Every point of a statics sweep of a
    scene's own bearing failed ("unknown bearing 'MY6304'"), and in a sweep over the
    lubricant every point but the scene's own failed ("unknown lubricant 'my oil'": a point
    builds the assembly to read the parameters of its lubricant and of the scene's). The
    payload now carries the client's registrations; each row equals the single run."""
    address, _ = deployment
    (tmp_path / "my.toml").write_text(_DATASHEET)
    statics = tmp_path / "own_bearing.toml"
    statics.write_text("""
title = "own bearing"
analysis = "statics"
bearings = "my.toml"
[assembly]
name = "deep_groove_ball_bearing"
bearing = "MY6304"
fidelity = "quasi-static"
[inputs]
shaft_speed = "1730 rpm"
""")
    res = run_sweep(statics, grid_points(parse_grid(["inputs.load.Fx=500,900"])),
                    scheduler=address, out=tmp_path / "o1", progress=False)
    assert len(res.ok) == 2, res.failures
    scene = load_scene(statics)
    single = run_scene(scene.replace(inputs={**scene.inputs, "load.Fx": 900.0}),
                       write=False).rows[0]
    assert res.rows[1]["Q_max"] == pytest.approx(single["Q_max"], rel=1e-12)
    assert res.rows[1]["L10h"] == pytest.approx(single["L10h"], rel=1e-12)

    steady = tmp_path / "own_oil.toml"
    steady.write_text("""
title = "own oil"
analysis = "steady"
outputs = ["Rs", "M_shaft"]
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
lubrication = "my oil"
[lubricants."my oil"]
base = "ISO VG 68"
temperature = "80 degC"
[inputs]
shaft_speed = "6000 rpm"
Fr = "500 N"
Fa = 50.0
""")
    res = run_sweep(steady, [{"assembly.lubrication": n} for n in ("my oil", "ISO VG 68")],
                    scheduler=address, out=tmp_path / "o2", progress=False)
    assert len(res.ok) == 2, res.failures
    scene = load_scene(steady)
    for row, oil in zip(res.rows, ("my oil", "ISO VG 68"), strict=True):
        one = run_scene(scene.replace(args={**scene.args, "lubrication": oil}),
                        write=False).rows[0]
        assert row["M_shaft"] == pytest.approx(one["M_shaft"], rel=1e-9)
    assert res.rows[0]["M_shaft"] != pytest.approx(res.rows[1]["M_shaft"], rel=1e-3)

    # a roller bearing of the scene's datasheet (its own registry: ROLLER_BEARINGS)
    (tmp_path / "nu.toml").write_text(NU206_AS_MINE)
    roller = tmp_path / "own_roller.toml"
    roller.write_text('title = "own NU"\nanalysis = "statics"\nbearings = "nu.toml"\n'
                      '[assembly]\nname = "cylindrical_roller_bearing"\nbearing = "MYNU206"\n'
                      'fidelity = "quasi-static"\n')
    res = run_sweep(roller, grid_points(parse_grid(["inputs.load.Fx=2000,8000"])),
                    scheduler=address, out=tmp_path / "o3", progress=False)
    assert len(res.ok) == 2, res.failures
    scene = load_scene(roller)
    single = run_scene(scene.replace(inputs={"load.Fx": 8000.0}), write=False).rows[0]
    assert res.rows[1]["Q_max"] == pytest.approx(single["Q_max"], rel=1e-12)
