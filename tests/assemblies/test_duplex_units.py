"""Numbers with units in the duplex pair's options and studies are taken as everywhere else in
the API (:func:`bearingsim.units.to_si`: "3000 rpm" is 314.16 rad/s), and a unit of another
quantity is refused naming the option and its unit.

Before: ``DuplexOptions(preload="500 N")`` raised "preload class must be 'light', 'medium' or
'heavy'", ``DuplexOptions(speed="3000 rpm")`` and ``DuplexModel.equilibrium(speed="3000 rpm")``
a bare ``ValueError: could not convert string to float``.
"""

import math

import pytest

from bearingsim.assemblies.duplex import DuplexOptions
from bearingsim.errors import ParameterError
from bearingsim.studies.duplex import DuplexModel


def test_options_take_numbers_with_units():
    o = DuplexOptions("7020C", "DF", preload="0.5 kN", speed="3000 rpm",
                      contact_angle="16 deg", ball_position_angle="9 deg")
    assert o.preload_force == pytest.approx(500.0, rel=1e-12)
    assert o.speed == pytest.approx(3000 * math.pi / 30, rel=1e-12)
    assert o.contact_angle == pytest.approx(math.radians(16.0), rel=1e-12)
    assert o.ball_position_angle == pytest.approx(math.radians(9.0), rel=1e-12)
    assert DuplexOptions("7020C", "DB", spacer_offset="10 um").spacer_width_difference == \
        pytest.approx(1e-5, rel=1e-12)


@pytest.mark.parametrize("option, value, message", [
    ("speed", "3 kN", r"duplex_pair: speed: 'kN' is not a unit of rad/s quantities"),
    ("preload", "2 m", r"duplex_pair: preload: 'm' is not a unit of N quantities"),
    ("speed", "fast", r"duplex_pair: speed: 'fast' is not a number with a unit; write e\.g\. "
                      r"'10000 rpm' or a number in rad/s"),
    ("preload", "strong", r"preload class must be 'light', 'medium' or 'heavy', or the preload "
                          r"an axial force in N \(a number > 0, or e.g. '500 N'\)"),
])
def test_a_bad_unit_or_word_names_the_option_and_its_unit(option, value, message):
    with pytest.raises(ParameterError, match=message):
        DuplexOptions("7020C", "DF", **{option: value})


def test_studies_take_numbers_with_units():
    model = DuplexModel("7020C", "DF", pair_options={"speed_effects": True})
    eq = model.equilibrium(loads={"Fx": "2 kN", "My": "100 N m"}, preload="500 N",
                           speed="3000 rpm")
    assert eq.inputs == {"shaft.Fx": 2000.0, "shaft.My": pytest.approx(100.0, rel=1e-12)}
    assert eq.parameters["shaft.speed"] == pytest.approx(3000 * math.pi / 30, rel=1e-12)
    same = model.equilibrium(loads={"Fx": 2000.0, "My": 100.0}, preload=500.0,
                             speed=3000 * math.pi / 30)
    assert eq.displacement == pytest.approx(same.displacement, rel=1e-9, abs=1e-15)
    with pytest.raises(ParameterError, match=r"DuplexModel.equilibrium: load Fx: 'm' is not a "
                                             r"unit of N quantities"):
        model.equilibrium(loads={"Fx": "3 m"})
