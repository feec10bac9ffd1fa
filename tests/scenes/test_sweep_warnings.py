"""The warnings of a sweep's points reach the user once per kind, on the client: before, each
worker printed its points' warnings on its own standard error in Python's raw format (file,
line and source line: ``.../entry_points.py:43: SpeedLimitWarning: ... return func(*args,
**kwargs)``), one per point, and the summary did not name them (found by a new-user trial of
``bearingsim sweep --sample inputs.shaft_speed=1000:8000``: speeds in rad/s, above the
bearing's limiting speed at 9 of 16 points)."""

from __future__ import annotations

import json
import warnings

import hypothesis.strategies as st
import pytest
from hypothesis import given

from bearingsim.errors import SpeedLimitWarning
from bearingsim.scenes.sweep import grid_points, run_sweep
from bearingsim.scenes.sweep_grid import parse_grid
from bearingsim.scenes.sweep_results import point_warnings
from tests.scenes.sweep_scenes import torque_level_scene

distributed = pytest.importorskip("distributed")



def test_a_points_warning_is_warned_once_on_the_client_with_its_points(tmp_path, client):
    path = tmp_path / "torque.toml"
    path.write_text(torque_level_scene())
    points = grid_points(parse_grid(["inputs.shaft_speed=100,4500,5000"]))  # limit 3979 rad/s
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = run_sweep(path, points, client=client, out=tmp_path / "out", progress=False)
    assert [r["status"] for r in res.rows] == ["ok"] * 3
    [kind] = res.warnings
    assert kind["category"] is SpeedLimitWarning and kind["points"] == [1, 2]
    said = [str(w.message) for w in caught if w.category is SpeedLimitWarning]
    assert len(said) == 1
    assert said[0].startswith("torque: 2 of 3 point(s) (1, 2): input shaft_speed reaches ")
    assert said[0].endswith("(point 1; the others alike)")
    summary = json.loads((tmp_path / "out" / "torque.sweep.json").read_text())
    assert summary["warnings"] == [{"category": "SpeedLimitWarning", "points": [1, 2],
                                    "message": kind["message"]}]


@given(st.lists(st.floats(1.0, 1e6, allow_nan=False), min_size=1, max_size=20))
def test_warnings_alike_but_for_their_numbers_are_one_kind(speeds):
    results = {k: {"warnings": [(SpeedLimitWarning, f"shaft_speed reaches {v:g} r/min"),
                                (RuntimeWarning, "a different text")]}
               for k, v in enumerate(speeds)}
    limit, other = point_warnings(results, len(speeds))
    assert limit["points"] == other["points"] == list(range(len(speeds)))
    assert limit["message"] == f"shaft_speed reaches {speeds[0]:g} r/min"
    assert limit["text"].startswith(f"{len(speeds)} of {len(speeds)} point(s) (")
