"""Deep-groove bearing, quasi-static level (issue 7): BallRow fidelity against the dynamic
model's own static solution, load trends, life trends and input errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.errors import ParameterError
from bearingsim.physics.ball_equilibrium import static_state
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.life import dynamic_load_rating, rating_life


def _row_loads(load):
    system = assemble(deep_groove_ball_bearing("6304", "quasi-static", loads={"Fx": load}))
    obs = system.observe(0.0, np.zeros(0))
    return np.array([obs[f"row.Q_i[{j}]"] for j in range(7)])


@pytest.mark.parametrize("load", [266.0, 500.0, 938.0])
def test_ball_row_matches_the_dynamic_models_static_solution(load):
    q_row = _row_loads(load)
    q_dyn = static_state(bearing_design("6304"), {"Fx": load}).q_inner
    assert q_row.max() == pytest.approx(q_dyn.max(), rel=5e-3)
    assert np.allclose(q_row, q_dyn, atol=5e-3 * load)


def test_load_distribution_balances_the_radial_load_and_grows_with_it():
    s = static_state(bearing_design("6304"), {"Fx": 500.0})
    theta = 2 * np.pi * np.arange(7) / 7
    assert np.sum(s.q_inner * np.cos(theta) * np.cos(s.alpha_inner)) == pytest.approx(500.0,
                                                                                   rel=1e-3)
    # with 20 um clearance the top ball carries more than Stribeck's 4.37 Fr / Z
    assert s.q_inner.max() > 4.37 * 500.0 / 7
    assert static_state(bearing_design("6304"), {"Fx": 938.0}).q_inner.max() > s.q_inner.max()


def test_centrifugal_force_loads_the_outer_race_more():
    s = static_state(bearing_design("6304"), {"Fx": 206.0}, w_cage=160.0)
    fc = bearing_design("6304").ball_mass * 0.018 * 160.0**2
    assert np.allclose(s.q_outer - s.q_inner, fc, rtol=0.05)


def test_iso281_life_falls_with_load():
    g = bearing_design("6304").geometry
    c = dynamic_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count)
    assert c == pytest.approx(g.dynamic_load_rating, rel=0.1)
    lives = [rating_life(c, p) for p in (206.0, 266.0, 903.0, 938.0)]
    assert np.all(np.diff(lives) < 0)


def test_bad_inputs_name_the_parameter():
    with pytest.raises(ParameterError, match="fidelity"):
        deep_groove_ball_bearing("6304", "kinematic")
    with pytest.raises(ParameterError, match="clearance"):
        deep_groove_ball_bearing("6304", clearance=-1e-6)
    with pytest.raises(ParameterError, match="housing"):
        deep_groove_ball_bearing("6304", housing="soft")


# ------------------------------------------------------------------ at speed (issue 17)
def _at_speed(factor: float, loads):
    from bearingsim.catalog import get_bearing

    w = factor * get_bearing("6304").limiting_speed
    return w, assemble(deep_groove_ball_bearing("6304", "quasi-static", speed=w, loads=loads))


@pytest.mark.parametrize("factor", [0.1, 0.5, 1.0, 1.5])
def test_quasi_static_level_solves_at_speed_up_to_one_and_a_half_limiting_speeds(factor):
    """Centrifugal and gyroscopic ball loads (Jones-Harris form): once NaN at every speed (the
    Newton blocks started every ball on the pitch circle, out of contact). The unloaded balls
    now press on the outer race with their centrifugal force m (dm/2) w_c^2, w_c the cage
    speed of pure rolling at the inner contact angle 0."""
    from bearingsim.simulation import linearize, simulate

    w, system = _at_speed(factor, {"Fx": 500.0})
    res = simulate(system, 1e-3, n_points=3)
    q_i = np.array([res[f"row.Q_i[{j}]"][-1] for j in range(7)])
    q_o = np.array([res[f"row.Q_o[{j}]"][-1] for j in range(7)])
    assert np.all(np.isfinite(q_i)) and np.all(np.isfinite(q_o))
    g = bearing_design("6304").geometry
    theta = 2 * np.pi * np.arange(7) / 7
    assert np.sum(q_i * np.cos(theta) * np.cos([res[f"row.alpha_i[{j}]"][-1]
                                                 for j in range(7)])) == pytest.approx(500.0,
                                                                                     rel=1e-6)
    gamma = g.ball_diameter / g.pitch_diameter
    w_cage = 0.5 * (1 - gamma) * w
    mass = 7850.0 * np.pi * g.ball_diameter**3 / 6
    f_c = mass * 0.5 * g.pitch_diameter * w_cage**2
    unloaded = q_i < 1e-3
    assert unloaded.any()
    np.testing.assert_allclose(q_o[unloaded], f_c, rtol=0.02)
    assert np.all(np.isfinite(linearize(system).D))


def test_load_inputs_at_speed_solve_like_constant_loads():
    """With load inputs the equilibrium moves away from the start values: the blocks get a line
    search, and the result equals the system built for the constant load."""
    from bearingsim.simulation import simulate

    _, constant = _at_speed(1.0, {"Fx": 800.0, "Fy": 0.0, "Fz": 200.0})
    _, inputs = _at_speed(1.0, None)
    assert inputs.rootfinder == "newton" and constant.rootfinder == "fast_newton"
    a = simulate(constant, 1e-3, n_points=3)
    b = simulate(inputs, 1e-3, n_points=3, inputs={"load.Fx": 800.0, "load.Fz": 200.0})
    for j in range(7):
        assert b[f"row.Q_o[{j}]"][-1] == pytest.approx(a[f"row.Q_o[{j}]"][-1], rel=1e-6,
                                                       abs=1e-6)


def test_a_speed_without_ball_equilibrium_is_named():
    import dataclasses

    from bearingsim.catalog import get_bearing
    from bearingsim.catalog.geometry import SPEED_LIMIT_MULTIPLE

    w = 30 * get_bearing("6304").limiting_speed
    # a catalogue bearing is refused above twice its limiting speed (docs/units.md) ...
    with pytest.raises(ParameterError, match=f"more than {SPEED_LIMIT_MULTIPLE:g} x the "
                                             f"limiting speed of 6304"):
        deep_groove_ball_bearing("6304", "quasi-static", speed=w, loads={"Fx": 500.0})
    # ... a geometry without a limiting speed reaches the equilibrium, which names the speed
    free = dataclasses.replace(get_bearing("6304"), limiting_speed=None)
    with pytest.raises(ParameterError, match=r"no quasi-static ball equilibrium at the "
                                             r"inner-ring speed .* r/min"):
        deep_groove_ball_bearing(free, "quasi-static", speed=w, loads={"Fx": 500.0})


def test_non_finite_variables_raise_a_named_simulation_error():
    """A Newton block that finds no solution used to come back as NaN series."""
    from bearingsim.errors import SimulationError
    from bearingsim.simulation import simulate

    system = assemble(deep_groove_ball_bearing("6304", "quasi-static", speed=2000.0),
                      rootfinder="fast_newton")
    with pytest.raises(SimulationError, match=r"not finite at t = 0 s: row\..*nonlinear blocks"):
        simulate(system, 1e-3, n_points=3, inputs={"load.Fx": 500.0})


@pytest.mark.parametrize("fidelity", ["quasi-static", "dynamic"])
def test_clearance_takes_a_number_with_a_unit(fidelity):
    """As simulate inputs and parameters do (docs/units.md); old code: TypeError: '<' not
    supported between instances of 'str' and 'float' (from bearing_design)."""
    def model(clearance):
        bearing = deep_groove_ball_bearing("6304", fidelity, clearance=clearance,
                                           **({"loads": {"Fx": 500.0}} if fidelity ==
                                              "quasi-static" else {}))
        system = assemble(bearing)
        return system.p0(), system.x0()

    for given, same in zip(model("20 um"), model(20e-6), strict=True):
        np.testing.assert_array_equal(given, same)
    assert deep_groove_ball_bearing("6304", "dynamic", clearance="20 um").design.clearance \
        == pytest.approx(20e-6, rel=1e-15)
    with pytest.raises(ParameterError, match=r"deep_groove_ball_bearing: clearance: '20' is not "
                                             r"a number with a unit"):
        deep_groove_ball_bearing("6304", fidelity, clearance="20")
    with pytest.raises(ParameterError, match=r"clearance = 0.001 \[m\] is outside the valid "
                                             r"range \[0, 9.52e-05\] \[m\]"):
        deep_groove_ball_bearing("6304", fidelity, clearance="1 mm")


@pytest.mark.parametrize("fidelity", ["quasi-static", "dynamic"])
def test_speed_takes_a_number_with_a_unit(fidelity):
    """``speed="3000 rpm"`` was refused, at the dynamic level by the internal SpeedSource
    ("SpeedSource: speed must be a number in rad/s"); now converted as clearance is."""
    with_unit = deep_groove_ball_bearing("6304", fidelity, speed="3000 rpm")
    in_si = deep_groove_ball_bearing("6304", fidelity, speed=3000 * math.pi / 30)
    if fidelity == "quasi-static":  # the speed is in the ball row's parameters
        np.testing.assert_allclose(assemble(with_unit).p0(), assemble(in_si).p0(), rtol=1e-15)
    else:
        assert with_unit.options.speed == pytest.approx(in_si.options.speed, rel=1e-15)
    with pytest.raises(ParameterError, match=r"deep_groove_ball_bearing: speed: 'kN' is not a "
                                             r"unit of rad/s quantities"):
        deep_groove_ball_bearing("6304", fidelity, speed="3 kN")
