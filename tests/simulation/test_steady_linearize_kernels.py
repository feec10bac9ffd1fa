"""steady_state and linearize on the system's kernel: generated C and the VM give the same
numbers, a parameter change compiles nothing, and without a compiler the VM answers."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.simulation import linearize, steady_state
from bearingsim.simulation.c_compiler import CompileError, compilations
from bearingsim.simulation.kernels import clear_kernel_cache, kernel
from bearingsim.simulation.steady import integrator_states


@pytest.fixture(scope="module")
def torque_level():
    """The 61905/61907 torque level driven at a speed: a steady middle-ring speed exists."""
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque", drive="speed"))


INPUTS = {"shaft_speed": 800.0, "Fr": 300.0, "Fa": 100.0}


def _u(system):
    u = system.u_default()
    for name, value in INPUTS.items():
        u[system.input_names.index(name)] = value
    return u


def test_steady_state_is_the_same_on_compiled_c_and_the_vm(kernel_cache, torque_level):
    vm = steady_state(torque_level, inputs=INPUTS, compiled=False)
    c = steady_state(torque_level, inputs=INPUTS, compiled=True)
    assert kernel(torque_level, "ode", True).backend == "compiled C"
    assert kernel(torque_level, "ode", False).backend == "CasADi VM"
    np.testing.assert_allclose(c, vm, rtol=1e-10, atol=1e-12)
    rhs = torque_level.functions["ode"](0.0, c, _u(torque_level),
                                        torque_level.p0())
    free = [k for k in range(torque_level.n_states)
            if k not in integrator_states(torque_level)]  # angles drift at steady speeds
    assert free and np.max(np.abs(np.asarray(rhs)[free])) < 1e-9


def test_linearize_is_the_same_on_compiled_c_and_the_vm(kernel_cache, torque_level):
    x = steady_state(torque_level, inputs=INPUTS, compiled=False)
    vm = linearize(torque_level, x, inputs=INPUTS, compiled=False)
    c = linearize(torque_level, x, inputs=INPUTS, compiled=True)
    for key in "ABCD":
        np.testing.assert_allclose(getattr(c, key), getattr(vm, key), rtol=1e-10, atol=0.0)
    # A is the system's own d(ode)/dx
    u = _u(torque_level)
    np.testing.assert_allclose(c.A, torque_level.functions["jac_x"](0.0, x, u,
                                                                     torque_level.p0()).full(),
                               rtol=1e-12, atol=0.0)


def test_a_parameter_change_compiles_nothing(kernel_cache, torque_level):
    steady_state(torque_level, inputs=INPUTS, compiled=True)
    n = compilations()
    name = torque_level.parameter_names[0]
    value = torque_level.p0()[0] * 1.05
    steady_state(torque_level, inputs=INPUTS, parameters={name: value}, compiled=True)
    linearize(torque_level, inputs=INPUTS, parameters={name: value}, compiled=True)
    assert compilations() == n


def test_without_a_compiler_auto_answers_on_the_vm_and_true_raises(kernel_cache, monkeypatch,
                                                                   torque_level, tmp_path):
    reference = steady_state(torque_level, inputs=INPUTS, compiled=False)
    empty = tmp_path / "empty"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    monkeypatch.setenv("CC", "no-such-compiler")
    clear_kernel_cache()
    np.testing.assert_allclose(steady_state(torque_level, inputs=INPUTS), reference,
                               rtol=1e-12)
    assert kernel(torque_level, "ode", "auto").reason == "no C compiler on PATH"
    with pytest.raises(CompileError, match="no C compiler"):
        steady_state(torque_level, inputs=INPUTS, compiled=True)
    with pytest.raises(CompileError, match="no C compiler"):
        linearize(torque_level, inputs=INPUTS, compiled=True)
