"""Values with a unit in grids, cases and sweep points are checked for their quantity.

Found by a new-user trial (each case ran before the fix, exit code 0): only the last value with
a unit of a grid's or the cases' input was compared with the model's unit (a dict entry per
input, overwritten value by value), so ``["5 furlong", "2 kN"]`` for a load ran at 1005.8 N
and ``"5 furlong"`` in one load case ran at 1005.8 rad/s; an assembly argument took any unit
(``"5 furlong"`` as a preload: 1005.8 N); a sweep point (``--grid inputs.shaft_speed=5furlong``)
was never compared with the model's units at all.
"""

import pytest

from bearingsim.scenes import SceneError, load_scene, parse_scene, validate_scene
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.scenes.sweep import SweepError, grid_points
from bearingsim.scenes.sweep_grid import parse_grid
from bearingsim.scenes.sweep_plan import plan_sweep

STATICS = """
title = "6304 under loads"
analysis = "statics"
outputs = ["row.Q_i[0]"]
[assembly]
name = "deep_groove_ball_bearing"
bearing = "6304"
fidelity = "quasi-static"
[inputs]
"load.Fx" = 938.0
{points}
"""


@pytest.mark.parametrize("values", [["5 furlong", "2 kN"], ["2 kN", "5 furlong"]])
def test_a_grid_mixing_quantities_is_refused_at_its_line(values):
    grid = '[grid]\n"inputs.load.Fx" = ' + str(values).replace("'", '"')
    with pytest.raises(SceneError, match=r"grid\.inputs\.load\.Fx: input load\.Fx is given in "
                                         r"(N|m) and, as '.*', in (m|N)") as caught:
        parse_scene(STATICS.format(points=grid))
    assert caught.value.line == 12  # the grid's line of the input


def test_a_grid_of_another_quantity_is_refused_at_the_grid():
    scene = parse_scene(STATICS.format(points='[grid]\n"inputs.load.Fx" = ["5 m", "6 m"]'))
    with pytest.raises(SceneError, match=r"input load\.Fx is in N, but its value is given in "
                                         r"m") as caught:
        validate_scene(scene)
    assert caught.value.key == "grid"


def test_a_load_case_of_another_quantity_is_refused():
    cases = ('[[cases]]\n"inputs.load.Fx" = "5 furlong"\n'
             '[[cases]]\n"inputs.load.Fx" = "2 kN"\n')
    with pytest.raises(SceneError, match=r"cases\.inputs\.load\.Fx: input load\.Fx is given in "
                                         r"m and, as '2 kN', in N"):
        parse_scene(STATICS.format(points=cases))


def test_an_assembly_argument_takes_only_units_of_its_quantity():
    text = builtin_scene_path("duplex_modes").read_text(encoding="utf-8")
    good = parse_scene(text.replace('"assembly.preload_force" = [250.0, 500.0',
                                    '"assembly.preload_force" = ["0.25 kN", "500 N"'))
    assert good.grid["assembly.preload_force"][:2] == pytest.approx([250.0, 500.0])
    with pytest.raises(SceneError, match=r"grid\.assembly\.preload_force: 'furlong' is not a "
                                         r"unit of N quantities"):
        parse_scene(text.replace('"assembly.preload_force" = [250.0',
                                 '"assembly.preload_force" = ["5 furlong"'))
    with pytest.raises(SceneError, match=r"'kN' is not a unit of rad/s"):
        parse_scene(text.replace('"assembly.speed" = ["0 rpm"', '"assembly.speed" = ["5 kN"'))


@pytest.mark.parametrize("flag", ["inputs.shaft_speed=5furlong,2000rpm",
                                  "inputs.shaft_speed=2000rpm,5kN"])
def test_a_sweep_point_of_another_quantity_stops_the_sweep_before_it_runs(flag):
    scene = parse_scene(builtin_scene_path("double_layer_friction").read_text(encoding="utf-8"))
    with pytest.raises(SweepError, match=r"sweep point .*input shaft_speed is in rad/s, but its "
                                         r"value is given in (m|N)"):
        plan_sweep(scene, grid_points(parse_grid([flag])))


