"""An FMU's inputs keep the ranges and limits the Python model gives them: ``min``/``max`` in the
model description, refusal of a value outside the range in ``fmi2SetReal``/``fmi3SetFloat64``
(the double-layer torque FMU took a radial load of 1e9 N and then looped on "step size became
too small", or returned a shaft torque of -2.7e7 N m), a warning once above the limit (a
limiting speed, the static load rating), and a start value checked at export."""

from __future__ import annotations

import re
from ctypes import c_double, c_size_t, c_uint

import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException

from bearingsim.assemblies.double_layer import double_layer_bearing
from bearingsim.errors import ParameterError, PlasticDeformationWarning
from bearingsim.fmu import cli_export, export_fmu
from tests.fmu.helpers import LogCapture, open_fmu, open_fmu3

FMI2_WARNING, FMI2_ERROR = 1, 3
C0_INNER, C0_OUTER = 4300.0, 6800.0
"""Static load ratings [N] of the default double layer's inner and outer layer (its parameters
``inner_layer.C0`` and ``outer_layer.C0``, checked below)."""


@pytest.fixture(scope="module")
def torque_fmus(tmp_path_factory):
    directory = tmp_path_factory.mktemp("input_ranges")
    paths = {}
    for version in ("2.0", "3.0"):
        path = directory / f"double_layer_{version}.fmu"
        assert cli_export(["double_layer_bearing", str(path), "--kinds", "ME,CS",
                           "--fmi-version", version, "--input", "shaft_speed=3000rpm",
                           "--input", "Fr=300"]) == 0
        paths[version] = path
    return paths


def _variables(path):
    return {v.name: v for v in read_model_description(str(path)).modelVariables}


def test_model_description_carries_input_ranges_and_start_in_si(torque_fmus):
    """Fr in [0, 10 C0] of the weaker (inner) layer, Fa in [0, 10 C0 / Y0] (Y0 = 0.5 for a
    deep-groove ball bearing, ISO 76), the shaft speed within +-4 x the limiting speed; the
    start value given as 3000 rpm is written in rad/s."""
    for path in torque_fmus.values():
        v = _variables(path)
        assert float(v["inner_layer.C0"].start) == C0_INNER
        assert float(v["outer_layer.C0"].start) == C0_OUTER
        assert (float(v["Fr"].min), float(v["Fr"].max)) == (0.0, 10 * C0_INNER)
        assert (float(v["Fa"].min), float(v["Fa"].max)) == (0.0, 10 * C0_INNER / 0.5)
        low, high = float(v["shaft_speed"].min), float(v["shaft_speed"].max)
        assert low == -high and high > 0
        assert float(v["shaft_speed"].start) == pytest.approx(3000 * 3.141592653589793 / 30)


def test_excluded_parameter_bound_is_the_next_double_inside(torque_fmus):
    """FMI's min is inclusive: a positive moment of inertia (range (0, inf)) is written as
    min = 5e-324, not 0, which the FMU refuses."""
    v = _variables(torque_fmus["2.0"])
    assert float(v["middle.sleeve.J"].min) == 5e-324
    assert float(v["Fr"].min) == 0.0  # an inclusive bound stays as it is


@pytest.mark.parametrize("kind", ["CS", "ME"])
def test_fmi2_refuses_an_input_outside_its_range(torque_fmus, tmp_path, kind):
    log = LogCapture()
    fmu, _, vr = open_fmu(torque_fmus["2.0"], tmp_path, kind=kind, log=log)
    fmu.setReal([vr["Fr"]], [1000.0])  # within range, below C0: silent
    assert log.messages == []
    with pytest.raises(FMICallException, match="error"):
        fmu.setReal([vr["Fr"]], [1e9])
    assert log.messages[-1][:2] == (FMI2_ERROR, "logStatusError")
    assert log.messages[-1][2] == ("input Fr = 1e+09 [N] is outside its valid range "
                                   "[0, 43000]; value not set")
    fmu.freeInstance()


def test_fmi2_refuses_a_negative_load_and_a_speed_beyond_its_bound(torque_fmus, tmp_path):
    for name, value in (("Fr", -100.0), ("shaft_speed", 1e6)):
        log = LogCapture()
        fmu, _, vr = open_fmu(torque_fmus["2.0"], tmp_path, log=log)
        with pytest.raises(FMICallException):
            fmu.setReal([vr[name]], [value])
        assert f"input {name} = " in log.text() and "outside its valid range" in log.text()
        fmu.freeInstance()


