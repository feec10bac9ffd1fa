"""Physics tables and catalogue rows against published tables (issue 3, verification, part 2).

Sources (full text read in the GitHub repository ArtemFilin1990/Mar; page numbers are the
documents' own):

* Koyo: *Ball & Roller Bearings, Popular Size*, CAT. NO. 203E-1 (1997), angular contact ball
  bearings, table of X, Y and e, p. B20 (``07_Бренды_и_каталоги/Бренды/каталоги/
  Каталог_шариковых_и_роликовых_подшипников_KOYO.md.txt``).
* SKF: *General Catalogue* 6000, Russian edition (data as of 2006), double row angular contact ball
  bearings, Table 3 "calculation factors", p. 440, and four-point contact ball bearings,
  "equivalent dynamic bearing load", p. 455 (``.../Общий_каталог_подшипников_SKF.md.txt``).
* GMN: *High precision ball bearings*, publication 4000 0813 EN, spindle ball bearing data
  pp. 38-39 (65 to 75 mm) and 42-43 (100 to 120 mm), deep groove ball bearing data pp. 54-55
  (``output_md/GMN_Paul_Müller_Industrie_GmbH_Co._KG.md``). GMN prints the ball set (dm, Dw, Z)
  next to C, C0 and the speeds, which no other retrieved catalogue does.
* NTN-SNR: *NTN ULTAGE* precision range (Russian edition), p. 4
  (``.../Каталог_высокопрецизионных_подшипников_NTN_серии_ULTAGE.md.txt``).

The single-row X, Y of 35 and 45 deg are checked indirectly, through SKF's printed double-row
factors and ISO 281's factor 2^0.7 between double- and single-row X, Y for Fa/Fr > e
(test_single_row_xy_from_skf_double_row_factors). Still unverified (no retrieved source prints
them): the single-row X, Y and e of 20 deg (ISO 281 Table 3), the Palmgren f0/f1 tables and the
SKF "73B" constants; see docs/physics.md, "Verification".
"""

import math

import numpy as np
import pytest

from bearingsim.catalog import get_bearing
from bearingsim.physics import life
from bearingsim.units import rpm_to_rad_s

# ISO 281 abscissae i f0 Fa/C0r of the 15 deg rows (the first eight confirmed by NSK CAT. No.
# E1102e, tests/physics/test_published_examples.py).
ISO_AC15_LOAD = (0.178, 0.357, 0.714, 1.07, 1.43, 2.14, 3.57, 5.35, 7.14)
# Koyo CAT. NO. 203E-1, p. B20, 15 deg, single row and tandem, Fa/Fr > e: (e, Y) of the nine rows
# (printed over Fa/C0r = 0.015, 0.029, 0.058, 0.087, 0.12, 0.17, 0.29, 0.44, 0.58), X = 0.44.
KOYO_AC15 = [(0.38, 1.47), (0.40, 1.40), (0.43, 1.30), (0.46, 1.23), (0.47, 1.19), (0.50, 1.12),
             (0.55, 1.02), (0.56, 1.00), (0.56, 1.00)]


@pytest.mark.parametrize(("relative", "row"), list(zip(ISO_AC15_LOAD, KOYO_AC15, strict=True)))
def test_xy_15_deg_rows_are_koyo_table(relative, row):
    """All nine 15 deg rows, including the last one (Fa/C0r = 0.58, i.e. i f0 Fa/C0r = 7.14) that
    NSK does not print: Koyo CAT. NO. 203E-1 (1997), p. B20, single row, Fa/Fr > e: X = 0.44 and
    e, Y as printed. Koyo tabulates over Fa/C0r (the older ISO 281 abscissa), NSK and ISO 281:2007
    over i f0 Fa/C0r; the (e, Y) sequences are the same row for row."""
    e_pub, y_pub = row
    c0, f0 = 10000.0, 14.0
    fa = relative * c0 / f0
    x, y, e = life.xy_factors(0.1 * fa, fa, c0, f0, np.radians(15.0))
    assert (float(x), float(y), float(e)) == pytest.approx((0.44, y_pub, e_pub), abs=1e-9)


@pytest.mark.parametrize(("alpha", "e_pub", "x_pub", "y_pub"),
                         [(30.0, 0.80, 0.39, 0.76), (40.0, 1.14, 0.35, 0.57)])
