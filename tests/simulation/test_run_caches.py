"""What a run remembers between calls on one system (names, default vectors, checked parameter
values, input signals and their values, the names a result shares) must never leak between
runs or into the system: every accessor hands out its own copy, and a remembered value is the
one computed anew.

Speed is measured in ``bench/per_call.py``, never asserted here.
"""

from __future__ import annotations

import copy
import pickle

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.errors import ParameterError
from bearingsim.simulation import simulate
from bearingsim.simulation.inputs import input_signal
from bearingsim.symbolic import sin

SPEED = {"shaft_speed": 100.0, "Fr": 200.0, "Fa": 50.0}


@pytest.fixture(scope="module")
def system():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"))


def _run(system, **kwargs):
    return simulate(system, 0.01, inputs=kwargs.pop("inputs", SPEED), n_points=3,
                    method="cvodes", compiled=False, **kwargs)


def test_a_result_changed_by_its_user_changes_no_later_result(system):
    first = _run(system, parameters={"inner_layer.omega_reg": 0.2})
    second = _run(system, parameters={"inner_layer.omega_reg": 0.2})
    expected = (list(second.names), dict(second.units), dict(second.descriptions),
                list(second.outputs), dict(second.inputs), dict(second.parameters))
    first.names.append("extra")
    first.units["Rs"] = "furlong"
    first.descriptions["Rs"] = "changed"
    first.outputs.clear()
    first.inputs["Fr"] = -1.0
    first.parameters["inner_layer.omega_reg"] = 99.0
    third = _run(system, parameters={"inner_layer.omega_reg": 0.2})
    for result in (second, third):
        assert (result.names, result.units, result.descriptions, result.outputs,
                result.inputs, result.parameters) == expected
    assert "extra" not in system.observed_names
    assert system.variable_units["Rs"] != "furlong"
    assert first.names[-1] == "extra" and first.parameters["inner_layer.omega_reg"] == 99.0


def test_a_result_holds_the_runs_own_parameters_and_inputs(system):
    res = _run(system, parameters={"inner_layer.omega_reg": 0.3})
    assert res.parameters == dict(zip(system.parameter_names,
                                      system.p0({"inner_layer.omega_reg": 0.3}), strict=True))
    assert res.parameters["inner_layer.omega_reg"] == 0.3
    assert _run(system).parameters["inner_layer.omega_reg"] == system.p0()[
        system.parameter_names.index("inner_layer.omega_reg")]
    assert res.inputs == SPEED  # constants: the same numbers at the end
    assert res.names == system.observed_names and res.names is not system.observed_names


def test_inputs_at_the_end_are_the_signal_evaluated_there_alone(system):
    """The result's inputs come from the inputs evaluated at all output times at once; they
    equal, bit for bit, the inputs evaluated at the last time alone."""
    table = ([0.0, 0.004, 0.007, 0.01], [100.0, 350.0, 120.0, 160.0])
    inputs = {"shaft_speed": lambda t: 100.0 + 30.0 * sin(317.0 * t), "Fr": table, "Fa": 10.0}
    res = _run(system, inputs=inputs)
    alone = input_signal(system, inputs).at(0.01)[:, 0]
    assert [res.inputs[n] for n in system.input_names] == alone.tolist()
    assert res.inputs["Fr"] == 160.0


def test_a_result_of_a_run_pickles_and_copies_with_its_own_fields(system):
    res = _run(system)
    for twin in (pickle.loads(pickle.dumps(res)), copy.copy(res), copy.deepcopy(res)):
        assert twin.names == res.names and twin.parameters == res.parameters
        assert twin.inputs == res.inputs and twin.units == res.units
        np.testing.assert_array_equal(twin.values, res.values)
        assert twin["middle.sleeve.w"][-1] == res["middle.sleeve.w"][-1]
        twin.names.append("extra")
        assert "extra" not in res.names


def test_the_lists_and_vectors_of_a_system_are_copies(system):
    for name in ("state_names", "input_names", "parameter_names"):
        names = getattr(system, name)
        names.append("extra")
        assert "extra" not in getattr(system, name)
    for vector in (system.x0, system.p0, system.u_default):
        values = vector()
        kept = values.copy()
        values[:] = -7.0
        np.testing.assert_array_equal(vector(), kept)
    assert system.x0({"middle.sleeve.w": 3.0})[1] == 3.0 and system.x0()[1] != 3.0


def test_a_parameter_value_checked_once_gives_the_same_vector_and_bad_ones_raise_each_time(
        system):
    k = system.parameter_names.index("inner_layer.dm")
    assert system.p0({"inner_layer.dm": "25 mm"})[k] == pytest.approx(0.025)
    assert system.p0({"inner_layer.dm": "25 mm"})[k] == system.p0({"inner_layer.dm": 0.025})[k]
    assert system.p0({"inner_layer.dm": 0.03})[k] == 0.03
    assert system.p0()[k] != 0.03
    for _ in range(2):
        with pytest.raises(ParameterError, match="inner_layer.dm"):
            system.p0({"inner_layer.dm": -1.0})
        with pytest.raises(ParameterError, match="unknown parameter 'inner_layer.dmm'"):
            system.p0({"inner_layer.dmm": 0.03})


def test_input_signals_are_shared_only_where_their_values_are_the_same(system):
    a = input_signal(system, {"shaft_speed": 100.0})
    assert input_signal(system, {"shaft_speed": 100.0}) is a
    assert input_signal(system, {"shaft_speed": 100}) is not a  # an int is keyed apart
    assert input_signal(system, {"shaft_speed": 101.0}).q.tolist() != a.q.tolist()
    zero, negative_zero = (input_signal(system, {"Fa": v, "shaft_speed": 1.0})
                           for v in (0.0, -0.0))
    assert zero is not negative_zero and np.signbit(negative_zero.q).any()
    calls = []

    def speed(t):
        calls.append(t)
        return 100.0 + t

    input_signal(system, {"shaft_speed": speed})
    input_signal(system, {"shaft_speed": speed})
    assert len(calls) == 2  # a plain function may read values that change: evaluated again
    with pytest.raises(ValueError):
        a.q[0] = 1.0  # shared by the runs with these inputs: read-only


def test_input_values_at_times_are_new_arrays(system):
    signal = input_signal(system, {"shaft_speed": lambda t: 100.0 + t, "Fr": 5.0})
    first = signal.at([0.0, 1.0])
    first[:] = -1.0
    np.testing.assert_array_equal(signal.at([0.0, 1.0])[2], [100.0, 101.0])
    assert signal.at([1.0])[2, 0] == 101.0




def test_states_are_finite_when_their_sum_overflows_and_not_with_one_nan_or_inf():
    """CVODES' states are added up first (one pass) and looked at one by one only when the
    sum is not finite."""
    from bearingsim.simulation.sundials import _all_finite

    assert _all_finite([1e308, 1e308, -5.0]) and _all_finite([])
    assert not _all_finite([1e308, 1e308, float("nan")])
    assert not _all_finite([1.0, float("inf"), 2.0])
    assert not _all_finite([float("inf"), float("-inf")])
