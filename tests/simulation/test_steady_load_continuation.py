"""steady_state raises the loads from 0 when Newton and MINPACK fail from the start. A spindle
(7014C DF pair and NU bearing at 0.5 m) under a 15 kN radial load had no steady state alone
("steady state not found", pair.shaft.vx 955 m/s2 left): from the unloaded start, Newton's line
search stalled and MINPACK's hybr made no progress, though a grid reached the point from its
neighbours. Each small rise of the load stays within Newton's reach."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies.registry import REGISTRY
from bearingsim.errors import SimulationError
from bearingsim.simulation import steady_state

LOAD = 15000.0
"""Radial load on the spindle's shaft [N]."""


@pytest.fixture(scope="module")
def spindle():
    spec = REGISTRY["spindle"]
    return assemble(spec.build(spec.with_defaults({"roller_distance": 0.5}), "quasi-static"))


def _derivatives(system, x, inputs):
    u = system.u_default()
    for name, value in inputs.items():
        u[system.input_names.index(name)] = value
    return np.asarray(system.functions["ode"](0.0, x, u, system.p0())).ravel()


def test_a_heavy_load_is_reached_from_the_unloaded_start(spindle):
    inputs = {"pair.shaft.Fx": LOAD}
    x = steady_state(spindle, inputs=inputs)
    assert np.abs(_derivatives(spindle, x, inputs)).max() <= 1e-9
    # the same state as a path of the user's own: the load raised by hand, 3 kN at a time
    walked = None
    for fraction in np.linspace(0.2, 1.0, 5):
        walked = steady_state(spindle, inputs={"pair.shaft.Fx": fraction * LOAD},
                              x_guess=walked)
    np.testing.assert_allclose(x, walked, rtol=1e-8, atol=1e-15)
    shaft_x = x[spindle.state_names.index("pair.shaft.x")]
    assert shaft_x > 0.0  # the shaft moves along the load


def test_a_load_beyond_any_steady_state_stays_an_error():
    """A load no steady state carries (a tandem pair pushed backwards by twice its 1 kN
    preload spring) stays an error: the rising load passes what the pair carries, the
    continuation finds no path, and MINPACK's message is raised."""
    from bearingsim.assemblies.duplex import duplex_pair

    system = assemble(duplex_pair("7020C", "DT", preload=1000.0))
    with pytest.raises(SimulationError, match="steady state not found"):
        steady_state(system, inputs={"shaft.Fz": -2000.0})  # a tandem pair held backwards
