"""Traction coefficients (regularized Coulomb, EHL curve) and slice integration."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.errors import ParameterError
from bearingsim.physics.lubricant import Dry, Oil
from bearingsim.physics.traction import (
    EHL_TRACTION_DEFAULT,
    ehl_traction,
    ehl_traction_peak,
    hertz_slice_weights,
    regularized_coulomb,
    slice_traction,
)

speeds = st.floats(-100.0, 100.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(s=speeds, mu=st.one_of(st.just(0.0), st.floats(1e-6, 1.0)))
def test_coulomb_is_odd_bounded_and_smooth(s, mu):
    f = regularized_coulomb(s, mu)
    assert f == pytest.approx(-regularized_coulomb(-s, mu), abs=1e-15)
    assert abs(f) <= mu
    assert regularized_coulomb(0.0, mu) == 0.0
    assert regularized_coulomb(7.1e-3, mu, 1e-3) >= 0.99 * mu  # documented 7.1 v_reg


@settings(max_examples=60, deadline=None)
@given(s=speeds)
def test_ehl_curve_is_odd_and_bounded_by_its_peak(s):
    f = ehl_traction(s)
    assert f == pytest.approx(-ehl_traction(-s), abs=1e-15)
    assert abs(f) <= ehl_traction_peak() + 1e-12
    assert np.isfinite(f)


def test_ehl_curve_values():
    # (A + B s) exp(-C s) + D evaluated by hand at s = 0.5 m/s with the defaults: 0.0805.
    c = EHL_TRACTION_DEFAULT
    s = 0.5
    expected = (c["A"] + c["B"] * s) * np.exp(-c["C"] * s) + c["D"]
    assert ehl_traction(s, v_reg=1e-12) == pytest.approx(expected, rel=1e-9)
    assert ehl_traction(0.0) == 0.0
    assert ehl_traction(1e3) == pytest.approx(c["D"], rel=1e-6)
    s_star = 1 / c["C"] - c["A"] / c["B"]
    assert ehl_traction_peak() == pytest.approx(ehl_traction(s_star, v_reg=1e-12), rel=1e-9)
    grid = np.linspace(0, 10, 20001)
    assert ehl_traction(grid).max() == pytest.approx(ehl_traction_peak(), rel=1e-6)


@pytest.mark.parametrize("n", [0, 1, 2, 5, 10, 50])
def test_slice_loads_sum_exactly_to_q(n):
    centres, weights = hertz_slice_weights(n)
    assert len(centres) == 2 * n + 1 and np.all(weights > 0)
    assert weights.sum() == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(weights, weights[::-1], atol=1e-16)  # symmetric
    res = slice_traction(1234.5, 2e-3, lambda x: (1.0, 0.0), lambda s: 0.05, n=n)
    assert sum(res.loads) == pytest.approx(1234.5, rel=1e-14)


def test_slice_weights_follow_hertz_line_load():
    # Load per unit length along the major axis is (3Q/4a)(1 - xi^2) (Harris & Kotzalas; Johnson).
    centres, weights = hertz_slice_weights(200)
    width = 2.0 / 401
    np.testing.assert_allclose(weights / width, 0.75 * (1 - centres**2), atol=1e-5)


def test_uniform_slip_gives_mu_q_and_no_spin_moment():
    res = slice_traction(1000.0, 1e-3, lambda x: (2.0, 0.0), lambda s: 0.06 + 0 * s, n=5)
    assert res.force_r == pytest.approx(-60.0, rel=1e-6)
    assert res.force_t == pytest.approx(0.0, abs=1e-12)
    assert res.moment_n == pytest.approx(0.0, abs=1e-12)


def test_pure_spin_gives_a_resisting_spin_moment():
    # Body spinning at w_n about n: du = w_n n x (x e_t) = -w_n x e_r. Constant mu: the moment
    # opposes the spin, M = -sign(w_n) mu sum Q_i |x_i|.
    Q, a, w_n, mu = 800.0, 1.5e-3, 100.0, 0.05
    res = slice_traction(Q, a, lambda x: (-w_n * x, 0.0), lambda s: mu + 0 * s, n=20)
    centres, weights = hertz_slice_weights(20)
    expected = -mu * Q * np.sum(weights * np.abs(centres) * a)
    assert res.moment_n == pytest.approx(expected, rel=1e-6)
    assert res.moment_n < 0 and res.force_r == pytest.approx(0.0, abs=1e-9)
    # Continuous limit: -mu Q a * int (3/4)(1 - xi^2)|xi| dxi = -3/8 mu Q a.
    assert res.moment_n == pytest.approx(-0.375 * mu * Q * a, rel=2e-3)


def test_lubricant_swap_changes_traction():
    def force(lub):
        return slice_traction(500.0, 1e-3, lambda x: (0.5, 0.0), lub.traction_coefficient).force_r
    assert force(Oil.from_iso_vg(68)) != pytest.approx(force(Dry(mu=0.3)), rel=0.1)
    assert force(Dry(mu=0.3)) == pytest.approx(-150.0, rel=1e-4)


def test_float_array_and_sx_agree():
    s = ca.SX.sym("s")
    f = ca.Function("f", [s], [ehl_traction(s), regularized_coulomb(s, 0.1)])
    xs = np.array([-3.0, -1e-4, 0.0, 2e-3, 0.7, 40.0])
    arr_e, arr_c = ehl_traction(xs), regularized_coulomb(xs, 0.1)
    for i, x in enumerate(xs):
        e, c = (float(v) for v in f(x))
        assert e == pytest.approx(ehl_traction(float(x)), rel=1e-12, abs=1e-16) == arr_e[i]
        assert c == pytest.approx(regularized_coulomb(float(x), 0.1), rel=1e-12, abs=1e-16)
        assert c == arr_c[i]
    q, u, w = ca.SX.sym("q"), ca.SX.sym("u"), ca.SX.sym("w")
    sym = slice_traction(q, 1e-3, lambda x: (u + w * x, 0.1 * u), ehl_traction)
    g = ca.Function("g", [q, u, w], [sym.force_r, sym.force_t, sym.moment_n])
    num = slice_traction(700.0, 1e-3, lambda x: (0.3 + 50.0 * x, 0.03), ehl_traction)
    np.testing.assert_allclose([float(v) for v in g(700.0, 0.3, 50.0)],
                               [num.force_r, num.force_t, num.moment_n], rtol=1e-12)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: regularized_coulomb(1.0, -0.1), r"mu = -0.1 \[-\]"),
        (lambda: regularized_coulomb(1.0, 0.1, v_reg=0.0), r"v_reg = 0.0 \[m/s\]"),
        (lambda: regularized_coulomb(np.nan, 0.1), "slip_speed must be finite"),
        (lambda: ehl_traction(1.0, B=-1.0), r"B = -1.0 \[s/m\]"),
        (lambda: ehl_traction(1.0, C=0.0), "C = 0.0"),
        (lambda: hertz_slice_weights(-1), "n = -1"),
        (lambda: slice_traction(-1.0, 1e-3, lambda x: (1.0, 0.0), ehl_traction), r"Q = -1.0 \[N\]"),
    ],
)
def test_invalid_input_is_rejected(call, match):
    with pytest.raises(ParameterError, match=match):
        call()
