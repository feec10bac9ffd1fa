"""FMI 3.0 export: the same runtime behind the FMI 3 API. fmpy validates the FMUs; ME (fmpy's
CVode) and CS (the FMU's Rodas3 stepper) reproduce the in-Python simulation; directional
derivatives, FMU state, range errors; motor and bearing FMUs coupled by a hand-written master."""

from __future__ import annotations

import ctypes
import re
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from bearingsim.assembler import assemble
from bearingsim.assemblies.motor_drive import motor_drive
from bearingsim.fmu import export_fmu
from bearingsim.fmu.build import fmi_header_dir
from tests.fmu.conftest import DRIVE_OUTPUTS, DRIVEN_OUTPUTS
from tests.fmu.helpers import open_fmu3 as open3
from tests.fmu.helpers import reference, rel_err, run_fmu


@pytest.fixture(scope="module")
def drive3(fmu_dir, drive_system):
    return export_fmu(drive_system, fmu_dir / "drive3.fmu", fmi_version="3.0")


@pytest.fixture(scope="module")
def driven3(fmu_dir, driven_system):
    return export_fmu(driven_system, fmu_dir / "driven3.fmu", fmi_version="3.0")


def test_model_description(drive3):
    assert validate_fmu(str(drive3)) == []
    md = read_model_description(str(drive3))
    assert md.fmiVersion == "3.0"
    with zipfile.ZipFile(drive3) as z:
        names = z.namelist()
        root = ET.fromstring(z.read("modelDescription.xml"))
    for kind in ("ModelExchange", "CoSimulation"):
        assert root.find(kind).get("providesDirectionalDerivatives") == "true"
        assert root.find(kind).get("canGetAndSetFMUState") == "true"
    assert md.coSimulation.canHandleVariableCommunicationStepSize
    variables = {v.name: v for v in md.modelVariables}
    assert variables["time"].causality == "independent"
    assert {v.type for v in md.modelVariables} == {"Float64"}
    assert variables["sd.tau"].unit == "N.m"
    assert variables["der(j2.w)"].derivative is variables["j2.w"]
    assert variables["sd.c"].variability == "tunable" and variables["sd.c"].min == "5e-324"
    assert [u.variable.name for u in md.outputs] == ["j1.phi", "j2.w", "sd.tau"]
    assert len(md.derivatives) == 4 and len(md.initialUnknowns) == 5
    deps = {u.variable.name: [d.name for d in u.dependencies] for u in md.derivatives}
    assert deps["der(j1.phi)"] == ["j1.w"]
    assert "binaries/x86_64-linux/drive.so" in names
    assert {"sources/fmi3_api.c", "sources/bsm_solver.c", "sources/fmi3Functions.h"} <= set(names)
    assert "sources/fmi2_api.c" not in names


def test_every_fmi3_function_and_nothing_else_is_exported(drive3, tmp_path):
    with zipfile.ZipFile(drive3) as z:
        z.extract("binaries/x86_64-linux/drive.so", tmp_path)
    out = subprocess.run(["nm", "-D", "--defined-only",
                          str(tmp_path / "binaries/x86_64-linux/drive.so")],
                         capture_output=True, text=True, check=True).stdout
    symbols = {line.split()[-1] for line in out.splitlines() if " T " in line}
    header = (fmi_header_dir() / "fmi3Functions.h").read_text()
    declared = set(re.findall(r"FMI3_Export\s+fmi3\w+TYPE\s+(fmi3\w+);", header))
    assert len(declared) > 70
    assert symbols == declared, (declared - symbols, symbols - declared)


@pytest.mark.parametrize("kind", ["ModelExchange", "CoSimulation"])
def test_drive_matches_python(kind, drive3, drive_system):
    ref = reference(drive_system, 2.0, 0.01)
    res = run_fmu(drive3, kind, 2.0, 0.01, DRIVE_OUTPUTS)
    np.testing.assert_allclose(res["time"], ref.t, atol=1e-12)
    for name in DRIVE_OUTPUTS:
        assert rel_err(res[name], ref[name]) < 1e-4, name


@pytest.mark.parametrize("kind", ["ModelExchange", "CoSimulation"])
def test_parameters_and_inputs(kind, driven3, driven_system):
    values = {"rotor.J": 0.2, "friction.d": 0.4, "tau_drive": 1.5, "tau_load": 0.3}
    ref = reference(driven_system, 3.0, 0.01, parameters={"rotor.J": 0.2, "friction.d": 0.4},
                    inputs={"tau_drive": 1.5, "tau_load": 0.3})
    res = run_fmu(driven3, kind, 3.0, 0.01, DRIVEN_OUTPUTS, start_values=values)
    for name in DRIVEN_OUTPUTS:
        assert rel_err(res[name], ref[name]) < 1e-4, name


def test_motor_drive_with_double_layer_bearing(fmu_dir):
    outputs = ["shaft.w", "bearing.w_middle", "bearing.M_shaft"]
    system = assemble(motor_drive(motor="pmsm", speed_ref=None), outputs=outputs)
    path = export_fmu(system, fmu_dir / "pmsm_drive3.fmu", fmi_version="3.0")
    assert validate_fmu(str(path)) == []
    inputs = {"motor.w_ref": 100.0, "bearing.Fr": 500.0}
    ref = reference(system, 0.5, 0.01, inputs=inputs)
    for kind in ("ModelExchange", "CoSimulation"):
        res = run_fmu(path, kind, 0.5, 0.01, outputs, start_values=inputs)
        for name in outputs:
            assert rel_err(res[name], ref[name]) < 1e-6, (kind, name)


