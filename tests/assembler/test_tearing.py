"""The tearing and block solving pass alone: a linear loop is solved symbolically, a nonlinear
one is left as a Newton block in its tearing variable."""

from __future__ import annotations

import casadi as ca
import pytest

from bearingsim.assembler.passes import tearing
from tests.assembler.hand_dae import dae, eq, evaluate, state_of, state_var, var


def test_a_linear_loop_is_solved_symbolically():
    """b + c = x, b - c = 1, d = b c: b = (x + 1) / 2, c = (x - 1) / 2."""
    x, dx = state_var("x", 3.0)
    b, c, d = var("b"), var("c"), var("d")
    e_sum, e_diff = eq(b.sym + c.sym - x.sym, "b + c = x"), eq(b.sym - c.sym - 1.0, "b - c = 1")
    e_d, e_der = eq(d.sym - b.sym * c.sym, "d = b c"), eq(dx.sym + d.sym, "der(x) = -d")
    blocks = [[(e_sum, b), (e_diff, c)], [(e_d, d)], [(e_der, dx)]]
    state = state_of(dae([x, dx, b, c, d], [e_sum, e_diff, e_d, e_der]), blocks=blocks)
    tearing.run(state)
    causal = state.causal
    assert causal.nonlinear == [] and causal.n_linear_loops == 1
    assert (causal.n_blocks, causal.largest_block) == (3, 2)
    for v in (b, c, d, dx):  # every unknown is a function of the state alone
        assert ca.symvar(causal.expr[v])[0].name() == "x" and len(ca.symvar(causal.expr[v])) == 1
    assert evaluate(causal.expr[b], {x: 5.0}) == pytest.approx(3.0)
    assert evaluate(causal.expr[c], {x: 5.0}) == pytest.approx(2.0)
    assert evaluate(causal.expr[dx], {x: 5.0}) == pytest.approx(-6.0)
    assert state.report["blocks"] == ("3 (largest 2; 1 linear loop(s) solved symbolically; "
                                      "0 nonlinear loop(s) by Newton)")


def test_a_nonlinear_loop_becomes_a_newton_block_in_one_tearing_variable():
    """b + c^3 = x, b - c = 0: c is torn, b = c follows, the residual is c + c^3 - x."""
    x, dx = state_var("x", 2.0)
    b, c = var("b", 0.5), var("c", 0.7)
    e_cube, e_equal = eq(b.sym + c.sym**3 - x.sym, "b + c^3 = x"), eq(b.sym - c.sym, "b = c")
    e_der = eq(dx.sym + b.sym, "der(x) = -b")
    blocks = [[(e_cube, b), (e_equal, c)], [(e_der, dx)]]
    state = state_of(dae([x, dx, b, c], [e_cube, e_equal, e_der]), blocks=blocks)
    tearing.run(state)
    causal = state.causal
    assert causal.n_linear_loops == 0 and len(causal.nonlinear) == 1
    block = causal.nonlinear[0]
    assert len(block.tears) == 1 and block.equations == [e_cube, e_equal]
    tear = block.tears[0]
    other = b if tear is c else c
    assert block.guess == [tear.start]
    assert ca.is_equal(causal.expr[tear], tear.sym)
    # at the root c = b = 1 of 1 + 1 = x = 2 the residual vanishes, elsewhere not
    assert evaluate(block.residuals, {tear: 1.0, x: 2.0}) == pytest.approx(0.0)
    assert evaluate(block.residuals, {tear: 0.5, x: 2.0}) != pytest.approx(0.0)
    assert evaluate(causal.expr[other], {tear: 1.0}) == pytest.approx(1.0)
    assert evaluate(causal.expr[dx], {tear: 1.0}) == pytest.approx(-1.0)
