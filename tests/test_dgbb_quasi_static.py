"""Deep-groove bearing, quasi-static level (issue 7): BallRow fidelity against the dynamic
model's own static solution, load trends, life trends and input errors."""

from __future__ import annotations

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
