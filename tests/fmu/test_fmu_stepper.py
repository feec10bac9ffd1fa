"""The co-simulation steppers of the C runtime: BDF (the stepping core of ``compiled_bdf``,
default from ``BDF_MIN_STATES`` states on), ROS34PW2 (Rosenbrock-W, default below, reuses the
Jacobian and its LU factorisation) and Rodas3 (``export_fmu(stepper="rodas3")``): order of
convergence against an analytic solution, reuse of the factorisation, agreement with
``simulate`` on a bearing model, FMI validation, the BDF history across doSteps and FMU
states."""

from __future__ import annotations

import math
import re

import casadi as ca
import numpy as np
import pytest
from fmpy.validation import validate_fmu

from bearingsim import Assembly, Input, connect
from bearingsim.assembler import assemble
from bearingsim.components.rotational import Fixed, Inertia, SpringDamper, TorqueSource
from bearingsim.errors import ParameterError
from bearingsim.fmu import export_fmu
from tests.fmu.conftest import STIFF_OUTPUTS
from tests.fmu.helpers import LogCapture, open_fmu, reference, rel_err

STEPPERS = ("ros34pw2", "rodas3")
"""The Rosenbrock steppers (order 3)."""
ALL_STEPPERS = ("bdf", *STEPPERS)
J, K, D, TAU = 1.0, 100.0, 2.0, 1.0
"""Oscillator: inertia [kg m^2], stiffness [N m/rad], damping [N m s/rad], torque [N m]."""


class Oscillator(Assembly):
    """A torque input turns an inertia held by a spring-damper: J phi'' + D phi' + K phi = tau."""

    def __init__(self):
        super().__init__("oscillator")
        self.tau = Input(TAU, "N.m", "driving torque")
        self.src = TorqueSource(None)
        self.rotor = Inertia(J)
        self.spring = SpringDamper(K, D)
        self.ground = Fixed()
        connect(self.src.flange, self.rotor.flange_a)
        connect(self.rotor.flange_b, self.spring.flange_a)
        connect(self.spring.flange_b, self.ground.flange)

    def equations(self):
        return [self.src.tau_in == self.tau]


def phi_exact(t):
    """Angle [rad] of the oscillator from rest under the constant torque TAU."""
    w0 = math.sqrt(K / J)
    zeta = D / (2.0 * math.sqrt(K * J))
    wd = w0 * math.sqrt(1.0 - zeta**2)
    return TAU / K * (1.0 - np.exp(-zeta * w0 * t) * (np.cos(wd * t)
                                                      + zeta * w0 / wd * np.sin(wd * t)))


def counters(log: LogCapture) -> dict[str, int]:
    """The stepper's counters from the fmi2Terminate message."""
    m = re.search(r"after (\d+) internal steps \((\d+) rejected\), (\d+) Jacobians, (\d+) LU",
                  log.text())
    assert m, log.text()
    return dict(zip(("steps", "rejected", "jacobians", "lu"), map(int, m.groups()),
                    strict=True))


def run_cs(path, tmp_path, h, t_end, outputs, tol, inputs=None):
    """Step an FMU from t = 0 with communication step h; returns (outputs at each
    communication point, counters)."""
    log = LogCapture()
    fmu, _, vr = open_fmu(path, tmp_path, log=log, logging_on=True)
    fmu.setupExperiment(tolerance=tol)
    fmu.enterInitializationMode()
    for name, value in (inputs or {}).items():
        fmu.setReal([vr[name]], [value])
    fmu.exitInitializationMode()
    refs = [vr[n] for n in outputs]
    out, t = [], 0.0
    for _ in range(int(round(t_end / h))):
        fmu.doStep(t, h)
        t += h
        out.append(fmu.getReal(refs))
    fmu.terminate()
    fmu.freeInstance()
    return np.array(out), counters(log)


@pytest.fixture(scope="module")
def oscillator(fmu_dir):
    system = assemble(Oscillator(), outputs=["rotor.phi"])
    return {s: export_fmu(system, fmu_dir / f"oscillator_{s}.fmu", kinds=("CS",), stepper=s,
                          model_name=f"oscillator_{s}") for s in ALL_STEPPERS}


@pytest.mark.parametrize("stepper", STEPPERS)
def test_order_three_on_the_oscillator(stepper, oscillator, tmp_path):
    assert validate_fmu(str(oscillator[stepper])) == []
    t_end, errors, steps = 0.4, [], [0.01, 0.005, 0.0025]
    for h in steps:
        # a loose tolerance: one internal step per communication step, so the error is the
        # method's at step h
        out, c = run_cs(oscillator[stepper], tmp_path / f"{h}", h, t_end, ["rotor.phi"], 0.9)
        n = int(round(t_end / h))
        assert c["steps"] == n and c["rejected"] == 0
        if stepper == "ros34pw2":  # linear, constant input: one Jacobian, one factorisation
            assert c["jacobians"] == 1 and c["lu"] == 1
        else:
            assert c["jacobians"] == n and c["lu"] == n
        errors.append(np.max(np.abs(out[:, 0] - phi_exact(h * np.arange(1, n + 1)))))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders > 2.7) & (orders < 3.5)), orders


