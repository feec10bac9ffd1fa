"""Options of the bearing assemblies that were ignored or failed deep inside: unknown keywords,
friction settings at levels without friction, moments on a ring held straight, drag without
oil, and range errors that did not name the argument. Construction only (no assembly)."""

from __future__ import annotations

import math

import pytest

from bearingsim.assembler import assemble_cached
from bearingsim.assemblies import deep_groove_ball_bearing, double_layer_bearing
from bearingsim.assemblies.double_layer import layer_option_names
from bearingsim.components.bearing_torque import PalmgrenBearing
from bearingsim.errors import CatalogError, ParameterError
from bearingsim.language import Parameter
from bearingsim.physics.ball_equilibrium import static_state
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.lubricant import Dry
from bearingsim.simulation import simulate
from bearingsim.validation import keyword_names

LOADS = {"Fx": 500.0}


# --- 1: unknown option names --------------------------------------------------------------

@pytest.mark.parametrize("model", ["palmgren", "skf"])
def test_torque_level_rejects_unknown_layer_options_and_lists_the_accepted_ones(model):
    with pytest.raises(ParameterError, match=r"unknown layer_options 'bogus'.*accepted: ") as e:
        double_layer_bearing(fidelity="torque", friction_model=model, layer_options={"bogus": 1})
    for name in layer_option_names(model):
        assert name in str(e.value)
    # the accepted ones still build
    bearing = double_layer_bearing(fidelity="torque", friction_model=model,
                                   layer_options={"omega_reg": 0.2})
    assert bearing.inner_layer.parameter("omega_reg").value == 0.2


def test_palmgren_layer_options_follow_the_constructor_signature():
    assert set(layer_option_names("palmgren")) == set(
        keyword_names(PalmgrenBearing, ("bearing", "lubricant", "name")))
    assert "smooth" in layer_option_names("palmgren")
    assert {"seal", "oil_level", "series"} <= set(layer_option_names("skf"))


@pytest.mark.parametrize("fidelity, kwargs, accepted", [
    ("quasi-static", {"layer_options": {"a": 1}}, "axial"),
    ("quasi-static", {"friction_model": "skf"}, "axial"),
    ("torque", {"bogus": 1}, "friction_model"),
    ("kinematic", {"bogus": 1}, "layer_options"),
    ("dynamic", {"bogus": 1}, "massive_balls"),
])
def test_double_layer_factory_rejects_keywords_the_level_does_not_take(fidelity, kwargs,
                                                                         accepted):
    with pytest.raises(ParameterError, match=rf"double_layer_bearing: unknown keyword.*"
                                             rf"{fidelity}.*accepted: .*{accepted}"):
        double_layer_bearing(fidelity=fidelity, **kwargs)


def test_quasi_static_double_layer_rejects_a_lubricant_it_does_not_use():
    with pytest.raises(ParameterError, match=r"lubrication = 'ISO VG 68' is not used.*"
                                             r"no friction"):
        double_layer_bearing(fidelity="quasi-static", lubrication="ISO VG 68")
    nested = double_layer_bearing(fidelity="quasi-static", axial=False)  # the default is fine
    assert nested.geometries[1].designation == "61907"


@pytest.mark.parametrize("options, match", [
    ({"bogus": 1}, r"unknown layer_options 'bogus' at the dynamic level; accepted: .*n_slices"),
    ({"oil_fraction": 0.1}, r"'oil_fraction' is not used.*no ball drag"),
    ({"rolling_resistance": False}, r"may not set 'rolling_resistance'"),
])
def test_dynamic_double_layer_checks_layer_options(options, match):
    with pytest.raises(ParameterError, match=match):
        double_layer_bearing(fidelity="dynamic", loads={"Fz": 100.0}, layer_options=options)


def test_deep_groove_factory_rejects_unknown_options_listing_the_accepted_ones():
    with pytest.raises(ParameterError, match=r"deep_groove_ball_bearing: unknown option\(s\) "
                                             r"'bogus' at fidelity 'dynamic'; accepted: .*"
                                             r"traction_scale.*pocket_clearance"):
        deep_groove_ball_bearing("6304", "dynamic", loads=LOADS, bogus=1)


# --- 2: friction settings at the kinematic levels -----------------------------------------

@pytest.mark.parametrize("fidelity", ["kinematic", "kinematic_approx"])
def test_kinematic_levels_check_friction_settings_they_ignore(fidelity):
    with pytest.raises(ParameterError, match=r"friction_model must be 'palmgren' or 'skf'"):
        double_layer_bearing(fidelity=fidelity, friction_model="coulomb")
    with pytest.raises(CatalogError, match=r"unknown lubricant 'ISO VG 33'"):
        double_layer_bearing(fidelity=fidelity, lubrication="ISO VG 33")
    # valid values build (a scene with fidelity "auto" passes them to every level)
    bearing = double_layer_bearing(fidelity=fidelity, friction_model="skf",
                                   lubrication=("ISO VG 68", "lithium grease"))
    assert bearing.geometries[0].designation == "61905"


