"""One sign convention for the bearing friction torque: ``M_shaft`` (and the motor drive's
``bearing.M_shaft``) is the torque the bearing exerts on the shaft, so it opposes the rotation:
negative while the shaft turns forward, positive backwards; the steady torque level and the
motor drive report the same value for the same bearing and speed."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.assemblies.motor_drive import motor_drive
from bearingsim.simulation import simulate
from bearingsim.studies.double_layer import steady_ratio


@pytest.fixture(scope="module")
def torque_level():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque", drive="speed"))


@pytest.mark.parametrize("speed", [50.0, 1000.0])
def test_the_friction_torque_on_the_shaft_opposes_its_rotation(torque_level, speed):
    _, forward, _ = steady_ratio(torque_level, speed, loads=(500.0, 0.0))
    _, backward, _ = steady_ratio(torque_level, -speed, loads=(500.0, 0.0))
    assert forward < 0.0 < backward
    np.testing.assert_allclose(backward, -forward, rtol=1e-9)  # odd in the speed


def test_the_motor_drive_reports_the_same_torque_as_the_bearing_alone(torque_level):
    """The drive holds 300 rad/s; at its end the bearing is at its steady state, so its
    ``bearing.M_shaft`` is the steady torque level's ``M_shaft`` (same sign, same value)."""
    bearing = double_layer_bearing("61905", "61907", fidelity="torque", drive="flange")
    drive = assemble(motor_drive(bearing, motor="dc", speed_ref=300.0, load_torque=0.0))
    res = simulate(drive, 3.0, method="cvodes", rtol=1e-9, atol=1e-11, n_points=3,
                   inputs={"Fr": 0.0, "Fa": 0.0} if "Fr" in drive.input_names else None)
    w = res.final("shaft.w")
    _, alone, _ = steady_ratio(torque_level, w, loads=(0.0, 0.0))
    assert res.final("bearing.M_shaft") < 0.0
    np.testing.assert_allclose(res.final("bearing.M_shaft"), alone, rtol=1e-4)
