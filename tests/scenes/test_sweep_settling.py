"""A sweep counts the points that had not settled apart from the settled ones, as ``bearingsim
run`` flags one such point: before, a sweep of four transient points that all ended unsettled
(rows ``settled`` False) was summed up as ``4 point(s): 4 ok, 0 failed`` without a warning."""

from __future__ import annotations

import dataclasses
import json
import warnings

import pytest

from bearingsim.scenes import load_scene, run_scene
from bearingsim.scenes.analyses import NotSettledWarning
from bearingsim.scenes.sweep import describe_points, grid_points, run_sweep
from bearingsim.scenes.sweep_grid import parse_grid
from tests.scenes.sweep_scenes import torque_level_scene

distributed = pytest.importorskip("distributed")

RAMP = """title = "speed ramp"
outputs = ["Rs"]
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = "rpm(1000) * ramp(0, 0.1)"
[simulation]
t_end = 0.2
n_points = 21
"""
"""A transient whose speed ratio still changes at any of the short end times swept here."""
SHORT = ["simulation.t_end=0.01,0.02,0.03,0.05"]



def _sweep(path, grid, client, **kwargs):
    """The sweep's result and the texts of the NotSettledWarnings it gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = run_sweep(path, grid_points(parse_grid(grid)), client=client, progress=False,
                        **kwargs)
    return res, [str(w.message) for w in caught if w.category is NotSettledWarning]


def test_points_that_had_not_settled_are_counted_apart_and_warned(tmp_path, client):
    path = tmp_path / "ramp.toml"
    path.write_text(RAMP)
    scene = load_scene(path)
    one = scene.replace(simulation=dataclasses.replace(scene.simulation, t_end=0.01))
    with pytest.warns(NotSettledWarning, match="not settled at t_end"):
        run_scene(one, write=False)  # what one point's run says
    res, said = _sweep(path, SHORT, client, out=tmp_path / "out")
    assert [r["status"] for r in res.rows] == ["ok"] * 4
    assert [r["settled"] for r in res.rows] == [False] * 4
    assert [r["unsettled"] for r in res.rows] == ["Rs"] * 4
    assert res.settling == "checked" and len(res.unsettled) == 4 and len(res.ok) == 4
    assert describe_points(res) == ("4 point(s): 0 settled, 4 not settled (values flagged: "
                                    "settled False), 0 failed")
    assert said == ["speed ramp: 4 of 4 point(s) had not settled at t_end (their rows say "
                    "settled False and name the outputs in unsettled). Run longer "
                    "(simulation.t_end), ask analysis = \"steady\" for the settled points, or "
                    "set transient_on_purpose = true"]
    summary = json.loads((tmp_path / "out" / "ramp.sweep.json").read_text())
    assert (summary["ok"], summary["not_settled"], summary["failed"]) == (4, 4, 0)


def test_rows_kept_by_resume_are_counted_by_their_settled_column(tmp_path, client):
    path = tmp_path / "ramp.toml"
    path.write_text(RAMP)
    _sweep(path, ["simulation.t_end=0.01,0.02"], client, out=tmp_path)
    res, said = _sweep(path, SHORT, client, out=tmp_path, resume=True)
    assert res.resumed == 2 and [r["settled"] for r in res.rows] == [False] * 4
    assert describe_points(res).startswith("4 point(s): 0 settled, 4 not settled")
    assert len(said) == 1 and said[0].startswith("speed ramp: 4 of 4 point(s)")


def test_settled_points_are_counted_as_settled_without_a_warning(tmp_path, client):
    path = tmp_path / "torque.toml"
    path.write_text(torque_level_scene())
    res, said = _sweep(path, ["inputs.shaft_speed=100,300"], client)
    assert [r["settled"] for r in res.rows] == [True, True] and said == []
    assert describe_points(res) == "2 point(s): 2 settled, 0 not settled, 0 failed"


def test_a_transient_on_purpose_is_not_checked_for_settling(tmp_path, client):
    """Its rows had ``settled`` False (and which outputs had not) where a single run of the
    scene says settled None, "not checked"; now they have no such columns."""
    path = tmp_path / "ramp.toml"
    path.write_text("transient_on_purpose = true\n" + RAMP)
    res, said = _sweep(path, SHORT[:1], client, out=tmp_path / "out")
    assert res.settling == "on purpose" and res.unsettled == [] and said == []
    assert describe_points(res) == ("4 point(s): 4 ok (transient on purpose: not checked for "
                                    "settling), 0 failed")
    header = (tmp_path / "out" / "ramp.sweep.csv").read_text().splitlines()[0].split(",")
    names = {column.split(" [")[0] for column in header}
    assert "Rs" in names and not {"settled", "time_constant", "unsettled"} & names
    assert all("settled" not in row for row in res.rows)
    single = run_scene(path, out=tmp_path / "single")
    assert single.summary["settled"] is None


def test_a_steady_sweep_counts_solved_points_as_ok(client):
    res, said = _sweep("double_layer_rs", ["inputs.shaft_speed=100,300", "inputs.Fr=200"],
                       client)
    assert res.settling == "" and said == []
    assert describe_points(res) == "2 point(s): 2 ok, 0 failed"
