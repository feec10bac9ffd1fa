"""One function per ball, mapped over the row (bearingsim.assembler.mapped): the same
right-hand side, residual, Jacobian and observed values as the inlined functions, on every
ball-level model; code that grows with one ball, not with Z; and the fallback to inlined
functions when the balls are not the same function."""

from __future__ import annotations

import casadi as ca
import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assembler.mapped_parts import NotMappable
from bearingsim.assemblies import deep_groove_ball_bearing, double_layer_bearing
from bearingsim.physics.lubricant import Oil
from bearingsim.simulation import simulate
from bearingsim.simulation.c_compiler import compilations
from bearingsim.simulation.c_units import generate_source
from bearingsim.simulation.kernels import kernel

OIL = Oil.from_iso_vg(32, method="oil_mist")


def _massive(designation: str = "6304"):
    return assemble(deep_groove_ball_bearing(designation, "dynamic_massive_balls", speed=100.0,
                                             loads={"Fx": 500.0}))


@pytest.fixture(scope="module")
def massive():
    return _massive()


def _point(system, form: str, seed: int = 0) -> list:
    """Kernel arguments away from the start values (every state perturbed)."""
    rng = np.random.default_rng(seed)
    x0 = system.x0()
    x = x0 * (1.0 + 0.01 * rng.standard_normal(x0.size)) + 1e-4 * rng.standard_normal(x0.size)
    u, p = system.u_default(), system.p0()
    if form == "dae":
        z = np.asarray(system.functions["dae_z"](0.01, x, u, p), dtype=float).ravel()
        return [0.01, x, z, u, p]
    return [0.01, x, u, p]


def _dense(value) -> np.ndarray:
    return np.array(ca.densify(value), dtype=float)


def _assert_same_kernels(system, form: str, rtol: float = 1e-13,
                         observe_tol: float = 1e-13) -> None:
    """Mapped against inlined (both on the VM): values and every Jacobian block to ``rtol`` of
    the largest entry, observed variables to ``observe_tol`` of each (or absolute)."""
    mapped = kernel(system, form, compiled=False, mapped=True)
    inlined = kernel(system, form, compiled=False, mapped=False)
    assert mapped.mapped.startswith("mapped:"), mapped.mapped
    assert inlined.mapped == "inlined: mapped=False"
    args = _point(system, form)
    values_m = mapped.function.call(args)
    values_i = inlined.function.call(args)
    for vm, vi in zip(values_m, values_i, strict=True):
        vm, vi = _dense(vm), _dense(vi)
        # Same expressions per ball, so the right-hand side agrees to the last bit or nearly.
        np.testing.assert_allclose(vm, vi, rtol=rtol, atol=rtol * np.max(np.abs(vi)))
    jac_m = mapped.function.jacobian().call([*args, *values_m])
    jac_i = inlined.function.jacobian().call([*args, *values_i])
    for name, jm, ji in zip(mapped.function.jacobian().name_out(), jac_m, jac_i, strict=True):
        jm, ji = _dense(jm), _dense(ji)
        scale = max(np.max(np.abs(ji)), 1e-300) if ji.size else 1.0
        # The chain rule sums the ring rows in another order: round-off of the largest entry.
        assert np.max(np.abs(jm - ji), initial=0.0) <= rtol * scale, name
    obs_m = _dense(mapped.observe.call(args)[0])
    obs_i = _dense(inlined.observe.call(args)[0])
    np.testing.assert_allclose(obs_m, obs_i, rtol=observe_tol, atol=observe_tol)


def test_massive_balls_mapped_equal_inlined(massive):
    _assert_same_kernels(massive, "ode")


@pytest.fixture(scope="module")
def quasi_static():
    return assemble(deep_groove_ball_bearing("6304", "dynamic", speed=100.0,
                                             loads={"Fx": 500.0}))


def test_quasi_static_balls_dae_form_mapped_equal_inlined(quasi_static):
    _assert_same_kernels(quasi_static, "dae")