def test_fmi2_warns_once_above_the_static_load_rating(torque_fmus, tmp_path):
    """Fr = 5 kN is above C0 = 4.3 kN of the inner layer: set with fmi2Warning and one
    logStatusWarning naming the limit; setting it again does not repeat the warning; the
    value is taken (the model runs)."""
    log = LogCapture()
    fmu, _, vr = open_fmu(torque_fmus["2.0"], tmp_path, log=log)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    status = fmu.fmi2SetReal(fmu.component, *_vr_value(vr["Fr"], 5000.0))
    assert status == FMI2_WARNING
    warnings = [m for m in log.messages if m[0] == FMI2_WARNING]
    assert len(warnings) == 1 and warnings[0][1] == "logStatusWarning"
    assert warnings[0][2].startswith("input Fr = 5000 [N] is above the load at which this "
                                     "component alone brings the static equivalent load")
    assert "4300 [N]" in warnings[0][2] and "deform permanently" in warnings[0][2]
    assert fmu.fmi2SetReal(fmu.component, *_vr_value(vr["Fr"], 6000.0)) == 0
    assert len([m for m in log.messages if m[0] == FMI2_WARNING]) == 1
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 1e-3)
    assert fmu.getReal([vr["Fr"]]) == [6000.0]
    fmu.terminate()
    fmu.freeInstance()


def test_an_input_extrapolated_out_of_its_range_is_held_at_the_bound(torque_fmus, tmp_path):
    """Co-simulation inputs follow the polynomial of the derivatives a master sets
    (fmi2SetRealInputDerivatives) within a step; Fr = 100 N falling at 1e6 N/s reached
    -900 N at the end of a 1 ms step and the model ran there, where setting -900 N is
    refused. The extrapolated input is held at its bound, with one warning."""
    log = LogCapture()
    fmu, _, vr = open_fmu(torque_fmus["2.0"], tmp_path, log=log)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.setReal([vr["Fr"]], [100.0])
    fmu.setRealInputDerivatives([vr["Fr"]], [1], [-1e6])
    fmu.doStep(0.0, 1e-3)
    assert fmu.getReal([vr["Fr"]]) == [0.0]
    warnings = [m[2] for m in log.messages if m[0] == FMI2_WARNING]
    assert len(warnings) == 1
    assert re.fullmatch(r"input Fr extrapolated from its derivatives reaches -[0-9.e+-]+ \[N\] "
                        r"at t = [0-9.e+-]+ s, outside its valid range; held at 0 \[N\] "
                        r"\(warned once per instance\)", warnings[0])
    fmu.setReal([vr["Fr"]], [100.0])
    fmu.setRealInputDerivatives([vr["Fr"]], [1], [-1e6])
    fmu.doStep(1e-3, 1e-3)  # once per instance
    assert len([m for m in log.messages if m[0] == FMI2_WARNING]) == 1
    fmu.terminate()
    fmu.freeInstance()


def _vr_value(ref: int, value: float):
    """The array arguments of a raw fmi2SetReal call for one value."""
    return (c_uint * 1)(ref), c_size_t(1), (c_double * 1)(value)


def test_fmi3_refuses_an_input_outside_its_range(torque_fmus, tmp_path):
    messages: list[str] = []
    fmu, _, vr = open_fmu3(torque_fmus["3.0"], tmp_path, messages=messages)
    with pytest.raises(Exception, match="fmi3SetFloat64"):
        fmu.setFloat64([vr["Fa"]], [1e6])
    assert messages[-1] == ("input Fa = 1e+06 [N] is outside its valid range [0, 86000]; "
                            "value not set")
    fmu.freeInstance()


def test_export_checks_the_start_values_of_inputs(tmp_path):
    """``export-fmu --input Fr=-100`` was accepted (the FMU then started outside its range);
    a start value above the limit warns as a run does."""
    model = double_layer_bearing()
    with pytest.raises(ParameterError, match=r"export_fmu: start value of input Fr = -100 \[N\]"
                                             r" .* outside its valid range \[0, 43000\]"):
        export_fmu(model, tmp_path / "bad.fmu", inputs={"Fr": -100.0})
    with pytest.raises(ParameterError, match="export_fmu: start value of input shaft_speed"):
        export_fmu(model, tmp_path / "bad.fmu", inputs={"shaft_speed": "3 kN"})
    with pytest.warns(PlasticDeformationWarning, match="input Fr reaches"):
        export_fmu(model, tmp_path / "warned.fmu", inputs={"Fr": 5000.0}, kinds=("ME",))
    assert not (tmp_path / "bad.fmu").exists()
