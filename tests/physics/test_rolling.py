"""EHL hydrodynamic rolling resistance (Houpert's curve fit): the formula, its scaling laws,
float/numpy/CasADi agreement and its relation to Palmgren's M0."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.catalog import get_bearing
from bearingsim.errors import ParameterError
from bearingsim.physics.contact_curvature import raceway_radii
from bearingsim.physics.film import rolling_entrainment_speed
from bearingsim.physics.friction import palmgren_m0
from bearingsim.physics.lubricant import Oil
from bearingsim.physics.rolling import hydrodynamic_rolling_force, rolling_resistance

E_STEEL = 2.275e11  # E' of steel on steel (Hamrock & Dowson)
# 6304-type inner-race contact (docs/studies.md, section C): Dw 9.52 mm, dm 36 mm, fi 0.52
DW, DM, FI = 9.52e-3, 36e-3, 0.52
RX = 0.5 * DW * (1 - DW / DM)
RY = FI * DW / (2 * FI - 1)


def test_formula_in_dimensionless_groups():
    eta, alpha, u, q = 0.03, 2.0e-8, 3.0, 200.0
    U, G, W = eta * u / (E_STEEL * RX), alpha * E_STEEL, q / (E_STEEL * RX**2)
    k = 1.0339 * (RY / RX) ** 0.636
    expected = 2.86 * E_STEEL * RX**2 * k**0.348 * G**0.022 * U**0.66 * W**0.47
    assert rolling_resistance(q, u, RX, RY, E_STEEL, eta, alpha) == pytest.approx(expected,
                                                                                   rel=1e-12)
    # a small ball bearing contact in oil: some hundredths of a newton, a few 1e-4 of the load
    assert 0.01 < expected < 0.2 and expected / q < 1e-3


def test_no_rolling_no_force_and_bad_inputs_are_rejected():
    assert rolling_resistance(100.0, 0.0, RX, RY, E_STEEL, 0.03, 2e-8) == 0.0
    assert rolling_resistance(100.0, 2.0, RX, RY, E_STEEL, 0.0, 2e-8) == 0.0
    with pytest.raises(ParameterError):
        rolling_resistance(-1.0, 2.0, RX, RY, E_STEEL, 0.03, 2e-8)
    with pytest.raises(ParameterError):
        hydrodynamic_rolling_force(1e-11, 4000.0, 1e-4, 0.0, E_STEEL, RX)


@settings(max_examples=60, deadline=None)
@given(u=st.floats(0.01, 30.0), q=st.floats(1.0, 3000.0), eta=st.floats(1e-3, 0.5),
       factor=st.floats(1.01, 20.0))
def test_rolling_force_scales_with_the_published_exponents(u, q, eta, factor):
    base = rolling_resistance(q, u, RX, RY, E_STEEL, eta, 2e-8)
    assert base > 0.0
    faster = rolling_resistance(q, u * factor, RX, RY, E_STEEL, eta, 2e-8)
    thicker = rolling_resistance(q, u, RX, RY, E_STEEL, eta * factor, 2e-8)
    heavier = rolling_resistance(q * factor, u, RX, RY, E_STEEL, eta, 2e-8)
    assert faster / base == pytest.approx(factor**0.66, rel=1e-9)
    assert thicker / base == pytest.approx(factor**0.66, rel=1e-9)
    assert heavier / base == pytest.approx(factor**0.47, rel=1e-9)


@settings(max_examples=40, deadline=None)
@given(s=st.floats(0.1, 10.0), u=st.floats(0.1, 20.0), q=st.floats(1.0, 1000.0))
def test_geometrically_similar_contacts_scale_with_rx_squared(s, u, q):
    # U = eta u/(E' Rx), W = Q/(E' Rx^2) and k are unchanged when Rx, Ry, u scale by s and
    # Q by s^2, so F_R / (E' Rx^2) is unchanged: F_R scales by s^2
    base = rolling_resistance(q, u, RX, RY, E_STEEL, 0.03, 2e-8)
    scaled = rolling_resistance(q * s * s, u * s, RX * s, RY * s, E_STEEL, 0.03, 2e-8)
    assert scaled / base == pytest.approx(s * s, rel=1e-9)


@settings(max_examples=30, deadline=None)
@given(u=st.floats(0.0, 30.0), q=st.floats(0.5, 3000.0), eta=st.floats(0.0, 0.5))
def test_float_numpy_and_casadi_agree(u, q, eta):
    value = rolling_resistance(q, u, RX, RY, E_STEEL, eta, 2e-8)
    array = rolling_resistance(np.array([q, q]), np.array([u, u]), RX, RY, E_STEEL, eta, 2e-8)
    us, qs = ca.SX.sym("u"), ca.SX.sym("q")
    f = ca.Function("f", [us, qs], [rolling_resistance(qs, us, RX, RY, E_STEEL, eta, 2e-8)])
    assert np.allclose(array, value, rtol=1e-12, atol=0.0)
    assert float(f(u, q)) == pytest.approx(value, rel=1e-12, abs=1e-300)


def _rolling_torque(bearing, oil, omega, load):
    """Torque equivalent of the rolling loss of a deep-groove bearing in pure rolling [N m]:
    ``2 Z F_R |v_rel| / omega`` with the load shared equally (axial load, all balls alike)."""
    g = get_bearing(bearing)
    dw, dm, z = g.ball_diameter, g.pitch_diameter, g.ball_count
    u = rolling_entrainment_speed(omega, dw, dm)
    gamma = dw / dm
    total = 0.0
    for race, f in (("inner", g.fi), ("outer", g.fo)):
        rx, ry = raceway_radii(dw, dm, f, 0.0, race)
        f_r = rolling_resistance(load / z, u, rx, ry, E_STEEL, float(oil.dynamic_viscosity()),
                                 float(oil.pressure_viscosity()))
        # ball centre relative to the race at the contact, pure rolling, outer ring fixed
        wc = 0.5 * (1 - gamma) * omega
        v_rel = wc * dm / 2 - (omega if race == "inner" else 0.0) * (dm / 2 + (
            -dw / 2 if race == "inner" else dw / 2))
        total += z * f_r * abs(v_rel)
    return total / omega


def test_rolling_loss_follows_palmgren_m0_speed_law_and_is_a_share_of_it():
    # Palmgren's M0 grows as (nu n)^(2/3), the rolling force as (eta u)^0.66: their ratio
    # changes by 10^(0.66 - 2/3 + ...) over a decade of speed, well under 5 %
    oil = Oil.from_iso_vg(32)
    nu = float(oil.kinematic_viscosity())
    dm = get_bearing("61905").pitch_diameter
    shares = []
    for omega in (100.0, 1000.0):
        m_roll = _rolling_torque("61905", oil, omega, 100.0)
        shares.append(m_roll / palmgren_m0(nu, omega, dm, 2.0))
    assert shares[1] / shares[0] == pytest.approx(1.0, abs=0.05)
    # the resolved rolling loss is a part of the total viscous loss, not more
    assert 0.05 < shares[0] < 0.5