def test_directional_derivatives_and_state(drive3, drive_system, tmp_path):
    fmu, md, vr = open3(drive3, tmp_path, kind="ME")
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.enterContinuousTimeMode()
    assert fmu.getNumberOfContinuousStates() == 4
    x = np.array([0.1, -0.3, 0.05, 0.2])
    fmu.setContinuousStates((ctypes.c_double * 4)(*x), 4)
    states = drive_system.state_names
    ders = [vr[f"der({s})"] for s in states]
    jac = np.column_stack([
        fmu.getDirectionalDerivative(ders + [vr["sd.tau"]], [vr[s]], [1.0]) for s in states
    ])
    p = drive_system.p0()
    jx = np.array(drive_system.functions["jac_x"](0.0, x, [], p))
    np.testing.assert_allclose(jac[:4], jx, rtol=1e-14, atol=1e-14)
    fmu.terminate()
    fmu.freeInstance()

    fmu, _, vr = open3(drive3, tmp_path)
    fmu.enterInitializationMode(tolerance=1e-8)
    fmu.exitInitializationMode()
    refs = [vr[n] for n in DRIVE_OUTPUTS]

    def run(t0, n):
        out = []
        for k in range(n):
            fmu.doStep(t0 + 0.1 * k, 0.1)
            out.append(fmu.getFloat64(refs))
        return np.array(out)

    run(0.0, 5)
    assert fmu.getFloat64([vr["time"]]) == [pytest.approx(0.5)]
    state = fmu.getFMUState()
    blob = fmu.serializeFMUState(state)
    first = run(0.5, 5)
    fmu.setFMUState(fmu.deserializeFMUState(blob))
    np.testing.assert_array_equal(run(0.5, 5), first)
    fmu.freeFMUState(state)
    fmu.terminate()
    fmu.freeInstance()


def test_parameter_out_of_range_is_refused(drive3, tmp_path):
    messages: list[str] = []
    fmu, _, vr = open3(drive3, tmp_path, messages=messages)
    with pytest.raises(Exception, match="fmi3SetFloat64"):
        fmu.setFloat64([vr["sd.c"]], [-1.0])
    assert any("parameter sd.c = -1 [N.m/rad] is outside its valid range" in m for m in messages)
    fmu.freeInstance()


@pytest.mark.slow
def test_motor_and_bearing_fmi3_cosimulation(cosim_pair, tmp_path):
    """The FMI 3 pair under a hand-written Jacobi master gives the FMI 2 SSP result."""
    from fmpy.ssp.simulation import simulate_ssp

    fmi2, fmi3 = cosim_pair("dc"), cosim_pair("dc", "3.0")
    h, n = 1e-3, 200
    motor, _, mv = open3(fmi3["motor"], tmp_path)
    bearing, _, bv = open3(fmi3["bearing"], tmp_path)
    for fmu in (motor, bearing):
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
    w = m = 0.0
    out = []
    for k in range(n):
        motor.setFloat64([mv["M_bearing"]], [m])
        bearing.setFloat64([bv["shaft_speed"]], [w])
        motor.doStep(k * h, h)
        bearing.doStep(k * h, h)
        w, m = motor.getFloat64([mv["w_shaft"]])[0], bearing.getFloat64([bv["M_shaft"]])[0]
        out.append((w, m))
    for fmu in (motor, bearing):
        fmu.terminate()
        fmu.freeInstance()
    res = simulate_ssp(str(fmi2["ssp"]), stop_time=n * h - h / 2, step_size=h)
    out = np.array(out)
    # fmpy accumulates time += h: the kink of the ramp at 0.1 s falls a few ulp differently
    np.testing.assert_allclose(out[:, 0], res["motor.w_shaft"], rtol=1e-7)
    np.testing.assert_allclose(out[:, 1], res["bearing.M_shaft"], rtol=1e-7, atol=1e-12)


def test_output_derivatives(drive3, tmp_path):
    """fmi3GetOutputDerivatives: a state reported as output gives its derivative, a computed
    output (the spring torque sd.tau = c (phi1 - phi2) + ...) the chain rule through the
    states, equal to the forward difference of a short doStep; second order is refused."""
    fmu, md, vr = open3(drive3, tmp_path)
    assert md.coSimulation.maxOutputDerivativeOrder == 1
    fmu.enterInitializationMode(tolerance=1e-10)
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 0.3)
    (dw,) = fmu.getOutputDerivatives([vr["j2.w"]], [1])
    assert dw == fmu.getFloat64([vr["der(j2.w)"]])[0]
    (dtau,) = fmu.getOutputDerivatives([vr["sd.tau"]], [1])
    h = 1e-6
    tau0 = fmu.getFloat64([vr["sd.tau"]])[0]
    fmu.doStep(0.3, h)
    assert (fmu.getFloat64([vr["sd.tau"]])[0] - tau0) / h == pytest.approx(dtau, rel=1e-4)
    with pytest.raises(FMICallException):
        fmu.getOutputDerivatives([vr["sd.tau"]], [2])
    fmu.freeInstance()
