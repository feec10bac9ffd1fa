"""Sweep results that survive: rows appended as points finish, a killed sweep resumed gives
the table of an uninterrupted one, a point over its time budget fails alone, and chunks are
sized from the measured time of a point."""

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

import bearingsim
from bearingsim.scenes.outputs import LOCK_NAME, OutputFolder, OutputFolderBusy
from bearingsim.scenes.sweep import (
    CHUNK_SECONDS,
    SweepError,
    chunk_size,
    grid_points,
    run_sweep,
)
from bearingsim.scenes.sweep_grid import parse_grid

distributed = pytest.importorskip("distributed")

SCENE = """outputs = ["Rs", "M_shaft"]
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
[inputs]
shaft_speed = 300.0
Fr = 100.0
[simulation]
t_end = 0.05
n_points = 3
method = "BDF"   # stopped at its next step when over a point's time budget (SUNDIALS: per call)
"""
GRID = ["inputs.shaft_speed=100,150,200,250,300,350,400,450,500,550,600,650",
        "inputs.Fr=100,400"]
PACKAGE_ROOT = Path(bearingsim.__file__).resolve().parents[1]
"""The folder of the bearingsim these tests import, for the commands they start."""



@pytest.fixture()
def scene(tmp_path):
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE)
    return path


def _table(folder: Path) -> list[dict[str, str]]:
    """The table without the wall time (the only column that differs between runs)."""
    rows = list(csv.DictReader((folder / "bearing.sweep.csv").open()))
    return [{k: v for k, v in r.items() if k != "wall_s [s]"} for r in rows]


def test_a_killed_sweep_resumed_gives_the_uninterrupted_table(scene, tmp_path, client):
    points = grid_points(parse_grid(GRID))
    whole = tmp_path / "whole"
    run_sweep(scene, points, client=client, out=whole, progress=False)
    # the same sweep from the command line, killed (SIGKILL: no clean-up of any kind) as soon
    # as its first rows are in the table
    killed = tmp_path / "killed"
    cmd = [sys.executable, "-m", "bearingsim.cli", "sweep", str(scene), "--out", str(killed),
           "--workers", "1", "--chunk", "1", "--no-progress"]
    for g in GRID:
        cmd += ["--grid", g]
    env = {**os.environ, "PYTHONPATH": str(PACKAGE_ROOT)}
    proc = subprocess.Popen(cmd, env=env, start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    table = killed / "bearing.sweep.csv"
    try:
        deadline = time.monotonic() + 240
        while time.monotonic() < deadline and proc.poll() is None:
            if table.is_file() and table.read_text().count("\n") >= 3:  # header + 2 rows
                break
            time.sleep(0.05)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    written = table.read_text().count("\n") - 1
    assert 2 <= written < len(points), "the sweep must be killed mid-way"
    # readable while it ran: whole rows under the header
    assert all(r["status"] == "ok" for r in csv.DictReader(table.open()))
    with table.open("a") as fh:  # and a row cut by the kill is dropped on resume
        fh.write("23,650,400,o")
    res = run_sweep(scene, points, client=client, out=killed, progress=False, resume=True)
    assert res.resumed == written and len(res.rows) == len(points)
    assert _table(killed) == _table(whole)


def test_resume_refuses_another_sweeps_table(scene, tmp_path, client):
    out = tmp_path / "out"
    run_sweep(scene, grid_points(parse_grid(["inputs.shaft_speed=100,200"])), client=client,
              out=out, progress=False)
    with pytest.raises(SweepError, match="point 1 .* other values"):
        run_sweep(scene, grid_points(parse_grid(["inputs.shaft_speed=100,300"])),
                  client=client, out=out, progress=False, resume=True)
    with pytest.raises(SweepError, match="other columns"):
        run_sweep(scene, grid_points(parse_grid(["inputs.Fr=100,300"])), client=client,
                  out=out, progress=False, resume=True)


@pytest.mark.filterwarnings("ignore::bearingsim.errors.LongRunWarning")
def test_a_point_over_its_time_budget_fails_alone(scene, tmp_path, client):
    """A point that would integrate 200 s in steps of at most 0.1 ms (millions of steps) is
    recorded as failed after its budget, and its solver stopped (at its next save point); the
    short one beside it is not affected."""
    points = [{"simulation.t_end": t_end, "simulation.method": "cvodes",
               "simulation.max_step": 1e-4, "simulation.n_points": n}
              for t_end, n in ((0.05, 6), (200.0, 20001))]
    t0 = time.perf_counter()
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False, timeout=3.0,
                    chunk=1)
    assert time.perf_counter() - t0 < 120
    assert [r["status"] for r in res.rows] == ["ok", "failed"]
    # CVODES, one call for the whole run, stopped itself on the point's budget
    assert res.rows[1]["error"].startswith("BudgetExceededError: cvodes stopped at t = ")
    assert "wall-time budget of 3 s" in res.rows[1]["error"]
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and any(t.name == "sweep-point-1"
                                              for t in threading.enumerate()):
        time.sleep(0.1)
    assert not any(t.name == "sweep-point-1" for t in threading.enumerate())
    with pytest.raises(SweepError, match="--timeout must be a positive"):
        run_sweep(scene, points, client=client, progress=False, timeout=0.0)


