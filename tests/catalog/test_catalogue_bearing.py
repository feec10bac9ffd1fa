"""The fields and checks every catalogued bearing shares (CatalogueBearing), ball and roller."""

from __future__ import annotations

import dataclasses
import warnings

import pytest

from bearingsim.catalog import get_bearing
from bearingsim.catalog.geometry import BearingGeometry, CatalogueBearing
from bearingsim.catalog.rollers import RollerBearingGeometry, get_roller_bearing
from bearingsim.errors import ParameterError, SpeedLimitWarning

SHARED = [f.name for f in dataclasses.fields(CatalogueBearing)]


@pytest.mark.parametrize("cls", [BearingGeometry, RollerBearingGeometry])
def test_the_shared_fields_come_first_and_the_elements_are_keywords(cls):
    fields = dataclasses.fields(cls)
    assert [f.name for f in fields][:len(SHARED)] == SHARED
    assert all(f.kw_only for f in fields[len(SHARED):])


def test_a_ball_bearing_still_takes_its_designation_by_position():
    g = BearingGeometry("hand", bore=0.040, outside_diameter=0.060, width=0.012, ball_count=10,
                        ball_diameter=0.005, pitch_diameter=0.050, fi=0.52, fo=0.53)
    assert (g.designation, g.ball_count) == ("hand", 10)


@pytest.mark.parametrize("rating,words", [
    (44.0, ["Z Lwe Dw", "did you pass kN?"]),          # NU 206's C given in kN
    (44000.0 * 10, ["Z Lwe Dw", "not this roller set's rating"]),
])
def test_a_roller_rating_out_of_its_area_range_says_why(rating, words):
    g = get_roller_bearing("NU206")
    with pytest.raises(ParameterError) as err:
        dataclasses.replace(g, dynamic_load_rating=rating)
    for word in words:
        assert word in str(err.value)


@pytest.mark.parametrize("geometry", [get_bearing("6204"), get_roller_bearing("NU206")],
                         ids=["ball", "roller"])
def test_both_check_a_speed_against_their_limiting_speed(geometry):
    limit = geometry.limiting_speed
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        geometry.check_speed(0.9 * limit, "test")  # below the limit: silent
    with pytest.warns(SpeedLimitWarning, match=geometry.designation):
        geometry.check_speed(1.5 * limit, "test")
    with pytest.raises(ParameterError, match="more than 2 x the limiting speed"):
        geometry.check_speed(-2.5 * limit, "test")