def test_quasi_static_balls_ode_form_mapped_equal_inlined(quasi_static):
    """The ODE form solves every ball's Newton block in one fast_newton rootfinder on the
    mapped DAE form and differentiates by the implicit function theorem; the inlined form has
    one rootfinder per block. Both stop where the ball's force balance reaches its round-off
    floor (the inlined blocks' residual at this point: 5e-8 N on forces of hundreds of N), not
    at the same iterate: the right-hand side and its Jacobian agree to 1e-9 of their largest
    entries (measured ~3e-12), the observed variables to 1e-6 (measured: der(ball[2].dr)
    5e-9 of itself, small ones such as der(ball[4].wr) = 0.03 rad/s^2 to 1e-7 absolute)."""
    _assert_same_kernels(quasi_static, "ode", rtol=1e-9, observe_tol=1e-6)


def test_quasi_static_balls_ode_form_compiled_equals_vm(kernel_cache):
    """fast_newton and the linear solves of the implicit Jacobian as generated C."""
    system = assemble(deep_groove_ball_bearing("6304", "dynamic", speed=100.0,
                                               loads={"Fx": 500.0}), rootfinder="fast_newton")
    vm = kernel(system, "ode", compiled=False)
    c = kernel(system, "ode", compiled=True)
    assert c.mapped == vm.mapped == "mapped: root: 7 members"
    args = _point(system, "ode", seed=5)
    value = c.function(*args)
    np.testing.assert_array_equal(_dense(value), _dense(vm.function(*args)))
    for got, want in zip(c.function.jacobian().call([*args, value]),
                         vm.function.jacobian().call([*args, value]), strict=True):
        np.testing.assert_array_equal(_dense(got), _dense(want))


def test_nested_dynamic_mapped_equal_inlined():
    system = assemble(double_layer_bearing("61905", "61907", fidelity="dynamic",
                                           lubrication=OIL,
                                           loads={"Fx": 0.0, "Fy": 0.0, "Fz": 100.0,
                                                  "Mx": 0.0, "My": 0.0}))
    assert system.mapped.summary == "inner_layer: 13 members, outer_layer: 14 members"
    _assert_same_kernels(system, "ode")


def test_compiled_mapped_kernel_equals_vm_and_reports_its_balls(massive, kernel_cache):
    vm = kernel(massive, "ode", compiled=False)
    c = kernel(massive, "ode", compiled=True)
    assert c.describe()["mapped"] == "mapped: root: 7 members"
    args = _point(massive, "ode", seed=3)
    np.testing.assert_array_equal(_dense(c.function(*args)), _dense(vm.function(*args)))
    res = simulate(massive, 2e-4, method="cvodes", compiled=True)
    assert res.stats["mapped"] == "mapped: root: 7 members"
    # a second system of the same model (other symbol names: the assembler's counters moved on)
    # finds the same library, named by its C source, and reads what it maps without rebuilding
    again = _massive()
    before = compilations()
    found = kernel(again, "ode", compiled=True)
    assert found.library == c.library
    assert found.mapped == c.mapped
    assert compilations() == before


def test_a_mapped_run_never_builds_the_inlined_functions():
    """The inlined right-hand side, observe and output functions (one elimination of common
    subexpressions over every ball) and their Jacobians are built on first access; a CVODES
    run on the mapped kernel reads none of them."""
    system = _massive()
    assert "ode" in system.functions and "jac_x" in system.functions  # asking builds nothing
    simulate(system, 2e-4, method="cvodes", compiled=False)
    assert not any(system.functions.built(name) for name in system.functions)
    inlined = kernel(system, "ode", compiled=False, mapped=False)  # the inlined kernel does
    assert inlined.mapped == "inlined: mapped=False"
    assert system.functions.built("ode") and system.functions.built("observe")


def test_a_packed_system_keeps_its_mapped_kernel(massive):
    """Sweeps and the system cache ship systems to other processes (assembler.cache): the
    mapped kernel goes along, built once on the sending side."""
    from bearingsim.assembler.cache import dumps_system, loads_system

    restored = loads_system(dumps_system(massive))
    assert restored.mapped.summary == "root: 7 members"
    with pytest.raises(NotMappable, match="no nonlinear blocks"):
        restored.mapped.get("dae")
    args = _point(massive, "ode")
    np.testing.assert_array_equal(
        _dense(kernel(restored, "ode", compiled=False).function(*args)),
        _dense(kernel(massive, "ode", compiled=False).function(*args)))


