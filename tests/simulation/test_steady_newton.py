"""steady_state's Newton iteration shortens a step that would raise the residual: from a start
point far from the root (the previous point of a steady sweep), full Newton steps on a
double-layer bearing's middle-ring speed oscillated with a growing residual
(218.9 -> -291 -> 473 -> -505 ... rad/s) and the solve fell back to MINPACK's hybr, importing
scipy.optimize (about 0.6 s) in the ``double_layer_rs`` scene's 13th point."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
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
