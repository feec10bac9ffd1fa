"""The index reduction pass alone on a Cartesian pendulum (index 3):

    der(x) = vx,  der(y) = vy,  der(vx) = -F x,  der(vy) = -F y - g,  x^2 + y^2 = 1

Pantelides differentiates the constraint twice and the two position equations once; the dummy
derivative selection leaves two states.
"""

from __future__ import annotations

import math
import sys

import casadi as ca
import numpy as np
import pytest
import scipy.linalg
import scipy.sparse

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


def test_an_augmenting_path_longer_than_the_recursion_limit_is_found(monkeypatch):
    """Issue 29: Pantelides' search is iterative. A chain v0 - e1 - v1 - ... - e_N where only
    e0 has a free variable: the augmenting path from e_N runs through all N equations, five
    times deeper than Python's default recursion limit (the recursive search raised
    RecursionError here; the pass used to raise the limit with sys.setrecursionlimit)."""
    from bearingsim.assembler.passes.index_reduction import _augment

    monkeypatch.setattr(sys, "setrecursionlimit", None)  # any call fails
    n = 5 * sys.getrecursionlimit()
    eqs = [f"e{k}" for k in range(n + 1)]
    incidence = {"e0": ["free", "v0"], **{f"e{k}": [f"v{k - 1}", f"v{k}"] for k in range(1, n)},
                 f"e{n}": [f"v{n - 1}"]}
    assign = {f"v{k}": f"e{k}" for k in range(n)}
    colored_e, colored_v = set(), set()
    assert _augment(eqs[-1], incidence.__getitem__, lambda v: True, assign, colored_e,
                    colored_v)
    # flipped along the path: each v_k now matched to e_{k+1}, the free variable to e0
    assert assign == {"free": "e0", **{f"v{k}": f"e{k + 1}" for k in range(n)}}
    assert colored_e == set(eqs) and colored_v == {f"v{k}" for k in range(n)}


def test_a_failed_search_colours_what_it_visited():
    """No free variable at the end of any path: False, every reachable node coloured, the
    assignment unchanged (the colours are the equations to differentiate)."""
    from bearingsim.assembler.passes.index_reduction import _augment

    incidence = {"a": ["x", "y"], "b": ["x"], "c": ["y", "x"]}
    assign = {"x": "b", "y": "c"}
    colored_e, colored_v = set(), set()
    assert not _augment("a", incidence.__getitem__, lambda v: True, assign, colored_e,
                        colored_v)
    assert assign == {"x": "b", "y": "c"}
    assert colored_e == {"a", "b", "c"} and colored_v == {"x", "y"}


def _pendulum_named(prefix: str, angle: float):
    x, dx = state_var(f"{prefix}x", math.sin(angle))
    y, dy = state_var(f"{prefix}y", -math.cos(angle), fixed=False)
    vx, dvx = state_var(f"{prefix}vx", 0.0)
    vy, dvy = state_var(f"{prefix}vy", 0.0, fixed=False)
    force = var(f"{prefix}F", G)
    return [x, dx, y, dy, vx, dvx, vy, dvy, force], [
        eq(dx.sym - vx.sym, f"der({prefix}x) = {prefix}vx"),
        eq(dy.sym - vy.sym, f"der({prefix}y) = {prefix}vy"),
        eq(dvx.sym + force.sym * x.sym, f"der({prefix}vx) = -F x"),
        eq(dvy.sym + force.sym * y.sym + G, f"der({prefix}vy) = -F y - g"),
        eq(x.sym**2 + y.sym**2 - 1.0, f"{prefix}x^2 + {prefix}y^2 = 1"),
    ]


def _dummies(model) -> set[str]:
    return {v.name for v in model.vars if v.dummy}


def test_independent_constraints_are_selected_block_by_block(monkeypatch):
    """Two pendulums in one model (one at 0.5 rad, one at 1.2 rad, where x is the better
    pivot): the dummy derivatives are chosen on each pendulum's own block of the Jacobian,
    never on a dense matrix of both (the memory of the selection is that of the largest
    block), and each pendulum gets the dummies it gets alone."""
    shapes = []
    select = index_reduction._select_columns

    def recording(h, m):
        shapes.append(h.shape)
        return select(h, m)

    alone = []
    for prefix, angle in (("a.", 0.5), ("b.", 1.2)):
        model = dae(*_pendulum_named(prefix, angle))
        index_reduction.run(state_of(model))
        alone.append(_dummies(model))
    monkeypatch.setattr(index_reduction, "_select_columns", recording)
    (va, ea), (vb, eb) = _pendulum_named("a.", 0.5), _pendulum_named("b.", 1.2)
    both = dae(va + vb, ea + eb)
    index_reduction.run(state_of(both))
    assert _dummies(both) == alone[0] | alone[1]
    assert alone[0] == {"der(a.y)", "der(a.vy)", "der(der(a.x))", "der(der(a.y))"}
    assert alone[1] == {"der(b.x)", "der(b.vx)", "der(der(b.x))", "der(der(b.y))"}
    assert shapes and max(rows for rows, _ in shapes) == 3  # one pendulum's level: 3 rows
    both.check_balance("index reduction")


def test_block_by_block_selection_agrees_with_pivoted_qr_of_the_whole_matrix():
    """A Jacobian of three independent blocks, rows and columns shuffled: the columns chosen
    block by block are those pivoted QR chooses on the whole dense matrix."""
    rng = np.random.default_rng(3)
    blocks = [rng.standard_normal((2, 3)), rng.standard_normal((3, 5)),
              rng.standard_normal((1, 2))]
    whole = scipy.linalg.block_diag(*blocks)
    rows, cols = rng.permutation(whole.shape[0]), rng.permutation(whole.shape[1])
    whole = whole[rows][:, cols]
    p = ca.SX.sym("p")
    jac_f = ca.Function("h", [p], [ca.SX(ca.DM(scipy.sparse.csc_matrix(whole)))])
    chosen = index_reduction._select_sparse(jac_f, np.zeros(1), np.random.default_rng(0))
    assert chosen == sorted(index_reduction._select_columns(whole, whole.shape[0]))
    assert len(index_reduction._blocks(jac_f.sparsity_out(0))) == 3
