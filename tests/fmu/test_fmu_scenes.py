"""Exporting an assembly by its scene name: the scene's outputs and inputs, nothing more."""

from __future__ import annotations

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from bearingsim.assemblies.registry import REGISTRY
from bearingsim.fmu import cli_export, export_fmu
from bearingsim.fmu.cli import scene_outputs
from tests.fmu.helpers import LogCapture, open_fmu


@pytest.mark.parametrize("name, fidelity, expected", [
    ("duplex_pair", "quasi-static", ["shaft.x", "shaft.z", "shaft.ty"]),
    ("double_layer_bearing", "torque", ["w_shaft", "w_middle", "Rs", "M_shaft"]),
    # the scene's default outputs (row.Q_i[0], ...) belong to the quasi-static level: the ball
    # level reports what its own output table names (shaft_speed is its input)
    ("deep_groove_ball_bearing", "dynamic_massive_balls", ["w_cage", "slip"]),
])
def test_scene_outputs_per_level(name, fidelity, expected):
    spec = REGISTRY[name]
    model = spec.build(spec.with_defaults({}), fidelity)
    assert scene_outputs(spec, model, fidelity) == expected


def test_scene_name_exports_its_outputs_and_inputs(tmp_path):
    path = tmp_path / "pair.fmu"
    assert cli_export(["duplex_pair", str(path), "--kinds", "ME,CS"]) == 0
    assert validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    assert sorted(outputs) == sorted(["shaft.x", "shaft.z", "shaft.ty"])
    assert inputs == ["shaft.Fx", "shaft.Fy", "shaft.Fz", "shaft.Mx", "shaft.My"]


def test_assembly_arguments_of_an_export_take_numbers_with_units(tmp_path, capsys):
    """``bearingsim export-fmu duplex_pair x.fmu --arg 'preload_force="1 kN"'`` ended in a
    traceback (``float('1 kN')``); the arguments take what a scene takes: numbers with units,
    designations in any letter case, and text that is no quantity is a named error."""
    path = tmp_path / "pair.fmu"
    assert cli_export(["duplex_pair", str(path), "--arg", 'preload_force="1 kN"',
                       "--kinds", "CS"]) == 0
    si = tmp_path / "si.fmu"
    assert cli_export(["duplex_pair", str(si), "--arg", "preload_force=1000.0",
                       "--kinds", "CS"]) == 0

    def parameters(fmu):
        return {v.name: v.start for v in read_model_description(str(fmu)).modelVariables
                if v.causality == "parameter"}

    assert parameters(path) == parameters(si)
    assert cli_export(["duplex_pair", str(path), "--arg", 'preload_force="light"']) == 2
    assert capsys.readouterr().err.startswith(
        "bearingsim export-fmu: duplex_pair: preload_force: 'light' is not a number with a unit")
    roller = tmp_path / "nu.fmu"
    assert cli_export(["cylindrical_roller_bearing", str(roller), "--arg", 'bearing="nu 208"',
                       "--arg", 'tilt_y="0.5 mrad"', "--arg", 'clearance="20 um"',
                       "--kinds", "CS"]) == 0
    started = parameters(roller)
    assert float(started["guide.ty"]) == pytest.approx(5e-4, rel=1e-12)
    assert float(started["row.Pd"]) == pytest.approx(20e-6, rel=1e-12)


def test_only_state_derivatives_are_derivatives(tmp_path):
    """Every variable of the kinematic double-layer bearing: the rate of the outer ring's angle
    (fixed, not a state) is no state derivative, so it is left out of the default outputs; the
    derivatives declared are exactly those of the states."""
    spec = REGISTRY["double_layer_bearing"]
    model = spec.build(spec.with_defaults({}), "kinematic")
    path = export_fmu(model, tmp_path / "dl.fmu", kinds=("ME",))
    md = read_model_description(str(path))
    states = {d.variable.derivative.name for d in md.derivatives}
    names = {v.name for v in md.modelVariables}
    rates = {n for n in names if n.startswith("der(")}
    assert rates == {f"der({s})" for s in states}
    for v in md.modelVariables:
        if v.derivative is not None:
            assert v.name == f"der({v.derivative.name})" and v.derivative.name in states


def test_model_exchange_terminate_is_silent_about_the_stepper(drive_fmu, tmp_path):
    for kind, says in (("ME", False), ("CS", True)):
        log = LogCapture()
        fmu, _, _ = open_fmu(drive_fmu, tmp_path, kind=kind, log=log, logging_on=True)
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        if kind == "CS":
            fmu.doStep(0.0, 0.1)
        fmu.terminate()
        fmu.freeInstance()
        assert ("internal steps" in log.text()) is says, (kind, log.text())