# --- 3: moments on an inner ring held straight --------------------------------------------

@pytest.mark.parametrize("moment", [{"Mx": 5.0}, {"My": None}, {"My": lambda t: 2.0 * t}])
@pytest.mark.parametrize("fidelity", ["dynamic", "dynamic_massive_balls"])
def test_dynamic_levels_reject_moments_without_free_tilt(fidelity, moment):
    with pytest.raises(ParameterError, match=r"loads\['M[xy]'\].*not applied with "
                                             r"free_tilt=False"):
        deep_groove_ball_bearing("6304", fidelity, loads={**LOADS, **moment})


def test_static_state_rejects_moments_it_would_ignore_and_zero_ones_are_fine():
    with pytest.raises(ParameterError, match=r"static_state: loads\['Mx'\].*free_tilt"):
        static_state(bearing_design("6304"), {"Fx": 500.0, "Mx": 3.0})
    bearing = deep_groove_ball_bearing("6304", "dynamic", loads={**LOADS, "Mx": 0.0, "My": 0.0})
    assert not bearing.ring.free_tilt


def test_a_ring_held_straight_has_no_moment_inputs_to_ignore():
    """Without free_tilt, load.Mx and load.My were inputs whose values had no effect (a run
    with load.Mx = 50 N m gave the same answer as without); now giving one is refused as an
    unknown input, and with free_tilt they are inputs."""
    straight = assemble_cached(deep_groove_ball_bearing("6304", "dynamic", loads={"Fx": 500.0}))
    assert "load.Mx" not in straight.input_names and "load.My" not in straight.input_names
    assert {"load.Fy", "load.Fz"} <= set(straight.input_names)
    with pytest.raises(ParameterError, match=r"unknown input\(s\) load.Mx"):
        simulate(straight, 1e-4, inputs={"shaft_speed": 100.0, "load.Mx": 50.0}, progress=False)
    tilting = assemble_cached(deep_groove_ball_bearing(
        "6304", "dynamic", loads={"Fx": 500.0}, free_tilt=True))
    assert {"load.Mx", "load.My"} <= set(tilting.input_names)


def test_dynamic_double_layer_rejects_moments_on_the_straight_shaft():
    with pytest.raises(ParameterError, match=r"double_layer_bearing: loads\['My'\] = 1.0 "
                                             r"\[N.m\] is not applied"):
        double_layer_bearing(fidelity="dynamic", loads={"Fz": 100.0, "My": 1.0})


# --- 4: drag without oil --------------------------------------------------------------------

def test_drag_with_a_dry_lubricant_raises_and_is_off_by_default():
    with pytest.raises(ParameterError, match=r"drag=True needs a viscous lubricant.*Dry"):
        deep_groove_ball_bearing("6304", "dynamic", Dry(0.05), loads=LOADS, drag=True)
    dry = deep_groove_ball_bearing("6304", "dynamic", Dry(0.05), loads=LOADS)
    assert not hasattr(dry, "drag")
    oiled = deep_groove_ball_bearing("6304", "dynamic", "ISO VG 32", loads=LOADS)
    assert len(oiled.drag) == oiled.design.geometry.ball_count


# --- 5: range errors name the argument ------------------------------------------------------

@pytest.mark.parametrize("key, value, unit", [
    ("traction_scale", -1.0, "1"), ("damping", -1.0, "s/m"), ("pocket_mu", -1.0, "1"),
    ("land_mu", 3.0, "1"), ("cage_damping", -1.0, "s/m"), ("film_damping", -1.0, "s"),
    ("damping", math.nan, "s/m"), ("traction_scale", "1", "1"),
])
def test_dynamic_level_range_errors_name_the_argument(key, value, unit):
    with pytest.raises(ParameterError, match=rf"deep_groove_ball_bearing: {key} .*\[{unit}\]"):
        deep_groove_ball_bearing("6304", "dynamic", loads=LOADS, **{key: value})


def test_unbound_parameter_errors_carry_the_description():
    with pytest.raises(ParameterError, match=r"\(traction multiplier\) = -1.0 \[1\] is outside"):
        Parameter(-1.0, "1", "traction multiplier", low=0.0)
    with pytest.raises(ParameterError, match=r"\(traction multiplier\) is NaN"):
        Parameter(math.nan, "1", "traction multiplier", low=0.0)
    with pytest.raises(ParameterError, match=r"double_layer_bearing: layer_options\[.omega_reg.\] "
                                             r"= -1.0 \[rad/s\] is outside"):
        double_layer_bearing(fidelity="torque", layer_options={"omega_reg": -1.0})
