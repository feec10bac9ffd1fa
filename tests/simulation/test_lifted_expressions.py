"""Scene expressions that differ only in their numbers share one input structure: their
numbers are lifted into the run's values ``q`` (``bearingsim.scenes.expressions``,
``LiftedExpression``), so a sweep over ``rpm(N) * ramp(0, T)`` builds and compiles its input
function, integrators and C once, not once per expression."""

from __future__ import annotations

import math

import casadi as ca
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.scenes.expressions import ExpressionError, compile_expression
from bearingsim.simulation import simulate
from bearingsim.simulation.c_compiler import c_compiler, compilations
from bearingsim.simulation.inputs import input_signal


@pytest.fixture(scope="module")
def torque_level():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"))


def _value(expr, t: float) -> float:
    ts = ca.SX.sym("t")
    return float(ca.Function("f", [ts], [ca.SX(expr(ts))])(t))


TEMPLATES = [
    "rpm({a}) * ramp({b}, {b} + {c})",
    "{a} + {b} * sin({c} * t)",
    "{a} if t < {b} else {c} * t",
    "max({a}, min(t * {b}, {c}))",
    "({a} * t)**2 + exp(-{b} * t) * {c}",
    "{a} * step({b}) - {c} / (1 + t)",
]
NUMBER = st.one_of(st.just(0.0), st.floats(0.01, 1e4).map(lambda x: float(f"{x:.6g}")))


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(TEMPLATES), NUMBER, NUMBER, NUMBER, st.floats(0.0, 3.0))
def test_the_lifted_form_is_the_expression(template, a, b, c, t):
    """The expression built from its template and numbers equals the expression compiled
    with its numbers in place, at any time; equal templates whatever the numbers."""
    try:
        f = compile_expression(template.format(a=a, b=b, c=c))
    except ExpressionError:  # ramp(b, b + 0)
        assume(False)
    form = f.lifted
    if 0.0 not in (a, b, c):  # (a zero stays in the structure)
        assert form.template == compile_expression(template.format(a=1, b=2, c=3)).lifted.template
    lifted = _value(lambda ts: form.build(ts, [ca.DM(x) for x in form.numbers]), t)
    assert lifted == pytest.approx(_value(f, t), rel=1e-14, abs=1e-300)


def test_exponents_stay_in_the_structure():
    """``t**2`` keeps its exponent (a power of a lifted symbol would differentiate to
    log(t) terms, undefined at t <= 0); the factor is lifted."""
    assert compile_expression("3 * t**2").lifted.numbers == (3.0,)
    assert compile_expression("3 * t**2").lifted.template != \
        compile_expression("3 * t**3").lifted.template


def test_expressions_with_other_numbers_share_the_signal(torque_level):
    one = input_signal(torque_level, {"shaft_speed": compile_expression(
        "rpm(1000) * ramp(0.002, 0.02)")})
    two = input_signal(torque_level, {"shaft_speed": compile_expression(
        "rpm(2500)*ramp(0.001, 0.05)")})
    assert one.key == two.key and one.u is two.u
    speed = torque_level.input_names.index("shaft_speed")
    for sig, n, t0, t1 in ((one, 1000, 0.002, 0.02), (two, 2500, 0.001, 0.05)):
        times = np.array([0.0, 0.01, 0.03, 0.1])
        expected = n * 2 * math.pi / 60 * np.clip((times - t0) / (t1 - t0), 0.0, 1.0)
        np.testing.assert_allclose(sig.at(times)[speed], expected, rtol=1e-15)


@pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")
@pytest.mark.parametrize("method", ["compiled_bdf", "cvodes"])
def test_a_second_expression_compiles_nothing_and_runs_as_its_own_function(
        torque_level, kernel_cache, method):
    """The second expression of the same template runs without a compiler run and gives what
    the same function given as a Python function of time (numbers in its structure) gives."""
    kw = {"method": method, "rtol": 1e-8, "atol": 1e-10, "n_points": 11}
    simulate(torque_level, 0.05, inputs={"shaft_speed": compile_expression(
        "rpm(1000) * ramp(0, 0.02)")}, **kw)
    before = compilations()
    lifted = simulate(torque_level, 0.05, inputs={"shaft_speed": compile_expression(
        "rpm(3000) * ramp(0, 0.03)")}, **kw)
    assert compilations() == before
    inline = simulate(torque_level, 0.05, inputs={
        "shaft_speed": lambda t: 3000 * (2 * math.pi / 60) * ca.fmin(ca.fmax(t / 0.03, 0), 1)},
        **kw)
    for name in ("Rs", "w_middle"):
        np.testing.assert_allclose(lifted[name], inline[name], rtol=1e-12, atol=1e-12,
                                   err_msg=name)
    assert lifted.inputs["shaft_speed"] == pytest.approx(3000 * 2 * math.pi / 60)


def test_several_expressions_and_constants_take_their_own_numbers(torque_level):
    """Each input's lifted numbers sit at its own place in q, between other inputs' numbers;
    an expression with more numbers than the lifted symbols keeps them in its structure."""
    many = "t * max(" + ", ".join(str(k) for k in range(1, 71)) + ")"  # 70 numbers: 70 t
    inputs = {"Fr": compile_expression("100 + 50 * t"), "Fa": 20.0,
              "shaft_speed": compile_expression("rpm(600) * ramp(0.5, 1.5)")}
    sig = input_signal(torque_level, inputs)
    other = input_signal(torque_level, {**inputs, "Fr": compile_expression("300 + 10 * t")})
    assert other.u is sig.u
    at = {n: k for k, n in enumerate(torque_level.input_names)}
    times = np.array([0.0, 1.0, 2.0])
    np.testing.assert_allclose(sig.at(times)[at["Fr"]], 100 + 50 * times, rtol=1e-15)
    np.testing.assert_allclose(other.at(times)[at["Fr"]], 300 + 10 * times, rtol=1e-15)
    np.testing.assert_allclose(sig.at(times)[at["Fa"]], 20.0)
    np.testing.assert_allclose(sig.at(times)[at["shaft_speed"]], [0.0, 10 * math.pi,
                                                                  20 * math.pi], rtol=1e-15)
    long = input_signal(torque_level, {**inputs, "Fr": compile_expression(many)})
    assert long.u is not sig.u
    np.testing.assert_allclose(long.at(times)[at["Fr"]], 70 * times, rtol=1e-15)


def test_a_zero_stays_in_the_structure(torque_level):
    """CasADi simplifies ``0 * x`` to 0 when it builds the expression; a lifted zero would be
    multiplied at run time, 0 * -inf = NaN for ``0 * log(t)`` at t = 0."""
    form = compile_expression("100 + 0 * log(t)").lifted
    assert form.numbers == (100.0,) and "0 * log(t)" in form.template
    sig = input_signal(torque_level, {"shaft_speed": compile_expression("100 + 0 * log(t)")})
    speed = torque_level.input_names.index("shaft_speed")
    assert sig.at(np.array([0.0, 1.0]))[speed].tolist() == [100.0, 100.0]