def test_an_input_of_another_quantity_in_the_swept_scene_stops_the_sweep():
    """``shaft_speed = "0.5 kN"`` in the scene itself: ``validate`` refused it, but a sweep
    over another key ran every point at 500 rad/s (the scene's copy per point held SI numbers
    only, so the model's check of the quantity was lost). A point that sets the input anew
    does not inherit the old value's unit."""
    text = builtin_scene_path("double_layer_friction").read_text(encoding="utf-8")
    line = next(ln for ln in text.splitlines() if ln.startswith("shaft_speed"))
    scene = parse_scene(text.replace(line, 'shaft_speed = "0.5 kN"'))
    with pytest.raises(SweepError, match=r"input shaft_speed is in rad/s, but its value is "
                                         r"given in N"):
        plan_sweep(scene, grid_points(parse_grid(["inputs.Fa=10,20"])))
    plan = plan_sweep(scene, grid_points(parse_grid(["inputs.shaft_speed=100,200rpm"])))
    assert [j.scene.inputs["shaft_speed"] for j in plan.jobs] == pytest.approx(
        [100.0, 200.0 * 2.0 * 3.141592653589793 / 60.0])


def test_a_copy_of_a_scene_keeps_its_inputs_quantity_check():
    """Scene.replace of another field keeps the unit an unchanged input was given in."""
    from bearingsim.scenes.preparation import prepare

    text = builtin_scene_path("double_layer_friction").read_text(encoding="utf-8")
    line = next(ln for ln in text.splitlines() if ln.startswith("shaft_speed"))
    scene = parse_scene(text.replace(line, 'shaft_speed = "0.5 kN"'))
    copy = scene.replace(title="copy")
    assert copy.input_units["shaft_speed"] == "N"
    with pytest.raises(SceneError, match=r"input shaft_speed is in rad/s, but its value is "
                                         r"given in N"):
        prepare(copy)
    assert "shaft_speed" not in scene.replace(inputs={**scene.inputs,
                                                      "shaft_speed": 100.0}).input_units


PARAMETER_SCENE = """
title = "parameters with units"
outputs = ["shaft.z"]
[assembly]
name = "duplex_pair"
bearing = "7020C"
arrangement = "DB"
preload = "light"
damping_ratio = 0.1
[inputs]
"shaft.Fz" = "2 kN"
[parameters]
"shaft.mass" = {mass}
[initial]
"shaft.z" = {z}
[simulation]
t_end = 0.02
"""


def test_parameters_and_initial_values_take_a_unit_of_their_quantity():
    """Parameters and initial values were numbers in SI units only ("must be a number in SI
    units, got the text '5 kg'") while inputs and assembly arguments took units."""
    from bearingsim.scenes import run_scene

    given = parse_scene(PARAMETER_SCENE.format(mass='"5000 g"', z='"1 um"'))
    si = parse_scene(PARAMETER_SCENE.format(mass="5.0", z="1e-6"))
    assert given.parameters == {"shaft.mass": 5.0} and given.initial == {"shaft.z": 1e-6}
    assert run_scene(given, write=False).series["shaft.z"][-1] == \
        run_scene(si, write=False).series["shaft.z"][-1]
    with pytest.raises(SceneError, match=r"parameters\.shaft\.mass: parameter shaft\.mass is "
                                         r"in kg, but its value is given in N"):
        validate_scene(parse_scene(PARAMETER_SCENE.format(mass='"5 N"', z="0.0")))
    with pytest.raises(SceneError, match=r"initial\.shaft\.z: state shaft\.z is in m, but its "
                                         r"value is given in rad/s"):
        validate_scene(parse_scene(PARAMETER_SCENE.format(mass="5.0", z='"1 rpm"')))
    # a copy keeps the check of an unchanged value, not of one set anew (in SI)
    wrong = parse_scene(PARAMETER_SCENE.format(mass='"5 N"', z="0.0"))
    assert wrong.replace(title="copy").value_units == {"parameters.shaft.mass": "N"}
    assert wrong.replace(parameters={"shaft.mass": 6.0}).value_units == {}


