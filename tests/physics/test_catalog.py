"""Tests of the bearing catalogue and BearingGeometry."""

import dataclasses
import math

import pytest

from bearingsim.catalog import BearingGeometry, PreloadClasses, get_bearing, list_bearings
from bearingsim.catalog.rollers import get_roller_bearing
from bearingsim.errors import CatalogError, ParameterError

REQUIRED = ["6204", "6205", "6206", "6304", "6305", "61905", "61907", "61908", "61909", "7020C",
            "7020A5", "7020A", "7014C", "7014AC"]


def test_required_designations_present():
    assert set(REQUIRED) <= set(list_bearings())


def test_unknown_designation_lists_known():
    with pytest.raises(CatalogError) as err:
        get_bearing("6299X")
    assert "6299X" in str(err.value) and "6204" in str(err.value) and "7020C" in str(err.value)
    assert "is a" not in str(err.value)


def test_a_designation_of_the_other_catalogue_says_which():
    """Before: 'unknown bearing 'NU208'; known: 6204, ...', as for a designation no catalogue
    has."""
    from bearingsim.catalog.rollers import ROLLER_BEARINGS

    with pytest.raises(CatalogError, match=r"'nu 208' is a cylindrical roller bearing$"):
        get_bearing("nu 208")
    with pytest.raises(CatalogError, match=r"'6304' is a ball bearing$"):
        ROLLER_BEARINGS["6304"]


def test_case_insensitive():
    assert get_bearing("7020c") is get_bearing("7020C")


def test_6304_study_section_c():
    """docs/studies.md, section C validation case: Z 7, dm 36, ball radius 4.76, groove
    bottoms 22.77/13.24 mm."""
    g = get_bearing("6304")
    assert g.ball_count == 7
    assert g.pitch_diameter == pytest.approx(36e-3)
    assert g.ball_diameter / 2 == pytest.approx(4.76e-3)
    # Pd = outer groove bottom diameter - inner groove bottom diameter - 2 Dw
    assert g.diametral_clearance == pytest.approx(2 * 22.77e-3 - 2 * 13.24e-3 - 2 * 9.52e-3)
    assert g.bearing_type == "deep_groove"
    assert g.preload is None


@pytest.mark.parametrize("name,alpha,preload", [
    ("7020C", 15, (540, 1270, 2550)),
    ("7020A5", 25, (830, 1960, 3920)),
    ("7020A", 30, (840, 2750, 4310)),
])
def test_7020_study_section_b(name, alpha, preload):
    g = get_bearing(name)
    assert (g.ball_count, g.ball_diameter, g.pitch_diameter, g.fi, g.fo) == pytest.approx(
        (20, 14.288e-3, 125.25e-3, 0.525, 0.515))
    assert (g.bore, g.outside_diameter, g.width) == pytest.approx((0.1, 0.15, 0.024))
    assert math.degrees(g.contact_angle) == pytest.approx(alpha)
    assert g.bearing_type == "angular_contact"
    assert (g.preload.light, g.preload.medium, g.preload["heavy"]) == preload
    assert g.free_contact_angle == g.contact_angle


def test_derived_geometry_harris_relations():
    """Harris & Kotzalas: B = fi + fo - 1, A = B Dw, cos a0 = 1 - Pd/(2A)."""
    g = get_bearing("6204")
    assert g.total_curvature == pytest.approx(0.05)
    assert g.groove_centre_distance == pytest.approx(0.05 * 7.938e-3)
    assert g.inner_groove_radius == pytest.approx(0.52 * 7.938e-3)
    assert g.outer_groove_radius == pytest.approx(0.53 * 7.938e-3)
    a0 = g.free_contact_angle
    assert math.cos(a0) == pytest.approx(1 - 12.5e-6 / (2 * 0.05 * 7.938e-3))
    # distance between the groove centre loci equals A cos a0 (radial projection)
    assert g.inner_groove_centre_radius - g.outer_groove_centre_radius == pytest.approx(
        g.groove_centre_distance * math.cos(a0))
    assert g.gamma == pytest.approx(7.938 / 33.5)