def test_chunks_hold_chunk_seconds_of_work_and_balance_the_workers():
    assert CHUNK_SECONDS == 2.0
    assert chunk_size(0.001, 100_000, 2) == 2000
    assert chunk_size(0.5, 1000, 2) == 4
    assert chunk_size(0.001, 64, 2) == 8  # 4 chunks per worker at the end
    assert chunk_size(2.0, 64, 2) == 1
    assert chunk_size(float("nan"), 64, 16) == 1


def test_ctrl_c_keeps_the_finished_points(scene, tmp_path):
    """SIGINT to the command's process group (what Ctrl-C in a terminal sends): exit status 130,
    a message saying how to go on, and the finished rows stay in the table. The workers (forked
    from the sweep's fork server, in the same group) ignore the signal: before, each printed a
    traceback of dask's nanny and asyncio ending in KeyboardInterrupt, 34 lines a worker."""
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "bearingsim.cli", "sweep", str(scene), "--out", str(out),
           "--workers", "1", "--chunk", "1", "--no-progress"]
    for g in GRID:
        cmd += ["--grid", g]
    proc = subprocess.Popen(cmd, env={**os.environ, "PYTHONPATH": str(PACKAGE_ROOT)},
                            start_new_session=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    table = out / "bearing.sweep.csv"
    try:
        deadline = time.monotonic() + 240
        while time.monotonic() < deadline and proc.poll() is None:
            if table.is_file() and table.read_text().count("\n") >= 3:
                break
            time.sleep(0.05)
        os.killpg(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 130, err[-2000:]
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err[-2000:]
    assert err.splitlines() == [f"bearingsim sweep: interrupted; the finished points are in "
                                f"{out}; add --resume to run the others"]
    rows = list(csv.DictReader(table.open()))
    assert len(rows) >= 2 and all(r["status"] == "ok" for r in rows)


def test_a_second_sweep_into_a_used_folder_needs_overwrite(scene, tmp_path, client):
    """The files of an earlier sweep are not replaced silently: the second sweep stops before
    anything runs, naming them; with ``overwrite`` it replaces them and its summary (written
    last) names the new files."""
    out = tmp_path / "out"
    points = grid_points(parse_grid(["inputs.shaft_speed=100,200"]))
    run_sweep(scene, points, client=client, out=out, progress=False)
    before = (out / "bearing.sweep.csv").read_bytes()
    with pytest.raises(SweepError, match=r"earlier sweep .*bearing\.sweep\.csv.*--overwrite"):
        run_sweep(scene, grid_points(parse_grid(["inputs.shaft_speed=300,400"])),
                  client=client, out=out, progress=False)
    assert (out / "bearing.sweep.csv").read_bytes() == before
    res = run_sweep(scene, grid_points(parse_grid(["inputs.shaft_speed=300,400"])),
                    client=client, out=out, progress=False, overwrite=True)
    assert [r["inputs.shaft_speed [rad/s]"] for r in _table(out)] == ["300.0", "400.0"]
    summary = json.loads((out / "bearing.sweep.json").read_text())
    assert res.files[-1] == out / "bearing.sweep.json"
    assert {f["name"] for f in summary["files"]} >= {"bearing.sweep.csv", "bearing.sweep.png"}
    assert not (out / LOCK_NAME).exists()


def test_a_sweep_into_a_folder_in_use_is_told_who_holds_it(scene, tmp_path, client):
    out = tmp_path / "out"
    with OutputFolder(out, "bearingsim run other.toml"), \
            pytest.raises(OutputFolderBusy, match=r"in use: held by process \d+ .*other\.toml"):
        run_sweep(scene, [{"inputs.shaft_speed": 100.0}], client=client, out=out,
                  progress=False)
    assert not (out / "bearing.sweep.csv").exists()


@pytest.mark.filterwarnings("ignore::bearingsim.errors.LongRunWarning")
def test_the_point_budget_comes_from_the_scene_unless_given(tmp_path, client):
    """``simulation.timeout`` of the scene is each point's budget; ``timeout`` overrides it."""
    path = tmp_path / "bearing.toml"
    path.write_text(SCENE + "timeout = 1.5\n")
    long = [{"simulation.t_end": 200.0, "simulation.max_step": 1e-4,
             "simulation.n_points": 20001}]
    res = run_sweep(path, long, client=client, progress=False, chunk=1)
    assert res.rows[0]["status"] == "failed"
    assert "budget of 1.5 s" in res.rows[0]["error"]
    res = run_sweep(path, long, client=client, progress=False, chunk=1, timeout=1.0)
    assert "budget of 1 s" in res.rows[0]["error"]


def test_a_resumed_sweep_with_nothing_left_says_so(scene, tmp_path, capsys, monkeypatch):
    """``--resume`` of a finished sweep said "1 model(s) built and shipped; 0 point(s) a task":
    nothing was shipped and no task ran. And it started a cluster for nothing (about 1 s): a
    resumed sweep now starts one only when points are left."""
    import bearingsim.scenes.sweep as sweep_module
    from bearingsim.cli import main

    clusters = []

    def counted(*args, **kwargs):
        clusters.append(args)
        return connect(*args, **kwargs)

    connect = sweep_module.connect
    monkeypatch.setattr(sweep_module, "connect", counted)

    out = tmp_path / "out"
    args = ["sweep", str(scene), "--grid", "inputs.shaft_speed=100,200", "--workers", "1",
            "--out", str(out), "--no-progress"]
    assert main(args) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert "1 model(s) built and sent to the workers, up to" in first and len(clusters) == 1
    assert main([*args, "--resume"]) == 0
    again = capsys.readouterr().out.splitlines()[0]
    assert again.startswith("2 point(s): 2 settled")
    assert "(2 from the earlier run); nothing left to run; " in again
    assert "sent to the workers" not in again and "per batch" not in again
    assert len(clusters) == 1
    rows = list(csv.DictReader((out / f"{scene.stem}.sweep.csv").open()))
    assert [r["status"] for r in rows] == ["ok", "ok"]
    # a resumed sweep with a point left starts its cluster after planning, and runs it
    assert main([*args[:3], "inputs.shaft_speed=100,200,300", *args[4:], "--resume"]) == 0
    assert "(2 from the earlier run)" in capsys.readouterr().out and len(clusters) == 2
    rows = list(csv.DictReader((out / f"{scene.stem}.sweep.csv").open()))
    assert [r["status"] for r in rows] == ["ok", "ok", "ok"]
