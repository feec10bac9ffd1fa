"""steady_state on a model whose angles turn with a speed input: steady running is periodic,
never a fixed point, and the error says so. It said ``steady state not found: The iteration
is not making good progress ...; residual max 1.96e+04 for states`` followed by all 75 state
names of the 6304's ball-level model (a scene with ``analysis = "steady"`` at 1730 r/min)."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim import Component, Input, Variable, der
from bearingsim.assembler import assemble
from bearingsim.errors import SimulationError
from bearingsim.simulation import steady_state
from bearingsim.symbolic import sin


class _Rotor(Component):
    """A rotor spun up to the input speed (``w' = (speed - w) / tau``), its angle (``phi' = w``)
    and a deflection that follows the angle (``y' = sin(phi) - y``): the angle matters, so
    steady_state must solve for it."""

    def __init__(self):
        super().__init__("rotor")
        self.speed = Input(0.0, "rad/s", "drive speed")
        self.w = Variable(0.0, "rad/s")
        self.phi = Variable(0.0, "rad")
        self.y = Variable(0.0, "m")

    def equations(self):
        return [der(self.w) == (self.speed - self.w) / 0.01, der(self.phi) == self.w,
                der(self.y) == 1e-3 * sin(self.phi) - self.y]


@pytest.fixture(scope="module")
def rotor():
    return assemble(_Rotor())


def test_a_turning_model_has_no_steady_state_and_the_error_says_why(rotor):
    with pytest.raises(SimulationError, match=r"rotor: no steady state: the inputs turn it "
                       r"\(speed = 100 rad/s\) and its angles turn with it \(phi: .*periodic, "
                       r"not a fixed point; run it in time") as caught:
        steady_state(rotor, inputs={"speed": 100.0})
    assert "y" not in str(caught.value).split("(phi")[1].split(")")[0]


def test_at_rest_the_same_model_has_its_steady_states(rotor):
    """At rest any angle is steady (not unique: the guess's is kept on request)."""
    x = steady_state(rotor, inputs={"speed": 0.0}, x_guess=np.array([0.0, 0.5, 0.0]),
                     require_unique=False)
    names = rotor.state_names
    assert x[names.index("w")] == 0.0
    assert x[names.index("y")] == pytest.approx(1e-3 * np.sin(x[names.index("phi")]), abs=1e-15)


def test_the_turning_angles_are_found_from_the_structure(rotor):
    """phi is read by y's derivative and its own derivative is the speed w: a turning angle.
    A free rotor's angle, which nothing reads, is not one (it has no steady value to solve)."""
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.simulation.steady import turning_angles

    assert turning_angles(rotor) == ["phi"]
    assert turning_angles(assemble(double_layer_bearing())) == []  # middle.sleeve.phi: free


def test_a_steady_scene_of_a_turning_model_is_refused_before_it_runs():
    """A steady scene of a ball-level bearing at speed passed `bearingsim validate` and failed
    at every point when run; the check is now the scene's, at its analysis key."""
    from bearingsim.scenes import SceneError, parse_scene, validate_scene

    text = ('analysis = "steady"\noutputs = ["cage.w"]\n[assembly]\n'
            'name = "deep_groove_ball_bearing"\nbearing = "6205"\n'
            'fidelity = "dynamic_massive_balls"\n[inputs]\nshaft_speed = "3000 rpm"\n'
            '[grid]\n"inputs.load.Fx" = [100.0, 500.0]\n')
    with pytest.raises(SceneError, match=r"analysis: deep_groove_ball_bearing at fidelity "
                       r"dynamic_massive_balls has no steady state while shaft_speed turns it: "
                       r"its angles turn with it \(cage.phi, ball\[0\].theta") as caught:
        validate_scene(parse_scene(text))
    assert caught.value.line == 1


def test_a_speed_controllers_integral_is_no_turning_angle():
    """A PI speed controller integrates the speed error, ``xi' = w_ref - w``, in rad: taken for
    a turning angle (one state, a speed, in its derivative), it made a steady or modes scene of
    the motor drive refused ("no steady state while motor.w_ref turns it ... periodic"),
    though the drive settles where w = w_ref. Its derivative also depends on the input w_ref,
    which a turning angle's (phi' = w) does not. The steady drive runs at the reference speed
    exactly (integral action) and its bearing has the Rs of the bare bearing at that speed."""
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.assemblies.motor_drive import motor_drive
    from bearingsim.scenes import parse_scene, run_scene
    from bearingsim.simulation.steady import turning_angles

    for motor in ("dc", "pmsm"):
        assert turning_angles(assemble(motor_drive(motor=motor))) == []
    rows = run_scene(parse_scene(
        'analysis = "steady"\noutputs = ["shaft.w", "bearing.Rs"]\n[assembly]\n'
        'name = "motor_drive"\n[grid]\n"inputs.motor.w_ref" = ["1000 rpm", "3000 rpm"]\n'),
        write=False).rows
    bare = assemble(double_layer_bearing())
    for row in rows:
        assert row["shaft.w"] == pytest.approx(row["motor.w_ref"], rel=1e-9)
        x = steady_state(bare, inputs={"shaft_speed": row["motor.w_ref"]})
        w_middle = x[bare.state_names.index("middle.sleeve.w")]
        assert row["bearing.Rs"] == pytest.approx(w_middle / row["motor.w_ref"], rel=1e-6)
