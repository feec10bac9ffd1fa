"""Bad inputs give fmi2Error (or fmi2Discard for a failed step) with a logged message, never
a crash or garbage."""

from __future__ import annotations

import math

import pytest
from fmpy.fmi1 import FMICallException

from bearingsim.fmu import export_fmu
from tests.fmu.fmu_models import Sqrt
from tests.fmu.helpers import LogCapture, open_fmu

FMI2_DISCARD, FMI2_ERROR = 2, 3


@pytest.fixture(scope="module")
def sqrt_fmu(fmu_dir):
    return export_fmu(Sqrt(), fmu_dir / "sqrt.fmu", outputs=["x"], kinds=("CS",))


def _initialized(path, tmp_path, start_time=0.0):
    log = LogCapture()
    fmu, _, vr = open_fmu(path, tmp_path, log=log)
    fmu.setupExperiment(tolerance=1e-8, startTime=start_time)
    fmu.enterInitializationMode()
    return fmu, vr, log


def test_parameter_out_of_range(drive_fmu, tmp_path):
    fmu, vr, log = _initialized(drive_fmu, tmp_path)
    with pytest.raises(FMICallException, match="error"):
        fmu.setReal([vr["j1.J"]], [-1.0])
    assert log.messages[-1][:2] == (FMI2_ERROR, "logStatusError")
    assert "parameter j1.J = -1 [kg.m2] is outside its valid range (0, inf)" in log.text()
    assert fmu.getReal([vr["j1.J"]]) == [1.0]  # the value was not taken
    fmu.freeInstance()


def test_nan_parameter(drive_fmu, tmp_path):
    fmu, vr, log = _initialized(drive_fmu, tmp_path)
    with pytest.raises(FMICallException):
        fmu.setReal([vr["sd.phi_rel0"]], [math.nan])
    assert "parameter sd.phi_rel0 must be finite, got NaN; value not set" in log.text()
    fmu.freeInstance()


def test_nan_input(driven_fmu, tmp_path):
    fmu, vr, log = _initialized(driven_fmu, tmp_path)
    fmu.exitInitializationMode()
    with pytest.raises(FMICallException):
        fmu.setReal([vr["tau_drive"]], [math.nan])
    assert "input tau_drive must be finite, got NaN" in log.text()
    fmu.freeInstance()


def test_parameters_only_change_between_steps(drive_fmu, tmp_path):
    """A tunable parameter set between communication steps takes effect; in the error state
    the FMU refuses to step."""
    fmu, vr, log = _initialized(drive_fmu, tmp_path)
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 0.1)
    fmu.setReal([vr["sd.c"]], [400.0])
    fmu.doStep(0.1, 0.1)
    with pytest.raises(FMICallException):
        fmu.doStep(0.1, 0.1)  # wrong communication point
    assert "the FMU is at t = 0.2" in log.text()
    fmu.freeInstance()


def test_non_finite_derivatives_at_initialization(sqrt_fmu, tmp_path):
    fmu, _, log = _initialized(sqrt_fmu, tmp_path, start_time=2.0)
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    assert "der(x) is not finite (NaN) at t = 2 s" in log.text()
    fmu.freeInstance()


def test_failed_step_is_discarded_and_state_restored(sqrt_fmu, tmp_path):
    fmu, vr, log = _initialized(sqrt_fmu, tmp_path)
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 0.5)
    x_half = fmu.getReal([vr["x"]])[0]
    assert x_half == pytest.approx((1 - 0.5**1.5) * 2 / 3, rel=1e-6)
    with pytest.raises(FMICallException, match="discard"):
        fmu.doStep(0.5, 1.0)
    assert log.messages[-1][:2] == (FMI2_DISCARD, "logStatusDiscard")
    assert "doStep from t = 0.5 s" in log.text() and "state restored" in log.text()
    assert fmu.getReal([vr["x"]])[0] == x_half
    fmu.freeInstance()

