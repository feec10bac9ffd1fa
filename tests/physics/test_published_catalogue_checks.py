"""Source checks of issue 15, item 6: the Palmgren friction factors against three catalogues and
the ISO 281 / ISO 76 tables against the scanned standards (GOST 18855-2013 = ISO 281:2007 MOD,
GOST 18854-94 = ISO 76-87). Every value is quoted with its page; where the sources disagree the
test says which one the model uses and why.

Sources (texts in the public repository ArtemFilin1990/Mar, commit 7b871a58):

* HR1: Schaeffler (INA/FAG) *Rolling Bearings*, catalogue HR 1, June 2006, pp. 55-60;
* Timken: *Timken Engineering Manual*, pp. 180 and 183-184 (Table 114);
* KRW: *Wälzlager Lieferprogramm / Bearings Delivery Programme*, Edition 2006, pp. 52-54
  (German) and 116-118 (English);
* GOST 18855-2013, Tables 2 (fc, pp. 5-6) and 3 (X, Y, e, pp. 8-9); GOST 18854-94, Tables 1
  (f0, pp. 3-4) and 2 (X0, Y0, p. 5) (scanned; read from the page images);
* NSK *Super Precision Bearings* (Russian ed.), Table 1.1 p. 139 and Table 2.1 p. 146.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.catalog import get_bearing
from bearingsim.physics import life
from bearingsim.physics.friction import palmgren_f1, palmgren_m0, palmgren_p1
from bearingsim.physics.lubrication import palmgren_f0

# ------------------------------------------------------------------------------- Palmgren f0
# HR1 p. 58 "Bearing factors for deep groove ball bearings" and p. 59 "... angular contact ball
# bearings": (grease or oil mist, oil bath or recirculating oil); merged cells read per block.
HR1_F0 = {
    ("deep_groove_ball", "618"): (1.1, 1.7), ("deep_groove_ball", "160"): (1.1, 1.7),
    ("deep_groove_ball", "60"): (1.1, 1.7), ("deep_groove_ball", "619"): (1.1, 1.7),
    ("deep_groove_ball", "62"): (1.3, 2.0), ("deep_groove_ball", "63"): (1.5, 2.3),
    ("deep_groove_ball", "64"): (1.5, 2.3),
    ("angular_contact_ball", "70"): (1.3, 2.0), ("angular_contact_ball", "72"): (1.3, 2.0),
    ("angular_contact_ball", "73"): (2.0, 3.0),
}
# Timken Table 114 p. 184, oil (p. 180: "The formulas apply to bearings lubricated by oil"):
# deep groove dimension series 39, 00, 02, 03; angular contact 02, 03.
TIMKEN_F0_OIL = {("deep_groove_ball", "619"): 1.7, ("deep_groove_ball", "60"): 1.7,
                 ("deep_groove_ball", "62"): 2.0, ("deep_groove_ball", "63"): 2.3,
                 ("angular_contact_ball", "72"): 2.0, ("angular_contact_ball", "73"): 3.0}
# KRW p. 117: (oil, grease) for 619/160/60 and 62/63/64.
KRW_F0 = {("deep_groove_ball", "619"): (1.75, 1.17), ("deep_groove_ball", "160"): (1.75, 1.17),
          ("deep_groove_ball", "60"): (1.75, 1.17), ("deep_groove_ball", "62"): (2.0, 1.34),
          ("deep_groove_ball", "63"): (2.0, 1.34), ("deep_groove_ball", "64"): (2.0, 1.34)}


@pytest.mark.parametrize(("key", "values"), list(HR1_F0.items()), ids=lambda v: str(v))
def test_f0_by_series_is_schaeffler_hr1(key, values):
    bearing_type, series = key
    grease, bath = values
    assert palmgren_f0(bearing_type, "grease", series) == grease
    assert palmgren_f0(bearing_type, "oil_mist", series) == grease  # same HR1 column
    assert palmgren_f0(bearing_type, "oil_bath", series) == bath
    assert palmgren_f0(bearing_type, "oil_jet", series) == bath  # "recirculating oil"


@pytest.mark.parametrize(("key", "oil"), list(TIMKEN_F0_OIL.items()), ids=lambda v: str(v))
def test_f0_oil_agrees_with_timken_table_114(key, oil):
    assert palmgren_f0(*key[:1], "oil_bath", key[1]) == pytest.approx(oil, rel=1e-12)


@pytest.mark.parametrize(("key", "values"), list(KRW_F0.items()), ids=lambda v: str(v))
def test_f0_agrees_with_krw_within_its_rounding(key, values):
    """KRW (DIN 732-2 draft) differs by at most 3 % (oil) and 6 % (grease) from HR1 for 619,
    160, 60 and 62; it groups 63 and 64 with 62 (oil 2, grease 1.34) where HR1 (and Timken, 03:
    2.3) give 2.3 and 1.5. The model uses HR1 because it is the only source with both columns for
    every series and with f1 and P1 for pairs (one consistent set)."""
    oil, grease = values
    bearing_type, series = key
    close = 0.06 if series in ("619", "160", "60", "62") else 0.15
    assert palmgren_f0(bearing_type, "oil_bath", series) == pytest.approx(oil, rel=close)
    assert palmgren_f0(bearing_type, "grease", series) == pytest.approx(grease, rel=close)


def test_the_study_bearings_get_the_619_row():
    for designation in ("61905", "61907", "61908", "61909"):
        assert get_bearing(designation).series == "619"
    assert get_bearing("6304").series == "63" and get_bearing("7014C").series == "70"
    # a series no catalogue row covers falls back to the per-type table (Harris & Kotzalas)
    assert palmgren_f0("deep_groove_ball", "oil_bath", None) == 2.0


# ------------------------------------------------------------------------------- Palmgren M0, M1
def test_m0_both_branches_as_hr1_timken_and_krw_print_them():
    """HR1 p. 55, Timken p. 184 and KRW p. 52 (German; the English p. 116 misprints the low
    branch): M0 = f0 (nu n)^(2/3) dm^3 1e-7 [N mm] for nu n >= 2000, else f0 160 1e-7 dm^3;
    nu in mm^2/s, n in r/min, dm in mm. 61905 (dm 33.5 mm), f0 1.7, nu 32 mm^2/s."""
    dm_mm, f0, nu = 33.5, 1.7, 32.0
    for rpm in (100.0, 10_000.0):
        expected_nmm = f0 * 1e-7 * dm_mm**3 * ((nu * rpm) ** (2 / 3) if nu * rpm >= 2000 else 160)
        m0 = palmgren_m0(nu * 1e-6, rpm * math.pi / 30, dm_mm * 1e-3, f0, smooth=False)
        assert float(m0) * 1e3 == pytest.approx(expected_nmm, rel=1e-12)


def test_f1_deep_groove_is_the_studys_and_differs_from_the_catalogues_for_619():
    """The double-layer study (docs/studies.md, section A) uses f1 = 0.0009 (P0/C0)^0.55, which the
    model keeps: the speed-ratio measurements it reproduces were fitted with it. HR1 p. 58 gives
    0.0009 (P0/C0)^0.5 for 62-64 and 0.0007 (P0/C0)^0.5 for 619 (KRW p. 117: 0.00089^0.53 and
    0.00067^0.5); Timken p. 184 a constant 0.00015 for series 39. Over P0/C0 in [0.01, 1] the
    model is 2 % to 29 % above HR1's 619 value."""
    ratios = np.logspace(-2, 0, 21)
    model = np.array([palmgren_f1("deep_groove_ball", r, 1.0) for r in ratios])
    assert model == pytest.approx(0.0009 * ratios**0.55, rel=1e-12)
    hr1_619 = 0.0007 * ratios**0.5
    excess = model / hr1_619 - 1.0
    assert excess.min() == pytest.approx(0.0091, abs=0.02)
    assert excess.max() == pytest.approx(0.2857, abs=1e-3)


