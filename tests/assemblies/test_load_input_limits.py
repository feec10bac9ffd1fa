"""Load inputs carry the bearing's static load rating as their limit, as constant loads do.

Before, a constant load beyond 10 C0 was refused when the bearing was built, but the same load
given as an input (a scene's ``[inputs]``, ``simulate(inputs=...)``) ran: a 6304 under
``-1e7 * ramp(0, 1)`` N reported ball 0 loaded with 2 765 kN at a contact angle of 180 deg (the
inner ring pushed through the balls), "settled". Now each load input warns above the load that
alone makes the ISO 76 static equivalent load reach C0 and is refused beyond 10 times it.

C0 and Y0 values: the catalogue's 6304 (C0 = 7.9 kN) and NU206; ISO 76:2006 Table 1 gives
Y0 = 0.5 for deep-groove ball bearings (so ``Fa`` alone reaches C0 at ``2 C0``).
"""

import warnings

import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import cylindrical_roller_bearing, deep_groove_ball_bearing
from bearingsim.catalog import get_bearing
from bearingsim.errors import ParameterError, PlasticDeformationWarning
from bearingsim.language import Input
from bearingsim.simulation import simulate

C0 = get_bearing("6304").static_load_rating


@pytest.fixture(scope="module")
def quasi_static():
    return assemble(deep_groove_ball_bearing("6304", "quasi-static"))


def test_the_inputs_carry_c0_and_ten_times_it(quasi_static):
    bounds = {s.name: (s.low, s.high, s.warn_above, s.limit) for s in quasi_static.inputs}
    assert C0 == pytest.approx(7900.0)
    assert bounds["load.Fx"] == pytest.approx((-10 * C0, 10 * C0, C0, "static load"))
    assert bounds["load.Fy"] == bounds["load.Fx"]
    assert bounds["load.Fz"][:3] == pytest.approx((-20 * C0, 20 * C0, 2 * C0))  # Y0 = 0.5


def test_a_load_below_c0_runs_without_a_warning(quasi_static):
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlasticDeformationWarning)
        result = simulate(quasi_static, 0.1, inputs={"load.Fx": 0.9 * C0,
                                                     "load.Fz": 1.9 * C0}, n_points=3)
    assert result["row.Q_i[0]"][-1] > 0.0


@pytest.mark.parametrize("name, value", [("load.Fx", 3.0 * C0), ("load.Fy", -3.0 * C0),
                                         ("load.Fz", 5.0 * C0)])
def test_a_load_input_beyond_c0_warns_naming_it(quasi_static, name, value):
    with pytest.warns(PlasticDeformationWarning,
                      match=rf"input {name} reaches .* above its limit .*static load rating "
                            r"C0: the raceways deform permanently \(ISO 76\)"):
        simulate(quasi_static, 0.1, inputs={name: value}, n_points=3)


@pytest.mark.parametrize("load", [
    -1e7,                                    # the constant of the defect
    ([0.0, 0.05, 0.1], [0.0, 0.0, -1e7]),    # a table
    lambda t: -1e8 * t,                      # a function of time (interval arithmetic)
])
def test_a_load_input_beyond_ten_c0_is_refused(quasi_static, load):
    with pytest.raises(ParameterError, match=r"input load\.Fx.*\[N\].*-79000.*the bound is 10 x "
                                             r"the load at which this component alone brings "
                                             r"the static equivalent load to the static "
                                             r"load rating C0: 7\.9 kN"):
        simulate(quasi_static, 0.1, inputs={"load.Fx": load}, n_points=3)


def test_the_dynamic_and_roller_levels_bound_their_load_inputs():
    fx = deep_groove_ball_bearing("6304", "dynamic_massive_balls",
                                  speed=300.0).load.declarations["Fx"]
    assert (fx.high, fx.warn_above) == pytest.approx((10 * C0, C0))
    roller = cylindrical_roller_bearing("NU206")
    c0 = roller.geometry.static_load_rating
    fx, fy = (roller.load.declarations[k] for k in ("Fx", "Fy"))
    assert (fx.low, fy.warn_above, fy.limit) == (pytest.approx(-10 * c0), pytest.approx(c0),
                                                 "static load")


def test_a_limit_needs_its_kind():
    with pytest.raises(ParameterError, match="warn_above needs a limit, one of speed, static "
                                             "load"):
        Input(0.0, "N", "a load", warn_above=100.0)
    with pytest.raises(ParameterError, match="limit='torque'"):
        Input(0.0, "N", "a load", warn_above=100.0, limit="torque")


def test_a_nested_bearing_bounds_its_loads_by_the_weaker_layer_they_pass_through():
    """The shaft's load passes through both layers (61905: C0 = 4.3 kN, 61907: 6.8 kN), the
    middle ring's only through the outer one."""
    from bearingsim.assemblies import double_layer_bearing

    c0_inner, c0_outer = (get_bearing(d).static_load_rating for d in ("61905", "61907"))
    assert c0_inner < c0_outer
    system = assemble(double_layer_bearing("61905", "61907", fidelity="quasi-static"))
    warn = {s.name: s.warn_above for s in system.inputs}
    assert warn["shaft.Fx"] == pytest.approx(c0_inner)
    assert warn["shaft.Fz"] == pytest.approx(2 * c0_inner)
    assert warn["middle.Fy"] == pytest.approx(c0_outer)
    torque = double_layer_bearing("61905", "61907", fidelity="torque").declarations
    assert (torque["Fr"].low, torque["Fr"].high, torque["Fa"].warn_above) == pytest.approx(
        (0.0, 10 * c0_inner, 2 * c0_inner))


def test_a_torque_level_bearing_refuses_a_radial_load_beyond_ten_c0():
    from bearingsim.components.bearing_torque import PalmgrenBearing

    declarations = PalmgrenBearing("6304", "ISO VG 68").declarations
    assert (declarations["Fr"].low, declarations["Fr"].high) == pytest.approx((0.0, 10 * C0))
    assert declarations["Fa"].warn_above == pytest.approx(2 * C0)


def test_constant_loads_of_the_dynamic_and_roller_levels_are_held_to_c0():
    """Before, the ball level took a constant 1e9 N (an inner-ring displacement of 73 mm,
    contact forces of 2.2e8 N) and the roller level only warned; the quasi-static ball level
    refused it. Now all three check the static equivalent load against C0 and 10 C0."""
    with pytest.raises(ParameterError, match=r"deep_groove_ball_bearing: the static equivalent "
                                             r"load 1e\+09 N is more than 10 x .*C0 = 7900 N"):
        deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0,
                                 loads={"Fx": 1e9})
    with pytest.warns(PlasticDeformationWarning, match="exceeds the static load rating"):
        deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0,
                                 loads={"Fx": 2.0 * C0})
    c0 = cylindrical_roller_bearing("NU206").geometry.static_load_rating
    with pytest.raises(ParameterError, match=r"cylindrical_roller_bearing\(quasi-static\): the "
                                             r"static equivalent load .* more than 10 x"):
        cylindrical_roller_bearing("NU206", loads={"Fx": 11.0 * c0})
