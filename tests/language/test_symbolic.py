"""Tests of the float/array/CasADi helpers (bearingsim.symbolic)."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.special import ellipe, ellipk

from bearingsim import symbolic as op


@given(st.floats(0.0, 1e12), st.integers(0, 3))
def test_sqrt_power_is_the_half_integer_power(x, k):
    """``x**k * sqrt(x)`` equals ``x ** (k + 1/2)`` to a few ulp, numeric and symbolic alike,
    with the derivative ``(k + 1/2) x^(k - 1/2)``."""
    expected = x ** (k + 0.5)
    assert op.sqrt_power(x, k) == pytest.approx(expected, rel=4e-16 * (k + 2), abs=0.0)
    s = ca.SX.sym("x")
    f = ca.Function("f", [s], [op.sqrt_power(s, k), ca.jacobian(op.sqrt_power(s, k), s)])
    value, slope = (float(v) for v in f(x))
    assert value == op.sqrt_power(x, k)
    if x > 0.0:
        assert slope == pytest.approx((k + 0.5) * x ** (k - 0.5), rel=1e-14)


def test_sqrt_power_at_zero_has_pows_derivative():
    """An unloaded Hertz contact has compression exactly 0: value and derivative 0, as
    ``pow``'s (the product form alone gives ``0 * inf = NaN``, which stopped the quasi-static
    balls' Newton iteration: bench/dgbb_long condition 2)."""
    s = ca.SX.sym("x")
    for k in (1, 2):
        f = ca.Function("f", [s], [op.sqrt_power(s, k), ca.jacobian(op.sqrt_power(s, k), s)])
        for x in (0.0, -1e-3):
            value, slope = (float(v) for v in f(x))
            assert (value, slope) == (0.0, 0.0)
        assert op.sqrt_power(0.0, k) == 0.0
        assert op.sqrt_power(-2.0, k) == 0.0


def test_sqrt_power_on_arrays():
    x = np.array([0.0, 0.25, 4.0, 1e-18])
    np.testing.assert_allclose(op.sqrt_power(x, 2), x**2.5, rtol=1e-15, atol=0.0)


_M = ca.SX.sym("m")
_ELLIPTIC = ca.Function("ke", [_M], [op.ellipk(_M), op.ellipe(_M)])


@given(st.one_of(st.floats(-10.0, 1.0 - 1e-15), st.floats(1e-15, 1e-9).map(lambda d: 1.0 - d)))
def test_elliptic_integrals_match_scipy_on_numbers_and_symbols(m):
    """The arithmetic-geometric mean gives scipy.special's K(m) and E(m) to a few ulp, the same
    for a number and for a CasADi symbol evaluated at it (one expression for both)."""
    symbolic = _ELLIPTIC(m)
    for ours, theirs, of_symbol in ((op.ellipk(m), ellipk(m), symbolic[0]),
                                    (op.ellipe(m), ellipe(m), symbolic[1])):
        assert ours == pytest.approx(theirs, rel=1e-14)
        assert float(of_symbol) == ours


def test_elliptic_integrals_on_arrays_and_refused_at_one():
    m = np.array([0.0, 0.5, 0.99, 1.0 - 1e-15])
    np.testing.assert_allclose(op.ellipk(m), ellipk(m), rtol=1e-14)
    for bad in (1.0, np.array([0.5, 1.5])):
        with pytest.raises(ValueError, match="m must be below 1"):
            op.ellipe(bad)
