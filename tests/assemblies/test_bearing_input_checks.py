"""Bearing assemblies reject bad input instead of silently building another bearing: unknown or
non-finite loads, options the quasi-static level does not use, its clearance, and out-of-range
options of the dynamic level. Only construction and the (fast) quasi-static level are run."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import deep_groove_ball_bearing, double_layer_bearing
from bearingsim.components.dynamic import RingLoad
from bearingsim.components.rotational import SpeedSource, _signal
from bearingsim.errors import ParameterError
from bearingsim.physics.bearing_design import bearing_design


def _qs_row_loads(**kwargs):
    system = assemble(deep_groove_ball_bearing("6304", "quasi-static", **kwargs))
    obs = system.observe(0.0, np.zeros(0))
    return np.array([obs[f"row.Q_i[{j}]"] for j in range(7)])


# --- 1: unknown load keys -------------------------------------------------------------------

@pytest.mark.parametrize(("key", "hint"), [("fx", "'Fx'"), ("Fr", "'Fx' or 'Fy'"),
                                           ("Fa", "'Fz'"), ("My ", "'My'")])
def test_ring_load_rejects_an_unknown_key_with_a_hint(key, hint):
    with pytest.raises(ParameterError, match="unknown load") as err:
        RingLoad({key: 1000.0})
    assert repr(key) in str(err.value)
    assert "Fx, Fy, Fz, Mx, My" in str(err.value)
    assert f"did you mean {hint}" in str(err.value)


@pytest.mark.parametrize("fidelity", ["quasi-static", "dynamic", "dynamic_massive_balls"])
def test_every_deep_groove_level_rejects_an_unknown_load_key(fidelity):
    with pytest.raises(ParameterError, match="unknown load 'Fr'"):
        deep_groove_ball_bearing("6304", fidelity, loads={"Fr": 1000.0})


def test_double_layer_rejects_an_unknown_load_key():
    with pytest.raises(ParameterError, match="unknown load 'fx'"):
        double_layer_bearing("61905", "61907", fidelity="dynamic", loads={"fx": 100.0})


# --- 2: non-finite constant loads -----------------------------------------------------------

@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_non_finite_constant_loads_are_rejected(value):
    with pytest.raises(ParameterError, match=r"loads\['Fx'\] must be finite.*\[N\]"):
        RingLoad({"Fx": value})
    with pytest.raises(ParameterError, match=r"loads\['My'\] must be finite.*\[N\.m\]"):
        RingLoad({"My": value})
    for fidelity in ("quasi-static", "dynamic"):
        with pytest.raises(ParameterError, match=r"loads\['Fx'\] must be finite"):
            deep_groove_ball_bearing("6304", fidelity, loads={"Fx": value})


def test_a_non_numeric_constant_load_is_rejected():
    # text is a number with a unit ("1 kN"); text without one is refused, saying so
    with pytest.raises(ParameterError, match=r"loads\['Fx'\]: '1000' is not a number with a "
                                             r"unit; write e.g. '2 kN' or a number in N"):
        RingLoad({"Fx": "1000"})
    with pytest.raises(ParameterError, match=r"loads\['Fx'\] must be a number in N or a "
                                             r"number with a unit"):
        RingLoad({"Fx": True})
    # a sequence: a named error (it was a TypeError from float() deep inside)
    for fidelity in ("quasi-static", "dynamic"):
        with pytest.raises(ParameterError, match=r"loads\['Fx'\] must be a number in N or a "
                                                 r"number with a unit \('2 kN'\), got \[100"):
            deep_groove_ball_bearing("6304", fidelity, loads={"Fx": [100.0]})


def test_a_non_finite_constant_signal_is_rejected_when_its_equation_is_built():
    source = SpeedSource(1.0)
    with pytest.raises(ParameterError, match=r"w_in must be finite.*rad/s"):
        _signal(math.nan, source, "w_in", "rad/s")
    assert float(_signal(2.5, source, "w_in", "rad/s")) == 2.5


# --- 3: the quasi-static deep-groove level --------------------------------------------------

def test_quasi_static_level_uses_the_clearance_override():
    alphas = {}
    for clearance in (None, 5e-6, 40e-6):
        bearing = deep_groove_ball_bearing("6304", "quasi-static", clearance=clearance,
                                           loads={"Fx": 1000.0})
        alphas[clearance] = bearing.row.parameter("alpha0").value
        design = bearing_design("6304", clearance)
        assert alphas[clearance] == pytest.approx(design.free_contact_angle, rel=1e-9)
    assert alphas[5e-6] < alphas[None] < alphas[40e-6]
    # more clearance, fewer balls carry the load: the top ball carries more
    q_tight = _qs_row_loads(clearance=5e-6, loads={"Fx": 1000.0}).max()
    q_loose = _qs_row_loads(clearance=40e-6, loads={"Fx": 1000.0}).max()
    assert q_tight < q_loose


@pytest.mark.parametrize("options", [{"free_tilt": True}, {"bogus_option": 3},
                                     {"damping": -5.0}, {"pocket_clearance": 1e-4}])
def test_quasi_static_level_rejects_options_it_does_not_use(options):
    with pytest.raises(ParameterError, match="quasi-static level takes no options") as err:
        deep_groove_ball_bearing("6304", "quasi-static", loads={"Fx": 1000.0}, **options)
    assert next(iter(options)) in str(err.value)


def test_quasi_static_level_takes_a_constant_speed_only():
    with pytest.raises(ParameterError, match="speed must be a constant.*dynamic fidelity"):
        deep_groove_ball_bearing("6304", "quasi-static", speed=lambda t: 100.0 * t)
    with pytest.raises(ParameterError, match="speed.*valid range"):
        deep_groove_ball_bearing("6304", "quasi-static", speed=-10.0)
    with pytest.raises(ParameterError, match="speed must be finite"):
        deep_groove_ball_bearing("6304", "quasi-static", speed=math.nan)
    # None (the default) is a bearing at rest; a constant speed switches the speed effects on
    rest = deep_groove_ball_bearing("6304", "quasi-static", loads={"Fx": 500.0})
    assert not rest.row.speed_effects
    turning = deep_groove_ball_bearing("6304", "quasi-static", speed=500.0,
                                       loads={"Fx": 500.0})
    assert turning.row.speed_effects
    assert turning.row.parameter("inner_speed").value == 500.0


def test_quasi_static_level_rejects_moments_it_cannot_take_and_accepts_zero_ones():
    for loads in ({"Fx": 1000.0, "Mx": 50.0}, {"Fx": 1000.0, "My": None},
                  {"Fx": 1000.0, "My": lambda t: 10.0 * t}):
        with pytest.raises(ParameterError, match="holds the inner ring straight"):
            deep_groove_ball_bearing("6304", "quasi-static", loads=loads)
    q_zero = _qs_row_loads(loads={"Fx": 1000.0, "Mx": 0.0, "My": 0.0})
    assert q_zero.max() == pytest.approx(_qs_row_loads(loads={"Fx": 1000.0}).max(), rel=1e-9)


# --- 4: out-of-range options of the dynamic level -------------------------------------------

@pytest.mark.parametrize("value", [5.0, 0.0, -0.1, math.nan])
def test_oil_fraction_must_be_a_fraction(value):
    with pytest.raises(ParameterError, match="oil_fraction"):
        deep_groove_ball_bearing("6304", "dynamic", loads={"Fx": 500.0}, oil_fraction=value)


@pytest.mark.parametrize("value", [2.5, -1, "2", True])
def test_n_slices_must_be_a_non_negative_integer(value):
    with pytest.raises(ParameterError, match="n_slices must be an integer >= 0"):
        deep_groove_ball_bearing("6304", "dynamic", loads={"Fx": 500.0}, n_slices=value)


def test_guide_clearance_must_be_below_the_pocket_clearance():
    with pytest.raises(ParameterError, match="guide_clearance = 0.0001 m.*smaller.*"
                                             "pocket_clearance = 1e-05 m"):
        bearing_design("6304", pocket_clearance=1e-5, guide_clearance=1e-4)
    with pytest.raises(ParameterError, match="guide_clearance"):
        deep_groove_ball_bearing("6304", "dynamic", loads={"Fx": 500.0},
                                 pocket_clearance=1e-5, guide_clearance=1e-4)
    design = bearing_design("6304", pocket_clearance=2e-4, guide_clearance=1e-4)
    assert design.cage.guide_clearance < design.cage.pocket_clearance
