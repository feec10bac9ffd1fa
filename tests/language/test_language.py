"""The modeling language: declarations, errors that name the culprit, connections, arrays and
nesting (issue 2)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from bearingsim import (
    Assembly,
    Component,
    Input,
    Variable,
    connect,
    der,
)
from bearingsim.assembler import assemble
from bearingsim.components.connectors import Flange
from bearingsim.components.rotational import Fixed, Inertia, Spring, TorqueSource
from bearingsim.errors import ConnectionError_, ModelError, ParameterError, UnconnectedInputError
from bearingsim.simulation import simulate
from tests.models import Pin, Resistor


def test_out_of_range_parameter_names_path_unit_and_range():
    class Holder(Assembly):
        def __init__(self):
            super().__init__("holder")
            self.j = Inertia(1.0)

    h = Holder()
    with pytest.raises(ParameterError) as err:
        h.j.J = -2.0
    msg = str(err.value)
    assert "j.J" in msg and "kg.m2" in msg and "(0, inf)" in msg


def test_wrongly_typed_parameter_is_rejected():
    with pytest.raises(ParameterError, match=r"'heavy' is not a number with a unit; write e\.g\. "
                                             r"'10 kg\.m2' or a number in kg\.m2"):
        Inertia(J="heavy")  # text is read as a number with a unit ("3 g m^2")
    with pytest.raises(ParameterError, match="must be a real number"):
        Inertia(J=[1.0])
    with pytest.raises(ParameterError, match="NaN|finite"):
        Inertia(J=float("nan"))


@given(st.floats(min_value=1e-6, max_value=1e6))
def test_valid_parameters_are_accepted_and_stored(value):
    j = Inertia(value)
    assert j.parameter("J").value == value


def test_connector_type_mismatch_is_an_error():
    class Bad(Assembly):
        def __init__(self):
            super().__init__("bad")
            self.r = Resistor()
            self.j = Inertia()
            connect(self.r.p, self.j.flange_a)

    with pytest.raises(ConnectionError_, match="Pin.*Flange|types differ"):
        Bad()


def test_unconnected_required_input_names_the_input():
    class NeedsInput(Component):
        def __init__(self, name=None):
            super().__init__(name)
            self.u = Input(unit="N.m", description="drive torque")
            self.w = Variable(0.0, "rad/s")

        def equations(self):
            return [der(self.w) == self.u]

    class Top(Assembly):
        def __init__(self):
            super().__init__("top")
            self.part = NeedsInput()

    with pytest.raises(UnconnectedInputError, match=r"part\.u \[N\.m\]"):
        assemble(Top())
    root = assemble(NeedsInput("alone"))  # inputs of the root become system inputs
    assert root.input_names == ["u"]
    res = simulate(root, 1.0, inputs={"u": 2.0})
    assert res.final("w") == pytest.approx(2.0)


def test_constant_equation_is_reported():
    class Trivial(Component):
        def __init__(self):
            super().__init__("trivial")
            self.x = Variable(0.0)

        def equations(self):
            return [der(self.x) == 1.0, 1.0 == 1.0]

    with pytest.raises(ModelError, match="constant"):
        assemble(Trivial())


class Ladder(Assembly):
    """An array of resistors between a source pin held at 1 V and ground."""

    def __init__(self, n=5):
        super().__init__("ladder")
        self.r = [Resistor(float(k + 1)) for k in range(n)]
        self.src = Source()
        self.gnd = Ground()
        connect(self.src.p, self.r[0].p)
        for a, b in zip(self.r[:-1], self.r[1:], strict=True):
            connect(a.n, b.p)
        connect(self.r[-1].n, self.gnd.p)


class Source(Component):
    def __init__(self, name=None):
        super().__init__(name)
        self.p = Pin()
        self.dummy = Variable(0.0)

    def equations(self):
        return [self.p.v == 1.0, der(self.dummy) == 0.0]


class Ground(Component):
    def __init__(self, name=None):
        super().__init__(name)
        self.p = Pin()

    def equations(self):
        return [self.p.v == 0.0]


def test_arrays_of_components_have_indexed_names_and_solve():
    system = assemble(Ladder(5))
    obs = system.observe(0.0, system.x0())
    total = sum(range(1, 6))
    assert obs["r[2].p.i"] == pytest.approx(1.0 / total)
    assert obs["r[4].n.v"] == pytest.approx(0.0, abs=1e-12)


class SpringMass(Assembly):
    """A nested assembly exposing an outside flange."""

    def __init__(self, name=None):
        super().__init__(name)
        self.flange = Flange()
        self.spring = Spring(100.0)
        self.mass = Inertia(1.0)
        connect(self.flange, self.spring.flange_a)
        connect(self.spring.flange_b, self.mass.flange_a)


def test_nested_assemblies_connect_through_outside_connectors():
    class Top(Assembly):
        def __init__(self):
            super().__init__("top")
            self.wall = Fixed()
            self.unit = SpringMass()
            connect(self.wall.flange, self.unit.flange)

    system = assemble(Top())
    assert set(system.state_names) == {"unit.mass.phi", "unit.mass.w"}
    res = simulate(system, 1.0, x0={"unit.mass.phi": 0.1}, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(res["unit.mass.phi"], 0.1 * np.cos(10.0 * res.t), atol=1e-7)
    # the wall carries the spring force: flows sum to zero across the nesting levels
    np.testing.assert_allclose(res["wall.flange.tau"], 100.0 * res["unit.mass.phi"], atol=1e-7)


def test_der_of_expression_uses_the_chain_rule():
    class Energy(Component):
        def __init__(self):
            super().__init__("e")
            self.x = Variable(1.0)
            self.p = Variable(unit="1")

        def equations(self):
            return [der(self.x) == -self.x, self.p == der(self.x**2)]

    system = assemble(Energy())
    res = simulate(system, 1.0, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(res["p"], -2.0 * np.exp(-2.0 * res.t), rtol=1e-6)


def test_time_functions_stay_symbolic():
    class Driven(Assembly):
        def __init__(self):
            super().__init__("driven")
            import casadi as ca

            self.src = TorqueSource(lambda t: ca.sin(t))
            self.j = Inertia(1.0)
            connect(self.src.flange, self.j.flange_a)

    res = simulate(assemble(Driven()), 2.0, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(res["j.w"], 1.0 - np.cos(res.t), atol=1e-8)


def test_declaring_twice_or_reusing_a_component_is_an_error():
    class Twice(Component):
        def __init__(self):
            super().__init__("twice")
            self.x = Variable(0.0)
            self.x = Variable(1.0)

    with pytest.raises(ModelError, match="declared twice"):
        Twice()
    shared = Inertia()

    class Reuse(Assembly):
        def __init__(self):
            super().__init__("reuse")
            self.a = shared
            self.b = shared

    with pytest.raises(ModelError, match="cannot also be"):
        Reuse()


def test_ad_hoc_assembly_without_subclassing():
    drive = Assembly("ad_hoc")
    drive.add("wall", Fixed())
    drive.add("spring", Spring(400.0))
    drive.add("mass", Inertia(1.0, phi0=0.05))
    drive.add("brake", TorqueSource(None))
    drive.add("damping", Variable(unit="N.m", description="viscous torque on the mass"))
    connect(drive.wall.flange, drive.spring.flange_a)
    connect(drive.spring.flange_b, drive.mass.flange_a)
    connect(drive.brake.flange, drive.mass.flange_b)
    drive.add_equation(drive.damping == -2.0 * drive.mass.w,
                       drive.brake.tau_in == drive.damping)
    res = simulate(assemble(drive), 1.0, rtol=1e-10, atol=1e-12)
    # J phi'' + 2 phi' + 400 phi = 0: underdamped, omega_d = sqrt(400 - 1)
    wd = np.sqrt(399.0)
    expected = 0.05 * np.exp(-res.t) * (np.cos(wd * res.t) + np.sin(wd * res.t) / wd)
    np.testing.assert_allclose(res["mass.phi"], expected, atol=1e-8)


def test_check_choice_names_the_argument_and_the_valid_values():
    from bearingsim.errors import ParameterError
    from bearingsim.validation import check_choice

    assert check_choice("Z", "structure", ("I", "Z"), "double_layer_bearing") == "Z"
    with pytest.raises(ParameterError) as info:
        check_choice("T", "structure", ("I", "Z"), "double_layer_bearing")
    assert str(info.value) == "double_layer_bearing: structure must be 'I' or 'Z', got 'T'"
    with pytest.raises(ParameterError, match=r"^race must be 'a', 'b' or 'c', got 2$"):
        check_choice(2, "race", ("a", "b", "c"))


def test_connector_guess_sets_start_values_of_potentials_only():
    from bearingsim.components.connectors import RingFrame

    class Holder(Component):
        def __init__(self):
            super().__init__("holder")
            self.frame = RingFrame()

    h = Holder()
    h.frame.guess(x=1e-5, tx=2e-4)
    assert h.frame.fields["x"].start == 1e-5 and h.frame.fields["tx"].start == 2e-4
    with pytest.raises(ModelError, match="'Fx' is not a potential of RingFrame"):
        h.frame.guess(Fx=1.0)
    with pytest.raises(ModelError, match="assign the connector to a component first"):
        RingFrame().guess(x=0.0)


def test_each_declares_a_vector_of_fields_in_order():
    from bearingsim.components.connectors import BallFrame, RingFrame
    from bearingsim.language import Flow, Potential, Variable

    x, y = Potential.each("m", "x position", "y position")
    assert (type(x), x.unit, x.description, y.description) == (Potential, "m", "x position",
                                                             "y position")
    assert [type(f) for f in Flow.each("N", "a", "b", "c")] == [Flow] * 3
    assert Variable.each("s") == ()
    assert list(RingFrame._field_decls) == ["x", "y", "z", "tx", "ty", "Fx", "Fy", "Fz", "Mx",
                                            "My"]
    ball = BallFrame._field_decls
    assert [ball[k].unit for k in ("w_orbit", "wr", "wt", "wz", "Fr", "Mz")] == \
        ["rad/s"] * 4 + ["N", "N.m"]
    assert ball["Ft"].description == "force on the ball along e_t"
    assert ball["wz"].description == "ball angular velocity along e_z"
