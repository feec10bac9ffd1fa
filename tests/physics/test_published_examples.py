"""The physics library against values published by bearing manufacturers (issue 3, verification).

Sources (full text read in the issue-3 search; page numbers are the catalogues' own):

* NSK: *Rolling Bearings*, NSK CAT. No. E1102e. Section 5.7 "Examples of Bearing Calculations"
  (pp. A34-A36), the single-row deep groove ball bearing tables (pp. B8-B11) and the angular contact
  ball bearing tables (pp. B50-B61), each with its table of X, Y and e. NSK states that its
  ratings follow ISO 281 and ISO 76 (p. A32: "4 200 MPa for other ball bearings").
* SKF: *General Catalogue* 6000, Russian edition (data as of early 2006). "Calculation examples",
  Example 1 (pp. 78-79); "Friction", new SKF model: Tables 2a, 3 and 3a (pp. 91-93), inlet shear
  and starvation factors (pp. 97-98, Table 5), mixed-lubrication weighting (pp. 100-101) and the
  worked example of a 22208 E (pp. 104-105); deep groove ball bearing tables (pp. 302-308).

No published worked example of a Hertz point contact or of a Hamrock-Dowson film thickness could
be retrieved (Harris & Kotzalas and Hamrock's textbooks were not available in the search), so the
Hertz and film functions have no test here; see docs/physics.md, "Verification".
"""

import numpy as np
import pytest

from bearingsim.catalog import get_bearing
from bearingsim.physics import friction, life
from bearingsim.physics.lubricant import Oil
from bearingsim.units import rpm_to_rad_s

# NSK CAT. No. E1102e, pp. B8-B11: designation -> (Cr [N], C0r [N], f0 [-]).
NSK_DEEP_GROOVE = {
    "6204": (12800.0, 6600.0, 13.1),
    "6304": (15900.0, 7900.0, 12.4),
    "6205": (14000.0, 7850.0, 13.9),
    "6305": (20600.0, 11200.0, 13.2),
    "6206": (19500.0, 11300.0, 13.8),
}
# SKF General Catalogue 6000 (2006 data), pp. 304-308: designation -> (C [kN], C0 [kN],
# reference speed [r/min], limiting speed [r/min]).
SKF_DEEP_GROOVE = {
    "6204": (13.5, 6.55, 32000.0, 20000.0),
    "6304": (16.8, 7.8, 30000.0, 19000.0),
    "6205": (14.8, 7.8, 28000.0, 18000.0),
    "6305": (23.4, 11.6, 24000.0, 16000.0),
    "6206": (20.3, 11.2, 24000.0, 15000.0),
    "61905": (7.02, 4.3, 36000.0, 22000.0),
    "61907": (9.56, 6.8, 26000.0, 16000.0),
    "61908": (13.8, 10.0, 24000.0, 14000.0),
    "61909": (14.0, 10.8, 20000.0, 13000.0),
}
# Rows whose ball complement is not estimated (bearingsim.catalog); NSK's C0r / f0 = Z Dw^2 agrees
# with it within 0.4 % for each (6204: 503.8 vs 504.1 mm^2).
MEASURED_BALL_SETS = ["6204", "6205", "6206", "6304"]


@pytest.mark.parametrize("name", sorted(NSK_DEEP_GROOVE))
def test_catalogue_c_c0_are_nsk_values(name):
    """bearings.csv carries the NSK ratings of the 62/63 rows (NSK CAT. No. E1102e, pp. B8-B11,
    single-row deep groove ball bearings, columns Cr, C0r)."""
    g = get_bearing(name)
    cr, c0r, _ = NSK_DEEP_GROOVE[name]
    assert g.dynamic_load_rating == pytest.approx(cr, abs=0.5)
    assert g.static_load_rating == pytest.approx(c0r, abs=0.5)


