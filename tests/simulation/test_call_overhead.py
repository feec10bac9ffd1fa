"""Fixed costs of a run (issue 31 item 1): input checks exact for constants and tables and done
once per input signal, cached functions, steady states by Newton with the exact Jacobian.

Speed itself is measured in ``bench/per_call.py``, never asserted here; these tests pin the
behaviour the savings must keep.
"""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.errors import ParameterError
from bearingsim.simulation import input_ranges as input_ranges_module
from bearingsim.simulation import simulate, steady_state
from bearingsim.simulation import steady as steady_module
from bearingsim.simulation.input_ranges import check_input_ranges
from bearingsim.simulation.inputs import input_signal


@pytest.fixture(scope="module")
def torque_level():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"))


def test_a_table_leaving_its_range_between_output_times_is_refused(torque_level):
    """Fr >= 0 N: a table row of -5 N at 0.0105 s lies between output times 0.01 and 0.02 s.
    The old check sampled tables at the output times only (pw_lin has no interval rule) and
    let it run."""
    load = ([0.0, 0.0105, 0.011, 0.1], [0.0, -5.0, 0.0, 0.0])
    with pytest.raises(ParameterError, match=r"input Fr = -5 \[N\] \(table value 1\) is "
                                             r"outside its valid range \[0, 43000\]"):
        simulate(torque_level, 0.1, inputs={"shaft_speed": 100.0, "Fr": load}, n_points=11,
                 method="cvodes", compiled=False)


def test_a_constant_outside_its_range_names_the_value_and_range(torque_level):
    with pytest.raises(ParameterError, match=r"input Fa = -1 \[N\] is outside its valid "
                                             r"range \[0, 86000\] \[N\]"):
        check_input_ranges(torque_level,
                           input_signal(torque_level, {"shaft_speed": 100.0, "Fa": -1.0}),
                           np.array([0.0, 1.0]))


def test_a_function_of_time_is_still_checked_between_the_output_times(torque_level):
    with pytest.raises(ParameterError, match=r"input Fr \[N\]: below its valid minimum 0 "
                                             r"between t = 0.0123"):
        check_input_ranges(torque_level, input_signal(
            torque_level, {"shaft_speed": 100.0, "Fr": lambda t: 1.0 - 2.0 * (t > 0.012345)}),
            np.array([0.0, 0.1]))


def test_an_input_signal_is_checked_once_per_numbers_and_span(torque_level, monkeypatch):
    calls = []
    original = input_ranges_module.locate_problem
    monkeypatch.setattr(input_ranges_module, "locate_problem",
                        lambda *a, **k: calls.append(a[1:3]) or original(*a, **k))
    input_ranges_module._CHECKED.clear()
    speed = {"shaft_speed": lambda t: 50.0 * (1.0 + t)}
    for _ in range(3):
        check_input_ranges(torque_level, input_signal(torque_level, speed),
                           np.array([0.0, 0.5, 1.0]))
    assert calls == [(0.0, 1.0)]  # the other two runs: found valid before
    check_input_ranges(torque_level, input_signal(torque_level, speed), np.array([0.0, 2.0]))
    assert calls == [(0.0, 1.0), (0.0, 2.0)]  # another span: checked again


def test_runs_that_differ_in_numbers_share_one_input_function(torque_level):
    a = input_signal(torque_level, {"shaft_speed": 10.0, "Fr": ([0.0, 1.0], [0.0, 5.0])})
    b = input_signal(torque_level, {"shaft_speed": 30.0, "Fr": ([0.0, 2.0], [1.0, 7.0])})
    assert a.u is b.u and a.key == b.key
    np.testing.assert_allclose(b.at([0.0, 1.0, 3.0])[0], [1.0, 4.0, 7.0])  # Fr: held after
    assert b.at(0.5)[2, 0] == 30.0


def test_newton_steady_state_agrees_with_the_trust_region_solution(torque_level, monkeypatch):
    newton = steady_state(torque_level, inputs={"shaft_speed": 500.0})
    monkeypatch.setattr(steady_module, "_newton", lambda *args: None)  # hybr only
    hybr = steady_state(torque_level, inputs={"shaft_speed": 500.0})
    np.testing.assert_allclose(newton, hybr, rtol=1e-9, atol=1e-12)
    skip = steady_module.integrator_states(torque_level)  # the rotor angles
    rates = torque_level.rhs(0.0, newton, [0.0, 0.0, 500.0])
    assert skip and np.max(np.abs(np.delete(rates, skip))) < 1e-9
