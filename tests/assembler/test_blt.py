"""The BLT sorting pass alone: explicit equations and a loop in block lower triangular order.

    der(x) = -d,   d = b c,   b + c = a,   b - c = 1,   a = x

sorts into [a], [b, c] (one loop), [d], [der(x)].
"""

from __future__ import annotations

from bearingsim.assembler.passes import blt
from tests.assembler.hand_dae import dae, eq, state_of, state_var, var


def test_blocks_follow_the_dependencies_and_the_loop_is_one_block():
    x, dx = state_var("x", 1.0)
    a, b, c, d = var("a"), var("b"), var("c"), var("d")
    e_der = eq(dx.sym + d.sym, "der(x) = -d")
    e_d = eq(d.sym - b.sym * c.sym, "d = b c")
    e_sum = eq(b.sym + c.sym - a.sym, "b + c = a")
    e_diff = eq(b.sym - c.sym - 1.0, "b - c = 1")
    e_a = eq(a.sym - x.sym, "a = x")
    model = dae([x, dx, a, b, c, d], [e_der, e_d, e_sum, e_diff, e_a])
    matched = {e_der: dx, e_d: d, e_sum: b, e_diff: c, e_a: a}
    state = state_of(model, matching=matched)
    blt.run(state)
    assert state.blocks == [[(e_a, a)], [(e_sum, b), (e_diff, c)], [(e_d, d)], [(e_der, dx)]]
