"""steady_state's Newton iteration shortens a step that would raise the residual: from a start
point far from the root (the previous point of a steady sweep), full Newton steps on a
double-layer bearing's middle-ring speed oscillated with a growing residual
(218.9 -> -291 -> 473 -> -505 ... rad/s) and the solve fell back to MINPACK's hybr, importing
scipy.optimize (about 0.6 s) in the ``double_layer_rs`` scene's 13th point."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim import Component, Variable, der
from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.errors import SimulationError
from bearingsim.simulation import steady_state

INPUTS = {"shaft_speed": 104.71975511965977, "Fr": 1000.0, "Fa": 0.0}
"""The scene's point of 1000 r/min and 1 kN [rad/s, N, N]."""
START = 218.87378242
"""The middle-ring speed the scene started that point from (its previous point's) [rad/s]."""


def test_newton_reaches_the_root_from_far_without_minpack(monkeypatch):
    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque", drive="speed"))
    guess = system.x0()
    guess[system.state_names.index("middle.sleeve.w")] = START

    def no_minpack(*args, **kwargs):
        raise AssertionError("steady_state fell back to MINPACK")

    monkeypatch.setattr("scipy.optimize.root", no_minpack)
    x = steady_state(system, inputs=INPUTS, x_guess=guess)
    near = steady_state(system, inputs=INPUTS)  # from the model's own start values
    np.testing.assert_allclose(x, near, rtol=1e-10)
    u = system.u_default()
    for name, value in INPUTS.items():
        u[system.input_names.index(name)] = value
    derivative = np.asarray(system.functions["ode"](0.0, x, u, system.p0())).ravel()
    w = system.state_names.index("middle.sleeve.w")
    assert abs(derivative[w]) <= 1e-9
    assert 0.0 < x[w] < INPUTS["shaft_speed"]  # between the housing and the shaft
    assert x[w] == pytest.approx(near[w], rel=1e-10)


class RunningOff(Component):
    """y' = a exp(y): no steady state; the derivative falls below any tolerance as y runs off
    towards minus infinity (below 1e-9 /s for y < -20.7)."""

    def __init__(self, a: float, start: float):
        super().__init__("running")
        self.a = a
        self.y = Variable(start, "1", "level")

    def equations(self):
        return [der(self.y) == self.a * ca.exp(self.y)]


class Relaxing(Component):
    """y' = b - a y: the steady state y = b / a."""

    def __init__(self, a: float, b: float):
        super().__init__("relaxing")
        self.a, self.b = a, b
        self.y = Variable(0.0, "m", "position")

    def equations(self):
        return [der(self.y) == self.b - self.a * self.y]


def test_derivatives_that_vanish_only_as_a_state_runs_off_are_no_steady_state():
    """steady_state of y' = exp(y) from y = 0 returned y = -138 (MINPACK stopped there after
    200 evaluations, the derivative 1e-60 /s below residual_tol, which accepted it): a point
    that is no steady state, given as one. A Newton step from it still moves y by -1; such a
    point is now refused, naming the state, its derivative and the step."""
    with pytest.raises(SimulationError, match=r"run off: where the solver stopped after \d+ "
                                              r"evaluations, y = -1\d\d\.\d+ \(derivative "
                                              r"\S+e-\d\d 1/s, Newton step -1\)"):
        steady_state(assemble(RunningOff(1.0, 0.0)), compiled=False)


@given(a=st.floats(0.1, 10.0), start=st.floats(-5.0, 5.0))
@settings(max_examples=8, deadline=None)
def test_no_start_finds_a_steady_state_where_there_is_none(a, start):
    """y' = a exp(y) from anywhere: refused (running off, or MINPACK stalled), never a
    value."""
    with pytest.raises(SimulationError, match="steady state not found"):
        steady_state(assemble(RunningOff(a, start)), compiled=False)


@given(a=st.floats(1e-4, 1e4), b=st.floats(-1e3, 1e3))
@settings(max_examples=8, deadline=None)
def test_a_linear_relaxation_has_its_analytic_steady_state(a, b):
    """y' = b - a y: y = b / a, over eight decades of the rate."""
    x = steady_state(assemble(Relaxing(a, b)), compiled=False)
    assert x[0] == pytest.approx(b / a, rel=1e-9, abs=1e-12)


def test_the_guess_is_not_overwritten():
    """steady_state wrote its solution into the caller's x_guess array (the guess a caller
    keeps for the next point, or a scene's start values, changed under it)."""
    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque", drive="speed"))
    guess = system.x0()
    kept = guess.copy()
    x = steady_state(system, inputs=INPUTS, x_guess=guess)
    np.testing.assert_array_equal(guess, kept)
    assert not np.array_equal(x, kept)  # the solution moved away from the guess