def test_f1_angular_contact_and_self_aligning_are_hr1():
    """HR1 p. 59: angular contact (all single-row series, pairs, four-point) 0.001 (P0/C0)^0.33;
    self-aligning ball 0.0003 (P0/C0)^0.4."""
    for r in (0.02, 0.1, 0.5):
        assert palmgren_f1("angular_contact_ball", r, 1.0) == pytest.approx(0.001 * r**0.33)
        assert palmgren_f1("self_aligning_ball", r, 1.0) == pytest.approx(0.0003 * r**0.4)


def test_p1_deep_groove_is_timkens_form_which_krw_confirms():
    """Timken p. 184: P1 = max(0.9 Fa cot(a) - 0.1 Fr, Fr); with the default a = atan(0.3) it is
    3 Fa - 0.1 Fr, which KRW p. 117 implies (its limit Fr = 2.7 Fa is where 3 Fa - 0.1 Fr = Fr).
    HR1 p. 60 prints 3.3 Fa - 0.1 Fr (10 % more on the axial term): the model keeps the form
    whose contact angle can follow the load."""
    fr, fa = 100.0, 1000.0
    assert palmgren_p1(fr, fa, "deep_groove_ball") == pytest.approx(3.0 * fa - 0.1 * fr, rel=1e-3)
    limit = 2.7 * fa
    assert palmgren_p1(limit, fa, "deep_groove_ball") == pytest.approx(limit, rel=0.02)
    assert (3.3 * fa - 0.1 * fr) / (3.0 * fa - 0.1 * fr) == pytest.approx(1.10, abs=0.002)


