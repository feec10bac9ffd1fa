"""The index reduction pass alone on a Cartesian pendulum (index 3):

    der(x) = vx,  der(y) = vy,  der(vx) = -F x,  der(vy) = -F y - g,  x^2 + y^2 = 1

Pantelides differentiates the constraint twice and the two position equations once; the dummy
derivative selection leaves two states.
"""

from __future__ import annotations

import math

import casadi as ca
import pytest

from bearingsim.assembler.passes import index_reduction
from bearingsim.errors import ModelError
from tests.assembler.hand_dae import dae, eq, evaluate, state_of, state_var, var

G = 9.81
ANGLE = 0.5


def _pendulum():
    x, dx = state_var("x", math.sin(ANGLE))
    y, dy = state_var("y", -math.cos(ANGLE), fixed=False)
    vx, dvx = state_var("vx", 0.0)
    vy, dvy = state_var("vy", 0.0, fixed=False)
    force = var("F", G)
    constraint = eq(x.sym**2 + y.sym**2 - 1.0, "x^2 + y^2 = 1")
    model = dae([x, dx, y, dy, vx, dvx, vy, dvy, force], [
        eq(dx.sym - vx.sym, "der(x) = vx"),
        eq(dy.sym - vy.sym, "der(y) = vy"),
        eq(dvx.sym + force.sym * x.sym, "der(vx) = -F x"),
        eq(dvy.sym + force.sym * y.sym + G, "der(vy) = -F y - g"),
        constraint,
    ])
    return model, constraint


def test_pantelides_differentiates_the_constraint_twice_and_the_position_equations_once():
    model, constraint = _pendulum()
    state = state_of(model)
    index_reduction.run(state)
    added = {e.text: e.order for e in model.eqs if e.order}
    assert added == {"d/dt(x^2 + y^2 = 1)": 1, "d/dt(d/dt(x^2 + y^2 = 1))": 2,
                     "d/dt(der(x) = vx)": 1, "d/dt(der(y) = vy)": 1}
    assert constraint.differentiated.differentiated.differentiated is None
    assert state.report["index reduction"].startswith("4 equation(s) differentiated")
    # the first derivative of the constraint is 2 x der(x) + 2 y der(y)
    velocity = constraint.differentiated.residual
    by_name = {v.name: v for v in model.vars}
    value = evaluate(velocity, {by_name["x"]: 0.6, by_name["y"]: -0.8,
                                by_name["der(x)"]: 2.0, by_name["der(y)"]: 1.5})
    assert value == pytest.approx(2 * 0.6 * 2.0 + 2 * -0.8 * 1.5)


def test_dummy_derivatives_leave_the_two_true_states():
    model, _ = _pendulum()
    index_reduction.run(state_of(model))
    # at 0.5 rad the vertical position is the better pivot: y and vy become dummies
    assert [v.name for v in model.states] == ["x", "vx"]
    assert sorted(v.name for v in model.vars if v.dummy) == [
        "der(der(x))", "der(der(y))", "der(vy)", "der(y)"]
    model.check_balance("index reduction")


def test_an_index_one_dae_is_left_alone():
    x, dx = state_var("x", 1.0)
    y = var("y")
    model = dae([x, dx, y], [eq(dx.sym + y.sym, "der(x) = -y"), eq(y.sym - ca.sin(x.sym), "y")])
    state = state_of(model)
    index_reduction.run(state)
    assert len(model.eqs) == 2 and "index reduction" not in state.report


def test_differentiating_an_input_is_refused():
    u = var("u", is_input=True)
    x, dx = state_var("x", 0.0)
    model = dae([u, x, dx], [eq(dx.sym - 1.0, "der(x) = 1"), eq(x.sym - u.sym, "x = u")])
    with pytest.raises(ModelError, match="time derivative of input u"):
        index_reduction.run(state_of(model))
