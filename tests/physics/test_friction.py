"""Palmgren and SKF friction torque."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from bearingsim.errors import CatalogError, ParameterError
from bearingsim.physics.friction import (
    SkfSeal,
    palmgren_f1,
    palmgren_m0,
    palmgren_p1,
    palmgren_torque,
    skf_friction_components,
    skf_friction_torque,
)
from bearingsim.physics.lubricant import Dry, Grease, Oil
from bearingsim.physics.lubrication import PALMGREN_F0, palmgren_f0
from bearingsim.units import rpm_to_rad_s

# An oil with exactly 20 mm^2/s at 40 degC, operating at 40 degC.
OIL20 = Oil(20.0, 40.0, 4.0, 100.0, temperature=313.15)


def test_palmgren_m0_worked_number():
    # Palmgren: M0 = 1e-7 f0 (nu n)^(2/3) dm^3 [N mm]. Deep groove, oil bath f0 = 2 (Harris table),
    # nu = 20 mm^2/s, n = 3000 r/min, dm = 33.5 mm: 1e-7 * 2 * 60000^(2/3) * 33.5^3 = 11.52 N mm.
    m = palmgren_torque(rpm_to_rad_s(3000.0), 33.5e-3, OIL20, "deep_groove_ball", smooth=False)
    assert -m * 1e3 == pytest.approx(11.52, abs=0.01)
    assert palmgren_f0("deep_groove_ball", "oil_bath") == 2.0
    # Low-speed branch: nu n = 20 * 50 = 1000 < 2000 -> 160e-7 f0 dm^3 = 0.1203 N mm.
    m_low = palmgren_torque(rpm_to_rad_s(50.0), 33.5e-3, OIL20, "deep_groove_ball", smooth=False,
                            omega_reg=1e-9)
    assert -m_low * 1e3 == pytest.approx(160e-7 * 2 * 33.5**3, rel=1e-9)


def test_smooth_blend_error_is_as_documented():
    nu_n = np.geomspace(100.0, 1e6, 4001)
    nu = 20e-6
    n = rpm_to_rad_s(nu_n / 20.0)
    exact = palmgren_m0(nu, n, 0.05, 2.0, smooth=False)
    smooth = palmgren_m0(nu, n, 0.05, 2.0, smooth=True)
    rel = np.abs(smooth / exact - 1)
    assert rel.max() <= 0.018
    outside = (nu_n < 1400) | (nu_n > 2700)
    assert rel[outside].max() < 1e-3


def test_load_term_m1():
    # M1 = f1 P1 dm, f1 = 0.0009 (P0/C0)^0.55 (deep groove, docs/studies.md / Palmgren).
    p0, c0, p1, dm = 1500.0, 10000.0, 1500.0, 0.04
    f1 = 0.0009 * (p0 / c0) ** 0.55
    assert palmgren_f1("deep_groove_ball", p0, c0) == pytest.approx(f1)
    assert palmgren_f1("angular_contact_ball", p0, c0) == pytest.approx(0.001 * 0.15**0.33)
    w = 300.0
    m0 = palmgren_m0(OIL20.kinematic_viscosity(), w, dm, 2.0)
    m = palmgren_torque(w, dm, OIL20, "deep_groove_ball", load_P1=p1, P0=p0, C0=c0, omega_reg=1e-6)
    assert -m == pytest.approx(m0 + f1 * p1 * dm, rel=1e-9)


def test_p1_per_harris():
    assert palmgren_p1(1000.0, 0.0, "deep_groove_ball") == pytest.approx(1000.0, abs=0.6)
    assert palmgren_p1(1000.0, 1000.0, "deep_groove_ball") == pytest.approx(2900.0, rel=1e-6)
    assert palmgren_p1(1000.0, 500.0, "angular_contact_ball_pair") == pytest.approx(1700.0)
    assert palmgren_p1(100.0, 500.0, "thrust_ball") == pytest.approx(500.0)


def test_speed_ratio_of_nested_bearing_matches_the_study():
    # docs/studies.md, section A: equal M0 of both layers gives Rs = Dp1^4.5 / (Dp1^4.5 + Dp2^4.5):
    # 0.5 at PDR = 1 and 0.17 at PDR = 0.7.
    oil = Oil.from_iso_vg(68)
    w_in = rpm_to_rad_s(10000.0)
    for dp1, dp2, expected in ((0.05, 0.05, 0.5), (0.035, 0.05, 0.17)):
        def balance(rs, dp1=dp1, dp2=dp2):
            inner = palmgren_torque(w_in * (1 - rs), dp1, oil, "deep_groove_ball")
            outer = palmgren_torque(w_in * rs, dp2, oil, "deep_groove_ball")
            return inner - outer
        rs = brentq(balance, 1e-3, 1 - 1e-3)
        assert rs == pytest.approx(expected, abs=0.005)
        assert rs == pytest.approx(dp1**4.5 / (dp1**4.5 + dp2**4.5), rel=1e-3)


@settings(max_examples=50, deadline=None)
@given(w=st.floats(-2000.0, 2000.0), load=st.floats(0.0, 5000.0), dl=st.floats(1.0, 1000.0),
       grade=st.sampled_from([10, 32, 68, 220, 460]))
def test_torque_opposes_speed_and_grows_with_load_and_viscosity(w, load, dl, grade):
    oil = Oil.from_iso_vg(grade)
    kw = {"P0": 1000.0, "C0": 10000.0}
    m = palmgren_torque(w, 0.04, oil, "deep_groove_ball", load_P1=load, **kw)
    assert np.isfinite(m) and m * w <= 0.0
    heavier = palmgren_torque(w, 0.04, oil, "deep_groove_ball", load_P1=load + dl, **kw)
    # at zero speed (and at subnormal speeds, where the signed torque underflows to 0) there
    # is nothing to grow
    assert abs(heavier) > abs(m) or abs(w) < 1e-150
    thicker = palmgren_torque(w, 0.04, Oil.from_iso_vg(grade, temperature=300.0),
                              "deep_groove_ball", load_P1=load, **kw)
    assert abs(thicker) >= abs(m)


def test_smooth_through_zero_speed():
    assert palmgren_torque(0.0, 0.04, OIL20, "deep_groove_ball") == 0.0
    w = ca.SX.sym("w")
    torque = palmgren_torque(w, 0.04, OIL20, "deep_groove_ball")
    dm_dw = ca.Function("d", [w], [ca.jacobian(torque, w)])
    slope = float(dm_dw(0.0))
    assert np.isfinite(slope) and slope < 0


def test_lubricant_swap_changes_torque():
    w = rpm_to_rad_s(3000.0)
    base = Oil.from_iso_vg(100, method="grease")
    torques = [abs(palmgren_torque(w, 0.04, lub, "deep_groove_ball")) for lub in (
        Oil.from_iso_vg(32), Oil.from_iso_vg(320), Grease(base, 0.25), Grease(base, 0.5), Dry())]
    assert torques[1] > torques[0]
    assert torques[3] > torques[2]  # more grease, more friction
    assert torques[4] == 0.0  # dry: no viscous torque


def test_float_array_and_sx_agree():
    w, p = ca.SX.sym("w"), ca.SX.sym("p")
    oil = Oil.from_iso_vg(46)
    f = ca.Function("f", [w, p], [palmgren_torque(w, 0.04, oil, "deep_groove_ball", load_P1=p,
                                                  P0=p, C0=1e4)])
    ws = np.array([-500.0, -0.05, 0.0, 3.0, 800.0])
    arr = palmgren_torque(ws, 0.04, oil, "deep_groove_ball", load_P1=2000.0, P0=2000.0, C0=1e4)
    for i, x in enumerate(ws):
        flt = palmgren_torque(float(x), 0.04, oil, "deep_groove_ball", load_P1=2000.0, P0=2000.0,
                              C0=1e4)
        assert float(f(x, 2000.0)) == pytest.approx(flt, rel=1e-12, abs=1e-18)
        assert arr[i] == pytest.approx(flt, rel=1e-14, abs=1e-18)
    T = ca.SX.sym("T")
    g = ca.Function("g", [T], [palmgren_torque(100.0, 0.04, oil, "deep_groove_ball", T=T)])
    assert float(g(350.0)) == pytest.approx(palmgren_torque(100.0, 0.04, oil, "deep_groove_ball",
                                                            T=350.0), rel=1e-12)


# SKF 6208 (d 40, D 80, dm 60 mm, C0 19 kN), Fr = 2000 N, ISO VG 68 at 70 degC, 3000 r/min.
SKF_CASE = {"C0": 19000.0, "d": 0.040, "D": 0.080}


def test_skf_model_matches_independent_catalogue_evaluation():
    # SKF General Catalogue 2005 "Friction", evaluated by hand in catalogue units.
    oil = Oil.from_iso_vg(68, temperature=343.15)
    nu, n, dm, fr = oil.kinematic_viscosity() * 1e6, 3000.0, 60.0, 2000.0
    grr = 3.9e-7 * dm**1.96 * fr**0.54
    gsl = 3.23e-3 * dm**-0.26 * fr ** (5 / 3)
    phi_ish = 1 / (1 + 1.84e-9 * (n * dm) ** 1.28 * nu**0.64)
    phi_rs = np.exp(-3e-8 * nu * n * (40 + 80) * np.sqrt(3.1 / (2 * (80 - 40))))
    phi_bl = np.exp(-2.6e-8 * (n * nu) ** 1.4 * dm)
    mu_sl = phi_bl * 0.15 + (1 - phi_bl) * 0.05
    expected = (phi_ish * phi_rs * grr * (nu * n) ** 0.6 + gsl * mu_sl) * 1e-3
    parts = skf_friction_components(rpm_to_rad_s(n), 0.060, oil, "62", fr, omega_reg=1e-9,
                                    **SKF_CASE)
    assert parts.total == pytest.approx(expected, rel=1e-9)
    assert 0 < parts.phi_ish < 1 and 0 < parts.phi_rs < 1 and 0 <= parts.phi_bl <= 1
    # Same order as Palmgren M0 + M1 for this case (both are catalogue-level estimates).
    palm = -palmgren_torque(rpm_to_rad_s(n), 0.060, oil, "deep_groove_ball", load_P1=fr, P0=fr,
                            C0=19000.0)
    assert 0.3 < parts.total / palm < 3.0


def test_skf_axial_load_seal_and_drag_terms():
    oil = Oil.from_iso_vg(68, temperature=343.15)
    w = rpm_to_rad_s(3000.0)
    base = skf_friction_components(w, 0.060, oil, "62", 2000.0, **SKF_CASE)
    axial = skf_friction_components(w, 0.060, oil, "62", 2000.0, 1000.0, **SKF_CASE)
    assert axial.rolling > base.rolling and axial.sliding > base.sliding
    sealed = skf_friction_components(w, 0.060, oil, "62", 2000.0, seal=SkfSeal(0.028, 2.0, 2.25,
                                                                               50.0), **SKF_CASE)
    assert sealed.seal == pytest.approx((0.028 * 50.0**2.25 + 2.0) * 1e-3)
    bath = skf_friction_components(w, 0.060, oil, "62", 2000.0, oil_level=0.01, Dw=0.012, Z=9,
                                   **SKF_CASE)
    assert bath.drag > 0 and base.drag == 0
    ac = skf_friction_components(w, 0.060, oil, "72B", 2000.0, 1000.0, **SKF_CASE)
    assert ac.total > 0
    m = skf_friction_torque(-w, 0.060, oil, "62", 2000.0, **SKF_CASE)
    assert m == pytest.approx(base.total, rel=1e-6)  # opposite to the (negative) speed


def test_skf_symbolic_speed_agrees():
    oil = Oil.from_iso_vg(68, temperature=343.15)
    w = ca.SX.sym("w")
    f = ca.Function("f", [w], [skf_friction_torque(w, 0.060, oil, "62", 2000.0, 500.0, **SKF_CASE)])
    for x in (-300.0, 0.0, 10.0, 600.0):
        assert float(f(x)) == pytest.approx(
            skf_friction_torque(x, 0.060, oil, "62", 2000.0, 500.0, **SKF_CASE), rel=1e-12,
            abs=1e-18)


@pytest.mark.parametrize(
    "call, exc, match",
    [
        (lambda: palmgren_f0("hovercraft", "oil_bath"), CatalogError, "known: angular_contact"),
        (lambda: palmgren_f0("deep_groove_ball", "splash"), CatalogError, "lubrication method"),
        (lambda: palmgren_torque(1.0, -0.04, OIL20, "deep_groove_ball"), ParameterError,
         r"dm = -0.04 \[m\]"),
        (lambda: palmgren_torque(1.0, 0.04, OIL20, "deep_groove_ball", load_P1=10.0),
         ParameterError, r"C0 \[N\] is required"),
        (lambda: palmgren_torque(np.inf, 0.04, OIL20, "deep_groove_ball"), ParameterError,
         "omega_rel must be finite"),
        (lambda: palmgren_f1("deep_groove_ball", 10.0, 0.0), ParameterError, r"C0 = 0.0 \[N\]"),
        (lambda: skf_friction_components(1.0, 0.06, OIL20, "99", 10.0, **SKF_CASE), CatalogError,
         "SKF bearing series '99'"),
        (lambda: skf_friction_components(1.0, 0.06, OIL20, "62", 10.0, C0=1e4, d=0.08, D=0.04),
         ParameterError, r"D = 0.04 \[m\]"),
    ],
)
def test_invalid_input_is_rejected(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


def test_f0_table_is_complete():
    for row in PALMGREN_F0.values():
        assert set(row) == {"grease", "oil_mist", "oil_bath", "oil_jet", "vertical_shaft"}


def test_skf_constants_match_checked_sources():
    """Issue 3 audit. SKF "Rolling bearings" catalogue (10000 EN), Friction, p. 105: mu_bl about
    0.15 and mu_EHL 0.05 for mineral oil (the Oil defaults). Table 2b has a single row "2, 3" for
    deep groove series 2 and 3 (4.4e-7, 1.7, 2e-3, 100 in a public transcription), so both
    series share it; series 3 had S1 = 1.70e-3 entered from memory before the audit."""
    from bearingsim.physics.friction import SKF_DEEP_GROOVE, SKF_KRS, SKF_KZ

    oil = Oil.from_iso_vg(68)
    assert (oil.mu_bl, oil.mu_ehl) == (0.15, 0.05)
    assert SKF_DEEP_GROOVE["2"] == SKF_DEEP_GROOVE["3"] == {
        "R1": 4.4e-7, "R2": 1.7, "S1": 2.00e-3, "S2": 100.0}
    assert SKF_DEEP_GROOVE["62"] == {"R1": 3.9e-7, "R2": 1.7, "S1": 3.23e-3, "S2": 36.5}
    assert (SKF_KRS["oil_bath"], SKF_KRS["grease"]) == (3e-8, 6e-8)
    assert SKF_KZ == {"deep_groove_ball": 3.1, "angular_contact_ball": 4.4}


def test_skf_starvation_factor_only_where_skf_applies_it():
    """SKF "Rolling bearings" 10000/3 (2017), p. 102: phi_rs applies to oil-air, oil jet, grease
    and an oil bath whose level is below the centre of the lowest rolling element. A given oil
    level (>= 0 above the lowest ball centre) means a full bath: phi_rs = 1; so does a vertical
    shaft. Without a level the bath is taken as low (Krs 3e-8)."""
    from bearingsim.units import rpm_to_rad_s

    def phi_rs(method, oil_level=None):
        oil = Oil.from_iso_vg(32, method=method)
        kwargs = {"oil_level": oil_level, "Dw": 4.0e-3, "Z": 13} if oil_level is not None else {}
        return float(skf_friction_components(
            rpm_to_rad_s(10_000.0), 0.0335, oil, "619", 200.0, 0.0, C0=4300.0, d=0.025,
            D=0.042, **kwargs).phi_rs)

    low_bath = phi_rs("oil_bath")
    assert 0.0 < low_bath < 0.99  # starved: Krs 3e-8
    assert phi_rs("oil_jet") == pytest.approx(low_bath, rel=1e-12)
    assert phi_rs("oil_bath", oil_level=0.0) == 1.0
    assert phi_rs("oil_bath", oil_level=0.01) == 1.0
    assert phi_rs("vertical_shaft") == 1.0
    assert phi_rs("grease") < low_bath  # Krs 6e-8
