"""Array members' equations derived from member 0's by substitution
(bearingsim.assembler.passes.member_equations): the same flat model as building every member
by its own code, and members that differ are built by their own code."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from bearingsim import Assembly, Component, Parameter, Variable, der
from bearingsim.assembler import assemble
from bearingsim.assembler.passes.flatten import flatten
from bearingsim.assembler.passes.member_equations import MemberEquations
from bearingsim.assemblies import double_layer_bearing
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing


def _symbols(dae):
    pairs = [(v.name, v.sym) for v in dae.vars] + [(p.name, p.sym) for p in dae.params]
    return dict(pairs)


def _same_flat_model(build):
    """Flatten two instances of one model, with and without substitution; the equations must
    be the same expressions (evaluated at one random point, bit for bit) in the same order."""
    fast_members = MemberEquations()
    fast = flatten(build(), fast_members)
    slow = flatten(build(), MemberEquations(enabled=False))
    assert [v.name for v in fast.vars] == [v.name for v in slow.vars]
    assert [p.name for p in fast.params] == [p.name for p in slow.params]
    assert [e.origin for e in fast.eqs] == [e.origin for e in slow.eqs]
    sym_fast, sym_slow = _symbols(fast), _symbols(slow)
    names = list(sym_fast)
    args_fast = ca.vertcat(fast.time, *[sym_fast[n] for n in names])
    args_slow = ca.vertcat(slow.time, *[sym_slow[n] for n in names])
    f_fast = ca.Function("f", [args_fast], [ca.vertcat(*[e.residual for e in fast.eqs])])
    f_slow = ca.Function("f", [args_slow], [ca.vertcat(*[e.residual for e in slow.eqs])])
    point = np.random.default_rng(1).uniform(0.5, 1.5, args_fast.numel())
    r_fast = np.asarray(f_fast(point)).ravel()
    r_slow = np.asarray(f_slow(point)).ravel()
    np.testing.assert_array_equal(r_fast, r_slow)
    return fast_members.instantiated


def test_deep_groove_massive_balls_flatten_the_same():
    count = _same_flat_model(lambda: deep_groove_ball_bearing(
        "6304", "dynamic_massive_balls", speed=100.0, loads={"Fx": 500.0}))
    assert count == 6 * 5  # ball, inner and outer contact, pocket, drag of balls 1..6


def test_nested_bearing_flattens_the_same():
    count = _same_flat_model(lambda: double_layer_bearing("61905", "61907", fidelity="dynamic"))
    assert count == 100  # the members 1.. of both layers' rows (12 + 13 balls, 4 each)


def test_assembly_report_counts_the_substituted_components():
    system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0))
    assert "components' equations by substitution" in system.report["flat"]


class _Cell(Component):
    """x' = -k (x - offset); ``offset`` a plain number, ``reach`` reads the parent's level."""

    def __init__(self, offset: float = 0.0, reach: bool = False):
        super().__init__()
        self.k = Parameter(2.0, unit="1/s")
        self.x = Variable(unit="m", start=1.0)
        self.offset = offset
        self.reach = reach

    def equations(self):
        target = self.offset + (self.parent.level if self.reach else 0.0)
        return [der(self.x) == -self.k * (self.x - target)]


class _Row(Assembly):
    def __init__(self, offsets, reach=False):
        super().__init__("row")
        self.level = Variable(unit="m", start=0.0)
        self.cell = [_Cell(o, reach) for o in offsets]

    def equations(self):
        return [der(self.level) == 0.0]


def _residual_of(dae, origin):
    (eq,) = [e for e in dae.eqs if e.origin == origin]
    return eq


@pytest.mark.parametrize("reach", [False, True])
def test_member_that_differs_is_built_by_its_own_code(reach):
    members = MemberEquations()
    dae = flatten(_Row([0.0, 0.0, 1.5], reach=reach), members)
    # cell[1] is cell[0] but for its symbols; cell[2] has another offset; with ``reach`` the
    # equations use a symbol outside the member, so no member is substituted
    assert members.instantiated == (0 if reach else 1)
    values = {v.name: 0.25 for v in dae.vars} | {p.name: 2.0 for p in dae.params}
    syms = _symbols(dae)
    for k, offset in enumerate([0.0, 0.0, 1.5]):
        eq = _residual_of(dae, f"cell[{k}]")
        f = ca.Function("r", [ca.vertcat(*syms.values())], [eq.residual])
        r = float(f(np.array([values[n] for n in syms])))
        der_x, x = 0.25, 0.25
        level = 0.25 if reach else 0.0
        assert r == pytest.approx(der_x + 2.0 * (x - offset - level))


def test_substituted_members_get_their_derivatives():
    members = MemberEquations()
    dae = flatten(_Row([0.0, 0.0, 0.0]), members)
    assert members.instantiated == 2
    assert [v.name for v in dae.vars if v.is_derivative] == [
        "der(level)", "der(cell[0].x)", "der(cell[1].x)", "der(cell[2].x)"]


class _Scaled(Component):
    """x' = -gain x, the gain an expression attribute of the member's own parameter."""

    def __init__(self, factor: float):
        super().__init__()
        self.k = Parameter(2.0, unit="1/s")
        self.x = Variable(unit="m", start=1.0)
        self.gain = factor * self.k

    def equations(self):
        return [der(self.x) == -self.gain * self.x]


class _ScaledRow(Assembly):
    def __init__(self, factors):
        super().__init__("row")
        self.cell = [_Scaled(f) for f in factors]


def test_expression_attributes_are_compared_with_the_members_symbols():
    members = MemberEquations()
    dae = flatten(_ScaledRow([3.0, 3.0, 5.0]), members)
    assert members.instantiated == 1  # cell[1]: 3 k with its own k; cell[2]: 5 k differs
    syms = _symbols(dae)
    values = {n: 0.5 for n in syms}
    f = ca.Function("r", [ca.vertcat(*syms.values())],
                    [ca.vertcat(*[_residual_of(dae, f"cell[{k}]").residual for k in range(3)])])
    r = np.asarray(f(np.array([values[n] for n in syms]))).ravel()
    np.testing.assert_allclose(r, [0.5 + 3.0 * 0.5 * 0.5, 0.5 + 3.0 * 0.25, 0.5 + 5.0 * 0.25])
