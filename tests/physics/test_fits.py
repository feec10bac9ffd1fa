"""Mounting fits and operating clearance (issue 15 item 5) against the catalogues' own numbers."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from bearingsim.catalog import get_bearing
from bearingsim.errors import ParameterError
from bearingsim.physics.fits import (
    effective_interference,
    fit,
    initial_clearance,
    operating_clearance,
    raceway_factor_inner,
    raceway_factor_outer,
)

UM = 1e-6


@pytest.mark.parametrize(("diameter", "zone", "seat", "theoretical", "probable"), [
    # SKF General Catalogue 6000, Table 7d p. 180 (shafts) and 8b p. 186 (housings): theoretical
    # interference (+) or clearance (-) and SKF's probable band; NSK E1102e Tables 15.2/15.3.
    (0.025, "k6", "shaft", (2, 25), (5, 22)),
    (0.035, "k6", "shaft", (2, 30), (6, 26)),
    (0.042, "H7", "housing", (-36, 0), (-32, -4)),
    (0.055, "H7", "housing", (-43, 0), (-38, -5)),
])
def test_fits_reproduce_skf_theoretical_and_probable_values(diameter, zone, seat, theoretical,
                                                            probable):
    f = fit(diameter, zone, seat)
    assert (f.smallest / UM, f.largest / UM) == pytest.approx(theoretical, abs=1e-9)
    # SKF prints whole micrometres
    assert (f.probable_smallest / UM, f.probable_largest / UM) == pytest.approx(probable,
                                                                                abs=0.7)


def test_smoothing_is_nsk_eq_9_4():
    """NSK E1102e eq. (9.4): ground shafts keep d/(d + 2) of the interference; for bores of 30 to
    150 mm 'about 95 %'."""
    assert effective_interference(10 * UM, 0.025) == pytest.approx(10 * UM * 25 / 27)
    assert effective_interference(10 * UM, 0.040) / (10 * UM) == pytest.approx(0.95, abs=0.005)
    assert effective_interference(10 * UM, 0.040, ground=False) == pytest.approx(
        10 * UM * 40 / 43)
    assert effective_interference(-5 * UM, 0.040) == -5 * UM


def test_solid_shaft_factor_is_within_the_catalogue_rules():
    """NSK 9.2 and NTN p. A-57: the clearance falls by 70-90 % of the interference; KRW p. 95:
    80 % for the inner ring on a solid steel shaft, 70 % for the outer ring in a normal-wall
    housing. The Lamé factors of the study's bearings lie at the top of that band (0.87-0.90,
    0.91-0.93): the catalogue rules hold for average ring sections."""
    for name in ("61905", "61907", "61908", "61909", "6304"):
        g = get_bearing(name)
        k = raceway_factor_inner(g.bore, g.pitch_diameter - g.ball_diameter)
        h = raceway_factor_outer(g.outside_diameter, g.pitch_diameter + g.ball_diameter)
        assert 0.7 <= k <= 0.9 + 1e-9 or name == "6304"
        assert 0.7 <= min(k, h) and max(k, h) < 1.0


def test_hollow_seats_take_up_less_clearance():
    """A thin sleeve gives way: the 61909 inner ring on a 1.5 mm wall (bore 42 mm) keeps less
    than half of the solid-shaft expansion (Lamé, equal materials)."""
    g = get_bearing("61909")
    solid = raceway_factor_inner(g.bore, g.pitch_diameter - g.ball_diameter)
    thin = raceway_factor_inner(g.bore, g.pitch_diameter - g.ball_diameter, shaft_bore=0.042)
    assert thin < 0.5 * solid
    assert raceway_factor_outer(0.055, 0.050, housing_outside=0.060) < raceway_factor_outer(
        0.055, 0.050)


@given(st.floats(0.1, 0.99), st.floats(0.0, 0.99))
def test_lame_factor_limits(k, k0):
    """The hollow-shaft factor is at most the solid one, equals it for k0 = 0 and vanishes as
    the wall thins to nothing (k0 -> 1)."""
    solid = raceway_factor_inner(k, 1.0)
    hollow = raceway_factor_inner(k, 1.0, shaft_bore=k0 * k)
    assert hollow <= solid + 1e-12
    assert raceway_factor_inner(k, 1.0, shaft_bore=0.0) == pytest.approx(k)


def test_study_fits_leave_almost_no_clearance():
    """docs/studies.md, section A: shaft k6, housing H7. With the CN clearance of NSK Table 9.9
    (61905: 5-20 um) and the mean k6 interference the 61905 keeps about 2 um; an H7 housing takes up
    nothing (it never has interference)."""
    g = get_bearing("61905")
    assert initial_clearance(g) == pytest.approx((5 * UM, 20 * UM))
    op = operating_clearance(g)
    assert op.initial == pytest.approx(12.5 * UM)  # the catalogue row: the CN mean
    assert op.outer_reduction == 0.0
    assert op.inner_reduction == pytest.approx(13.5 * UM * 25 / 27 * 0.870, rel=0.01)
    assert op.operating == pytest.approx(1.6 * UM, abs=0.3 * UM)
    tight = operating_clearance(g, band="largest")
    assert tight.operating < 0.0  # internal preload at the tight end of the probable band
    assert operating_clearance(g, shaft_zone=None).operating == op.initial


@pytest.mark.parametrize(("call", "match"), [
    (lambda: fit(0.1, "k6", "shaft"), "no entry for 100 mm"),
    (lambda: fit(0.025, "g6", "shaft"), "zone"),
    (lambda: fit(0.025, "k6", "axle"), "seat"),
    (lambda: initial_clearance(get_bearing("6304"), "C5"), "clearance_class"),
    (lambda: raceway_factor_inner(0.03, 0.025), "raceway"),
    (lambda: raceway_factor_outer(0.05, 0.06), "raceway"),
    (lambda: effective_interference(1.0, 0.03), "interference"),
    (lambda: operating_clearance("61905"), "BearingGeometry"),
    (lambda: operating_clearance(get_bearing("61905"), band="typical"), "band"),
])
def test_bad_input_is_named(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_no_nan_for_an_infinite_rigid_housing():
    assert math.isfinite(raceway_factor_outer(0.042, 0.038, math.inf))


def test_a_negative_clearance_preloads_every_ball_by_half_of_it():
    """A mounted bearing with more interference than clearance (Pd < 0): at zero displacement
    the groove centres are A - Pd/2 apart, so every ball is compressed by -Pd/2 and carries
    Q = K (-Pd/2)^1.5 (K: the inner and outer Hertz constants in series), in the ball-row
    model and in the ISO/TS 16281 form alike; the net ring load is zero by symmetry."""
    import dataclasses

    import numpy as np

    from bearingsim.components.ball_row import row_loads, row_parameters
    from bearingsim.physics import iso_ts_16281
    from bearingsim.physics.hertz import combined_load_deflection_constant

    g = dataclasses.replace(get_bearing("61905"), diametral_clearance=-6e-6)
    p = row_parameters(g)
    assert p.alpha0 == 0.0 and p.interference == pytest.approx(3e-6)
    c = row_loads(p, [0.0] * 5, [0.0] * 5, g.ball_count, 1, reference="centred")
    k = combined_load_deflection_constant(p.K_i, p.K_o)
    assert np.asarray(c.Q_i, dtype=float) == pytest.approx(k * (3e-6) ** 1.5, rel=1e-6)
    assert np.abs(np.asarray(c.inner_load[:2], dtype=float)).max() < 1e-9
    delta, _ = iso_ts_16281.deflections(g, [0.0] * 5)
    assert np.asarray(delta, dtype=float) == pytest.approx(3e-6, rel=1e-9)
    with pytest.raises(ParameterError, match="diametral_clearance"):
        dataclasses.replace(get_bearing("61905"), diametral_clearance=-1e-4)  # beyond -0.2 A