def test_code_grows_with_one_ball_not_with_z(massive):
    """6304 (Z = 7) against 6206 (Z = 9), same model structure: the per-ball function is the
    same size and the mapped library's source grows by a few per cent (the gathers of the
    extra balls' states), while the inlined right-hand side grows with Z."""
    nine = _massive("6206")
    sizes = {}
    for name, system in (("7", massive), ("9", nine)):
        found = system.mapped.get("ode")
        sizes[name] = (found.ball_function.n_instructions(),
                       len(generate_source([found.function, found.jacobian, found.observe])),
                       system.functions["ode"].n_instructions())
    assert sizes["7"][0] == sizes["9"][0]
    assert sizes["9"][1] / sizes["7"][1] < 1.05
    assert sizes["9"][2] / sizes["7"][2] > 1.2


def test_a_ball_with_its_own_constant_is_not_mapped_and_stays_exact():
    """A pocket whose angular position is bound to a number instead of left a parameter makes
    its ball a different function: the kernel falls back to the inlined functions, says why,
    and gives the same right-hand side as the mapped model."""
    model = deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0,
                                     loads={"Fx": 500.0})
    model.pocket[3].phase = ca.SX(2.0 * np.pi * 3 / 7)  # a binding: the symbol becomes 0.897...
    system = assemble(model)
    with pytest.raises(NotMappable, match="of a repeated set is not the same function as member 0"):
        system.mapped.get("ode")
    fallback = kernel(system, "ode", compiled=False)
    assert fallback.mapped.startswith("inlined: member ")
    reference = _massive()
    mapped = kernel(reference, "ode", compiled=False)
    assert mapped.mapped.startswith("mapped:")
    t, x, u, _ = _point(reference, "ode")
    np.testing.assert_allclose(_dense(fallback.function(t, x, u, system.p0())),
                               _dense(mapped.function(t, x, u, reference.p0())),
                               rtol=1e-12, atol=1e-9)


def test_fmu_of_a_ball_level_model_uses_the_mapped_functions(tmp_path):
    """The exported FMU's derivatives and directional derivatives (model exchange) equal the
    inlined right-hand side and Jacobian of the same system."""
    import ctypes

    from bearingsim.fmu import export_fmu
    from bearingsim.fmu.codegen import fmu_functions
    from tests.fmu.helpers import open_fmu

    model = deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0,
                                     loads={"Fx": 500.0})
    system = assemble(model, ["cage.w"], rootfinder="fast_newton")
    functions = fmu_functions(system, ["cage.w"])
    assert functions["ode"].is_a("MXFunction")  # the mapped right-hand side
    path = export_fmu(model, tmp_path / "massive.fmu", outputs=["cage.w"])
    fmu, _, vr = open_fmu(path, tmp_path, kind="ME")
    fmu.setupExperiment()
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    fmu.enterContinuousTimeMode()
    _, x, u, p = _point(system, "ode")
    n = system.n_states
    fmu.setContinuousStates((ctypes.c_double * n)(*x), n)
    dx = (ctypes.c_double * n)()
    fmu.getDerivatives(dx, n)
    ref = system.rhs(0.0, x, u, p)
    np.testing.assert_allclose(np.array(dx), ref, rtol=1e-13, atol=1e-13 * np.max(np.abs(ref)))
    states = system.state_names
    ders = [vr[f"der({s})"] for s in states]
    jx = _dense(system.functions["jac_x"](0.0, x, u, p))
    for k in (0, 12, 40, n - 1):  # a ring, a ball, another ball, the drive
        column = np.array(fmu.getDirectionalDerivative(ders, [vr[states[k]]], [1.0]))
        assert np.max(np.abs(column - jx[:, k])) <= 1e-13 * np.max(np.abs(jx)), states[k]
    fmu.terminate()
    fmu.freeInstance()