def test_xy_30_40_deg_are_koyo_table(alpha, e_pub, x_pub, y_pub):
    """Koyo CAT. NO. 203E-1, p. B20, single row: 30 deg e 0.80, X 0.39, Y 0.76; 40 deg e 1.14,
    X 0.35, Y 0.57 (a second catalogue besides NSK E1102e); below e, X = 1, Y = 0."""
    x, y, e = life.xy_factors(100.0, 1000.0, 10000.0, 14.0, np.radians(alpha))
    assert (float(x), float(y), float(e)) == pytest.approx((x_pub, y_pub, e_pub), abs=1e-9)
    x, y, _ = life.xy_factors(1000.0 / (0.99 * e_pub), 1000.0, 10000.0, 14.0, np.radians(alpha))
    assert (float(x), float(y)) == (1.0, 0.0)


@pytest.mark.parametrize(("alpha", "e_pub"), [(30.0, 0.8), (40.0, 1.14), (45.0, 1.34)])
def test_xy_limit_e_matches_skf_double_row_table(alpha, e_pub):
    """SKF General Catalogue 6000 (2006 data), p. 440, Table 3 (double row angular contact ball
    bearings): e = 0.8 for 32 A/33 A (30 deg), 1.14 for 33 DNRCBM (40 deg) and 1.34 for 33 D
    (45 deg). ISO 281 Table 3 has a single e column for single- and double-row bearings from
    20 deg up, so the 45 deg e of our single-row table must be 1.34. (SKF's X, Y there are the
    double-row factors, which our single-row table does not hold; the single-row X, Y follow from
    them in test_single_row_xy_from_skf_double_row_factors.)"""
    _, _, e = life.xy_factors(100.0, 1000.0, 10000.0, 14.0, np.radians(alpha))
    assert float(e) == pytest.approx(e_pub, abs=1e-9)


# GMN 4000 0813 EN: designation -> (catalogue row, dm [mm], Dw [mm], Z, alpha [deg], C [N],
# C0 [N], speed with oil [r/min]); pp. 38-39.
GMN_SPINDLE = {
    "7014C": ("S 6014 C TA", 90.0, 11.906, 21, 15.0, 48500.0, 46000.0, 19000.0),
    "7014AC": ("S 6014 E TA", 90.0, 11.906, 21, 25.0, 46000.0, 43500.0, 16000.0),
}


@pytest.mark.parametrize("name", sorted(GMN_SPINDLE))
def test_7014_rows_are_gmn_spindle_bearings(name):
    """bearings.csv carries GMN's ball set, ratings and oil speed for the 7014 rows: GMN High
    precision ball bearings (4000 0813 EN), pp. 38-39, S 6014 C TA (15 deg) and S 6014 E TA
    (25 deg): dm 90 mm, Dw 11.906 mm, Z 21; C 48 500 / 46 000 N, C0 46 000 / 43 500 N, speed with
    oil lubrication 19 000 / 16 000 r/min (stored as the limiting speed). The previous estimate
    (Z 18, Dw 11.112 mm) gave an ISO 281 C of 38 kN, 21 % below the catalogue."""
    _, dm, dw, z, alpha, c, c0, n_oil = GMN_SPINDLE[name]
    g = get_bearing(name)
    assert (g.ball_count, g.ball_diameter, g.pitch_diameter) == pytest.approx(
        (z, dw * 1e-3, dm * 1e-3), rel=1e-12)
    assert math.degrees(g.contact_angle) == pytest.approx(alpha)
    assert (g.dynamic_load_rating, g.static_load_rating) == pytest.approx((c, c0), abs=0.5)
    assert g.limiting_speed == pytest.approx(rpm_to_rad_s(n_oil), rel=1e-12)
    assert g.reference_speed is None
    assert not {"Z", "Dw", "dm"} & set(g.estimated)


@pytest.mark.parametrize("name", sorted(GMN_SPINDLE))
def test_iso281_c_reproduces_gmn_7014_rating(name):
    """ISO 281 C = bm fc (i cos a)^0.7 Z^(2/3) Dw^1.8 from GMN's printed ball set reproduces GMN's C
    within 0.5 % (found -0.2 % at 15 deg, -0.3 % at 25 deg; GMN pp. 38-39), which checks the
    angular-contact branch of dynamic_load_rating (fc at Dw cos a/dm = 0.128 and 0.120) against a
    published rating with a published ball set. ISO 76 C0 = f0 Z Dw^2 cos a is 2.1 % and 1.4 %
    below GMN's C0; NTN prints C0r = 45.0 kN for 7014UCG (ULTAGE p. 4), 0.1 % from our 45.05 kN."""
    _, dm, dw, z, alpha, c, c0, _ = GMN_SPINDLE[name]
    a = np.radians(alpha)
    assert life.dynamic_load_rating(dw * 1e-3, dm * 1e-3, z, a) == pytest.approx(c, rel=0.005)
    assert life.static_load_rating(dw * 1e-3, dm * 1e-3, z, a) == pytest.approx(c0, rel=0.025)