def test_a_swept_parameter_takes_a_unit_of_its_quantity():
    scene = parse_scene(PARAMETER_SCENE.format(mass="5.0", z="0.0"))
    plan = plan_sweep(scene, grid_points(parse_grid(["parameters.shaft.mass=5kg,6000g"])))
    assert [j.scene.parameters["shaft.mass"] for j in plan.jobs] == [5.0, 6.0]
    with pytest.raises(SweepError, match=r"parameter shaft\.mass is in kg, but its value is "
                                         r"given in N"):
        plan_sweep(scene, grid_points(parse_grid(["parameters.shaft.mass=5N"])))
    # the scene's own value in another quantity stops a sweep over another key
    wrong = parse_scene(PARAMETER_SCENE.format(mass='"5 N"', z="0.0"))
    with pytest.raises(SweepError, match=r"parameter shaft\.mass is in kg, but its value is "
                                         r"given in N"):
        plan_sweep(wrong, grid_points(parse_grid(["inputs.shaft.Fz=1000,2000"])))


def test_swept_values_with_units_are_stored_as_si_numbers():
    """``--grid "assembly.preload_force=1 kN,2 kN"`` ran at 1000 and 2000 N but the table held
    the texts "1 kN", "2 kN" under its column (no figure: no numeric key); a time with a unit
    was refused for a simulation setting (``must be a number in s``), in a scene as in a
    sweep."""
    modes = builtin_scene_path("duplex_modes")
    plan = plan_sweep(load_scene(modes), grid_points(parse_grid(
        ["assembly.preload_force=1 kN,2500 N"])))
    assert [v["assembly.preload_force"] for v in plan.values] == [1000.0, 2500.0]
    transient = builtin_scene_path("double_layer_friction")
    plan = plan_sweep(load_scene(transient), grid_points(parse_grid(
        ["simulation.t_end=50 ms,0.1", "assembly.lubrication=ISO VG 32"])))
    assert [v["simulation.t_end"] for v in plan.values] == [0.05, 0.1]
    assert plan.values[0]["assembly.lubrication"] == "ISO VG 32"  # names stay as given
    with pytest.raises(SweepError, match=r"simulation\.t_end: 'N' is not a unit of s"):
        plan_sweep(load_scene(transient), [{"simulation.t_end": "3 N"}])


def test_a_scene_takes_its_times_with_a_unit():
    text = builtin_scene_path("double_layer_friction").read_text(encoding="utf-8")
    scene = parse_scene(text.replace("[simulation]", '[simulation]\nmax_step = "2 ms"'))
    assert scene.simulation.max_step == pytest.approx(2e-3, rel=1e-15)
    with pytest.raises(SceneError, match=r"simulation\.max_step: 'kN' is not a unit of s"):
        parse_scene(text.replace("[simulation]", '[simulation]\nmax_step = "2 kN"'))


def test_an_assembly_argument_that_is_no_number_has_no_unit():
    """The unit of an assembly argument was the first ``[...]`` of its description, so the
    double-layer bearing's lubrication (``[inner, outer]``: one name per layer) was headed
    ``lubrication [inner, outer]``; only numbers have units (ArgSpec.unit)."""
    from bearingsim.scenes.operating_points import key_unit

    scene = load_scene(builtin_scene_path("double_layer_friction"))
    assert key_unit(None, scene, "assembly.lubrication") == ""
    assert key_unit(None, scene, "assembly.oil_level") == "m"
    modes = load_scene(builtin_scene_path("duplex_modes"))
    assert [key_unit(None, modes, f"assembly.{k}") for k in
            ("preload_force", "speed", "damping_ratio")] == ["N", "rad/s", "1"]