_SCENE = """
title = "friction"
transient_on_purpose = true
outputs = ["Rs", "M_shaft", "P_loss_total"]
[assembly]
name = "double_layer_bearing"
fidelity = "torque"
lubrication = "VG 46 at 60 degC"
[lubricants."VG 46 at 60 degC"]
base = "ISO VG 46"
temperature = "60 degC"
[inputs]
shaft_speed = "3000 rpm"
Fr = 200.0
Fa = "10 + 10"          # a constant expression
[parameters]
"inner_layer.f0" = 2.0
[simulation]
t_end = 2.0
rtol = 1e-8
atol = 1e-10
"""


def test_a_scene_exports_the_model_it_runs(tmp_path, capsys):
    """``bearingsim export-fmu scene.toml model.fmu``: the scene's assembly at its level with
    its own lubricant, its outputs (a post-processed quantity said to be left out), its
    [parameters] and constant inputs as start values; stepped over the scene's span, the
    FMU ends where the scene's run ends. Before, only an assembly name or a factory could be
    exported, without the scene's lubricant, parameters or inputs."""
    from fmpy import simulate_fmu

    from bearingsim.cli import main
    from bearingsim.scenes import parse_scene, run_scene

    scene = tmp_path / "friction.toml"
    scene.write_text(_SCENE)
    path = tmp_path / "friction.fmu"
    assert main(["export-fmu", str(scene), str(path), "--kinds", "CS"]) == 0
    assert "not FMU outputs: P_loss_total (computed from " in capsys.readouterr().err
    variables = {v.name: v for v in read_model_description(str(path)).modelVariables}
    assert [n for n, v in variables.items() if v.causality == "output"] == ["Rs", "M_shaft"]
    assert float(variables["shaft_speed"].start) == pytest.approx(314.1592653589793)
    assert float(variables["Fa"].start) == 20.0 and float(variables["Fr"].start) == 200.0
    assert float(variables["inner_layer.f0"].start) == 2.0
    viscosity = float(variables["inner_layer.nu"].start)
    assert viscosity < 3e-5  # ISO VG 46 at 60 degC, thinner than at 40 degC (46 mm^2/s)
    result = simulate_fmu(str(path), stop_time=2.0, output_interval=0.5)
    single = run_scene(parse_scene(_SCENE, str(scene)), write=False).series
    assert result["Rs"][-1] == pytest.approx(float(single["Rs"][-1]), rel=1e-4)
    assert result["M_shaft"][-1] == pytest.approx(float(single["M_shaft"][-1]), rel=1e-4)
    assert main(["export-fmu", str(scene), str(path), "--arg", "inner=61905"]) == 2
    assert "takes its arguments from the scene's" in capsys.readouterr().err
    scene.write_text(_SCENE.replace('fidelity = "torque"', 'fidelity = "fast"'))
    assert main(["export-fmu", str(scene), str(path)]) == 2
    assert "assembly.fidelity" in capsys.readouterr().err


def test_a_built_in_steady_scene_exports_its_model_and_says_its_grid_is_not_in_it(tmp_path,
                                                                                 capsys):
    from bearingsim.cli import main

    path = tmp_path / "rs.fmu"
    assert main(["export-fmu", "double_layer_rs", str(path), "--kinds", "CS"]) == 0
    assert ("the scene's grid (inputs.shaft_speed, inputs.Fr) are operating points of its "
            "runs, not of the FMU") in capsys.readouterr().err
    variables = read_model_description(str(path)).modelVariables
    assert [v.name for v in variables if v.causality == "output"] == ["Rs", "w_middle", "M_shaft"]
    assert {v.name for v in variables if v.causality == "input"} == {"shaft_speed", "Fr", "Fa"}


def test_a_statics_scene_exports_the_models_own_outputs(tmp_path, capsys):
    """A statics scene's outputs are its statics columns (Q_max, L10h ...), which its solver
    computes from the model: the export asked the model for them and failed ("unknown output
    variable 'Q_max'"). Its FMU outputs what the assembly's scenes report at that level."""
    from bearingsim.cli import main

    path = tmp_path / "statics.fmu"
    assert main(["export-fmu", "deep_groove_statics", str(path), "--kinds", "CS"]) == 0
    assert "the statics columns (Q_max, p_max" in capsys.readouterr().err
    variables = read_model_description(str(path)).modelVariables
    assert [v.name for v in variables if v.causality == "output"] == \
        ["row.Q_i[0]", "row.alpha_i[0]"]