@pytest.mark.parametrize("name", sorted(SKF_DEEP_GROOVE))
def test_catalogue_speeds_and_619_ratings_are_skf_values(name):
    """Reference and limiting speeds of every deep-groove row, and C, C0 of the 619 rows, are the
    SKF General Catalogue 6000 values (Russian edition, 2006 data, pp. 304-308, columns
    "номинальная"/"предельная" частота вращения). The 62/63 rows carry NSK's C, C0 instead (SKF's
    Explorer ratings exceed plain ISO 281, see test_life.py)."""
    g = get_bearing(name)
    c, c0, ref, lim = SKF_DEEP_GROOVE[name]
    assert g.reference_speed == pytest.approx(rpm_to_rad_s(ref), rel=1e-12)
    assert g.limiting_speed == pytest.approx(rpm_to_rad_s(lim), rel=1e-12)
    if name.startswith("619"):
        assert g.dynamic_load_rating == pytest.approx(c * 1e3, abs=0.5)
        assert g.static_load_rating == pytest.approx(c0 * 1e3, abs=0.5)


@pytest.mark.parametrize("name", MEASURED_BALL_SETS)
def test_iso281_c_reproduces_nsk_rating(name):
    """ISO 281 C = bm fc (i cos a)^0.7 Z^(2/3) Dw^1.8 (bm 1.3, fc interpolated in our Table 2) from
    the row's geometry reproduces NSK's Cr (NSK CAT. No. E1102e, pp. B8-B11) within 0.5 %
    (found: 6204 -0.05 %, 6205 +0.1 %, 6206 -0.3 %, 6304 +0.1 %). With these ball sets (Dw/dm
    0.20 to 0.26) this checks fc between 0.20 and 0.26 and the formula; NSK prints Cr to three
    figures."""
    g = get_bearing(name)
    c = life.dynamic_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count)
    assert c == pytest.approx(NSK_DEEP_GROOVE[name][0], rel=0.005)


@pytest.mark.parametrize("name", MEASURED_BALL_SETS)
def test_iso76_f0_and_c0_reproduce_nsk(name):
    """ISO 76 f0 at the row's Dw/dm equals the f0 NSK prints (NSK CAT. No. E1102e, pp. B8-B11,
    column "Factor f0", one decimal) within its rounding of 0.05, and C0 = f0 Z Dw^2 reproduces
    NSK's C0r within 0.5 %. The rows' pitch diameters are estimates good to about 1 %, which moves
    f0 by at most 0.05 here."""
    g = get_bearing(name)
    _, c0r, f0 = NSK_DEEP_GROOVE[name]
    assert life.static_factor(g.ball_diameter, g.pitch_diameter) == pytest.approx(f0, abs=0.05)
    c0 = life.static_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count)
    assert c0 == pytest.approx(c0r, rel=0.005)


def test_nsk_example_1_rating_life_6208():
    """NSK CAT. No. E1102e, p. A34, Example 1: deep groove ball bearing 6208 (Cr = 29 100 N) under
    Fr = 2 500 N at 900 r/min: fn = 0.333, fh = fn Cr/P = 3.88, "approximately 29 000 hours".
    With Lh = 500 fh^3 (NSK Table 5.2) our L10 in hours gives fh = 3.880."""
    l10 = life.rating_life(29100.0, 2500.0)
    hours = life.life_hours(l10, rpm_to_rad_s(900.0))
    assert (hours / 500.0) ** (1.0 / 3.0) == pytest.approx(3.88, abs=0.005)
    assert hours == pytest.approx(29000.0, rel=0.01)


def test_nsk_example_3_equivalent_load_6208():
    """NSK CAT. No. E1102e, p. A34, Example 3: 6208 with Fr = 2 500 N, Fa = 1 000 N, f0 = 14.0,
    C0r = 17 900 N: f0 Fa/C0r = 0.782, e about 0.26, Fa/Fr = 0.4 > e, X = 0.56, Y = 1.67 (linear
    interpolation in the table), P = 3 070 N, Cr/P = 9.48. Found: Y 1.666, e 0.265, P 3 066 N."""
    fr, fa, c0r, f0 = 2500.0, 1000.0, 17900.0, 14.0
    x, y, e = life.xy_factors(fr, fa, c0r, f0)
    assert float(x) == pytest.approx(0.56, abs=1e-12)
    assert float(y) == pytest.approx(1.67, abs=0.005)
    assert float(e) == pytest.approx(0.26, abs=0.01)
    p = life.equivalent_dynamic_load(fr, fa, c0r, f0)
    assert float(p) == pytest.approx(3070.0, rel=0.002)
    assert 29100.0 / float(p) == pytest.approx(9.48, rel=0.002)


