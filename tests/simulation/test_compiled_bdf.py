"""The BDF integrator in C on the compiled kernels (method="compiled_bdf",
bearingsim.simulation.compiled_bdf): analytic solutions, tolerance proportionality, agreement
with CVODES on a ball-level model with a time-varying input and on a model with a Newton block,
dense output across calls of the C loop, and clear errors."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from bearingsim import Component, Variable, der
from bearingsim.assembler import assemble
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation import compiled_bdf, simulate
from bearingsim.simulation.c_compiler import CompileError, c_compiler
from tests.models import Pendulum, SpringMassChain

pytestmark = pytest.mark.skipif(c_compiler() is None, reason="needs a C compiler")


def _states(result, system) -> np.ndarray:
    return np.array([result[name] for name in system.state_names])


def _exact_linear(system, times: np.ndarray) -> np.ndarray:
    """x(t) = expm(A t) x0 of a linear system without inputs."""
    a = np.asarray(system.functions["jac_x"](0.0, system.x0(), system.u_default(),
                                             system.p0()).full(), dtype=float)
    return np.column_stack([scipy.linalg.expm(a * t) @ system.x0() for t in times])


def test_linear_chain_matches_the_matrix_exponential_and_the_error_follows_the_tolerance(
        kernel_cache):
    """Two-mass torsional chain (eigenfrequencies 13 and 36 rad/s), 1 s, 401 outputs: the
    global error falls with the tolerance (a BDF's error is proportional to it) and stays
    within a few hundred tolerances over the five periods."""
    system = assemble(SpringMassChain(phi0=0.1))
    times = np.linspace(0.0, 1.0, 401)
    exact = _exact_linear(system, times)
    errors = {}
    for rtol in (1e-4, 1e-6, 1e-8):
        res = simulate(system, 1.0, method="compiled_bdf", rtol=rtol, atol=rtol * 1e-3,
                       n_points=401)
        np.testing.assert_array_equal(res.t, times)
        errors[rtol] = np.max(np.abs(_states(res, system) - exact)) / np.max(np.abs(exact))
        assert errors[rtol] < 300 * rtol, (rtol, errors[rtol])
    assert errors[1e-8] < 1e-2 * errors[1e-4], errors
    assert res.stats["method"] == "compiled_bdf"
    assert res.stats["backend"] == "compiled C"
    assert res.stats["nsteps"] > 0 and res.stats["nfevals"] >= res.stats["nsteps"]


def test_agrees_with_cvodes_on_the_6304_massive_ball_level_with_a_speed_ramp(kernel_cache):
    """The ball-level model the method is for: 76 states, the shaft speed a ramp input (C of
    the input signal in a library of its own), 2 ms of the start-up at tight tolerances."""
    import casadi as ca

    from bearingsim.assemblies import deep_groove_ball_bearing

    system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=None,
                                               loads={"Fx": 500.0}, n_slices=0))
    inputs = {"shaft_speed": lambda t: 300.0 * ca.fmin(t / 0.005, 1.0)}
    runs = {method: simulate(system, 2e-3, method=method, rtol=1e-9, atol=1e-11, n_points=21,
                             inputs=inputs)
            for method in ("cvodes", "compiled_bdf")}
    a, b = runs["cvodes"], runs["compiled_bdf"]
    assert b.stats["mapped"] == "mapped: root: 7 members"
    for name in ("cage.w", "ball[1].wr", "ball[3].dr", "inner[2].F_roll"):
        scale = np.max(np.abs(a[name]))
        np.testing.assert_allclose(b[name], a[name], rtol=0, atol=1e-5 * scale, err_msg=name)
    assert b["cage.w"][-1] > 0.3 * 300.0 / 2 * (2e-3 / 0.005)  # the cage follows the ramp


def test_a_newton_block_in_the_right_hand_side(kernel_cache):
    """Cartesian pendulum: the rod force from fast_newton inside the compiled right-hand side;
    same trajectory as CVODES and the constraint held."""
    system = assemble(Pendulum())
    a = simulate(system, 2.0, method="cvodes", rtol=1e-10, atol=1e-12, n_points=41)
    b = simulate(system, 2.0, method="compiled_bdf", rtol=1e-10, atol=1e-12, n_points=41)
    for name in ("x", "y", "vx", "F"):
        np.testing.assert_allclose(b[name], a[name], atol=1e-6, err_msg=name)
    assert np.max(np.abs(b["x"] ** 2 + b["y"] ** 2 - 1.0)) < 1e-9


def test_outputs_are_the_same_however_the_c_loop_is_called(kernel_cache, monkeypatch):
    """Between calls of the C loop (progress bar, Ctrl-C) the last step has usually passed the
    next output times: they come from that step's interpolating polynomial, as they would in
    one call; here one step per call."""
    system = assemble(SpringMassChain(phi0=0.1))
    one = simulate(system, 0.5, method="compiled_bdf", rtol=1e-6, atol=1e-9, n_points=300)
    assert one.stats["nsteps"] < compiled_bdf.STEPS_PER_CALL
    monkeypatch.setattr(compiled_bdf, "STEPS_PER_CALL", 1)
    many = simulate(system, 0.5, method="compiled_bdf", rtol=1e-6, atol=1e-9, n_points=300,
                    progress=True)
    np.testing.assert_array_equal(_states(many, system), _states(one, system))
    assert many.stats["nsteps"] == one.stats["nsteps"]


def test_a_new_input_structure_compiles_its_inputs_not_the_integrator(kernel_cache,
                                                                        monkeypatch):
    """Inputs of three structures (a constant, a ramp, a line) on one model: one integrator
    library, and a small library of the inputs per structure. Before, the integrator was
    compiled again with each structure's inputs (about 1 s a structure: a sweep over speed
    expressions paid it per new expression)."""
    import casadi as ca

    from bearingsim.assemblies import double_layer_bearing

    monkeypatch.setattr(compiled_bdf, "_PREPARED", {})  # nothing from other tests' caches
    compiled_bdf._driver.cache_clear()
    system = assemble(double_layer_bearing("61905", "61907", fidelity="torque"))
    speeds = (100.0, lambda t: 100.0 * ca.fmin(t / 0.01, 1.0), lambda t: 50.0 + 1e3 * t)
    runs = [simulate(system, 0.02, inputs={"shaft_speed": s}, method="compiled_bdf",
                     n_points=3) for s in speeds]
    libraries = sorted(p.name.split("_")[1] for p in kernel_cache.rglob("bsm_*.so")
                       if p.name.startswith(("bsm_bdf_", "bsm_signal_")))
    assert libraries == ["bdf", "signal", "signal", "signal"]
    np.testing.assert_allclose([r.inputs["shaft_speed"] for r in runs], [100.0, 100.0, 70.0])


class Blowup(Component):
    """x' = x^2, x(0) = 1: x = 1 / (1 - t), infinite at t = 1."""

    def __init__(self):
        super().__init__("blowup")
        self.x = Variable(1.0, "1", "grows without bound")

    def equations(self):
        return [der(self.x) == self.x**2]