def test_p1_angular_contact_single_row_is_hr1_and_krw():
    """HR1 p. 60 and KRW p. 117: P1 = Fa - 0.1 Fr, at least Fr."""
    assert palmgren_p1(100.0, 1000.0, "angular_contact_ball") == pytest.approx(990.0, rel=1e-3)
    assert palmgren_p1(1000.0, 100.0, "angular_contact_ball") == pytest.approx(1000.0, rel=1e-3)


# ------------------------------------------------------------------------------- ISO 281, ISO 76
GOST_18855_FC = (29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 56.6, 57.5, 58.2,
                 58.8, 59.3, 59.6, 59.8, 59.9, 60.0, 59.9, 59.8, 59.6, 59.3, 59.0, 58.6, 58.2,
                 57.7, 57.1, 56.6, 56.0, 55.3, 54.6, 53.9, 53.2, 52.4, 51.7, 50.9, 50.0, 49.2,
                 48.4)
"""GOST 18855-2013 Table 2: fc of single-row radial and angular contact ball bearings at
gamma = Dw cos(a) / dm = 0.01, 0.02, ..., 0.40."""
GOST_18854_F0 = (14.7, 14.9, 15.1, 15.3, 15.5, 15.7, 15.9, 16.1, 16.3, 16.5, 16.4, 16.1, 15.9,
                 15.6, 15.4, 15.2, 14.9, 14.7, 14.4, 14.2, 14.0, 13.7, 13.5, 13.2, 13.0, 12.8,
                 12.5, 12.3, 12.1, 11.8, 11.6, 11.4, 11.2, 10.9, 10.7, 10.5, 10.3, 10.0, 9.8, 9.6,
                 9.4)
"""GOST 18854-94 Table 1: f0 of radial and angular contact ball bearings at gamma = 0, ..., 0.40."""


@pytest.mark.parametrize("k", range(40))
def test_fc_is_gost_18855_table_2_at_every_hundredth(k):
    gamma = 0.01 * (k + 1)
    dm = 0.05
    c1 = life.dynamic_load_rating(gamma * dm, dm, 10)  # bm fc (i cos a)^0.7 Z^(2/3) Dw^1.8
    fc = c1 / (1.3 * 10 ** (2 / 3) * (gamma * dm * 1e3) ** 1.8)  # bm = 1.3, the default
    assert fc == pytest.approx(GOST_18855_FC[k], abs=1e-9)


