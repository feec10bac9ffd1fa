"""Deep-groove bearing with a rotating outer ring (``outer_ring="flange"``): driving both rings
at the same speed turns the whole bearing as one rigid body."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim import Assembly, connect
from bearingsim.assembler import assemble
from bearingsim.assemblies.deep_groove import (
    DeepGrooveBallBearing,
    DeepGrooveOptions,
    FilmOptions,
    RingOptions,
)
from bearingsim.components.rotational import SpeedSource
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.physics.lubricant import Oil
from bearingsim.simulation import simulate

W = 100.0  # rad/s


class CoRotating(Assembly):
    def __init__(self):
        super().__init__("rig")
        options = DeepGrooveOptions(massive_balls=True, speed=W, loads={"Fx": 300.0},
                                    rings=RingOptions(outer_ring="flange"),
                                    film=FilmOptions(n_slices=1, drag=False))
        self.bearing = DeepGrooveBallBearing(bearing_design("6304"), Oil.from_iso_vg(32),
                                             options)
        self.outer_drive = SpeedSource(W)
        connect(self.outer_drive.flange, self.bearing.outer_flange)


@pytest.mark.slow
def test_rings_at_the_same_speed_carry_the_cage_along_rigidly():
    system = assemble(CoRotating(), outputs=["bearing.w_cage", "bearing.w_outer",
                                             "bearing.w_epicyclic", "bearing.ball[0].w_orbit"])
    res = simulate(system, 0.4, method="cvodes", rtol=1e-6, atol=1e-9, n_points=41)
    assert res.final("bearing.w_outer") == pytest.approx(W)
    assert res.final("bearing.w_epicyclic") == pytest.approx(W)  # (1-g)/2 W + (1+g)/2 W
    np.testing.assert_allclose(res["bearing.w_cage"][-3:], W, rtol=2e-3)
    np.testing.assert_allclose(res["bearing.ball[0].w_orbit"][-3:], W, rtol=2e-3)
