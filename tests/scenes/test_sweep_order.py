"""The order a sweep's points run in: longest first by an estimate of their wall time (a priori
the rotation each point simulates, then a robust fit of the measured times), and a table that
does not depend on it."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.scenes import load_scene
from bearingsim.scenes.sweep import grid_points, run_sweep
from bearingsim.scenes.sweep_grid import parse_grid
from bearingsim.scenes.sweep_order import PointCosts, point_features, trimmed_least_squares
from bearingsim.scenes.sweep_plan import plan_sweep
from tests.scenes.sweep_scenes import torque_level_scene

distributed = pytest.importorskip("distributed")

RPM = 2.0 * math.pi / 60.0
"""1 r/min in rad/s."""


@pytest.fixture()
def scene(tmp_path) -> Path:
    path = tmp_path / "bearing.toml"
    path.write_text(torque_level_scene(t_end=0.1))
    return path


def _costs(scene: Path, grid: list[str]) -> tuple[PointCosts, dict[int, dict[str, float]]]:
    plan = plan_sweep(load_scene(scene), grid_points(parse_grid(grid)))
    features = {j.index: point_features(j, plan.values[j.index],
                                        plan.prepared[plan.structure[j.index]].system.
                                        variable_units) for j in plan.jobs}
    return PointCosts(features), features


def test_a_ramped_speed_is_read_by_its_mean_and_the_rotation_it_simulates(scene):
    """``rpm(1000) * ramp(0, 0.02)`` over 0.1 s: the speed is 0 at t = 0 and 1000 r/min from
    0.02 s, so its mean is 0.9 x 1000 r/min and the shaft turns 1.5 revolutions (3 pi rad);
    a constant 300 rad/s over 0.05 s turns 15 rad."""
    _, features = _costs(scene, ['inputs.shaft_speed="rpm(1000) * ramp(0, 0.02)";300',
                                 "simulation.t_end=0.1,0.05"])
    ramp, constant = features[0], features[3]
    assert ramp["inputs.shaft_speed"] == pytest.approx(0.9 * 1000 * RPM, rel=1e-12)
    assert ramp["rotation"] == pytest.approx(3.0 * math.pi, rel=1e-12)
    assert ramp["span"] == pytest.approx(0.1) and ramp["simulation.t_end"] == 0.1
    assert constant["rotation"] == pytest.approx(15.0) and constant["span"] == 0.05


def test_before_any_time_is_measured_the_points_rank_by_the_rotation_they_simulate(scene):
    """Speeds 100-400 rad/s x t_end 0.05, 0.1 s: the rotation (speed x time) ranks them; equal
    rotations (200 rad/s for 0.1 s, 400 rad/s for 0.05 s) keep their order; no estimate in
    seconds yet."""
    costs, features = _costs(scene, ["inputs.shaft_speed=100,200,400",
                                     "simulation.t_end=0.05,0.1"])
    order = costs.longest_first(list(features))
    rotations = [features[k]["rotation"] for k in order]
    assert rotations == sorted(rotations, reverse=True)
    assert order == [5, 3, 4, 1, 2, 0]  # 40, 20 (3 before 4), 20, 10, 10 (1 before 2), 5 rad
    assert math.isnan(costs.estimate(0))


def test_the_fit_learns_the_cost_of_a_point_and_ignores_each_workers_first(scene):
    """Measured times that follow the cost of bench section 19's ball-level points (about
    0.30 s at 1000 r/min to 0.50 s at 3000 r/min, 0.02 s more per 1000 N of load), the first
    point of each of two workers 1.5 s longer (model and kernel load) and one more point
    disturbed by 0.4 s: the fit gives the others' times within 1 %, and orders the points not
    yet run longest first."""
    speeds = ",".join(f"rpm({n})" for n in range(1000, 3001, 250))
    costs, features = _costs(scene, [f"inputs.shaft_speed={speeds}", "inputs.Fr=500,1000,1500"])

    def law(k: int) -> float:
        f = features[k]
        return 0.2 + 0.1 * f["inputs.shaft_speed"] / (1000 * RPM) + 2e-5 * f["inputs.Fr"]

    assert costs.n_coefficients == 3  # constant, speed, load (rotation follows the speed)
    measured = [0, 26, 5, 9, 13, 14, 22, 2, 17, 6]
    for i, k in enumerate(measured):
        costs.add(k, law(k) + (1.5 if i < 2 else 0.4 if k == 13 else 0.0),
                  first_on_worker=i < 2)
    rest = [k for k in features if k not in measured]
    for k in rest:
        assert costs.estimate(k) == pytest.approx(law(k), rel=0.01)
    order = costs.longest_first(rest)
    assert [law(k) for k in order] == sorted((law(k) for k in rest), reverse=True)
    # the typical time (the chunks' size before the fit) counts every measured point
    assert costs.typical_s == pytest.approx(np.median(
        [law(k) + (1.5 if i < 2 else 0.4 if k == 13 else 0.0) for i, k in enumerate(measured)]))


def test_swept_values_up_to_the_largest_float_give_finite_estimates():
    """A sweep may hold a value of 1e308 (an initial speed the run then refuses): the fit
    standardizes it without overflow and its estimates stay finite (this raised
    ``LinAlgError: SVD did not converge`` from the standardized column of NaN)."""
    features = {k: {"span": 0.02, "rotation": 0.02 * w, "initial.w": big}
                for k, (w, big) in enumerate([(100.0, 0.0), (100.0, 1e308), (200.0, 0.0),
                                              (200.0, 1e308), (300.0, 0.0), (300.0, 1e308)])}
    costs = PointCosts(features)
    assert costs.n_coefficients == 3  # constant, speed (rotation), initial value
    for k in (0, 2, 4, 5, 1):
        costs.add(k, 0.01 + 1e-4 * features[k]["rotation"] / 0.02
                  + (0.002 if features[k]["initial.w"] else 0.0))
    assert costs.estimate(3) == pytest.approx(0.01 + 0.02 + 0.002, rel=0.01)
    assert costs.longest_first(list(features))[0] == 5


@settings(max_examples=200, deadline=None)
@given(coef=st.lists(st.floats(-10.0, 10.0), min_size=2, max_size=4),
       n=st.integers(15, 40), seed=st.integers(0, 2**32 - 1),
       disturbed=st.lists(st.floats(1.0, 100.0), max_size=3))
def test_the_trimmed_fit_recovers_a_linear_law_past_a_few_disturbed_points(coef, n, seed,
                                                                              disturbed):
    """Times that follow a linear law in standardized features, up to 1e-6 of noise, with up
    to 3 of at least 15 points (20 %) disturbed by 1-100 (another process took their core):
    the coefficients come back within 1e-4, as a least-squares fit of the undisturbed points
    alone gives them (the disturbed points are left out)."""
    rng = np.random.default_rng(seed)
    a = np.column_stack([np.ones(n), rng.standard_normal((n, len(coef) - 1))])
    law = np.asarray(coef)
    y = a @ law + 1e-6 * rng.standard_normal(n)
    y[: len(disturbed)] += disturbed
    assert trimmed_least_squares(a, y) == pytest.approx(law, abs=1e-4)


def _table(folder: Path) -> list[list[str]]:
    """The sweep's table without the wall time of each point."""
    with (folder / "bearing.sweep.csv").open() as fh:
        rows = list(csv.reader(fh))
    drop = rows[0].index("wall_s [s]")
    return [[c for j, c in enumerate(r) if j != drop] for r in rows]