@pytest.mark.parametrize("k", range(1, 41))
def test_f0_is_gost_18854_table_1_at_every_hundredth(k):
    gamma = 0.01 * k
    assert life.static_factor(gamma * 0.05, 0.05) == pytest.approx(GOST_18854_F0[k], abs=1e-9)


# GOST 18855-2013 Table 3 p. 9: alpha -> (e, X, Y single row for Fa/Fr > e; Y1 for Fa/Fr <= e,
# X2, Y2 double row)
GOST_18855_AC = {20: (0.57, 0.43, 1.00, 1.09, 0.70, 1.63), 25: (0.68, 0.41, 0.87, 0.92, 0.67, 1.41),
                 30: (0.80, 0.39, 0.76, 0.78, 0.63, 1.24), 35: (0.95, 0.37, 0.66, 0.66, 0.60, 1.07),
                 40: (1.14, 0.35, 0.57, 0.55, 0.57, 0.93), 45: (1.34, 0.33, 0.50, 0.47, 0.54, 0.81)}


@pytest.mark.parametrize(("alpha", "row"), list(GOST_18855_AC.items()))
def test_angular_contact_xy_e_are_gost_18855_table_3(alpha, row):
    e, x, y, y1, x2, y2 = row
    a = math.radians(alpha)
    c0, f0 = 10_000.0, 14.0
    heavy = life.xy_factors(100.0, 1000.0, c0, f0, a, rows=1)     # Fa/Fr = 10 > e
    light = life.xy_factors(1000.0, 100.0, c0, f0, a, rows=1)     # Fa/Fr = 0.1 <= e
    heavy2 = life.xy_factors(100.0, 1000.0, c0, f0, a, rows=2)
    light2 = life.xy_factors(1000.0, 100.0, c0, f0, a, rows=2)
    assert [float(v) for v in heavy] == pytest.approx([x, y, e])
    assert [float(v) for v in light] == pytest.approx([1.0, 0.0, e])
    assert [float(v) for v in heavy2] == pytest.approx([x2, y2, e])
    assert [float(v) for v in light2] == pytest.approx([1.0, y1, e])


def test_the_nsk_18_deg_row_is_the_iso_20_deg_row():
    """NSK super precision Table 1.1 p. 139 prints at 18 deg exactly GOST 18855's 20 deg row
    (e 0.57; X 0.43, Y 1.00; DB/DF Y1 1.09, X2 0.70, Y2 1.63): NSK applies the 20 deg factors to
    its 18 deg BNR series. bearingsim interpolates at 18 deg (15 deg factors depend on the
    relative axial load), so a user comparing with NSK enters 20 deg."""
    x20, y20, e20 = (float(v) for v in life.xy_factors(100.0, 1000.0, 1e4, 14.0,
                                                       math.radians(20.0)))
    assert (x20, y20, e20) == pytest.approx((0.43, 1.00, 0.57))
    x18, y18, e18 = (float(v) for v in life.xy_factors(100.0, 1000.0, 1e4, 14.0,
                                                       math.radians(18.0)))
    assert e18 < e20 and y18 > y20


def test_static_y0_are_gost_18854_table_2():
    """GOST 18854-94 Table 2 p. 5: single-row Y0 0.46, 0.42, 0.38, 0.33, 0.29, 0.26, 0.22 at 15,
    20, ..., 45 deg, X0 0.5; radial (deep groove) X0 0.6, Y0 0.5. NSK Table 2.1 p. 146 prints
    the 20 deg values under 18 deg (X0 0.5, Y0 0.42)."""
    import dataclasses

    g = get_bearing("7014C")
    for alpha, y0 in zip((15, 20, 25, 30, 35, 40, 45), (0.46, 0.42, 0.38, 0.33, 0.29, 0.26, 0.22),
                         strict=True):
        x0_, y0_ = life.static_load_factors(dataclasses.replace(g, contact_angle=math.radians(
            alpha)))
        assert (x0_, y0_) == pytest.approx((0.5, y0))
    assert life.static_load_factors(get_bearing("6304")) == pytest.approx((0.6, 0.5))
