"""ME (fmpy's CVode) and CS (the FMU's Rosenbrock stepper) reproduce the in-Python simulation;
parameters, inputs, input slopes, directional derivatives and FMU states."""

from __future__ import annotations

import ctypes

import numpy as np
import pytest

from bearingsim.simulation import simulate
from tests.fmu.conftest import DRIVE_OUTPUTS, DRIVEN_OUTPUTS
from tests.fmu.helpers import open_fmu, reference, rel_err, run_fmu


@pytest.mark.parametrize("kind", ["ModelExchange", "CoSimulation"])
def test_drive_matches_python(kind, drive_fmu, drive_system):
    ref = reference(drive_system, 2.0, 0.01)
    res = run_fmu(drive_fmu, kind, 2.0, 0.01, DRIVE_OUTPUTS)
    np.testing.assert_allclose(res["time"], ref.t, atol=1e-12)
    for name in DRIVE_OUTPUTS:
        assert rel_err(res[name], ref[name]) < 1e-4, name


@pytest.mark.parametrize("kind", ["ModelExchange", "CoSimulation"])
def test_parameters_and_inputs_change_the_result_as_in_python(kind, driven_fmu, driven_system):
    values = {"rotor.J": 0.2, "friction.d": 0.4, "tau_drive": 1.5, "tau_load": 0.3}
    ref = reference(driven_system, 3.0, 0.01,
                    parameters={"rotor.J": 0.2, "friction.d": 0.4},
                    inputs={"tau_drive": 1.5, "tau_load": 0.3})
    res = run_fmu(driven_fmu, kind, 3.0, 0.01, DRIVEN_OUTPUTS, start_values=values)
    for name in DRIVEN_OUTPUTS:
        assert rel_err(res[name], ref[name]) < 1e-4, name
    default = run_fmu(driven_fmu, kind, 3.0, 0.01, DRIVEN_OUTPUTS,
                      start_values={"tau_drive": 1.5, "tau_load": 0.3})
    assert rel_err(default["rotor.w"], ref["rotor.w"]) > 0.1
    # steady state (tau_drive - tau_load) / d
    assert res["rotor.w"][-1] == pytest.approx(1.2 / 0.4 * (1 - np.exp(-0.4 / 0.2 * 3.0)),
                                               rel=1e-6)


def test_input_slopes_interpolate_within_a_step(driven_fmu, driven_system, tmp_path):
    """With fmi2SetRealInputDerivatives a ramp input is exact at a coarse communication step."""
    fmu, _, vr = open_fmu(driven_fmu, tmp_path)
    fmu.setupExperiment(tolerance=1e-10)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    h, t, out = 0.25, 0.0, []
    while t < 2.0 - 1e-12:
        fmu.setReal([vr["tau_drive"]], [2.0 * t])
        fmu.setRealInputDerivatives([vr["tau_drive"]], [1], [2.0])
        fmu.doStep(t, h)
        t += h
        out.append(fmu.getReal([vr["rotor.w"]])[0])
    fmu.terminate()
    fmu.freeInstance()
    ref = simulate(driven_system, 2.0, inputs={"tau_drive": lambda t: 2.0 * t}, n_points=9,
                   rtol=1e-11, atol=1e-13)
    assert rel_err(out, ref["rotor.w"][1:]) < 1e-7


def test_directional_derivatives_are_the_exact_jacobians(drive_fmu, drive_system, tmp_path):
    fmu, md, vr = open_fmu(drive_fmu, tmp_path, kind="ME")
    fmu.setupExperiment()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.enterContinuousTimeMode()
    x = np.array([0.1, -0.3, 0.05, 0.2])
    fmu.setContinuousStates((ctypes.c_double * 4)(*x), 4)
    states = drive_system.state_names
    ders = [vr[f"der({s})"] for s in states]
    jac = np.column_stack([
        fmu.getDirectionalDerivative(ders + [vr["sd.tau"]], [vr[s]], [1.0]) for s in states
    ])
    p = drive_system.p0()
    jx = np.array(drive_system.functions["jac_x"](0.0, x, [], p))
    jy = np.array(drive_system.functions["out_jac_x"](0.0, x, [], p))[1]
    np.testing.assert_allclose(jac[:4], jx, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(jac[4], jy, rtol=1e-14, atol=1e-14)
    dx = (ctypes.c_double * 4)()
    fmu.getDerivatives(dx, 4)
    np.testing.assert_allclose(np.array(dx), drive_system.rhs(0.0, x, [], p), rtol=1e-15)
    fmu.terminate()
    fmu.freeInstance()


def test_fmu_state_get_set_and_serialize(drive_fmu, tmp_path):
    fmu, _, vr = open_fmu(drive_fmu, tmp_path)
    fmu.setupExperiment(tolerance=1e-8)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    refs = [vr[n] for n in DRIVE_OUTPUTS]

    def run(t0, n):
        out = []
        for k in range(n):
            fmu.doStep(t0 + 0.1 * k, 0.1)
            out.append(fmu.getReal(refs))
        return np.array(out)

    run(0.0, 5)
    state = fmu.getFMUstate()
    blob = fmu.serializeFMUstate(state)
    first = run(0.5, 5)
    fmu.setFMUstate(state)
    np.testing.assert_array_equal(run(0.5, 5), first)
    restored = fmu.deSerializeFMUstate(blob)
    fmu.setFMUstate(restored)
    np.testing.assert_array_equal(run(0.5, 5), first)
    fmu.freeFMUstate(state)
    fmu.freeFMUstate(restored)
    fmu.terminate()
    fmu.freeInstance()