def test_iso76_c0_of_gmn_7014_ball_set_matches_ntn():
    """NTN ULTAGE 7014UCG/GNP42 (15 deg), NTN-SNR precision range, p. 4: C0r 45 kN, Cr 48.5 kN (the
    same Cr as GMN). ISO 76 C0 of the GMN ball set (21 x 11.906 mm on 90 mm, 15 deg) is 45.05 kN."""
    c0 = life.static_load_rating(11.906e-3, 90e-3, 21, np.radians(15.0))
    assert c0 == pytest.approx(45.0e3, rel=0.005)


def test_7020_gmn_ball_set_differs_from_models_md():
    """Why the 7020 rows carry no C, C0: GMN (4000 0813 EN, pp. 42-43) builds S 6020 C/E TA with
    22 balls of 15.081 mm on 125 mm and rates them 78.0/74.0 kN; our 7020 geometry (models.md
    section B: 20 x 14.288 mm on 125.25 mm) has an ISO 281 C of 63.4 kN at 15 deg, 19 % lower. The
    catalogue ratings belong to a different ball set and would be inconsistent with the geometry
    the simulation uses."""
    g = get_bearing("7020C")
    assert g.dynamic_load_rating is None and g.static_load_rating is None
    ours = life.dynamic_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count,
                                    g.contact_angle)
    gmn = life.dynamic_load_rating(15.081e-3, 125e-3, 22, np.radians(15.0))
    assert ours == pytest.approx(63.4e3, rel=0.005)
    assert ours / 78.0e3 < 0.85
    # GMN's own ball set comes within 4 % of GMN's C (75.3 kN computed).
    assert gmn == pytest.approx(78.0e3, rel=0.04)


# GMN 4000 0813 EN, pp. 54-55, deep groove ball bearings: designation -> (dm [mm], Dw [mm], Z).
GMN_DEEP_GROOVE = {"6204": (33.5, 7.938, 8), "6205": (39.1, 7.938, 9), "6206": (46.0, 9.525, 9)}


@pytest.mark.parametrize("name", sorted(GMN_DEEP_GROOVE))
def test_deep_groove_ball_sets_match_gmn(name):
    """GMN High precision ball bearings (4000 0813 EN), pp. 54-55, deep groove ball bearings,
    columns dm, Dw, Z: 6204 33.5 mm, 7.938 mm, 8; 6205 39.1 mm, 7.938 mm, 9; 6206 46.0 mm,
    9.525 mm, 9. Ball count and ball diameter agree exactly; the pitch diameters within 0.1 mm
    (6205 carries the measured 39.04 mm of the CWRU data; 6206's formerly estimated 46 mm is
    GMN's value)."""
    dm, dw, z = GMN_DEEP_GROOVE[name]
    g = get_bearing(name)
    assert g.ball_count == z
    assert g.ball_diameter == pytest.approx(dw * 1e-3, rel=1e-12)
    assert g.pitch_diameter == pytest.approx(dm * 1e-3, abs=0.1e-3)
    assert "dm" not in g.estimated


def test_xy_limit_e_35_deg_matches_skf_four_point_contact():
    """SKF General Catalogue 6000 (2006 data), p. 455, four-point contact ball bearings QJ 2/QJ 3,
    contact angle 35 deg (p. 452): P = Fr + 0.66 Fa when Fa/Fr <= 0.95 and P = 0.6 Fr + 1.07 Fa
    when Fa/Fr > 0.95. These are ISO 281's double-row factors at 35 deg (four-point contact
    bearings are rated as double row), and ISO 281 Table 3 has one e column for single and double
    row from 20 deg up, so the 35 deg e of our single-row table must be 0.95. (The single-row
    X = 0.37, Y = 0.66 at 35 deg are not printed there; they follow from the double-row 0.6, 1.07
    in test_single_row_xy_from_skf_double_row_factors.)"""
    _, _, e = life.xy_factors(100.0, 1000.0, 10000.0, 14.0, np.radians(35.0))
    assert float(e) == pytest.approx(0.95, abs=1e-9)
    # The switch between X = 1, Y = 0 and the heavy-axial factors sits at SKF's Fa/Fr = 0.95.
    x_below, y_below, _ = life.xy_factors(1000.0 / 0.94, 1000.0, 10000.0, 14.0, np.radians(35.0))
    x_above, y_above, _ = life.xy_factors(1000.0 / 0.96, 1000.0, 10000.0, 14.0, np.radians(35.0))
    assert (float(x_below), float(y_below)) == (1.0, 0.0)
    assert (float(x_above), float(y_above)) != (1.0, 0.0)


