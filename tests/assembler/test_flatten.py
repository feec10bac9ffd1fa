"""The flatten pass alone: a two-resistor divider becomes scalar variables and equations."""

from __future__ import annotations

import casadi as ca
import pytest

from bearingsim import (
    Assembly,
    Component,
    Parameter,
    Variable,
    connect,
    der,
)
from bearingsim.assembler import AssemblyState
from bearingsim.assembler.passes import flatten
from bearingsim.errors import ModelError
from tests.models import Resistor


class Divider(Assembly):
    """r1 and r2 in series; r1's resistance is bound to twice the divider's own parameter."""

    def __init__(self):
        super().__init__("div")
        self.R = Parameter(10.0, "Ohm", "half the resistance of r1")
        self.r1 = Resistor(1.0)
        self.r2 = Resistor(2.0)
        self.r1.R = 2 * self.R
        connect(self.r1.n, self.r2.p)


def _flat():
    state = AssemblyState(Divider(), None)
    flatten.run(state)
    return state


def test_flatten_expands_the_connection_set_and_zeroes_unconnected_flows():
    state = _flat()
    dae = state.dae
    assert [v.name for v in dae.vars] == [
        "r1.p.v", "r1.p.i", "r1.n.v", "r1.n.i", "r2.p.v", "r2.p.i", "r2.n.v", "r2.n.i"]
    assert state.report["flat"] == "8 variables, 8 equations"
    texts = [e.text for e in dae.eqs if e.text]
    assert texts == ["r1.n.v = r2.p.v", "+r1.n.i +r2.p.i = 0",
                     "r1.p.i = 0 (unconnected flow)", "r2.n.i = 0 (unconnected flow)"]
    by_name = {v.name: v.sym for v in dae.vars}
    potential = next(e for e in dae.eqs if e.text == "r1.n.v = r2.p.v").residual
    assert ca.is_equal(potential, by_name["r1.n.v"] - by_name["r2.p.v"], 2)
    flow = next(e for e in dae.eqs if e.text == "+r1.n.i +r2.p.i = 0").residual
    assert ca.is_equal(flow, by_name["r1.n.i"] + by_name["r2.p.i"], 2)


def test_flatten_substitutes_parameter_bindings():
    dae = _flat().dae
    assert [(p.name, p.value, p.unit) for p in dae.params] == [("R", 10.0, "Ohm"),
                                                              ("r2.R", 2.0, "Ohm")]
    ohm = dae.eqs[0]  # r1: p.v - n.v = R * p.i with R bound to 2 * div.R
    names = {s.name() for s in ca.symvar(ohm.residual)}
    r_sym = dae.params[0].sym
    assert r_sym.name() in names and not any("r1" in n for n in names)
    values = {v.sym.name(): k + 1.0 for k, v in enumerate(dae.vars)}  # r1.p.v = 1, r1.p.i = 2 ...
    syms = [v.sym for v in dae.vars] + [r_sym]
    residual = ca.Function("r", syms, [ohm.residual])(*values.values(), 10.0)
    assert float(residual) == pytest.approx(1.0 - 3.0 - 20.0 * 2.0)


class _Cancelling(Component):
    def __init__(self):
        super().__init__("c")
        self.x = Variable(1.0, "m")

    def equations(self):
        return [der(self.x) == -self.x, self.x - self.x == 2.0]


def test_flatten_refuses_an_equation_without_unknowns():
    with pytest.raises(ModelError, match=r"^<root>: equation .* reduces to the constant .*; it "
                                         r"has no unknowns$"):
        flatten.run(AssemblyState(_Cancelling(), None))
