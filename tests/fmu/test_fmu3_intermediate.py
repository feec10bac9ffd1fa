"""FMI 3.0 co-simulation with inputs between communication points (intermediate update): the
FMU calls the importer's ``intermediateUpdate`` callback at every time its stepper evaluates
the model inside ``fmi3DoStep`` and uses the inputs set there; driven through the callback, a
co-simulation FMU follows ``simulate`` with the same input function at any communication step,
where holding the inputs is far off; the motor/bearing pair coupled through the callback gives
the FMI 2.0 input-derivative coupling's result."""

from __future__ import annotations

import xml.etree.ElementTree as ET
import zipfile

import casadi as ca
import numpy as np
import pytest
from fmpy.validation import validate_fmu

from bearingsim.assembler import assemble
from bearingsim.fmu import export_fmu
from tests.fmu.cosim_masters import (
    REF_OUTPUTS,
    derivative_run,
    intermediate_update_run,
    value_reference,
)
from tests.fmu.fmu_models import SpeedDrivenLoad
from tests.fmu.helpers import open_fmu3, reference, rel_err

H = 0.05
"""Communication step of the single-FMU runs [s] (a tenth of the input's period)."""
T_STOP = 0.5

INPUTS = {
    "ramp": (lambda t: 40.0 * t, lambda t: 40.0 * t),
    "sine": (lambda t: 5.0 * np.sin(20.0 * t), lambda t: 5.0 * ca.sin(20.0 * t)),
}
"""Shaft speed w_in(t) [rad/s] as (numeric, symbolic for ``simulate``)."""


@pytest.fixture(scope="module")
def load3(fmu_dir):
    """The spring-coupled load driven at the input shaft speed w_in, CS, FMI 3.0."""
    return export_fmu(SpeedDrivenLoad(), fmu_dir / "load3.fmu", outputs=["sensor.tau"],
                      kinds=("CS",), fmi_version="3.0")


def test_model_description_offers_intermediate_update(load3):
    assert validate_fmu(str(load3)) == []
    with zipfile.ZipFile(load3) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    cs = root.find("CoSimulation")
    assert cs.get("providesIntermediateUpdate") == "true"
    assert cs.get("canReturnEarlyAfterIntermediateUpdate") == "false"
    flagged = {v.get("name"): v.get("intermediateUpdate") for v in root.iter("Float64")}
    assert flagged["w_in"] == "true"
    assert flagged["sensor.tau"] is None  # no intermediate outputs


def drive_load(path, tmp_path, w_in, through_callback: bool, calls: list | None = None):
    """Co-simulate the load over T_STOP at step H: at each communication point the importer
    sets ``w_in(t)``; with ``through_callback`` it also sets it at every time the FMU calls
    back inside the step. Returns sensor.tau at the communication points (t = 0 first)."""
    state = {}

    def callback(env, t, set_requested, get_allowed, finished, can_return_early, *_):
        if calls is not None:
            calls.append((state["t0"], t, set_requested, get_allowed, finished,
                          can_return_early))
        state["fmu"].setFloat64([state["vr"]], [w_in(t)])

    if through_callback:
        fmu, _, vr = open_fmu3(path, tmp_path, intermediate_update=callback,
                               required=[value_reference(path, "w_in")])
    else:
        fmu, _, vr = open_fmu3(path, tmp_path)
    state.update(fmu=fmu, vr=vr["w_in"])
    fmu.enterInitializationMode(tolerance=1e-8)
    fmu.exitInitializationMode()
    out = [fmu.getFloat64([vr["sensor.tau"]])[0]]
    n = int(round(T_STOP / H))
    for k in range(n):
        state["t0"] = k * H
        fmu.setFloat64([vr["w_in"]], [w_in(k * H)])
        fmu.doStep(k * H, H)
        out.append(fmu.getFloat64([vr["sensor.tau"]])[0])
    fmu.terminate()
    fmu.freeInstance()
    return np.array(out)


@pytest.mark.parametrize("signal", sorted(INPUTS))
def test_inputs_through_the_callback_match_simulate(signal, load3, tmp_path):
    """At a 50 ms communication step the FMU driven through the callback is within 1e-6 of
    ``simulate`` with the same input function (the stepper's tolerance: the input is exact at
    every stage, linear or not); holding the input over each step is off by 5 % or more."""
    numeric, symbolic = INPUTS[signal]
    system = assemble(SpeedDrivenLoad(), outputs=["sensor.tau"])
    ref = reference(system, T_STOP, H, inputs={"w_in": symbolic})["sensor.tau"]
    between = rel_err(drive_load(load3, tmp_path, numeric, True), ref)
    held = rel_err(drive_load(load3, tmp_path, numeric, False), ref)
    assert between < 1e-6, between
    assert held > 0.05 and held > 1e4 * between, (held, between)


