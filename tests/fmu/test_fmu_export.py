"""The exported archive: validation, model description, exported symbols, CLI, export errors."""

from __future__ import annotations

import subprocess
import zipfile

import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from bearingsim.errors import ParameterError
from bearingsim.fmu import cli_export, export_fmu


@pytest.mark.parametrize("name", ["drive_fmu", "driven_fmu", "load_fmu", "stiff_fmu"])
def test_fmpy_validation_finds_no_problems(name, request):
    assert validate_fmu(str(request.getfixturevalue(name))) == []


def test_archive_layout(drive_fmu):
    with zipfile.ZipFile(drive_fmu) as z:
        names = set(z.namelist())
    assert {"modelDescription.xml", "binaries/linux64/drive.so"} <= names
    for src in ("sources/bsm_c_ode.c", "sources/bsm_casadi.h", "sources/model_config.h",
                "sources/model_data.c", "sources/fmi2_api.c", "sources/bsm_solver.c",
                "sources/fmi2Functions.h"):
        assert src in names


def test_only_fmi_functions_are_exported(drive_fmu, tmp_path):
    with zipfile.ZipFile(drive_fmu) as z:
        z.extract("binaries/linux64/drive.so", tmp_path)
    lib = tmp_path / "binaries/linux64/drive.so"
    out = subprocess.run(["nm", "-D", "--defined-only", str(lib)], capture_output=True,
                         text=True, check=True).stdout
    symbols = {line.split()[-1] for line in out.splitlines() if " T " in line}
    assert "fmi2DoStep" in symbols and "fmi2GetDirectionalDerivative" in symbols
    assert all(s.startswith("fmi2") for s in symbols), symbols


def test_model_description(drive_fmu, drive_system):
    md = read_model_description(str(drive_fmu))
    v = {x.name: x for x in md.modelVariables}
    # exported from an assembled system: its name, not the System class docstring
    assert md.description == f"{drive_system.name} (an assembled bearingsim system)"
    assert md.modelExchange.providesDirectionalDerivative
    assert md.coSimulation.canGetAndSetFMUstate and md.coSimulation.canSerializeFMUstate
    # states: local or (when requested as output) output, with exact start values
    assert (v["j1.w"].causality, v["j1.w"].variability, v["j1.w"].initial) == (
        "local", "continuous", "exact")
    assert v["j2.w"].causality == "output"
    assert v["der(j1.w)"].derivative is v["j1.w"] and v["der(j1.w)"].unit == "rad/s2"
    # outputs and tunable parameters with units, ranges and descriptions
    assert v["sd.tau"].causality == "output" and v["sd.tau"].unit == "N.m"
    c = v["sd.c"]
    assert (c.causality, c.variability, float(c.start), c.unit) == (
        "parameter", "tunable", 100.0, "N.m/rad")
    # c > 0: FMI's inclusive min is the next double above 0
    assert float(c.min) == 5e-324 and c.description == "spring constant"
    units = {u.name: u for u in md.unitDefinitions}
    assert units["N.m"].baseUnit.kg == 1 and units["N.m"].baseUnit.s == -2
    # structure from the Jacobian sparsity: der(j1.phi) = j1.w only
    deriv = {u.variable.name: {d.name for d in u.dependencies} for u in md.derivatives}
    assert deriv["der(j1.phi)"] == {"j1.w"}
    assert deriv["der(j1.w)"] == {"j1.phi", "j1.w", "j2.phi", "j2.w"}
    outputs = {u.variable.name: {d.name for d in u.dependencies} for u in md.outputs}
    assert outputs["j2.w"] == {"j2.w"} and outputs["j1.phi"] == {"j1.phi"}
    assert outputs["sd.tau"] == {"j1.phi", "j1.w", "j2.phi", "j2.w"}
    initial = {u.variable.name: {d.name for d in u.dependencies} for u in md.initialUnknowns}
    assert "sd.c" in initial["der(j1.w)"] and "j2.J" not in initial["der(j1.w)"]


def test_inputs_have_causality_input(driven_fmu):
    md = read_model_description(str(driven_fmu))
    v = {x.name: x for x in md.modelVariables}
    assert v["tau_drive"].causality == "input" and float(v["tau_drive"].start) == 0.0
    deriv = {u.variable.name: {d.name for d in u.dependencies} for u in md.derivatives}
    assert deriv["der(rotor.w)"] == {"rotor.w", "tau_drive", "tau_load"}


def test_cli_export(tmp_path):
    path = tmp_path / "cli.fmu"
    status = cli_export(["tests.models:TwoInertiaDrive", str(path), "--outputs", "j2.w,sd.tau",
                         "--kinds", "CS", "--param", "sd.c=250", "--name", "Drive CLI",
                         "--stepper", "rodas3"])
    assert status == 0 and validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    assert md.modelExchange is None and md.coSimulation.modelIdentifier == "Drive_CLI"
    assert float({v.name: v for v in md.modelVariables}["sd.c"].start) == 250.0
    with zipfile.ZipFile(path) as z:
        assert "#define BSM_STEPPER_RODAS3 1" in z.read("sources/model_config.h").decode()


def test_cli_reports_errors(tmp_path, capsys):
    status = cli_export(["tests.models:TwoInertiaDrive", str(tmp_path / "x.fmu"),
                         "--param", "sd.c=-1"])
    err = capsys.readouterr().err  # bad input: 2, as the other commands (before: 1)
    assert status == 2 and err.startswith("bearingsim export-fmu: ") and "sd.c" in err


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"fmi_version": "1.0"}, "fmi_version"),
        ({"kinds": ("XX",)}, "kinds"),
        ({"outputs": ["nope"]}, "nope"),
        ({"parameters": {"sd.c": -1.0}}, "sd.c"),
        ({"inputs": {"tau": 1.0}}, "unknown input"),
    ],
)
def test_export_errors(kwargs, match, tmp_path, drive_system):
    with pytest.raises(ParameterError, match=match):
        export_fmu(drive_system, tmp_path / "x.fmu", **kwargs)


def test_export_from_assembly_with_inputs_and_parameters(tmp_path):
    from tests.fmu.fmu_models import DrivenInertia

    path = export_fmu(DrivenInertia(), tmp_path / "d.fmu", outputs=["rotor.w", "tau_drive"],
                      inputs={"tau_drive": 3.0}, parameters={"rotor.J": 0.25},
                      kinds=("ME",), model_name="driven2")
    md = read_model_description(str(path))
    v = {x.name: x for x in md.modelVariables}
    assert float(v["tau_drive"].start) == 3.0 and float(v["rotor.J"].start) == 0.25
    assert [u.variable.name for u in md.outputs] == ["rotor.w"]  # an input is not an output
    assert md.description == DrivenInertia.__doc__.strip().split("\n")[0]
