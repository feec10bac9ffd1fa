"""Audit gaps: linearize at a run's own inputs and parameters, Hertz contact loads reject a
non-finite approach, and diameters passed in millimetres are flagged.

Each test failed before its fix: ``linearize(system, result)`` used the default inputs and
parameters at t = 0, ``contact_load``/``contact_stiffness`` returned NaN for ``delta = nan``,
and ``palmgren_torque(dm=40)`` and its neighbours returned huge numbers for millimetre values.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from bearingsim import Component, Input, Parameter, Variable, der, time
from bearingsim.assembler import assemble
from bearingsim.errors import ParameterError
from bearingsim.physics import contact_curvature, contact_law, film, life
from bearingsim.physics.friction import (
    palmgren_m0,
    palmgren_torque,
    skf_friction_components,
    skf_friction_torque,
)
from bearingsim.physics.lubricant import get_lubricant
from bearingsim.simulation import linearize, simulate

OIL = get_lubricant("ISO VG 68")


class _Decay(Component):
    """``x' = -k speed x (1 + t)``: A depends on the input, the parameter and the time."""

    def __init__(self, name="decay", parameter="k"):
        super().__init__(name)
        self.x = Variable(1.0, "m")
        self.speed = Input(1.0, "rad/s", "speed", low=0.0)
        setattr(self, parameter, Parameter(1.0, "1"))
        self._parameter = parameter

    def equations(self):
        k = getattr(self, self._parameter)
        return [der(self.x) == -k * self.speed * self.x * (1.0 + time)]


@pytest.fixture(scope="module")
def decay():
    return assemble(_Decay())


def test_linearize_a_result_uses_the_runs_inputs_parameters_and_end_time(decay):
    res = simulate(decay, 1.0, inputs={"speed": 3.0}, parameters={"k": 2.0})
    assert res.inputs == {"speed": 3.0}
    assert res.parameters == {"k": 2.0}
    lin = linearize(decay, res)
    # A = -k speed (1 + t) at k = 2, speed = 3, t = 1; B = -k x (1 + t)
    np.testing.assert_allclose(lin.A, [[-12.0]], rtol=1e-12)
    np.testing.assert_allclose(lin.B, [[-2.0 * res.final("x") * 2.0]], rtol=1e-12)
    np.testing.assert_allclose(lin.u_op, [3.0])
    np.testing.assert_allclose(lin.x_op, [res.final("x")])


def test_linearize_a_result_takes_time_varying_inputs_at_the_last_output_time(decay):
    res = simulate(decay, 2.0, inputs={"speed": lambda t: 1.0 + t},
                   t_eval=np.linspace(0.0, 1.5, 4))
    assert res.inputs["speed"] == pytest.approx(2.5, rel=1e-12)
    np.testing.assert_allclose(linearize(decay, res).A, [[-2.5 * 2.5]], rtol=1e-12)
    table = simulate(decay, 1.0, inputs={"speed": ([0.0, 0.5], [1.0, 4.0])})
    np.testing.assert_allclose(linearize(decay, table).u_op, [4.0])


def test_explicit_inputs_parameters_and_time_override_single_entries_of_the_run(decay):
    res = simulate(decay, 1.0, inputs={"speed": 3.0}, parameters={"k": 2.0})
    np.testing.assert_allclose(linearize(decay, res, inputs={"speed": 5.0}).A, [[-20.0]])
    np.testing.assert_allclose(linearize(decay, res, parameters={"k": 1.0}).A, [[-6.0]])
    np.testing.assert_allclose(linearize(decay, res, t=0.0).A, [[-6.0]])
    # a state dict or vector keeps the defaults (speed = 1, k = 1, t = 0)
    np.testing.assert_allclose(linearize(decay, {"x": 0.5}).A, [[-1.0]])
    with pytest.raises(ParameterError,
                       match=r"linearize: inputs: speed = -1.0 \[rad/s\] .*\[0, inf\)"):
        linearize(decay, res, inputs={"speed": -1.0})
    with pytest.raises(ParameterError, match="unknown parameter 'kk'"):
        linearize(decay, res, parameters={"kk": 1.0})