def test_skf_example_1_rating_life_6309():
    """SKF General Catalogue 6000 (2006 data), p. 78, Example 1: SKF Explorer 6309, C = 55.3 kN,
    P = Fr = 10 kN, 3 000 r/min: L10 = (55.3/10)^3 = 169 million revolutions,
    L10h = 10^6/(60 * 3 000) * 169 = 940 operating hours."""
    l10 = life.rating_life(55.3e3, 10e3)
    assert l10 == pytest.approx(169.0, abs=0.5)
    assert life.life_hours(l10, rpm_to_rad_s(3000.0)) == pytest.approx(940.0, abs=1.0)


# NSK CAT. No. E1102e, table of X, Y, e above every single-row deep groove table (pp. B8-B11), the
# rows of ISO 281 Table 3 for radial contact groove ball bearings: (f0 Fa/C0r, e, Y), X = 0.56.
NSK_DEEP_GROOVE_XY = [
    (0.172, 0.19, 2.30), (0.345, 0.22, 1.99), (0.689, 0.26, 1.71), (1.03, 0.28, 1.55),
    (1.38, 0.30, 1.45), (2.07, 0.34, 1.31), (3.45, 0.38, 1.15), (5.17, 0.42, 1.04),
    (6.89, 0.44, 1.00),
]


@pytest.mark.parametrize(("relative", "e_pub", "y_pub"), NSK_DEEP_GROOVE_XY)
def test_xy_deep_groove_rows_are_nsk_table(relative, e_pub, y_pub):
    """Every row of the deep-groove X, Y, e table (NSK CAT. No. E1102e, pp. B8-B11): for
    Fa/Fr > e, X = 0.56 and Y as printed; for Fa/Fr <= e, X = 1, Y = 0."""
    c0, f0 = 10000.0, 14.0
    fa = relative * c0 / f0
    x, y, e = life.xy_factors(0.5 * fa, fa, c0, f0)
    assert (float(x), float(y), float(e)) == pytest.approx((0.56, y_pub, e_pub), abs=1e-9)
    x, y, _ = life.xy_factors(fa / (0.99 * e_pub), fa, c0, f0)
    assert (float(x), float(y)) == (1.0, 0.0)


# NSK CAT. No. E1102e, X, Y, e of single-row (and DT) angular contact ball bearings, pp. B50-B61.
# 15 deg: (i f0 Fa/C0r, e, Y), X = 0.44.
NSK_AC15_XY = [
    (0.178, 0.38, 1.47), (0.357, 0.40, 1.40), (0.714, 0.43, 1.30), (1.07, 0.46, 1.23),
    (1.43, 0.47, 1.19), (2.14, 0.50, 1.12), (3.57, 0.55, 1.02), (5.35, 0.56, 1.00),
]
# 25, 30, 40 deg: (alpha, e, X, Y).
NSK_AC_FIXED = [(25.0, 0.68, 0.41, 0.87), (30.0, 0.80, 0.39, 0.76), (40.0, 1.14, 0.35, 0.57)]


@pytest.mark.parametrize(("relative", "e_pub", "y_pub"), NSK_AC15_XY)
def test_xy_angular_contact_15_deg_rows_are_nsk_table(relative, e_pub, y_pub):
    """15 deg single-row angular contact rows (NSK CAT. No. E1102e, pp. B50-B61, "Single, DT",
    Fa/Fr > e): X = 0.44 and e, Y as printed."""
    c0, f0 = 10000.0, 14.0
    fa = relative * c0 / f0
    x, y, e = life.xy_factors(0.1 * fa, fa, c0, f0, np.radians(15.0))
    assert (float(x), float(y), float(e)) == pytest.approx((0.44, y_pub, e_pub), abs=1e-9)


