"""The statics of a cylindrical roller bearing (``roller_statics`` and the ``statics`` scene
of ``cylindrical_roller_bearing``): roller loads, contact pressure, stiffness, holding moment
and roller-form life per load case."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.errors import ParameterError
from bearingsim.scenes import parse_scene, run_scene
from bearingsim.studies.roller_statics import roller_statics


def test_zero_clearance_gives_stribecks_line_contact_value():
    """At zero clearance the most loaded roller carries 4.08 Fr / Z (line contact, epsilon =
    0.5: NSK CAT. No. E728g, section 5.1, eq. (5)); the discrete rollers of an NU 206 (Z = 12)
    come within 2 % of it."""
    res = roller_statics("NU206", {"Fx": "5 kN"}, clearance=0.0)
    assert res.roller_loads.max() * 12 / 5000.0 == pytest.approx(4.08, rel=0.02)
    assert res.displacement[1] == 0.0 and res.moment.tolist() == [0.0, 0.0]


def test_stiffness_is_the_slope_of_the_load_displacement_curve():
    """k_xx from the exact Jacobian equals the central difference of the equilibrium's radial
    displacement under a load change of +-1 %."""
    res = roller_statics("NU208", {"Fx": 10000.0})
    up = roller_statics("NU208", {"Fx": 10100.0}).displacement[0]
    down = roller_statics("NU208", {"Fx": 9900.0}).displacement[0]
    assert res.stiffness[0, 0] == pytest.approx(200.0 / (up - down), rel=1e-3)
    assert res.stiffness[0, 0] > 0.0


def test_misalignment_is_held_by_a_moment_odd_in_the_tilt_and_costs_life():
    straight = roller_statics("NU206", {"Fx": 8000.0})
    tilted = roller_statics("NU206", {"Fx": 8000.0}, misalignment=(0.0, "1 mrad"))
    back = roller_statics("NU206", {"Fx": 8000.0}, misalignment=(0.0, -1e-3))
    assert tilted.moment[1] == pytest.approx(-back.moment[1], rel=1e-9) and tilted.moment[1] != 0
    assert tilted.max_pressure > straight.max_pressure
    assert tilted.reference_life < straight.reference_life
    assert math.isinf(roller_statics("NU206").reference_life)  # no load, no fatigue


def test_a_load_beyond_the_static_rating_warns_and_one_beyond_steel_is_refused():
    """As the deep-groove statics: above ISO 76's pressure of the static load rating (4 000
    MPa for roller bearings) the raceways deform permanently (a warning); a load that would
    press far beyond the strength of steel is a unit slip, refused."""
    from bearingsim.catalog.rollers import get_roller_bearing
    from bearingsim.errors import PlasticDeformationWarning

    c0 = get_roller_bearing("NU206").static_load_rating
    with pytest.warns(PlasticDeformationWarning, match="above the 4000 MPa of ISO 76"):
        assert roller_statics("NU206", {"Fx": 1.5 * c0}).max_pressure > 4.0e9
    with pytest.raises(ParameterError, match=r"beyond the strength of bearing steel \(N given "
                                             r"for kN\?\)"):
        roller_statics("NU206", {"Fx": 20.0 * c0})


def test_bad_input_is_named():
    with pytest.raises(ParameterError, match="loads may have the keys Fx, Fy"):
        roller_statics("NU206", {"Fz": 100.0})
    with pytest.raises(ParameterError, match=r"misalignment\[1\] = 0.02 \[rad\] is outside"):
        roller_statics("NU206", {"Fx": 100.0}, misalignment=(0.0, 0.02))
    with pytest.raises(ParameterError, match="misalignment must be"):
        roller_statics("NU206", {"Fx": 100.0}, misalignment=0.001)


_SCENE = """
analysis = "{analysis}"
{outputs}
[assembly]
name = "cylindrical_roller_bearing"
bearing = "NU 208"
fidelity = "quasi-static"
tilt_y = "0.5 mrad"
[grid]
"inputs.load.Fx" = ["2 kN", "20 kN"]
{speed}
"""


def test_statics_scene_agrees_with_the_steady_model_and_gives_hours_at_speed():
    """A statics scene of the roller bearing (it had none: "no statics analysis for the
    assembly cylindrical_roller_bearing") gives per load case what the quasi-static model's
    steady state gives through its post-processed quantities (the same equations), the life
    in hours at the case's speed, and the ISO 76 limit of roller bearings (4 000 MPa)."""
    from bearingsim.scenes.preparation import prepare
    from bearingsim.scenes.statics_table import statics_of

    statics = run_scene(parse_scene(_SCENE.format(
        analysis="statics", outputs="", speed='"inputs.shaft_speed" = ["1500 rpm"]')),
        write=False).rows
    steady = run_scene(parse_scene(_SCENE.format(
        analysis="steady", outputs='outputs = ["Q_max", "p_max", "L10r"]', speed="")),
        write=False).rows
    for s, t in zip(statics, steady, strict=True):
        for name in ("Q_max", "p_max", "L10r"):
            assert s[name] == pytest.approx(t[name], rel=1e-6), name
        assert s["L10h"] == pytest.approx(s["L10r"] * 1e6 / (1500.0 * 60.0), rel=1e-12)
        assert s["My"] != 0.0 and s["Mx"] == 0.0 and s["k_radial"] > 1e8
    assert statics[1]["Q_max"] > 5.0 * statics[0]["Q_max"]
    prep = prepare(parse_scene(_SCENE.format(analysis="statics", outputs="", speed="")))
    assert statics_of(prep).pressure_limit == 4.0e9
    at_rest = run_scene(prep.scene, write=False).rows
    assert [row["L10h"] for row in at_rest] == ["not defined at zero speed"] * 2
    assert np.isfinite([row["L10r"] for row in at_rest]).all()
