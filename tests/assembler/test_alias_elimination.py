"""The alias elimination pass alone on a hand-made DAE:

    der(x) + c a - y = 0,   y - sin(x) = 0,   a - x = 0,   b + a = 0,   c - 3 = 0

leaves ``der(x) = y - 3 x``, ``y = sin(x)`` with ``a = x``, ``b = -x`` and ``c = 3`` as aliases.
"""

from __future__ import annotations

import casadi as ca
import pytest

from bearingsim.assembler.dae import Alias
from bearingsim.assembler.passes import alias_elimination
from tests.assembler.hand_dae import dae, eq, evaluate, state_of, state_var, var


def _model():
    x, dx = state_var("x", 0.5)
    y, a, b, c = var("y"), var("a", unit="m", description="copy of x"), var("b"), var("c")
    model = dae([x, dx, y, a, b, c], [
        eq(dx.sym + c.sym * a.sym - y.sym, "der(x) = y - c a"),
        eq(y.sym - ca.sin(x.sym), "y = sin(x)"),
        eq(a.sym - x.sym, "a = x"),
        eq(b.sym + a.sym, "b = -a"),
        eq(c.sym - 3.0, "c = 3"),
    ])
    return model, x, dx, y


def test_aliases_are_eliminated_with_scale_representative_and_offset():
    model, x, dx, y = _model()
    state = state_of(model)
    alias_elimination.run(state)
    assert [v.name for v in model.vars] == ["x", "der(x)", "y"]
    assert [e.text for e in model.eqs] == ["der(x) = y - c a", "y = sin(x)"]
    assert model.aliases == {
        "a": Alias("a", 1.0, x, 0.0, "m", "copy of x"),
        "b": Alias("b", -1.0, x, 0.0),
        "c": Alias("c", 0.0, None, 3.0),
    }
    assert state.report["aliases eliminated"] == 3
    # the remaining equation has a = x and c = 3 substituted: der(x) + 3 x - y
    ode = model.eqs[0].residual
    assert evaluate(ode, {dx: 0.0, x: 2.0, y: 1.0}) == pytest.approx(5.0)


def test_an_alias_of_an_eliminated_alias_follows_it_to_the_remaining_variable():
    x, dx = state_var("x", 0.5)
    a, b, c = var("a"), var("b"), var("c")
    model = dae([x, dx, a, b, c], [
        eq(dx.sym + x.sym, "der(x) = -x"),
        eq(c.sym + b.sym, "c = -b"),
        eq(b.sym + a.sym, "b = -a"),
        eq(a.sym + x.sym, "a = -x"),
    ])
    alias_elimination.eliminate_aliases(model)
    assert [v.name for v in model.vars] == ["x", "der(x)"]
    scales = {name: (al.scale, al.representative, al.offset) for name, al in model.aliases.items()}
    assert scales == {"a": (-1.0, x, 0.0), "b": (1.0, x, 0.0), "c": (-1.0, x, 0.0)}


def test_a_negated_derivative_is_not_an_alias():
    """``der(x) = -v`` stays an equation: eliminating it would lose the derivative link."""
    x, dx = state_var("x", 0.5)
    v = var("v")
    model = dae([x, dx, v], [eq(dx.sym + v.sym, "der(x) = -v"), eq(v.sym - x.sym**2, "v = x^2")])
    alias_elimination.run(state_of(model))
    assert [e.text for e in model.eqs] == ["der(x) = -v", "v = x^2"]
    assert model.aliases == {}


def test_a_derivative_recreated_after_its_alias_became_a_constant_is_observed_once():
    """``der(x) = w``, ``w = 100``: der(x) is eliminated (its value is the constant), then
    re-created as a variable to keep the derivative link of x; its name must not also stay an
    alias (the deep-groove drive at a constant speed had ``der(drive.phi)`` twice among its
    observed names, and its FMU export with the default outputs failed)."""
    x, dx = state_var("x", 0.0)
    w = var("w")
    model = dae([x, dx, w], [eq(dx.sym - w.sym, "der(x) = w"), eq(w.sym - 100.0, "w = 100")])
    alias_elimination.eliminate_aliases(model)
    names = [v.name for v in model.vars] + list(model.aliases)
    assert sorted(names) == ["der(x)", "w", "x"]
    assert model.aliases["w"].offset == 100.0
    (link,) = [e for e in model.eqs if ca.depends_on(e.residual, x.derivative.sym)]
    assert float(ca.substitute(link.residual, x.derivative.sym, ca.SX(100.0))) == 0.0


def test_the_deep_groove_drive_at_a_constant_speed_observes_each_name_once():
    from bearingsim.assembler import assemble
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
    from bearingsim.fmu.export import _outputs

    system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0))
    assert len(system.observed_names) == len(set(system.observed_names))
    assert system.observe(0.0, system.x0())["der(drive.phi)"] == 100.0
    names, _, _ = _outputs(system, None)  # the FMU's default outputs
    assert len(names) == len(set(names))
