"""The sparse LU of the compiled integrators (c/bsm_lu.c through
bearingsim.simulation.sparse_lu): solutions against numpy's dense LU on Newton matrices with a
bearing's Jacobian pattern in any order, no fill-in in the fill-reducing order, refactorisation
on the kept pattern identical to a fresh one (the FMU's mode) or kept while its pivots are
acceptable (the BDF integrator's), the pivot order changing when it must (and back, or not),
singular matrices reported, and the Newton matrix's ordered pattern."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import sparse

from bearingsim.assembler import assemble
from bearingsim.simulation import simulate
from bearingsim.simulation.c_compiler import c_compiler
from bearingsim.simulation.ordering import newton_pattern
from bearingsim.simulation.sparse_lu import SparseLu
from tests.models import SpringMassChain

pytestmark = pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")


def _bearing_jacobian(members: int, per_member: int, shared: int, seed: int) -> sparse.csc_matrix:
    """The pattern of a bearing's Jacobian (each ball's block coupled to the ring and cage
    states every ball couples to), shuffled, with random values; every other state's diagonal
    is zero (as an angle's, whose derivative is a speed): in I - c J that diagonal stays 1
    while its column grows with c, so large steps need other pivots."""
    n = shared + members * per_member
    mask = np.zeros((n, n), dtype=bool)
    mask[:shared, :shared] = True
    for k in range(members):
        block = slice(shared + k * per_member, shared + (k + 1) * per_member)
        mask[block, block] = mask[block, :shared] = mask[:shared, block] = True
    mask[np.arange(0, n, 2), np.arange(0, n, 2)] = False
    rng = np.random.default_rng(seed)
    shuffle = rng.permutation(n)
    mask = mask[shuffle][:, shuffle]
    return sparse.csc_matrix(np.where(mask, rng.standard_normal((n, n)), 0.0))


def _pattern(a: sparse.csc_matrix) -> ca.Sparsity:
    coo = a.tocoo()
    return ca.Sparsity.triplet(a.shape[0], a.shape[1], coo.row.tolist(), coo.col.tolist())


def _newton(jac: sparse.csc_matrix, c: float):
    """The ordered pattern, the nonzeros of the ordered I - c J, and that matrix dense."""
    pattern = newton_pattern(_pattern(jac))
    values = pattern.values(jac.data, c)
    dense = sparse.csc_matrix((values, pattern.index, pattern.start),
                              shape=jac.shape).toarray()
    return pattern, values, dense


def _growth(dense: np.ndarray, rows: np.ndarray) -> float:
    """Growth factor of Gaussian elimination of ``dense`` with its rows in the order ``rows``:
    the largest entry met over the matrix's largest. It bounds the backward error of the LU
    (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM 2002, chapter 9:
    the computed solution solves (A + dA) x = b with ||dA|| of order n rho eps ||A||); with
    threshold pivoting (pivots >= 1e-3 of their column's largest) rho may exceed partial
    pivoting's."""
    a = dense[rows].copy()
    largest = grown = np.abs(a).max()
    for k in range(a.shape[0] - 1):
        a[k + 1:] -= np.outer(a[k + 1:, k] / a[k, k], a[k])
        grown = max(grown, np.abs(a[k + 1:]).max())
    return grown / largest


def _assert_solves(lu: SparseLu, dense: np.ndarray, seed: int) -> np.ndarray:
    """The solution agrees with numpy's within the condition number times the LU's backward
    error bound (growth of the factorisation in its own pivot order included)."""
    b = np.random.default_rng(seed).standard_normal(dense.shape[0])
    x = lu.solve(b)
    expected = np.linalg.solve(dense, b)
    scale = (np.linalg.cond(dense) * np.finfo(float).eps * np.abs(expected).max()
             * max(1.0, _growth(dense, lu.row_of)))
    np.testing.assert_allclose(x, expected, rtol=0, atol=1e3 * scale)
    return x


bearing_shapes = st.tuples(st.integers(1, 12), st.integers(1, 8), st.integers(1, 10),
                           st.integers(0, 2**32 - 1))


@settings(max_examples=40, deadline=None)
@given(bearing_shapes, st.floats(-6.0, 4.0))
def test_solves_newton_matrices_of_a_bearing_pattern_as_numpy_does(shape, log_c):
    jac = _bearing_jacobian(*shape)
    pattern, values, dense = _newton(jac, 10.0 ** log_c)
    lu = SparseLu(pattern.start, pattern.index)
    assert lu.factor(values) == 0
    _assert_solves(lu, dense, shape[3])


@settings(max_examples=25, deadline=None)
@given(bearing_shapes)
def test_fill_reducing_order_and_diagonal_pivots_give_factors_without_fill_in(shape):
    """Diagonally dominant (a small step): the diagonal pivots are kept, and in the
    minimum-degree order L + U hold exactly the matrix's off-diagonal nonzeros."""
    jac = _bearing_jacobian(*shape)
    n = jac.shape[0]
    pattern, values, _ = _newton(jac, 1e-3 / max(np.abs(jac.data).max(), 1.0) / n)
    lu = SparseLu(pattern.start, pattern.index)
    assert lu.factor(values) == 0
    np.testing.assert_array_equal(lu.row_of, np.arange(n))
    assert sum(lu.nnz) == pattern.index.size - n


def _pivots_acceptable(dense: np.ndarray, rows: np.ndarray, tol: float = 1e-3) -> bool:
    """Whether Gaussian elimination of ``dense`` with its rows in the order ``rows`` (dense,
    numpy) meets pivots of at least ``tol`` times their column's largest candidate."""
    a = dense[rows].copy()
    for k in range(a.shape[0]):
        column = np.abs(a[k:, k])
        if not column[0] >= tol * column.max():
            return False
        a[k + 1:] -= np.outer(a[k + 1:, k] / a[k, k], a[k])
    return True


@settings(max_examples=30, deadline=None)
@given(bearing_shapes, st.lists(st.floats(-6.0, 4.0), min_size=2, max_size=6))
def test_the_kept_order_is_kept_exactly_while_its_pivots_are_acceptable(shape, log_cs):
    """keep_order: the same sequences as below, each solution numpy's; a fresh factorisation
    exactly when the last order's pivots (checked by a dense elimination in that order) fall
    below the threshold."""
    jac = _bearing_jacobian(*shape)
    lu = None
    for k, log_c in enumerate(log_cs):
        pattern, values, dense = _newton(jac, 10.0 ** log_c)
        if lu is None:
            lu = SparseLu(pattern.start, pattern.index, keep_order=True)
            assert lu.factor(values) == 0
            continue
        rows, pivotings = lu.row_of, lu.pivotings
        kept = _pivots_acceptable(dense, rows)
        assert lu.factor(values) == 0
        assert lu.pivotings == pivotings + (not kept)
        if kept:
            np.testing.assert_array_equal(lu.row_of, rows)
        _assert_solves(lu, dense, shape[3] + k)


@settings(max_examples=30, deadline=None)
@given(bearing_shapes, st.lists(st.floats(-6.0, 4.0), min_size=2, max_size=6))
def test_a_factorisation_on_the_kept_pattern_is_the_fresh_factorisation(shape, log_cs):
    """A sequence of Newton matrices of one pattern (step sizes over ten decades, so the
    pivot order must sometimes change): each solution is bit for bit that of factorising the
    same matrix afresh, and matches numpy's."""
    jac = _bearing_jacobian(*shape)
    lu = None
    for k, log_c in enumerate(log_cs):
        pattern, values, dense = _newton(jac, 10.0 ** log_c)
        lu = lu or SparseLu(pattern.start, pattern.index)
        fresh = SparseLu(pattern.start, pattern.index)
        assert lu.factor(values) == 0
        assert fresh.factor(values) == 0
        x = _assert_solves(lu, dense, shape[3] + k)
        np.testing.assert_array_equal(x, fresh.solve(np.random.default_rng(shape[3] + k)
                                                     .standard_normal(dense.shape[0])))
        np.testing.assert_array_equal(lu.row_of, fresh.row_of)
    assert 1 <= lu.pivotings <= len(log_cs)


@pytest.mark.parametrize("keep_order, back", [(False, ([0, 1, 2], 3)), (True, ([1, 0, 2], 2))])
def test_the_pivot_order_changes_when_a_pivot_falls_below_the_threshold(keep_order, back):
    """Full 3x3 pattern. [[4,1,1],[1,4,1],[1,1,4]]: diagonal pivots. Then the first diagonal
    entry 1e-4 (below 1e-3 of its column's largest, 2): row 1 is pivoted first, a new order;
    the same matrix again keeps it. The first matrix again: following the rule, back to the
    diagonal (a third fresh factorisation); keep_order, the second order kept (its pivot 1 is
    above 1e-3 of its column's 4)."""
    start = np.array([0, 3, 6, 9])
    index = np.tile(np.arange(3), 3)
    lu = SparseLu(start, index, keep_order=keep_order)
    dominant = np.array([[4.0, 1, 1], [1, 4, 1], [1, 1, 4]])
    small_pivot = np.array([[1e-4, 4, 1], [2, 4, 1], [1, 1, 4]])
    for matrix, rows, pivotings in ((dominant, [0, 1, 2], 1), (small_pivot, [1, 0, 2], 2),
                                    (small_pivot, [1, 0, 2], 2), (dominant, *back)):
        assert lu.factor(matrix.ravel(order="F")) == 0
        np.testing.assert_array_equal(lu.row_of, rows)
        assert lu.pivotings == pivotings
        _assert_solves(lu, matrix, 0)


@pytest.mark.parametrize("values, step", [
    ([1.0, 2.0, 0.0, 0.0], 2),            # second column zero: singular at step 2
    ([0.0, 0.0, 1.0, 1.0], 1),            # first column zero
    ([1.0, np.nan, 1.0, 1.0], 1),         # not finite
])
@pytest.mark.parametrize("keep_order", [False, True])
def test_singular_or_non_finite_matrices_are_reported_with_their_step(values, step,
                                                                      keep_order):
    lu = SparseLu([0, 2, 4], [0, 1, 0, 1], keep_order=keep_order)
    assert lu.factor(np.array([2.0, 1.0, 1.0, 2.0])) == 0  # a pattern kept first
    assert lu.factor(np.array(values)) == step
    assert SparseLu([0, 2, 4], [0, 1, 0, 1]).factor(np.array(values)) == step


def test_newton_pattern_orders_the_matrix_and_adds_the_diagonal():
    jac = sparse.csc_matrix(np.array([[0.0, 2.0, 0.0], [3.0, 0.0, 0.0], [0.0, 5.0, 7.0]]))
    order = np.array([2, 0, 1])
    pattern = newton_pattern(_pattern(jac), order)
    dense = sparse.csc_matrix((pattern.values(jac.data, 0.5), pattern.index, pattern.start),
                              shape=(3, 3)).toarray()
    np.testing.assert_array_equal(dense, (np.eye(3) - 0.5 * jac.toarray())[order][:, order])
    assert pattern.index.size == jac.nnz + 2  # the diagonal's (2, 2) was a nonzero of J


def test_compiled_bdf_counts_its_fresh_factorisations(kernel_cache):
    res = simulate(assemble(SpringMassChain(phi0=0.1)), 0.5, method="compiled_bdf")
    assert 1 <= res.stats["npivotings"] <= res.stats["nlinsetups"]


def test_timing_loops_leave_the_factors_and_the_right_hand_side_as_they_were():
    """``time_calls`` factorises and solves copies inside C: afterwards the factors solve as
    numpy does, the right-hand side given is unchanged and the costs are finite."""
    jac = _bearing_jacobian(7, 6, 8, seed=3)
    pattern, values, dense = _newton(jac, 1e-3)
    lu = SparseLu(pattern.start, pattern.index, keep_order=True)
    b = np.random.default_rng(4).standard_normal(dense.shape[0])
    kept = b.copy()
    factor_s, solve_s = lu.time_calls(values, b, repeats=50, loops=2)
    np.testing.assert_array_equal(b, kept)
    assert np.isfinite(factor_s) and np.isfinite(solve_s)
    assert lu.pivotings == 1  # the repeated factorisations kept the first pivot order
    _assert_solves(lu, dense, 5)