def test_bdf_stepper_takes_the_inputs_through_the_callback(fmu_dir, tmp_path):
    """The BDF stepper (its right-hand side at every Newton iteration) asks the callback for
    the inputs as the Rosenbrock steppers do: driven through it, the FMU follows ``simulate``
    with the sine input; held over each step it is 5 % or more off."""
    path = export_fmu(SpeedDrivenLoad(), fmu_dir / "load3_bdf.fmu", outputs=["sensor.tau"],
                      kinds=("CS",), fmi_version="3.0", stepper="bdf")
    numeric, symbolic = INPUTS["sine"]
    system = assemble(SpeedDrivenLoad(), outputs=["sensor.tau"])
    ref = reference(system, T_STOP, H, inputs={"w_in": symbolic})["sensor.tau"]
    between = rel_err(drive_load(path, tmp_path, numeric, True), ref)
    held = rel_err(drive_load(path, tmp_path, numeric, False), ref)
    assert between < 1e-5, between
    assert held > 0.05 and held > 1e3 * between, (held, between)


def test_callback_times_and_flags(load3, tmp_path):
    """Every call back lies inside its doStep, asks for inputs, allows no reads and no early
    return (tentative stage times: intermediateStepFinished is false), and each step is
    called back at its end (the input there is the one the FMU keeps)."""
    calls = []
    drive_load(load3, tmp_path, INPUTS["ramp"][0], True, calls)
    t0, t, set_requested, get_allowed, finished, early = np.array(calls).T
    assert np.all((t >= t0) & (t <= t0 + H + 1e-15))
    assert set_requested.all() and not get_allowed.any() and not finished.any()
    assert not early.any()
    for k in range(int(round(T_STOP / H))):
        assert np.any(np.isclose(t[t0 == k * H], (k + 1) * H, rtol=0, atol=1e-12)), k


def test_only_required_inputs_are_set_and_only_in_the_callback(load3, tmp_path):
    """requiredIntermediateVariables must be inputs; a callback without inputs refused at
    instantiation; inside the callback only those inputs may be set and nothing read."""
    messages = []
    tau = value_reference(load3, "sensor.tau")
    with pytest.raises(Exception, match="Failed to instantiate"):
        open_fmu3(load3, tmp_path, messages=messages, intermediate_update=lambda *a: None,
                  required=[tau])
    assert any("is not an input" in m for m in messages)
    seen = {}

    def callback(env, t, *_):
        from fmpy.fmi1 import FMICallException

        for name, call in (("set output", lambda: fmu.setFloat64([tau], [1.0])),
                           ("get", lambda: fmu.getFloat64([w_in]))):
            try:
                call()
                seen[name] = "ok"
            except FMICallException:
                seen[name] = "refused"
        fmu.setFloat64([w_in], [2.0])

    w_in = value_reference(load3, "w_in")
    fmu, _, vr = open_fmu3(load3, tmp_path, messages=messages, intermediate_update=callback,
                           required=[w_in])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 0.01)
    assert seen == {"set output": "refused", "get": "refused"}
    assert fmu.getFloat64([vr["w_in"]]) == [2.0]  # the value set at the end of the step
    fmu.freeInstance()


@pytest.mark.slow
def test_motor_and_bearing_through_intermediate_update_equal_input_derivatives(cosim_pair,
                                                                                tmp_path):
    """The FMI 3.0 pair coupled through the callback with the extrapolation of FMI 2.0's input
    derivatives gives the FMI 2.0 pair's input-derivative result (same inputs inside every
    step; the tolerance covers the two masters' different order of operations)."""
    h = 1e-3
    t3, fmi3 = intermediate_update_run(cosim_pair("dc", "3.0"), h, tmp_path)
    t2, fmi2 = derivative_run(cosim_pair("dc"), h, tmp_path)
    np.testing.assert_array_equal(t3, t2)
    for name in REF_OUTPUTS:
        np.testing.assert_allclose(fmi3[name], fmi2[name], rtol=1e-6,
                                   atol=1e-9 * np.max(np.abs(fmi2[name])), err_msg=name)