def test_fmu_functions_of_the_quasi_static_level_solve_the_balls_through_the_mapped_form():
    """FMUs of the `dynamic` level get the ODE form built on the mapped DAE form (one
    fast_newton rootfinder for every ball): its derivatives and Jacobian equal the inlined
    system's to the Newton floor (see the ODE-form test above)."""
    from bearingsim.fmu.codegen import fmu_functions

    system = assemble(deep_groove_ball_bearing("6304", "dynamic", speed=100.0,
                                               loads={"Fx": 500.0}), ["cage.w"],
                      rootfinder="fast_newton")
    functions = fmu_functions(system, ["cage.w"])
    assert "newton_balls" in str(functions["ode"].find_functions(-1))
    args = _point(system, "ode", seed=2)
    ref = system.rhs(*args)
    got = _dense(functions["ode"](*args)).ravel()
    np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-9 * np.max(np.abs(ref)))
    jx = _dense(system.functions["jac_x"](*args))
    np.testing.assert_allclose(_dense(functions["jac_x"](*args)), jx, rtol=1e-9,
                               atol=1e-9 * np.max(np.abs(jx)))


def _assert_same_functions(got: dict, want, args: list, rtol: float) -> None:
    """Each function of ``got`` against the same-named one of ``want`` at ``args``: to
    ``rtol`` of its largest entry."""
    for name, fn in got.items():
        a, b = _dense(fn(*args)), _dense(want[name](*args))
        assert a.shape == b.shape, name
        scale = max(np.max(np.abs(b), initial=0.0), 1e-300)
        assert np.max(np.abs(a - b), initial=0.0) <= rtol * scale, name


def test_compile_system_maps_the_balls_and_builds_no_inlined_function(tmp_path):
    """compile_system (the scipy path) generates the mapped functions: the right-hand side,
    its Jacobians, observed and output variables equal the inlined ones to round-off, the
    inlined functions are not built, and the outputs' Jacobians stay available (symbolic)."""
    from bearingsim.simulation.compile import compile_system

    system = _massive()
    compiled = compile_system(system, cache_dir=tmp_path)
    assert compiled.report["compiled_balls"] == "mapped"
    assert not any(system.functions.built(name) for name in system.functions)
    assert all(compiled.functions.built(k) for k in ("ode", "jac_x", "jac_u", "observe",
                                                      "output"))
    args = _point(system, "ode", seed=7)
    ready = {k: compiled.functions[k] for k in ("ode", "jac_x", "jac_u", "observe", "output")}
    _assert_same_functions(ready, system.functions, args, rtol=1e-12)
    # built on first access, from the symbolic originals
    _assert_same_functions({k: compiled.functions[k] for k in ("out_jac_x", "out_jac_u")},
                           system.functions, args, rtol=0.0)
    a = simulate(system, 2e-4, method="BDF", rtol=1e-8, atol=1e-10)
    b = simulate(compiled, 2e-4, method="BDF", rtol=1e-8, atol=1e-10)
    for name in ("cage.w", "ball[1].dr", "inner[2].F_roll"):
        np.testing.assert_allclose(b[name], a[name], rtol=1e-6,
                                   atol=1e-6 * np.max(np.abs(a[name])))


def test_mapped_ode_functions_of_the_quasi_static_level_equal_the_inlined(quasi_static):
    """Through the one rootfinder of the mapped ODE form: to the Newton floor, as the kernel
    (test_quasi_static_balls_ode_form_mapped_equal_inlined)."""
    from bearingsim.assembler.passes.codegen import mapped_ode_functions

    functions = mapped_ode_functions(quasi_static)
    assert set(functions) == {"ode", "jac_x", "jac_u", "observe", "output"}
    args = _point(quasi_static, "ode")
    _assert_same_functions({k: functions[k] for k in ("ode", "jac_x", "jac_u")},
                           quasi_static.functions, args, rtol=1e-9)
    for key in ("observe", "output"):
        np.testing.assert_allclose(_dense(functions[key](*args)),
                                   _dense(quasi_static.functions[key](*args)),
                                   rtol=1e-6, atol=1e-6)