# ISO 281: double-row X, Y for Fa/Fr > e are the single-row ones times i^0.7 = 2^0.7.
DOUBLE_ROW_FACTOR = 2.0**0.7
# Printed double-row factors for Fa/Fr > e: alpha [deg] -> (SKF series, page, e, X, Y2).
SKF_DOUBLE_ROW = {
    30.0: ("32 A/33 A", 440, 0.80, 0.63, 1.24),
    35.0: ("QJ 2/QJ 3", 455, 0.95, 0.60, 1.07),
    40.0: ("33 DNRCBM", 440, 1.14, 0.57, 0.93),
    45.0: ("33 D", 440, 1.34, 0.54, 0.81),
}


def _single_from_double(single, double):
    """True if a two-decimal single-row factor is consistent with a two-decimal double-row one:
    the double row rounds 2^0.7 times the unrounded single-row value, so
    |double - 2^0.7 single| <= 0.005 + 2^0.7 * 0.005, and the single-row value is the nearest
    two-decimal number to double / 2^0.7."""
    k = DOUBLE_ROW_FACTOR
    return (abs(double - k * single) <= 0.005 + k * 0.005 + 1e-12
            and round(double / k, 2) == round(single, 2))


@pytest.mark.parametrize("alpha", sorted(SKF_DOUBLE_ROW))
def test_single_row_xy_from_skf_double_row_factors(alpha):
    """Single-row X, Y (Fa/Fr > e) of our ISO 281 table against SKF's printed double-row factors,
    SKF General Catalogue 6000, Russian edition (2006 data):

    * p. 440, Table 3 "calculation factors for double row angular contact ball bearings"
      (P = Fr + Y1 Fa for Fa/Fr <= e, P = X Fr + Y2 Fa for Fa/Fr > e; columns e, X, Y1, Y2, Y0):
      32 A (52 A) and 33 A (53 A), 30 deg (p. 435): 0.8, 0.63, 0.78, 1.24, 0.66;
      33 DNRCBM, 40 deg (p. 436): 1.14, 0.57, 0.55, 0.93, 0.52;
      33 D, 45 deg (p. 436): 1.34, 0.54, 0.47, 0.81, 0.44.
    * p. 455, four-point contact ball bearings QJ 2/QJ 3, 35 deg (p. 452), rated as double row:
      P = Fr + 0.66 Fa for Fa/Fr <= 0.95, P = 0.6 Fr + 1.07 Fa for Fa/Fr > 0.95.

    The relation used is ISO 281's structure (from knowledge of the standard, not read here):
    for Fa/Fr > e the double-row X, Y are the single-row ones times i^0.7 = 2^0.7 = 1.6245, the
    i^0.7 of the rating. It is demonstrated by this same test on 30 and 40 deg, whose single-row
    values NSK E1102e and Koyo 203E-1 print. At 30 deg the printed Y2 1.24 is 0.0054 above
    1.6245 x 0.76 = 1.2346, so the double-row numbers come from the unrounded single-row ones and
    the tolerance must include the single-row rounding: |double - 2^0.7 single| <= 0.005 +
    2^0.7 x 0.005 = 0.013; in addition the single-row value must be the nearest two-decimal
    number to double / 2^0.7. Found: 35 deg X 0.60/1.6245 = 0.369 (0.37), Y 1.07/1.6245 = 0.659
    (0.66); 45 deg X 0.54/1.6245 = 0.332 (0.33), Y 0.81/1.6245 = 0.499 (0.50). The double-row
    values are known to +-0.005, so the unrounded X1, Y1 to +-0.0031: 45 deg X in [0.3293, 0.3355]
    (0.34 only if it were in [0.3350, 0.3355]), Y in [0.4955, 0.5017]; 35 deg X in
    [0.3663, 0.3724], Y in [0.6556, 0.6617]; our two-decimal values add +-0.005. SKF's
    "0,6" is taken as 0.60 (SKF drops trailing zeros, e.g. e "0,8" for 30 deg, ISO 0.80). One
    e column serves single and double row, so e is compared too. A neighbour 0.01 away from each
    of our values fails the check, so the test pins the two-decimal values.
    """
    series, page, e_pub, x2, y2 = SKF_DOUBLE_ROW[alpha]
    x1, y1, e = life.xy_factors(100.0, 1000.0, 10000.0, 14.0, np.radians(alpha))
    x1, y1 = float(x1), float(y1)
    assert float(e) == pytest.approx(e_pub, abs=1e-9), (series, page)
    assert _single_from_double(x1, x2), (series, page, x1, x2)
    assert _single_from_double(y1, y2), (series, page, y1, y2)
    for step in (-0.01, 0.01):
        assert not _single_from_double(x1 + step, x2), (series, x1 + step)
        assert not _single_from_double(y1 + step, y2), (series, y1 + step)
