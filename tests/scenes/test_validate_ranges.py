"""``validate`` (and the preparation of every run and sweep) checks the inputs' values as the
run would (found by a new-user trial: each of these said "valid" and ``run`` then refused the
value without naming the file and line; a sweep ran the invalid point and recorded it as
failed, although docs/sweeps.md promises that an invalid value stops the sweep before anything
runs).

Bounds: the 61905's static load rating C0 = 4.3 kN gives ``Fa`` (axial, deep groove Y0 = 0.5,
ISO 76) 0 .. 86 kN; the nested bearing's limiting shaft speed 38 000 r/min gives the shaft speed
+-2 x that (+-7958.7 rad/s).
"""

import pytest

from bearingsim.scenes import SceneError, parse_scene, validate_scene
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.scenes.sweep import SweepError, grid_points
from bearingsim.scenes.sweep_grid import parse_grid
from bearingsim.scenes.sweep_plan import plan_sweep

TEXT = builtin_scene_path("double_layer_friction").read_text(encoding="utf-8")


@pytest.mark.parametrize("line, value, match", [
    ("Fa = 50.0", "Fa = -500.0", r"inputs\.Fa: input Fa = -500 \[N\] is outside its valid "
                                 r"range \[0, 86000\] \[N\]"),
    ("Fa = 50.0", 'Fa = { times = [0, 1, 2], values = [0, 50, -1] }',
     r"inputs\.Fa: input Fa = -1 \[N\] \(table value 2\) is outside its valid range"),
    ('shaft_speed = "rpm(6000) * ramp(0, 0.5)"', "shaft_speed = 10000",
     r"inputs\.shaft_speed: input shaft_speed = 10000 \[rad/s\] is outside its valid range "
     r"\[-7958\.7, 7958\.7\]"),
])
def test_validate_refuses_an_input_the_run_would_refuse_at_its_line(line, value, match):
    text = TEXT.replace(line, value)
    with pytest.raises(SceneError, match=match) as caught:
        validate_scene(parse_scene(text))
    assert text.splitlines()[caught.value.line - 1].startswith(value.split(" =")[0])


def test_the_shipped_scene_is_valid():
    validate_scene(parse_scene(TEXT))


def test_a_sweep_point_out_of_range_stops_the_sweep_before_it_runs():
    with pytest.raises(SweepError, match=r"sweep point \{'inputs\.Fa': 120000\}: .*input Fa = "
                                         r"120000 \[N\] is outside its valid range"):
        plan_sweep(parse_scene(TEXT), grid_points(parse_grid(["inputs.Fa=100,120000"])))


@pytest.mark.parametrize("line, value, match", [
    ('preload = "light"', "preload_force = -100.0",
     r"assembly\.preload_force: -100\.0 is out of range; allowed: \(0\.0, inf\] N"),
    ('preload = "light"', 'preload_force = "heavy"', r"must be a number in N, got the text"),
    ("damping_ratio = 0.1", 'damping_ratio = "low"', r"must be a number in -, got the text"),
])
def test_an_assembly_argument_out_of_range_names_its_unit(line, value, match):
    """The range of a number argument is stated in the argument's unit (it said "SI units")."""
    text = builtin_scene_path("duplex_pair_axial").read_text(encoding="utf-8")
    assert line in text
    with pytest.raises(SceneError, match=match):
        validate_scene(parse_scene(text.replace(line, value)))
