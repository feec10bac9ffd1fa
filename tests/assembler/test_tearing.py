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


def _row(offsets: list[float], coupled: bool = False):
    """Members ``ball[k]`` (state x, parameter a, a nonlinear loop in b, c and d = b c + offset)
    around a shared ring whose derivative sums the members' d; the BLT blocks in order. With
    ``coupled``, every d also reads the shared sum s of all b."""
    from tests.assembler.hand_dae import param

    ring, dring = state_var("ring.y", 0.0)
    total = var("ring.s")
    variables, equations, params, blocks, ds = [ring, dring], [], [], [], []
    loops, rest, bs = [], [], []
    for k, offset in enumerate(offsets):
        x, dx = state_var(f"ball[{k}].x", 1.0 + k)
        a = param(f"ball[{k}].a", 2.0)
        b, c, d = var(f"ball[{k}].b", 0.5), var(f"ball[{k}].c", 0.7), var(f"ball[{k}].d")
        e_cube = eq(b.sym + c.sym**3 - a.sym * x.sym - ring.sym, "b + c^3 = a x + y")
        e_equal = eq(b.sym - c.sym, "b = c")
        e_d = eq(d.sym - b.sym * c.sym - offset - (total.sym if coupled else 0.0),
                 "d = b c + offset (+ s)")
        e_der = eq(dx.sym + d.sym * x.sym, "der(x) = -d x")
        variables += [x, dx, b, c, d]
        params.append(a)
        equations += [e_cube, e_equal, e_d, e_der]
        loops.append([(e_cube, b), (e_equal, c)])
        rest += [[(e_d, d)], [(e_der, dx)]]
        ds.append(d.sym)
        bs.append(b.sym)
    e_ring = eq(dring.sym + sum(ds), "der(y) = -sum d")
    if not coupled:
        blocks = [block for k in range(len(offsets))
                  for block in (loops[k], rest[2 * k], rest[2 * k + 1])]
        return dae(variables, [*equations, e_ring], params), [*blocks, [(e_ring, dring)]]
    e_total = eq(total.sym - sum(bs), "s = sum b")
    blocks = [*loops, [(e_total, total)], *rest, [(e_ring, dring)]]
    return dae([*variables, total], [*equations, e_total, e_ring], params), blocks


def _values(causal, model, seed: int = 1) -> list:
    """Every solution and nonlinear residual at a random point of time, states, inputs,
    parameters and tearing variables (nonlinear blocks by their first tearing variable's
    name)."""
    import numpy as np

    tears = sorted((t for blk in causal.nonlinear for t in blk.tears), key=lambda t: t.name)
    base = ([model.time] + [v.sym for v in model.vars if v.is_state or v.is_input]
            + [q.sym for q in model.params])
    syms = ca.vertcat(*base, *[t.sym for t in tears])
    blocks = sorted(causal.nonlinear, key=lambda blk: blk.tears[0].name)
    unknowns = [v for v in model.vars if v in causal.expr]
    f = ca.Function("f", [syms], [ca.vertcat(*[causal.expr[v] for v in unknowns]),
                                  ca.vertcat(*[blk.residuals for blk in blocks])])
    point = np.random.default_rng(seed).uniform(0.5, 1.5, syms.numel())
    return [np.asarray(out).ravel() for out in f(point)]


def test_repeating_members_are_copied_from_member_0_and_give_the_same_solutions():
    """Members 1 and 3 repeat member 0 and get its solutions with their own symbols; member 2
    has its own constant and is solved on its own; everything equals solving every block."""
    import numpy as np

    from bearingsim.assembler.passes.ball_sets import find_ball_sets

    model, blocks = _row([0.0, 0.0, 0.25, 0.0])
    sets = find_ball_sets(model)
    assert [(s.name, s.count) for s in sets] == [("", 4)]
    assert set(tearing._Mirrors(model, blocks, sets).sigma) == {(0, 1), (0, 3)}
    copied = tearing.causalize(model, blocks, sets)
    solved = tearing.causalize(model, blocks)
    assert len(copied.nonlinear) == len(solved.nonlinear) == 4
    assert copied.copied == {("", 4, 1), ("", 4, 3)}
    assert (copied.n_blocks, copied.largest_block) == (solved.n_blocks, solved.largest_block)
    for got, want in zip(_values(copied, model), _values(solved, model), strict=True):
        np.testing.assert_array_equal(got, want)
    # a copied nonlinear block is the member's own: its tearing variable, start value, equations
    member_1 = next(blk for blk in copied.nonlinear if blk.tears[0].name.startswith("ball[1]"))
    assert member_1.guess == [0.5 if member_1.tears[0].name.endswith(".b") else 0.7]
    assert all(e in model.eqs[4:8] for e in member_1.equations)