def test_a_blow_up_is_reported_with_the_time_and_the_state(kernel_cache):
    system = assemble(Blowup())
    with pytest.raises(SimulationError, match=r"compiled_bdf failed at t = 0\.99\d* s.*x"):
        simulate(system, 2.0, method="compiled_bdf", rtol=1e-6, atol=1e-9)
    res = simulate(system, 0.9, method="compiled_bdf", rtol=1e-8, atol=1e-10, n_points=10)
    np.testing.assert_allclose(res["x"], 1.0 / (1.0 - res.t), rtol=1e-5)


def test_the_vm_is_refused_and_a_missing_compiler_named(kernel_cache, monkeypatch):
    system = assemble(SpringMassChain())
    with pytest.raises(ParameterError, match="compiled_bdf.*compiled=False"):
        simulate(system, 0.1, method="compiled_bdf", compiled=False)
    monkeypatch.setattr("bearingsim.simulation.kernels.c_compiler", lambda: None)
    with pytest.raises(CompileError, match="no C compiler on PATH"):
        simulate(system, 0.1, method="compiled_bdf")


def test_a_kept_solver_repeats_a_new_ones_run_bit_for_bit(kernel_cache, monkeypatch):
    """A thread keeps its solver of a model between runs (``bsm_bdf_reset`` instead of a new
    allocation): a run after other runs on it (another start, tolerance, span and output
    count, and a failed run) gives the states, observed variables and counts of the same run
    on a new solver, bit for bit; so a sweep's result does not depend on the order of its
    points."""
    system = assemble(Pendulum())
    blowup = assemble(Blowup())

    def run(**kw):
        return simulate(system, 0.7, method="compiled_bdf", rtol=1e-7, atol=1e-10,
                        n_points=9, **kw)

    monkeypatch.setattr(compiled_bdf, "_PREPARED", {})  # new solvers
    first = run()
    simulate(system, 1.3, method="compiled_bdf", rtol=1e-4, atol=1e-6, n_points=301,
             x0={"x": 0.6, "vx": 0.1})
    with pytest.raises(SimulationError):
        simulate(blowup, 2.0, method="compiled_bdf", rtol=1e-6, atol=1e-9)
    again = run()
    monkeypatch.setattr(compiled_bdf, "_PREPARED", {})
    fresh = run()
    for other in (again, fresh):
        for name in system.observed_names:
            np.testing.assert_array_equal(other[name], first[name], err_msg=name)
        assert {k: v for k, v in other.stats.items() if k.startswith("n")} == \
            {k: v for k, v in first.stats.items() if k.startswith("n")}


