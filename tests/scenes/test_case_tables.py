"""A table of load cases states, in every row, the value each point key had in that case's
run: a case that leaves a key out used the scene's own value or the model's default, and the
cell said nothing (blank in the CSV, the key missing from the console line; the columns of the
keys only later cases give came after the results)."""

import csv

import pytest

from bearingsim.scenes import parse_scene, prepare, run_scene
from bearingsim.scenes.analyses import run_operating_point

SCENE = """
title = "two load cases"
analysis = "statics"
[assembly]
name = "deep_groove_ball_bearing"
bearing = "6304"
fidelity = "quasi-static"
[inputs]
shaft_speed = "3000 rpm"
"load.Fy" = "100 N"
[[cases]]
name = "radial"
"inputs.load.Fx" = "1 kN"
[[cases]]
name = "axial"
"inputs.load.Fz" = "500 N"
[[cases]]
name = "radial with Fy"
"inputs.load.Fx" = "2 kN"
"inputs.load.Fy" = "300 N"
[output]
folder = "out"
"""


def test_a_case_row_holds_the_values_its_run_used(tmp_path):
    path = tmp_path / "cases.toml"
    path.write_text(SCENE, encoding="utf-8")
    run_scene(path)
    with (tmp_path / "out" / "cases.csv").open(newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0][:4] == ["name", "load.Fx [N]", "load.Fz [N]", "load.Fy [N]"]
    assert [r[:4] for r in rows[1:]] == [
        ["radial", "1000.0", "0.0", "100.0"],    # Fz: the model's default; Fy: the scene's
        ["axial", "0.0", "500.0", "100.0"],
        ["radial with Fy", "2000.0", "0.0", "300.0"],
    ]
    assert all(cell != "" for row in rows for cell in row)


def test_the_filled_values_are_the_ones_solved(tmp_path):
    """The axial case's row says Fx = 0 and it is the solution at Fx = 0: the same as the
    case given with Fx = 0 explicitly."""
    prep = prepare(parse_scene(SCENE))
    implicit = run_operating_point(prep, {"name": "a", "inputs.load.Fz": 500.0})
    explicit = run_operating_point(prep, {"name": "a", "inputs.load.Fz": 500.0,
                                          "inputs.load.Fx": 0.0})
    assert implicit["load.Fx"] == 0.0 and implicit["load.Fy"] == 100.0
    assert implicit["Q_max"] == pytest.approx(explicit["Q_max"], rel=1e-12)