@pytest.mark.parametrize(("alpha", "e_pub", "x_pub", "y_pub"), NSK_AC_FIXED)
def test_xy_angular_contact_fixed_rows_are_nsk_table(alpha, e_pub, x_pub, y_pub):
    """25, 30 and 40 deg single-row angular contact rows (NSK CAT. No. E1102e, pp. B50-B61)."""
    x, y, e = life.xy_factors(100.0, 1000.0, 10000.0, 14.0, np.radians(alpha))
    assert (float(x), float(y), float(e)) == pytest.approx((x_pub, y_pub, e_pub), abs=1e-9)


@pytest.mark.parametrize("alpha_deg", [0.0, 15.0, 25.0, 40.0])
def test_raceway_ratings_invert_iso281_rating(alpha_deg):
    """The contact-angle exponent question of ISO/TS 16281. ISO 281 (formula as published, also
    in ISO/TR 1281-1) rates C = bm fc(gamma) (i cos a)^0.7 Z^(2/3) Dw^1.8 with gamma = Dw cos(a)/dm.
    Lundberg-Palmgren's raceway capacity Q_c (Harris & Kotzalas) carries (Dw/dm)^0.3 =
    gamma^0.3 cos(a)^-0.3, and C = 0.407 Z Q_c i^0.7 cos(a) (1 + x^(10/3))^-0.3, so ISO 281's
    (cos a)^0.7 is cos(a) times the cos(a)^-0.3 hidden in fc(gamma). The ball load rating that
    inverts C is therefore Q_c = C (1 + x^(10/3))^0.3 / (0.407 Z i^0.7 cos a), which is what
    raceway_dynamic_ratings uses. Checked here: the ratio of that Q_c to the Lundberg-Palmgren
    capacity does not depend on the contact angle (to 1e-12); dividing by (i cos a)^0.7 instead
    would make it vary as cos(a)^0.3 (1.0 % at 15 deg, 2.9 % at 25 deg, 7.7 % at 40 deg). The
    ratio itself, 1.244 (inner) and 1.245 (outer), is ISO 281's bm = 1.3 within 4.5 %
    (test_life.py).
    What ISO/TS 16281 prints was not retrievable; this settles only which form is consistent with
    ISO 281 and Lundberg-Palmgren."""
    dw, gamma, z = 10e-3, 0.2, 12
    ratios = []
    for angle in (0.0, np.radians(alpha_deg)):
        dm = dw * np.cos(angle) / gamma
        c = life.dynamic_load_rating(dw, dm, z, angle)
        qci, qce = life.raceway_dynamic_ratings(c, 0.52, 0.52, gamma, z, angle)
        lp_i = life.raceway_contact_capacity(dw, dm, 0.52, z, angle, "inner")
        lp_e = life.raceway_contact_capacity(dw, dm, 0.52, z, angle, "outer")
        ratios.append((qci / lp_i, qce / lp_e))
    assert ratios[1] == pytest.approx(ratios[0], rel=1e-12)
    assert ratios[0] == pytest.approx((1.244, 1.245), abs=1e-3)


# SKF General Catalogue 6000 (2006 data), Table 3a, p. 93: deep groove ball bearings.
SKF_TABLE_3A = {
    ("2", "3"): (4.4e-7, 1.7, 2.00e-3, 100.0),
    ("42",): (5.4e-7, 0.96, 3.00e-3, 40.0),
    ("60",): (4.1e-7, 1.7, 3.73e-3, 14.6),
    ("62",): (3.9e-7, 1.7, 3.23e-3, 36.5),
    ("63",): (3.7e-7, 1.7, 2.84e-3, 92.8),
    ("64",): (3.6e-7, 1.7, 2.43e-3, 198.0),
    ("160",): (4.3e-7, 1.7, 4.63e-3, 4.25),
    ("618",): (4.7e-7, 1.7, 6.50e-3, 0.78),
    ("619",): (4.3e-7, 1.7, 4.75e-3, 3.6),
}