def test_double_layer_pitch_diameter_ratios():
    """docs/studies.md, section A: PDR of 61905 inside 61907/61908/61909 about 0.75, 0.66, 0.59."""
    inner = get_bearing("61905").pitch_diameter
    for outer, pdr in (("61907", 0.75), ("61908", 0.66), ("61909", 0.59)):
        assert inner / get_bearing(outer).pitch_diameter == pytest.approx(pdr, abs=0.01)


def test_estimated_fields_are_flagged_and_sourced():
    for name in list_bearings():
        g = get_bearing(name)
        assert g.source
        assert set(g.estimated) <= {"Z", "Dw", "dm", "fi", "fo", "Pd"}
    assert "Z" in get_bearing("61905").estimated
    assert get_bearing("7020C").estimated == ()


def _valid(**changes):
    base = dict(designation="t", bore=0.02, outside_diameter=0.047, width=0.014, ball_count=8,
                ball_diameter=7.938e-3, pitch_diameter=33.5e-3, fi=0.52, fo=0.53)
    base.update(changes)
    return BearingGeometry(**base)


@pytest.mark.parametrize("changes,words", [
    (dict(fi=0.5), ["fi", "(0.5, 1]"]),
    (dict(fo=0.49), ["fo"]),
    (dict(ball_count=2), ["ball_count", "3"]),
    (dict(ball_count=8.0), ["integer"]),
    (dict(diametral_clearance=-1e-4), ["diametral_clearance", "m"]),  # preload beyond -0.2 A
    (dict(contact_angle=math.radians(50)), ["contact_angle", "rad"]),
    (dict(ball_diameter=0.015), ["do not fit"]),
    (dict(ball_count=14), ["pitch circle"]),
    (dict(diametral_clearance=1e-3), ["free contact angle"]),
    (dict(bore=float("nan")), ["bore", "finite"]),
    # issue 17: millimetres for metres, kN for N, C0 ten times C
    (dict(bore=20.0, outside_diameter=47.0, width=14.0, ball_diameter=7.938,
          pitch_diameter=33.5), ["bore", "did you pass mm?"]),
    (dict(dynamic_load_rating=12.7), ["dynamic_load_rating = 12.7 N", "did you pass kN?"]),
    (dict(dynamic_load_rating=4000.0, static_load_rating=40000.0),
     ["static_load_rating / dynamic_load_rating = 10", "swapped or mistyped"]),
    (dict(static_load_rating=127000.0), ["252 N/mm^2", "not this ball set's rating"]),
])
def test_invalid_geometry_rejected(changes, words):
    with pytest.raises(ParameterError) as err:
        _valid(**changes)
    for word in words:
        assert word in str(err.value)


def test_user_geometry_and_frozen():
    g = _valid(contact_angle=math.radians(25))
    assert g.bearing_type == "angular_contact"
    with pytest.raises(dataclasses.FrozenInstanceError):
        g.fi = 0.51


def test_preload_classes_validated():
    with pytest.raises(ParameterError):
        PreloadClasses(100.0, 50.0, 200.0)
    with pytest.raises(ParameterError):
        PreloadClasses(1.0, 2.0, 3.0)["extreme"]


@pytest.mark.parametrize("changes,words", [
    (dict(roller_diameter=0.02), ["the rollers do not fit the ring section", "Dw = 0.02"]),
    (dict(roller_count=30), ["30 rollers of Dw", "do not fit on the pitch circle"]),
    (dict(fatigue_load_limit=-1.0), ["fatigue_load_limit", "[N]"]),
    (dict(limiting_speed=0.0), ["limiting_speed", "[rad/s]"]),
])
def test_roller_geometry_refuses_rollers_that_do_not_fit_and_bad_ratings(changes, words):
    with pytest.raises(ParameterError) as err:
        dataclasses.replace(get_roller_bearing("NU206"), **changes)
    for word in words:
        assert word in str(err.value)
