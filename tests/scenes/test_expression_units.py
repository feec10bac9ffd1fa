"""The unit an input expression fixes with rpm() or deg(), and scenes that give it to an input
of another quantity.

Before, ``"rpm(100)"`` given to a force was read as 10.47 N: the expression language has SI
numbers only, and nothing compared the speed rpm() makes with the input's unit.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.scenes import parse_scene
from bearingsim.scenes.expression_units import expression_unit
from bearingsim.scenes.expressions import ExpressionError, constant_value
from bearingsim.scenes.preparation import prepare
from bearingsim.scenes.scene import SceneError


@pytest.mark.parametrize(("text", "unit"), [
    ("rpm(100)", "rad/s"),
    ("rpm(6000) * ramp(0, 0.5)", "rad/s"),
    ("-rpm(3000) * sin(2 * pi * t) if t > 1 else rpm(10)", "rad/s"),
    ("max(rpm(100), 0)", "rad/s"),
    ("deg(3)", "rad"),
    ("rpm(100) / t", None),          # the 1/s of t is not fixed: t is a bare time here
    ("rpm(100) / step(0)", "rad/s"),
    ("rpm(100) ** 2", "rad2/s2"),
    ("sqrt(rpm(100) ** 2)", "rad/s"),
    ("rpm(100) * deg(1)", "rad2/s"),
    ("10 * rpm(100)", None),         # the 10 may carry any unit
    ("rpm(1000) * t", None),         # 1000 r/min per second, times t: a speed ramp
    ("2000 * (rpm(3000) / rpm(1000)) ** 2", None),
    ("rpm(3000) / rpm(1000)", None),  # a pure number
    ("200 + 800 * step(1.5)", None),
    ("sin(t)", None),
])
def test_the_unit_rpm_and_deg_fix(text, unit):
    assert expression_unit(text) == unit


@pytest.mark.parametrize("text", ["rpm(100) + deg(3)", "rpm(1) if t > 1 else deg(1)",
                                  "min(rpm(1), deg(1), 2)"])
def test_mixed_units_are_refused(text):
    with pytest.raises(ExpressionError, match=r"inputs\.x: cannot use the expression .* mixes "
                                              r"values in rad/s and rad"):
        expression_unit(text, "inputs.x")


_NUMBERS = st.floats(-1e3, 1e3, allow_nan=False).map(lambda x: f"{x:g}")
_PLAIN = st.recursive(
    st.one_of(_NUMBERS, st.just("t"), st.just("pi")),
    lambda inner: st.one_of(
        st.tuples(inner, st.sampled_from(["+", "-", "*", "/"]), inner).map(
            lambda p: f"({p[0]} {p[1]} {p[2]})"),
        inner.map(lambda e: f"sin({e})"),
        inner.map(lambda e: f"step({e})"),
        st.tuples(inner, inner).map(lambda p: f"max({p[0]}, {p[1]})"),
    ),
    max_leaves=8)


@settings(max_examples=150, deadline=None)
@given(_PLAIN)
def test_an_expression_without_rpm_or_deg_fixes_no_unit(text):
    """Bare numbers and t are SI values of any quantity: such an expression is never refused
    for its unit."""
    try:
        unit = expression_unit(text)
    except ExpressionError as exc:  # not a valid expression (1/0 ...): not about units
        assert "mixes values" not in str(exc)
        return
    assert unit is None


@settings(max_examples=100, deadline=None)
@given(_PLAIN, st.floats(1.0, 1e4))
def test_a_speed_times_a_pure_number_stays_a_speed(text, n):
    """rpm(n) times a function of the time without a unit (a step, a sine) is a speed; times
    a bare number or t, open."""
    try:
        factor = expression_unit(f"step({text})")
    except ExpressionError:
        return
    assert factor is None
    assert expression_unit(f"rpm({n:g}) * step({text})") == "rad/s"
    assert expression_unit(f"rpm({n:g}) * ({text})") in (None, "rad/s")


def _statics(value: str) -> str:
    return f"""
title = "t"
analysis = "statics"
[assembly]
name = "cylindrical_roller_bearing"
bearing = "NU206"
fidelity = "quasi-static"
[inputs]
"load.Fx" = {value}
"""


def test_a_speed_given_to_a_load_is_refused_at_its_key():
    """The issue found: ``"load.Fx" = "rpm(100)"`` ran a statics point at Fx = 10.47 N."""
    with pytest.raises(SceneError, match=r"inputs\.load\.Fx: input load\.Fx is in N, but its "
                                         r"value is given in rad/s") as info:
        prepare(parse_scene(_statics('"rpm(100)"')))
    assert info.value.line == 9
    with pytest.raises(SceneError, match=r"inputs\.load\.Fx: .* mixes values in rad/s and rad"):
        parse_scene(_statics('"rpm(100) + deg(1)"'))
    # a bare factor may carry any unit: accepted, and its value is the SI number
    scene = parse_scene(_statics('"10 * rpm(100)"'))
    assert scene.inputs["load.Fx"] == pytest.approx(constant_value("10 * rpm(100)"), rel=1e-15)
    prepare(scene)


def test_a_transient_names_each_input_whose_expression_has_another_unit():
    scene = parse_scene("""
title = "t"
[simulation]
t_end = 1.0
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = "rpm(6000) * ramp(0, 0.5)"
Fr = "rpm(6000) * step(1)"
Fa = "deg(3) * sin(rpm(100) * t)"
""")
    assert scene.input_units == {"shaft_speed": "rad/s", "Fr": "rad/s", "Fa": "rad"}
    with pytest.raises(SceneError) as info:
        prepare(scene)
    shown = str(info.value)
    assert "2 problems" in shown and "shaft_speed" not in shown
    assert ("inputs.Fr: input Fr is in N, but its value is given in rad/s (the expression "
            "'rpm(6000) * step(1)': rpm() converts r/min to rad/s") in shown
    assert "inputs.Fa: input Fa is in N, but its value is given in rad" in shown