@pytest.mark.parametrize(("series", "row"), sorted(SKF_TABLE_3A.items()))
def test_skf_deep_groove_geometry_constants(series, row):
    """R1, R2, S1, S2 of the SKF model for deep groove ball bearings equal SKF General Catalogue
    6000 (2006 data), Table 3a, p. 93 (rows "2, 3", "42, 43", "60, 630", "62, 622", "63, 623", "64",
    "160, 161", "617, 618, 628, 637, 638", "619, 639")."""
    for key in series:
        c = friction.SKF_DEEP_GROOVE[key]
        assert (c["R1"], c["R2"], c["S1"], c["S2"]) == row


def test_skf_angular_contact_single_row_constants():
    """SKF General Catalogue 6000 (2006 data), Table 3, p. 92: single-row angular contact ball
    bearings (one row for all series) R1 5.03e-7, R2 1.97, R3 1.90e-12, S1 1.30e-2, S2 0.68,
    S3 1.91e-12, our "72B" row. (The "73B" row has no counterpart there and stays unverified.)"""
    c = friction.SKF_ANGULAR_CONTACT["72B"]
    assert (c["R1"], c["R2"], c["R3"], c["S1"], c["S2"], c["S3"]) == (
        5.03e-7, 1.97, 1.90e-12, 1.30e-2, 0.68, 1.91e-12)


def test_skf_replenishment_constants():
    """SKF General Catalogue 6000 (2006 data), p. 98: Krs = 3e-8 for a low oil level bath and oil
    jet, 6e-8 for grease and oil-air; Table 5: Kz = 3.1 for deep groove ball bearings, 4.4 for
    single-row angular contact ball bearings."""
    assert friction.SKF_KRS["oil_bath"] == friction.SKF_KRS["oil_jet"] == 3e-8
    assert friction.SKF_KRS["grease"] == friction.SKF_KRS["oil_mist"] == 6e-8
    assert friction.SKF_KZ == {"deep_groove_ball": 3.1, "angular_contact_ball": 4.4}


# The 22208 E worked example: d = 40 mm, D = 80 mm (dm = 60 mm), 3 500 r/min, oil bath, mineral oil
# with nu = 68 mm^2/s at the operating temperature of 40 degC.
VG68_AT_40C = Oil.from_iso_vg(68, temperature=313.15)


def _example_22208e():
    # C0 enters only the axial-load branch of Grr/Gsl, not the factors checked here.
    return friction.skf_friction_components(
        rpm_to_rad_s(3500.0), 0.060, VG68_AT_40C, "62", 2990.0, 100.0,
        C0=90e3, d=0.040, D=0.080)


def test_skf_example_22208e_inlet_shear_factor():
    """SKF General Catalogue 6000 (2006 data), p. 104, worked example (spherical roller bearing
    22208 E, n = 3 500 r/min, dm = 60 mm, nu = 68 mm^2/s): phi_ish =
    1/(1 + 1.84e-9 (n dm)^1.28 nu^0.64) "approximately 0.85". The factor does not depend on the
    bearing type, so our deep-groove implementation must give it (found 0.849). The same example
    assumes full film (kappa > 2) and mu_sl = 0.05 for mineral oil: our weighting phi_bl vanishes
    here and mu_sl equals the Oil default mu_EHL = 0.05 (p. 101)."""
    assert VG68_AT_40C.kinematic_viscosity() == pytest.approx(68e-6, rel=1e-9)
    parts = _example_22208e()
    assert float(parts.phi_ish) == pytest.approx(0.85, abs=0.005)
    assert float(parts.phi_bl) < 1e-6
    assert float(parts.mu_sl) == pytest.approx(0.05, abs=1e-9)


def test_skf_example_22208e_starvation_factor(monkeypatch):
    """SKF General Catalogue 6000 (2006 data), p. 105, same example: phi_rs =
    1/e^(Krs nu n (d + D) sqrt(Kz / (2 (D - d)))) with Krs = 3e-8 (oil bath), Kz = 5.5 (spherical
    roller bearings, Table 5), "approximately 0.8". Our model has Kz only for ball bearings, so the
    formula is checked by giving the deep-groove entry the example's Kz (found 0.799)."""
    monkeypatch.setitem(friction.SKF_KZ, "deep_groove_ball", 5.5)
    assert float(_example_22208e().phi_rs) == pytest.approx(0.8, abs=0.01)