def test_a_member_read_before_member_0_is_complete_is_copied_once_then_solved():
    """Each d reads the sum of every ball's b: the sum needs balls 1..3's b before ball 0's d
    is solved, so their loops are copied then and their d solved afterwards (a second copy
    would duplicate the first one's subexpressions). Same solutions as solving every block."""
    import numpy as np

    from bearingsim.assembler.passes.ball_sets import find_ball_sets

    model, blocks = _row([0.0, 0.0, 0.0, 0.0], coupled=True)
    copied = tearing.causalize(model, blocks, find_ball_sets(model))
    solved = tearing.causalize(model, blocks)
    assert copied.copied_members == 3 and len(copied.nonlinear) == 4
    assert copied.copied == set()  # their d blocks were solved, not copied
    for got, want in zip(_values(copied, model), _values(solved, model), strict=True):
        np.testing.assert_array_equal(got, want)


@pytest.mark.parametrize("fidelity", ["dynamic_massive_balls", "dynamic"])
def test_the_balls_of_a_bearing_are_copied_bit_for_bit(fidelity):
    """The 6304 ball levels: tearing copies balls 1..6 from ball 0 (massive balls: explicit
    blocks; quasi-static balls: a Newton block per ball) and gets exactly what solving every
    ball's blocks gets."""
    from types import SimpleNamespace

    import numpy as np

    from bearingsim.assembler import assemble
    from bearingsim.assembler.passes.ball_sets import find_ball_sets
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing

    seen = {}

    def compare(state):
        sets = find_ball_sets(state.dae)
        seen["copied"] = len(tearing._Mirrors(state.dae, state.blocks, sets).sigma)
        seen["whole"] = sorted(k for *_, k in state.causal.copied)
        solved = tearing.causalize(state.dae, state.blocks)
        for got, want in zip(_values(state.causal, state.dae), _values(solved, state.dae),
                             strict=True):
            np.testing.assert_array_equal(got, want)
        seen["nonlinear"] = len(solved.nonlinear), len(state.causal.nonlinear)

    check = SimpleNamespace(NAME="compare with every block solved", run=compare)
    assemble(deep_groove_ball_bearing("6304", fidelity, speed=100.0, loads={"Fx": 500.0}),
             extra_passes={tearing.NAME: check})
    assert seen["copied"] == 6
    assert seen["whole"] == [1, 2, 3, 4, 5, 6]  # every block of each, so mapping skips them
    assert seen["nonlinear"] == ((0, 0) if fidelity == "dynamic_massive_balls" else (7, 7))


def test_a_member_block_reached_before_member_0_is_solved_and_not_copied_again():
    """Ball 1's loop comes before ball 0's in the block order: it is solved when reached, and
    copying ball 1's later blocks from ball 0 leaves it alone (one Newton block per ball)."""
    import numpy as np

    from bearingsim.assembler.passes.ball_sets import find_ball_sets

    model, blocks = _row([0.0, 0.0])
    blocks = [blocks[3], *blocks[:3], *blocks[4:]]  # ball 1's loop first
    copied = tearing.causalize(model, blocks, find_ball_sets(model))
    solved = tearing.causalize(model, blocks)
    assert copied.copied_members == 1 and len(copied.nonlinear) == 2
    assert copied.copied == set()
    for got, want in zip(_values(copied, model), _values(solved, model), strict=True):
        np.testing.assert_array_equal(got, want)