def test_the_order_the_points_run_in_changes_nothing_in_the_table(scene, tmp_path):
    """The same sweep longest first and in the given order: the same rows, in point order;
    longest first, the fastest points ran first."""
    points = grid_points(parse_grid(["inputs.shaft_speed=100,200,300,400",
                                     "inputs.Fr=100,400"]))
    runs = {}
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as client:
        for name, longest in (("longest first", True), ("given", False)):
            runs[name] = run_sweep(scene, points, client=client, out=tmp_path / name,
                                   progress=False, chunk=1, longest_first=longest)
    started = {name: sorted(res.spans, key=lambda k: res.spans[k][1])
               for name, res in runs.items()}
    assert started["given"] == list(range(8))
    assert started["longest first"][:2] == [6, 7]  # 400 rad/s first
    assert started["longest first"] != started["given"]
    lpt, given = _table(tmp_path / "longest first"), _table(tmp_path / "given")
    assert lpt == given
    assert [int(r[0]) for r in lpt[1:]] == list(range(8))
    assert [r["point"] for r in runs["longest first"].rows] == list(range(8))


@pytest.mark.parametrize("timeout", [None, 60.0])
def test_each_point_reports_the_cpu_time_of_its_thread_beside_its_wall_time(scene, timeout):
    """``point_cpu``: the CPU time of the thread that ran each point (the worker's, or the
    point's own thread under a time budget), positive and not above the point's wall time (a
    thread's CPU time cannot exceed the time it ran; the difference is the time it waited
    for a core)."""
    points = grid_points(parse_grid(["inputs.shaft_speed=100,400", "inputs.Fr=100,400"]))
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as client:
        res = run_sweep(scene, points, client=client, progress=False, timeout=timeout)
    assert set(res.point_cpu) == set(res.spans) == set(range(4))
    for k, cpu in res.point_cpu.items():
        wall = res.spans[k][2]
        assert 0.0 < cpu <= wall + 1e-3


def test_the_client_leaves_the_objects_alive_before_its_points_to_themselves(scene, tmp_path,
                                                                              monkeypatch):
    """While the sweep draws its figure (after its points), the objects alive before the
    points (the model, CasADi's and dask's) are frozen out of Python's garbage collector
    (each full collection scanned them all: about 0.1 s of the client's CPU, two to three
    times a sweep); afterwards the collector is as the sweep found it."""
    import gc

    from bearingsim.scenes import sweep as sweep_module

    seen = []
    drawing = sweep_module.sweep_figures

    def recording(*args):
        seen.append(gc.get_freeze_count())
        return drawing(*args)

    monkeypatch.setattr(sweep_module, "sweep_figures", recording)
    before = gc.get_freeze_count()
    points = grid_points(parse_grid(["inputs.shaft_speed=100,400"]))
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1,
                            dashboard_address=":0") as client:
        run_sweep(scene, points, client=client, out=tmp_path / "out", progress=False)
    assert len(seen) == 1 and seen[0] > before + 10_000
    assert gc.get_freeze_count() == before
