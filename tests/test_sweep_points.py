"""Sweeps give, at every point, what a single run of the same point gives: every shipped scene
over two points (post-processed quantities included), and the crash of issue 32
(``bearingsim sweep scenes/double_layer_friction.toml --grid assembly.outer=61907,61909``:
``TypeError: _total_loss() takes 1 positional argument but 2 were given``, no table)."""

from __future__ import annotations

import csv
import dataclasses
from pathlib import Path

import pytest

from bearingsim.scenes import load_scene, run_scene
from bearingsim.scenes.sweep import grid_points, parse_grid, run_sweep

distributed = pytest.importorskip("distributed")

SCENES = sorted((Path(__file__).resolve().parent.parent / "scenes").glob("*.toml"))
T_SHORT = 0.04
"""Simulated time of the points [s] (short: the test compares, it does not study)."""


@pytest.fixture(scope="module")
def client():
    """One in-process dask worker (threads): the sweep machinery without process start-up."""
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as c:
        yield c


def _single(scene, t_end, **args):
    sim = dataclasses.replace(scene.simulation, t_end=t_end)
    changed = scene.replace(simulation=sim, args={**scene.args, **args}) if args else \
        scene.replace(simulation=sim)
    return run_scene(changed, write=False).series


@pytest.mark.parametrize("path", SCENES, ids=[p.stem for p in SCENES])
def test_every_shipped_scene_sweeps_as_it_runs(path, client, tmp_path):
    scene = load_scene(path)
    t_end = min(scene.simulation.t_end, T_SHORT)
    times = [t_end / 2, t_end]
    points = grid_points(parse_grid([f"simulation.t_end={times[0]!r},{times[1]!r}"]))
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False)
    assert [r["status"] for r in res.rows] == ["ok", "ok"], res.failures
    outputs = [k for k in res.rows[0] if k not in ("point", "simulation.t_end", "status",
                                                   "wall_s", "error")]
    assert outputs
    for row, t in zip(res.rows, times, strict=True):
        single = _single(scene, t)
        assert set(outputs) == set(single)
        for name in outputs:
            assert row[name] == pytest.approx(float(single[name][-1]), rel=1e-12, abs=0.0), name
    table = list(csv.DictReader((tmp_path / f"{path.stem}.sweep.csv").open()))
    assert [r["point"] for r in table] == ["0", "1"]


def test_issue_32_structural_grid_with_post_processed_quantities(client, tmp_path):
    """The issue's command: two bearings (two models), five outputs of which three are computed
    after the integration (total friction power, two ISO 281 lives); each row equals the single
    run of its point and the table is written."""
    scene = load_scene(SCENES[0].parent / "double_layer_friction.toml")
    points = grid_points(parse_grid(["assembly.outer=61907,61909",
                                     f"simulation.t_end={T_SHORT!r}"]))
    res = run_sweep(scene, points, client=client, out=tmp_path, progress=False)
    assert res.models_built == 2 and len(res.ok) == 2, res.failures
    for row, outer in zip(res.rows, ("61907", "61909"), strict=True):
        single = _single(scene, T_SHORT, outer=outer)
        for name in ("Rs", "M_shaft", "P_loss_total", "inner_layer.L10h", "outer_layer.L10h"):
            assert row[name] == pytest.approx(float(single[name][-1]), rel=1e-12), name
        assert row["P_loss_total"] > 0
    assert res.rows[0]["outer_layer.L10h"] != res.rows[1]["outer_layer.L10h"]
    assert (tmp_path / "double_layer_friction.sweep.csv").is_file()