def test_linearize_rejects_a_result_of_another_system(decay):
    other = assemble(_Decay("other", parameter="c"))
    res = simulate(other, 1.0, inputs={"speed": 3.0})
    with pytest.raises(ParameterError, match=r"linearize: the result's recorded parameters "
                       r"are not this system's .*'c'.*'k'"):
        linearize(decay, res)


@pytest.mark.parametrize("function", [contact_law.contact_load, contact_law.contact_stiffness])
@pytest.mark.parametrize("smooth", [None, 1e-8])
def test_contact_load_and_stiffness_reject_a_non_finite_approach(function, smooth):
    name = function.__name__
    for delta in (float("nan"), np.inf, np.array([1e-6, np.nan])):
        with pytest.raises(ParameterError, match=rf"{name}: delta must be finite.*\[m\]"):
            function(1e10, delta, smooth)
    # numbers of either sign and symbols still pass
    assert np.all(np.isfinite(function(1e10, np.array([-1e-6, 0.0, 1e-6]), smooth)))
    d = ca.SX.sym("d")
    assert isinstance(function(1e10, d, smooth), ca.SX)


MM_SLIPS = [
    (lambda: palmgren_torque(100.0, 40.0, OIL, "deep_groove_ball"), "palmgren_torque", "dm"),
    (lambda: palmgren_m0(1e-5, 100.0, 38.5, 2.0), "palmgren_m0", "dm"),
    (lambda: skf_friction_components(100.0, 38.5, OIL, "62", 500.0, C0=7800.0, d=0.025,
                                     D=0.052), "skf_friction_components", "dm"),
    (lambda: skf_friction_torque(100.0, 0.0385, OIL, "62", 500.0, C0=7800.0, d=25.0,
                                 D=52.0), "skf_friction_components", "d"),
    (lambda: skf_friction_components(100.0, 0.0385, OIL, "62", 500.0, C0=7800.0, d=0.025,
                                     D=52.0), "skf_friction_components", "D"),
    (lambda: film.rolling_entrainment_speed(100.0, 7.94, 38.5), "rolling_entrainment_speed",
     "Dw"),
    (lambda: life.dynamic_load_rating(7.94, 38.5, 9), "dynamic_load_rating", "ball_diameter"),
    (lambda: life.static_load_rating(0.00794, 38.5, 9), "static_load_rating",
     "pitch_diameter"),
    (lambda: life.static_factor(7.94, 38.5), "static_factor", "ball_diameter"),
    (lambda: life.raceway_contact_capacity(7.94, 38.5, 0.52, 9, 0.0, "inner"),
     "raceway_contact_capacity", "ball_diameter"),
    (lambda: contact_curvature.raceway_radii(0.00794, 38.5, 0.52, 0.0, "outer"), "raceway_radii",
     "pitch_diameter"),
]


@pytest.mark.parametrize(("call", "where", "name"), MM_SLIPS,
                         ids=[f"{w}-{n}" for _, w, n in MM_SLIPS])
def test_millimetre_diameters_are_flagged(call, where, name):
    with pytest.raises(ParameterError, match=rf"^{where}: {name} = .* \[m\] is outside the "
                       r"valid range \(0, .*\] \[m\] \(did you pass mm\?\)$"):
        call()


def test_diameter_checks_keep_large_bearings_arrays_and_symbols():
    with pytest.raises(ParameterError, match=r"did you pass mm\?"):
        palmgren_torque(100.0, np.array([0.04, 40.0]), OIL, "deep_groove_ball")
    # a slewing bearing of 4 m pitch diameter with 100 mm balls is still accepted
    rating = life.dynamic_load_rating(0.1, 4.0, 120, rows=1)
    assert np.isfinite(rating) and rating > 0.0
    torque = palmgren_torque(np.array([1.0, 2.0]), np.array([4.0, 0.04]), OIL,
                             "deep_groove_ball")
    assert np.all(np.isfinite(torque)) and np.all(torque < 0.0)
    dm = ca.SX.sym("dm")
    assert isinstance(palmgren_torque(100.0, dm, OIL, "deep_groove_ball"), ca.SX)
    assert isinstance(film.rolling_entrainment_speed(100.0, 0.00794, dm), ca.SX)
    # non-positive values keep the plain range message (not a millimetre slip)
    with pytest.raises(ParameterError) as err:
        palmgren_m0(1e-5, 100.0, -0.04, 2.0)
    assert "did you pass mm" not in str(err.value)
