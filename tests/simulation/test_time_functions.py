"""Functions of time (``simulate`` inputs, ``TorqueSource``, the motor's speed reference) may be
written with numpy math: numpy's functions of a CasADi symbol give CasADi's, and CasADi's
dozen-line warning about it is no longer shown (with ``-W error`` it became a ParameterError
whose text was that warning). A function that cannot take a symbol is refused in one line
naming what it gives."""

from __future__ import annotations

import warnings

import casadi as ca
import numpy as np
import pytest

from bearingsim import Component, Input, Variable, der
from bearingsim.assembler import assemble
from bearingsim.components.rotational import TorqueSource
from bearingsim.errors import ParameterError
from bearingsim.language.symbols import of_time, time
from bearingsim.simulation import simulate


class Driven(Component):
    """x'' = u - x - 0.1 x'."""

    def __init__(self):
        super().__init__("driven")
        self.u = Input(unit="N", description="force")
        self.x = Variable(0.0, "m", "position")
        self.v = Variable(0.0, "m/s", "speed")

    def equations(self):
        return [der(self.x) == self.v, der(self.v) == self.u - self.x - 0.1 * self.v]


def test_numpy_math_gives_casadi_math_without_a_warning():
    system = assemble(Driven())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with_numpy = simulate(system, 1.0, inputs={"u": lambda t: np.sin(t) + np.exp(-t)},
                              method="cvodes", rtol=1e-10, atol=1e-12)
    with_casadi = simulate(system, 1.0, inputs={"u": lambda t: ca.sin(t) + ca.exp(-t)},
                           method="cvodes", rtol=1e-10, atol=1e-12)
    assert with_numpy.final("x") == with_casadi.final("x")
    assert with_numpy.final("x") == pytest.approx(0.46988, rel=1e-4)
    assert str(of_time(lambda t: np.cos(2 * t), time, "a test")) == str(ca.cos(2 * time))


def test_a_choice_written_in_python_is_refused_in_one_line():
    system = assemble(Driven())
    with pytest.raises(ParameterError) as err:
        simulate(system, 1.0, inputs={"u": lambda t: 1.0 if t < 0.5 else 2.0})
    text = str(err.value)
    assert text.startswith("input u: the function of time could not be evaluated")
    assert "casadi.if_else" in text and "\n" not in text
    with pytest.raises(ParameterError, match=r"TorqueSource: tau_in: the function of time"):
        TorqueSource(lambda t: 1.0 if t < 0.5 else 2.0).equations()


def test_a_torque_source_in_numpy_math():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        source = TorqueSource(lambda t: 0.5 * np.tanh(t))
        equations = source.equations()
    assert any("tanh" in str(e) for e in equations)
