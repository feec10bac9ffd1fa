"""A statics load case is held to the same limits as a run (found by a new-user trial; each
case ran before the fix, exit code 0): a shaft speed of 1e6 r/min (26 x the 6304's limiting
speed) gave an L10h of 55 h without a word, and a radial load of 1e9 N an inner-ring
displacement of 10 cm and an L10h of 1.6e-13 h with only a warning.

The limits: the catalogue limiting speed of the 6304, 19 000 r/min (warn above it, refuse above
2 x, as every run does), and 10 x the static load rating C0 (ISO 76: 4 200 MPa at C0; the Hertz
pressure grows as the load to the power 1/3, so about 9 050 MPa at 10 C0), as constant loads of
the assemblies are.
"""

import math

import pytest

from bearingsim.catalog import get_bearing
from bearingsim.errors import ParameterError, PlasticDeformationWarning, SpeedLimitWarning
from bearingsim.scenes import parse_scene, prepare
from bearingsim.scenes.analyses import run_operating_point
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.studies.deep_groove_statics import deep_groove_statics

RPM = math.pi / 30.0


@pytest.fixture(scope="module")
def statics():
    return prepare(parse_scene(builtin_scene_path("deep_groove_statics").read_text(
        encoding="utf-8")))


def test_a_load_case_above_twice_the_limiting_speed_is_refused(statics):
    assert get_bearing("6304").limiting_speed == pytest.approx(19000 * RPM)
    with pytest.raises(ParameterError, match=r"inputs\.shaft_speed: speed .*1000000 r/min.* "
                                             r"more than 2 x the limiting speed of 6304"):
        run_operating_point(statics, {"inputs.shaft_speed": 1e6 * RPM,
                                      "inputs.load.Fx": 938.0})
    with pytest.warns(SpeedLimitWarning):
        row = run_operating_point(statics, {"inputs.shaft_speed": 25000 * RPM,
                                            "inputs.load.Fx": 938.0})
    assert 0.0 < row["L10h"] < math.inf


def test_a_load_beyond_ten_c0_is_refused_by_its_pressure():
    c0 = get_bearing("6304").static_load_rating
    with pytest.warns(PlasticDeformationWarning):
        deep_groove_statics("6304", {"Fx": 3.0 * c0})
    with pytest.raises(ParameterError, match=r"largest contact pressure of \d+ MPa, above the "
                                             r"9049 MPa of 10 x the static load rating C0"):
        deep_groove_statics("6304", {"Fx": 1e9})


def test_a_steady_state_not_found_is_reported_on_one_line():
    """scipy's message of a failed ``root`` wraps its line ("...measured by the \\n improvement
    ..."): the error printed it across two lines. A 7020C without a limiting speed (the
    catalogue's refuses 1e6 r/min before the solver), so 1e6 r/min reaches the solver."""
    import dataclasses

    from bearingsim.catalog import register_bearing, unregister_bearing
    from bearingsim.errors import SimulationError

    register_bearing(dataclasses.replace(get_bearing("7020C"), designation="7020X",
                                         limiting_speed=None))
    try:
        text = builtin_scene_path("duplex_modes").read_text(encoding="utf-8")
        prep = prepare(parse_scene(text.replace('bearing = "7020C"', 'bearing = "7020X"')))
        with pytest.raises(SimulationError, match="steady state not found") as caught:
            run_operating_point(prep, {"assembly.speed": 1e6 * RPM,
                                       "assembly.preload_force": 250.0})
    finally:
        unregister_bearing("7020X")
    assert "\n" not in str(caught.value)
    # the compiled ball equations find no root at such speeds: said so, not a RuntimeError
    # from the kernel (since compiled Newton blocks report failing to converge)
    assert "a nonlinear block of the model found no root" in str(caught.value)