@pytest.mark.parametrize("stepper", ALL_STEPPERS)
def test_tight_tolerance_matches_the_analytic_solution(stepper, oscillator, tmp_path):
    out, _ = run_cs(oscillator[stepper], tmp_path, 0.01, 1.0, ["rotor.phi"], 1e-9)
    t = 0.01 * np.arange(1, 101)
    assert rel_err(out[:, 0], phi_exact(t)) < 1e-7


def test_factorisation_reused_on_a_stiff_nonlinear_chain(stiff_fmu, stiff_system, tmp_path):
    out, c = run_cs(stiff_fmu, tmp_path, 0.05, 1.0, STIFF_OUTPUTS, 1e-8)
    ref = reference(stiff_system, 1.0, 0.05)
    for k, name in enumerate(STIFF_OUTPUTS):
        assert rel_err(out[:, k], ref[name][1:]) < 1e-4, name
    assert c["lu"] < c["steps"] / 5 and c["jacobians"] < c["steps"] / 10, c


@pytest.fixture(scope="module")
def bearing(fmu_dir):
    """The double-layer bearing 61905/61907 (torque level) with both steppers."""
    from bearingsim.studies.motor_bearing_cosim import bearing_model

    outputs = ["M_shaft", "w_middle", "Rs"]
    system = assemble(bearing_model(), outputs=outputs)
    return system, outputs, {s: export_fmu(system, fmu_dir / f"bearing_{s}.fmu", kinds=("CS",),
                                           stepper=s, model_name=f"bearing_{s}")
                             for s in ALL_STEPPERS}


@pytest.mark.parametrize("stepper", ALL_STEPPERS)
def test_bearing_agrees_with_simulate(stepper, bearing, tmp_path):
    system, outputs, fmus = bearing
    assert validate_fmu(str(fmus[stepper])) == []
    inputs = {"shaft_speed": 100.0, "Fr": 500.0}
    out, c = run_cs(fmus[stepper], tmp_path, 0.01, 0.5, outputs, 1e-8, inputs=inputs)
    ref = reference(system, 0.5, 0.01, inputs=inputs)
    for k, name in enumerate(outputs):
        assert rel_err(out[:, k], ref[name][1:]) < 1e-6, (name, c)
    if stepper == "ros34pw2":
        assert c["lu"] < c["steps"] / 2, c


def test_restored_state_continues_bit_for_bit(stiff_fmu, tmp_path):
    """The Jacobian the W-method uses is named by the FMU state, so a run from a restored state
    repeats the first run exactly (also when the instance's cached Jacobian moved on)."""
    fmu, _, vr = open_fmu(stiff_fmu, tmp_path)
    fmu.setupExperiment(tolerance=1e-8)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    refs = [vr[n] for n in STIFF_OUTPUTS]

    def run(t, n):
        out = []
        for _ in range(n):
            fmu.doStep(t, 0.05)
            t += 0.05
            out.append(fmu.getReal(refs))
        return np.array(out)

    run(0.0, 3)
    state = fmu.getFMUstate()
    first = run(0.15, 5)
    fmu.setFMUstate(state)
    np.testing.assert_array_equal(run(0.15, 5), first)
    fmu.freeFMUstate(state)
    fmu.terminate()
    fmu.freeInstance()


def test_unknown_stepper_is_refused(tmp_path):
    with pytest.raises(ParameterError,
                       match="stepper must be one of auto, bdf, ros34pw2, rodas3"):
        export_fmu(Oscillator(), tmp_path / "x.fmu", stepper="euler")


def test_time_ramp_input_through_the_stepper(fmu_dir, tmp_path):
    """A baked-in time function (jac_t) and an input: both steppers agree with simulate."""
    class Ramped(Oscillator):
        def equations(self):
            return [self.src.tau_in == self.tau * ca.fmin(self.time / 0.1, 1.0)]

    system = assemble(Ramped(), outputs=["rotor.phi"])
    ref = reference(system, 0.5, 0.01)
    for s in STEPPERS:
        path = export_fmu(system, fmu_dir / f"ramped_{s}.fmu", kinds=("CS",), stepper=s,
                          model_name=f"ramped_{s}")
        out, _ = run_cs(path, tmp_path / s, 0.01, 0.5, ["rotor.phi"], 1e-9)
        assert rel_err(out[:, 0], ref["rotor.phi"][1:]) < 1e-6, s


def test_fill_reducing_order_keeps_the_hub_for_last():
    """An arrow pattern (state 0 coupled to all others): eliminating 0 first would fill the
    whole matrix; the minimum-degree order keeps it until one other state is left (then the
    two tie)."""
    import casadi as ca

    from bearingsim.simulation.ordering import fill_reducing_order

    n = 6
    rows = [0] * n + list(range(n)) + list(range(1, n))
    cols = list(range(n)) + list(range(n)) + [0] * (n - 1)
    order = list(fill_reducing_order(ca.Sparsity.triplet(n, n, rows, cols)))
    assert sorted(order) == list(range(n)) and order.index(0) >= n - 2
