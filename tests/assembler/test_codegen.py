"""The code generation pass alone, from hand-made solved forms (``Causal``) to functions whose
values and Jacobians are checked against hand computation."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from bearingsim.assembler.dae import Alias, Eq
from bearingsim.assembler.ir import Causal, NonlinearBlock
from bearingsim.assembler.passes import codegen
from bearingsim.errors import StructuralError
from tests.assembler.hand_dae import dae, eq, param, state_of, state_var, var

K, C = 4.0, 0.3
X = np.array([1.5, -0.5])


def _oscillator(outputs):
    """der(x1) = x2, der(x2) = -k x1 - c x2, y = x1^2; aliases z = -2 x2 and g = 9.81."""
    x1, dx1 = state_var("x1", 1.0)
    x2, dx2 = state_var("x2", 0.0)
    y = var("y", unit="m2")
    k, c = param("k", K), param("c", C)
    model = dae([x1, dx1, x2, dx2, y], [eq(dx1.sym, "der(x1)"), eq(dx2.sym, "der(x2)"),
                                        eq(y.sym, "y")], [k, c])
    model.aliases = {"z": Alias("z", -2.0, x2, 0.0, "m/s", "minus twice the speed"),
                     "g": Alias("g", 0.0, None, 9.81, "m/s2")}
    causal = Causal(expr={dx1: x2.sym, dx2: -k.sym * x1.sym - c.sym * x2.sym, y: x1.sym**2})
    state = state_of(model, outputs, causal=causal)
    codegen.run(state)
    return state.system


def _call(system, name, x, p=None):
    p = system.p0() if p is None else p
    return np.array(system.functions[name](0.0, x, system.u_default(), p), dtype=float)


def test_the_ode_its_jacobian_and_the_observed_values_match_hand_computation():
    system = _oscillator(None)
    assert system.state_names == ["x1", "x2"] and system.parameter_names == ["k", "c"]
    np.testing.assert_allclose(_call(system, "ode", X).ravel(), [-0.5, -K * 1.5 + C * 0.5])
    np.testing.assert_allclose(_call(system, "jac_x", X), [[0.0, 1.0], [-K, -C]])
    assert system.observed_names == ["x1", "der(x1)", "x2", "der(x2)", "y", "z", "g"]
    observed = _call(system, "observe", X).ravel()
    np.testing.assert_allclose(observed, [1.5, -0.5, -0.5, -5.85, 2.25, 1.0, 9.81])
    assert (system.observed_units["z"], system.observed_descriptions["z"]) == (
        "m/s", "minus twice the speed")
    assert system.output_names == ["x1", "der(x1)", "x2", "der(x2)", "y"]  # variables, no aliases
    assert system.rootfinder is None and "dae_alg" not in system.functions


def test_requested_outputs_and_their_jacobian_include_aliases():
    system = _oscillator(["y", "z"])
    assert [(s.name, s.unit) for s in system.outputs] == [("y", "m2"), ("z", "m/s")]
    np.testing.assert_allclose(_call(system, "output", X).ravel(), [2.25, 1.0])
    np.testing.assert_allclose(_call(system, "out_jac_x", X), [[3.0, 0.0], [0.0, -2.0]])
    # new parameter values reach the same functions
    np.testing.assert_allclose(_call(system, "ode", X, p=[1.0, 0.0]).ravel(), [-0.5, -1.5])


def test_a_newton_block_gives_its_root_and_the_implicit_jacobian():
    """der(x) = -y with y^3 + y = x: at x = 2, y = 1 and d(der x)/dx = -1 / (3 y^2 + 1)."""
    x, dx = state_var("x", 2.0)
    y = var("y", 0.0)
    e_cubic = eq(y.sym**3 + y.sym - x.sym, "y^3 + y = x")
    block = NonlinearBlock([y], y.sym**3 + y.sym - x.sym, [0.0], [e_cubic])
    causal = Causal(expr={y: y.sym, dx: -y.sym}, nonlinear=[block])
    model = dae([x, dx, y], [e_cubic, eq(dx.sym + y.sym, "der(x) = -y")])
    state = state_of(model, None, causal=causal, rootfinder="fast_newton")
    codegen.run(state)
    system = state.system
    assert system.rootfinder == "fast_newton"
    assert _call(system, "ode", [2.0]).item() == pytest.approx(-1.0, abs=1e-12)
    assert _call(system, "jac_x", [2.0]).item() == pytest.approx(-0.25, abs=1e-12)
    assert _call(system, "observe", [10.0])[2, 0] == pytest.approx(2.0, abs=1e-12)
    z = float(system.functions["dae_z"](0.0, 2.0, ca.DM(0, 1), ca.DM(0, 1)))
    assert z == pytest.approx(1.0, abs=1e-12)
    assert float(system.functions["dae_alg"](0.0, 2.0, 0.5, ca.DM(0, 1), ca.DM(0, 1))) == (
        pytest.approx(0.125 + 0.5 - 2.0))


def _free_start(initial_residuals):
    x, dx = state_var("x", 0.5, fixed=False)
    model = dae([x, dx], [eq(dx.sym + x.sym, "der(x) = -x")])
    model.initial_eqs = [Eq(r(x.sym), "hand", initial=True) for r in initial_residuals]
    return state_of(model, None, causal=Causal(expr={dx: -x.sym}))


def test_initial_equations_become_a_residual_of_the_free_states():
    state = _free_start([lambda x: x - 2.0])
    codegen.run(state)
    system = state.system
    assert system.free_initial_states == [0]
    residual = system.init_residual(0.0, 0.5, ca.DM(0, 1), ca.DM(0, 1))
    assert float(residual) == pytest.approx(-1.5)


def test_initial_equations_must_match_the_free_states():
    with pytest.raises(StructuralError, match="2 initial equation"):
        codegen.run(_free_start([lambda x: x - 2.0, lambda x: x**2 - 4.0]))
