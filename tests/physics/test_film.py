"""Hamrock-Dowson film thickness, entrainment speed and lambda ratio."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.errors import ParameterError
from bearingsim.physics.film import (
    central_film_thickness,
    dimensionless_load,
    dimensionless_material,
    dimensionless_speed,
    ellipticity,
    entrainment_speed,
    hamrock_dowson,
    lambda_ratio,
    minimum_film_thickness,
    rolling_entrainment_speed,
)
from bearingsim.physics.lubricant import Oil

E_STEEL = 2.275e11  # E' of steel on steel (Hamrock & Dowson)

# 6304-type inner-race contact (docs/studies.md, section C validation bearing): Dw = 9.52 mm,
# dm = 36 mm, fi = 0.52. Reduced radii Rx = Dw/2 (1 - gamma), Ry = fi Dw / (2 fi - 1).
DW, DM, FI = 9.52e-3, 36e-3, 0.52
GAMMA = DW / DM
RX = 0.5 * DW * (1 - GAMMA)
RY = FI * DW / (2 * FI - 1)


def test_dimensionless_groups_and_formulas_match_the_study():
    eta, alpha, u, q = 0.02, 2.0e-8, 5.0, 300.0
    res = hamrock_dowson(q, u, RX, RY, E_STEEL, eta, alpha)
    U, G, W = eta * u / (E_STEEL * RX), alpha * E_STEEL, q / (E_STEEL * RX**2)
    k = 1.0339 * (RY / RX) ** 0.636
    assert (res.U, res.G, res.W, res.k) == pytest.approx((U, G, W, k), rel=1e-12)
    hmin = RX * 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1 - np.exp(-0.68 * k))
    hc = RX * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1 - 0.61 * np.exp(-0.73 * k))
    assert res.h_min == pytest.approx(hmin, rel=1e-12)
    assert res.h_c == pytest.approx(hc, rel=1e-12)
    # Physically sensible for a small ball bearing in oil: tenths of a micrometre, h_c > h_min.
    assert 0.05e-6 < res.h_min < 1e-6 < res.h_c * 10 and res.h_c > res.h_min


def test_central_film_exceeds_minimum_film_over_the_bearing_range():
    # Hamrock & Dowson (1977): the central film is thicker than the minimum (side-lobe) film.
    U, W, k = np.meshgrid(np.geomspace(1e-13, 1e-9, 9), np.geomspace(1e-8, 1e-5, 7), [1, 3, 8.0])
    hc = central_film_thickness(U, 5000.0, W, k, 0.01)
    hmin = minimum_film_thickness(U, 5000.0, W, k, 0.01)
    assert np.all(hc > hmin)


@settings(max_examples=50, deadline=None)
@given(u=st.floats(0.01, 50.0), factor=st.floats(1.01, 10.0), eta=st.floats(1e-3, 1.0))
def test_film_grows_with_speed_and_viscosity_by_the_published_exponents(u, factor, eta):
    base = hamrock_dowson(500.0, u, RX, RY, E_STEEL, eta, 2e-8)
    faster = hamrock_dowson(500.0, u * factor, RX, RY, E_STEEL, eta, 2e-8)
    thicker = hamrock_dowson(500.0, u, RX, RY, E_STEEL, eta * factor, 2e-8)
    assert faster.h_min / base.h_min == pytest.approx(factor**0.68, rel=1e-9)
    assert thicker.h_c / base.h_c == pytest.approx(factor**0.67, rel=1e-9)
    assert np.isfinite(base.h_min) and base.h_min > 0


def test_film_falls_weakly_with_load():
    light = hamrock_dowson(100.0, 5.0, RX, RY, E_STEEL, 0.02, 2e-8)
    heavy = hamrock_dowson(1000.0, 5.0, RX, RY, E_STEEL, 0.02, 2e-8)
    assert heavy.h_min / light.h_min == pytest.approx(10**-0.073, rel=1e-9)


def test_lubricant_swap_changes_film():
    thin, thick = Oil.from_iso_vg(22), Oil.from_iso_vg(220)
    h = [hamrock_dowson(300.0, 5.0, RX, RY, E_STEEL, o.dynamic_viscosity(333.15),
                        o.pressure_viscosity(333.15)).h_min for o in (thin, thick)]
    assert h[1] > 3 * h[0]


def test_entrainment_speeds():
    assert entrainment_speed(3.0, 5.0) == pytest.approx(4.0)
    omega = 300.0
    expected = 0.25 * DM * (1 - GAMMA**2) * omega
    assert rolling_entrainment_speed(omega, DW, DM) == pytest.approx(expected)
    assert rolling_entrainment_speed(-omega, DW, DM) == pytest.approx(expected)
    assert rolling_entrainment_speed(0.0, DW, DM) >= 0.0


def test_lambda_ratio():
    assert lambda_ratio(0.3e-6, 0.04e-6, 0.03e-6) == pytest.approx(6.0)
    with pytest.raises(ParameterError, match="composite roughness"):
        lambda_ratio(0.3e-6, 0.0, 0.0)


def test_float_array_and_sx_agree():
    q, u = ca.SX.sym("q"), ca.SX.sym("u")
    res = hamrock_dowson(q, u, RX, RY, E_STEEL, 0.02, 2e-8)
    f = ca.Function("f", [q, u], [res.h_min, res.h_c])
    qs, us = np.array([50.0, 500.0, 2000.0]), np.array([0.5, 5.0, 30.0])
    arr = hamrock_dowson(qs, us, RX, RY, E_STEEL, 0.02, 2e-8)
    for i in range(3):
        hm, hc = (float(v) for v in f(qs[i], us[i]))
        flt = hamrock_dowson(float(qs[i]), float(us[i]), RX, RY, E_STEEL, 0.02, 2e-8)
        assert hm == pytest.approx(flt.h_min, rel=1e-12) == arr.h_min[i]
        assert hc == pytest.approx(flt.h_c, rel=1e-12)
    w = ca.SX.sym("w")
    g = ca.Function("g", [w], [rolling_entrainment_speed(w, DW, DM)])
    assert float(g(100.0)) == pytest.approx(rolling_entrainment_speed(100.0, DW, DM), rel=1e-12)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: dimensionless_speed(-0.01, 1.0, E_STEEL, RX), r"eta0 = -0.01 \[Pa s\]"),
        (lambda: dimensionless_load(0.0, E_STEEL, RX), r"Q = 0.0 \[N\]"),
        (lambda: dimensionless_material(2e-8, 0.0), r"E_eff = 0.0 \[Pa\]"),
        (lambda: ellipticity(RX, -1.0), r"Ry = -1.0 \[m\]"),
        (lambda: minimum_film_thickness(1e-11, 5000, 1e-6, np.nan, RX), "k must be finite"),
        (lambda: rolling_entrainment_speed(1.0, 0.04, 0.036), r"dm = 0.036 \[m\]"),
    ],
)
def test_invalid_input_is_rejected(call, match):
    with pytest.raises(ParameterError, match=match):
        call()