def test_the_observed_variables_are_the_kernels_at_the_output_states(kernel_cache):
    """The driver evaluates the kernel library's ``observe`` at the output times (instead of
    a mapped CasADi call after the run): the same numbers as that call on the run's states
    and inputs, on the 6304's ball level with a ramp input (951 observed variables)."""
    import casadi as ca

    from bearingsim.assemblies import deep_groove_ball_bearing
    from bearingsim.simulation.inputs import input_signal
    from bearingsim.simulation.kernels import kernel
    from bearingsim.simulation.sundials import observe_at

    system = assemble(deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=None,
                                               loads={"Fx": 500.0}, n_slices=0))
    inputs = {"shaft_speed": lambda t: 300.0 * ca.fmin(t / 0.005, 1.0)}
    res = simulate(system, 2e-3, method="compiled_bdf", n_points=5, inputs=inputs)
    kern = kernel(system, "ode", True)
    states = np.array([res[name] for name in system.state_names])
    expected = observe_at(kern, input_signal(system, inputs), system.p0(), res.t, states,
                          None)
    assert expected.shape == (len(system.observed_names), 5)
    got = np.array([res[name] for name in system.observed_names])
    np.testing.assert_allclose(got, expected, rtol=1e-13, atol=1e-300)
    assert np.ptp(res["cage.w"]) > 0  # the observed values move with the run


def test_threads_run_on_solvers_of_their_own(kernel_cache):
    """Runs in two threads at once (each thread its own kept solver) give what the same runs
    give one after the other."""
    import concurrent.futures

    system = assemble(SpringMassChain(phi0=0.1))
    settings = [{"rtol": 10.0 ** -k, "atol": 10.0 ** -(k + 3), "n_points": 50 + 10 * k}
                for k in (4, 5, 6, 7, 8, 9)]

    def run(kw):
        return _states(simulate(system, 1.0, method="compiled_bdf", **kw), system)

    alone = [run(kw) for kw in settings]
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        together = list(pool.map(run, settings * 3))
    for k, states in enumerate(together):
        np.testing.assert_array_equal(states, alone[k % len(settings)])


def test_a_long_series_is_not_held_by_the_kept_solver(kernel_cache, monkeypatch):
    """The kept solver's output arrays hold up to KEPT_OUTPUT_TIMES output times between runs;
    a run with more writes into arrays of its own (a series of a million output times would
    otherwise stay allocated with the thread's solver), with the same numbers."""
    system = assemble(SpringMassChain(phi0=0.1))
    long_kept = simulate(system, 1.0, method="compiled_bdf", n_points=60)
    monkeypatch.setattr(compiled_bdf, "_PREPARED", {})
    monkeypatch.setattr(compiled_bdf, "KEPT_OUTPUT_TIMES", 20)
    simulate(system, 1.0, method="compiled_bdf", n_points=5)
    long_apart = simulate(system, 1.0, method="compiled_bdf", n_points=60)
    np.testing.assert_array_equal(_states(long_apart, system), _states(long_kept, system))
    (prep,) = compiled_bdf._PREPARED.values()
    (solver,) = prep.solvers.by_size.values()
    assert [a.shape[0] for a in solver._outputs[0]] == [5, 5, 5]  # not grown to 60
