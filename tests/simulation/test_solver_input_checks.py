"""Argument checks of simulate, table inputs and the double-layer entry points.

Each case was silently accepted (or failed with a misleading error) before: a CasADi backend
with a scipy method, output times outside the run, ``max_step`` ignored by CVODES, tables
extrapolated past their ends, unchecked middle-ring types and kinematic-level options, and
study arguments ignored next to ``system=``.
"""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim import Assembly, Input, Variable
from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.assemblies.double_layer import DoubleLayerBearing, DoubleLayerOptions
from bearingsim.errors import ParameterError, SimulationError
from bearingsim.simulation import simulate, steady_state
from bearingsim.studies.double_layer import speed_ratio_sweep, steady_ratio

SPEED = {"shaft_speed": 100.0}


@pytest.fixture(scope="module")
def torque_system():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque"),
                    outputs=["Rs", "w_shaft", "M_shaft"])


# ------------------------------------------------------------------ backend and method
@pytest.mark.parametrize(("backend", "method", "owner"), [
    ("casadi", "Radau", "scipy"), ("casadi", "BDF", "scipy"), ("scipy", "cvodes", "casadi"),
    ("scipy", "IDAS", "casadi"),
])
def test_method_of_the_other_backend_is_rejected(torque_system, backend, method, owner):
    with pytest.raises(ParameterError, match=rf"method '{method}' belongs to backend '{owner}'"
                       r".*'scipy': BDF, Radau.*'casadi': cvodes, idas"):
        simulate(torque_system, 0.1, inputs=SPEED, backend=backend, method=method)
    # each backend alone picks its default method
    assert simulate(torque_system, 0.1, inputs=SPEED, backend="casadi",
                    n_points=3).stats["method"] == "cvodes"
    assert simulate(torque_system, 0.1, inputs=SPEED, backend="scipy",
                    n_points=3).stats["method"] == "BDF"
    # neither given: the default method for the system (tests/simulation/test_method_choice.py); the
    # 3-state torque level is tiny, so CVODES on the VM
    assert simulate(torque_system, 0.1, inputs=SPEED, n_points=3).stats["method"] == "cvodes"


def test_unknown_method_lists_the_methods_per_backend(torque_system):
    with pytest.raises(ParameterError, match=r"unknown method 'rk4'.*backend 'scipy': BDF"):
        simulate(torque_system, 0.1, inputs=SPEED, method="rk4")


# ------------------------------------------------------------------ output times
@pytest.mark.parametrize("method", ["BDF", "cvodes", "idas"])
@pytest.mark.parametrize(("t_start", "t_eval", "message"), [
    (0.0, [0.0, 0.5, 2.0], r"t_eval = array with min 0, max 2 \[s\] is outside the valid "
                           r"range \[0, 1\] \[s\]"),
    (0.5, [0.0, 0.7, 1.0], r"t_eval = .* outside the valid range \[0.5, 1\] \[s\]"),
    (0.0, [0.5, 0.2, 1.0], r"t_eval must be strictly increasing \[s\], got t_eval\[1\] = 0.2"),
    (0.0, [0.0, 0.5, 0.5], r"t_eval must be strictly increasing"),
    (0.0, [0.0, np.nan, 1.0], r"t_eval must be finite"),
    (0.0, [], r"t_eval must be a non-empty one-dimensional array"),
])
def test_t_eval_must_lie_in_the_run_and_increase(torque_system, method, t_start, t_eval,
                                                  message):
    with pytest.raises(ParameterError, match=message):
        simulate(torque_system, 1.0, t_start=t_start, inputs=SPEED, t_eval=t_eval,
                 method=method)
    # times inside the run come back exactly, the start and end included
    res = simulate(torque_system, 1.0, t_start=0.25, inputs=SPEED, t_eval=[0.25, 0.5, 1.0],
                   method=method)
    np.testing.assert_array_equal(res.t, [0.25, 0.5, 1.0])


@pytest.mark.parametrize(("n_points", "message"), [
    (0, r"n_points = 0 \[1\] is outside the valid range \[2, 1\.34218e\+08\]"),
    (1, r"n_points = 1 \[1\] is outside the valid range \[2, 1\.34218e\+08\]"),
    (2.5, r"n_points must be an integer >= 2"),
    ("11", r"n_points must be an integer >= 2"),
])
def test_n_points_must_be_an_integer_of_at_least_two(torque_system, n_points, message):
    with pytest.raises(ParameterError, match=message):
        simulate(torque_system, 1.0, inputs=SPEED, n_points=n_points)


# ------------------------------------------------------------------ max_step
@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_sundials_methods_honour_max_step(torque_system, method):
    free = simulate(torque_system, 0.1, inputs=SPEED, method=method, n_points=3)
    limited = simulate(torque_system, 0.1, inputs=SPEED, method=method, n_points=3,
                       max_step=1e-4)
    assert free.stats["nsteps"] < 500
    assert limited.stats["nsteps"] >= 1000
    np.testing.assert_allclose(limited["Rs"], free["Rs"], rtol=1e-3, atol=1e-6)


@pytest.mark.parametrize("max_step", [0.0, -1.0, np.nan])
def test_max_step_must_be_positive(torque_system, max_step):
    with pytest.raises(ParameterError, match=r"simulate: max_step"):
        simulate(torque_system, 0.1, inputs=SPEED, max_step=max_step)


# ------------------------------------------------------------------ table inputs
@pytest.mark.parametrize("method", ["BDF", "cvodes"])
def test_table_inputs_hold_their_end_values(torque_system, method):
    after = simulate(torque_system, 3.0, inputs={"shaft_speed": ([0.0, 1.0], [0.0, 100.0])},
                     n_points=7, method=method)
    np.testing.assert_allclose(after["w_shaft"], [0, 50, 100, 100, 100, 100, 100], atol=1e-9)
    before = simulate(torque_system, 3.0,
                      inputs={"shaft_speed": ([1.0, 2.0], [50.0, 100.0])}, n_points=7,
                      method=method)
    np.testing.assert_allclose(before["w_shaft"], [50, 50, 50, 75, 100, 100, 100], atol=1e-9)


# ------------------------------------------------------------------ double-layer assemblies
@pytest.mark.parametrize("structure", ["X", "i", "z"])
def test_quasi_static_level_checks_the_structure(structure):
    with pytest.raises(ParameterError, match=r"double_layer_bearing: structure must be 'I' or "
                       rf"'Z', got '{structure}'"):
        double_layer_bearing("61905", "61907", structure=structure, fidelity="quasi-static")


def test_quasi_static_level_keeps_the_i_type_fit_check():
    with pytest.raises(ParameterError, match="I-type"):
        double_layer_bearing("61905", "61907", structure="I", fidelity="quasi-static")
    assert double_layer_bearing("61905", "61909", fidelity="quasi-static").structure == "I"


@pytest.mark.parametrize("fidelity", ["kinematic", "kinematic_approx"])
def test_kinematic_levels_reject_unused_layer_options(fidelity):
    with pytest.raises(ParameterError, match=rf"layer_options 'nonsense' not used at fidelity "
                       rf"'{fidelity}'; its only option is 'k'"):
        double_layer_bearing("61905", "61907", fidelity=fidelity,
                             layer_options={"k": 5.0, "nonsense": 1})
    system = assemble(double_layer_bearing("61905", "61907", fidelity=fidelity,
                                           layer_options={"k": 5.0}))
    p = dict(zip(system.parameter_names, system.p0(), strict=True))
    assert p["inner_layer.k"] == p["outer_layer.k"] == 5.0


# ------------------------------------------------------------------ studies
def test_sweep_refuses_bearing_arguments_next_to_a_system(torque_system):
    for kwargs in ({"inner": "61906"}, {"outer": "61908"}, {"structure": "Z"}):
        with pytest.raises(ParameterError, match=r"speed_ratio_sweep: .* cannot be combined "
                           r"with system="):
            speed_ratio_sweep([100.0], system=torque_system, **kwargs)


class _LoadedByDefault(Assembly):
    """A torque-level bearing whose radial load is an input with a non-zero start value."""

    def __init__(self):
        super().__init__("loaded")
        self.bearing = DoubleLayerBearing(DoubleLayerOptions(
            inner="61905", outer="61907", fidelity="torque",
            layer_options={"load_dependent": True}))
        self.shaft_speed = Input(0.0, "rad/s", "shaft speed")
        self.load = Input(2000.0, "N", "radial load", low=0.0)
        self.Rs = Variable(unit="1")
        self.M_shaft = Variable(unit="N.m")

    def equations(self):
        b = self.bearing
        return [b.shaft_speed == self.shaft_speed, b.Fr == self.load, b.Fa == 0.0,
                self.Rs == b.Rs, self.M_shaft == b.M_shaft]


def test_steady_ratio_evaluates_with_the_default_inputs():
    system = assemble(_LoadedByDefault(), outputs=["Rs", "M_shaft"])
    rs, torque, x = steady_ratio(system, 100.0)
    u = system.u_default()
    u[system.input_names.index("shaft_speed")] = 100.0
    obs = system.observe(0.0, x, u, system.p0())
    assert u[system.input_names.index("load")] == 2000.0
    assert torque == pytest.approx(obs["M_shaft"], rel=1e-12)
    assert rs == pytest.approx(obs["Rs"], rel=1e-12)



@pytest.mark.parametrize("speed", [0.0, -0.0])
def test_steady_ratio_refuses_a_shaft_at_rest(torque_system, speed):
    """Rs = w_middle / w_shaft is 0/0 at rest: steady_ratio returned Rs = 0 (the regularized
    ratio's value there) as if it were an answer."""
    with pytest.raises(ParameterError, match=r"steady_ratio: speed = 0 rad/s: the speed ratio "
                       r"Rs = w_middle / w_shaft is 0/0 at rest.*valid range: a finite shaft "
                       r"speed other than 0 \[rad/s\]"):
        steady_ratio(torque_system, speed, loads=(200.0, 0.0))
    with pytest.raises(ParameterError, match=r"steady_ratio: speed must be finite"):
        steady_ratio(torque_system, float("nan"), loads=(200.0, 0.0))


@pytest.mark.parametrize(("loads", "match"), [
    ((200.0,), r"loads \(Fr, Fa\) must have 2 entries \[N\], got 1"),  # was IndexError
    ((200.0, 0.0, 5.0), r"must have 2 entries \[N\], got 3"),  # was silently dropped
    (200.0, r"must have 2 entries \[N\], got 1"),  # was TypeError: not subscriptable
    (("0.2 rpm", 0.0), r"loads\[0\]: 'rpm' is not a unit of N quantities"),  # ValueError
    ((float("nan"), 0.0), r"loads\[0\] must be finite"),
])
def test_steady_ratio_loads_are_two_finite_numbers(torque_system, loads, match):
    with pytest.raises(ParameterError, match=match):
        steady_ratio(torque_system, 100.0, loads=loads)
    rs, _, _ = steady_ratio(torque_system, 100.0, loads=(200.0, 0.0))
    assert rs == pytest.approx(0.2072, abs=1e-3)  # the torque level's Rs, measured


@pytest.mark.parametrize(("p", "match"), [
    (np.ones(3), r"steady_state: p must have 14 entries \[SI units of "
                 r"system.parameter_names\], got 3"),  # was ValueError: could not broadcast
    ({"inner_layer.nu": 3e-5}, r"steady_state: p must be 14 numbers"),  # was TypeError
    ("x", r"steady_state: p must be 14 numbers"),  # was ValueError: could not convert
    (np.full(14, np.nan), r"steady_state: p must be finite"),  # was SimulationError
    (np.ones(14), r"steady_state: p: inner_layer.nu = 1.0 \[m2/s\] is outside the valid "
                  r"range"),  # was accepted
])
def test_steady_state_checks_the_parameter_vector(torque_system, p, match):
    inputs = {"shaft_speed": 100.0, "Fr": 200.0}
    with pytest.raises(ParameterError, match=match):
        steady_state(torque_system, inputs=inputs, p=p)
    given = steady_state(torque_system, inputs=inputs, p=list(torque_system.p0()))
    np.testing.assert_array_equal(given, steady_state(torque_system, inputs=inputs))
    assert given[torque_system.state_names.index("middle.sleeve.w")] == pytest.approx(
        0.2072 * 100.0, rel=1e-3)

# ------------------------------------------------------------------ between the output points
@pytest.mark.parametrize(("name", "text", "match"), [
    ("shaft_speed", "tan(pi/2)", r"pole pi/2 \+ k pi of tan"),
    # (scaled so that the speed stays within its bounds, twice the limiting speed, up to the
    # pole: the earliest problem is then the pole itself)
    ("shaft_speed", "1e-9 * tan(t + 1.0)", r"tan at its pole .* between t = 0\.57079"),
    ("shaft_speed", "1e-9/(t - 0.1234567)", r"division by zero between t = 0\.123456[67]"),
    ("shaft_speed", "1e300*t", r"overflow"),
    ("shaft_speed", "log(t - 0.5)", r"logarithm of a non-positive number between t = 0 s"),
    ("shaft_speed", "sqrt(0.25 - t)", r"square root of a negative number between t = 0\.2499"),
    ("Fr", "-5 * step(0.0051) * (1 - step(0.0052))",
     r"input Fr \[N\]: below its valid minimum 0 between t = 0\.005099"),
])
def test_input_signals_are_checked_between_the_output_points(torque_system, name, text, match):
    """Singularities, overflow and range violations that fall between the output points (three
    points over 1 s here) were accepted: the check looked at the output grid only. Interval
    arithmetic now bounds each input over the whole run and bisects to the span at fault."""
    from bearingsim.scenes.expressions import compile_expression

    with pytest.raises(ParameterError, match=match):  # constant parts fail when compiled
        inputs = {**SPEED, name: compile_expression(text, f"inputs.{name}")}
        simulate(torque_system, 1.0, inputs=inputs, n_points=3)


def test_interval_check_passes_kinks_guards_and_tables(torque_system):
    from bearingsim.scenes.expressions import compile_expression

    inputs = {"shaft_speed": compile_expression("rpm(3000) * ramp(0, 0.2)"),
              "Fr": compile_expression("1/(t - 2) + 1 if t < 1 else 0"),
              "Fa": ([0.0, 0.3, 0.30001, 1.0], [100.0, 100.0, 0.0, 0.0])}
    res = simulate(torque_system, 1.0, inputs=inputs, n_points=5)
    assert np.all(np.isfinite(res["Rs"]))


@pytest.mark.parametrize("text", ["ramp(0.5, 0.5)", "ramp(1, 0)"])
def test_ramp_needs_a_rising_time_span(text):
    from bearingsim.scenes.expressions import ExpressionError, compile_expression

    with pytest.raises(ExpressionError, match=r"ramp\(t0, t1\) .* needs t1 > t0"):
        compile_expression(text, "inputs.shaft_speed")


# ------------------------------------------------------------------ bounded work (issue 17)
class _Doubler(Assembly):
    """y = 2 u: no states."""

    def __init__(self):
        super().__init__("doubler")
        self.u = Input(1.0, "N", "input")
        self.y = Variable(unit="N", description="output")

    def equations(self):
        return [self.y == 2 * self.u]


def test_runs_too_large_to_be_meant_are_refused_with_the_estimate(torque_system):
    from bearingsim.errors import LongRunWarning

    with pytest.raises(ParameterError, match=r"n_points = 1000000000000 .* outside the valid"):
        simulate(torque_system, 1.0, inputs=SPEED, n_points=int(1e12))
    with pytest.raises(ParameterError, match=r"would take \d+\.\d GiB"):
        simulate(torque_system, 1.0, inputs=SPEED, n_points=100_000_000)
    with pytest.raises(ParameterError, match=r"forces at least 1e\+09 steps"):
        simulate(torque_system, 1.0, inputs=SPEED, max_step=1e-9)
    doubler = assemble(_Doubler())  # no states: nothing is integrated, only checked
    with pytest.warns(LongRunWarning, match=r"forces at least 2e\+06 steps"):
        simulate(doubler, 0.002, max_step=1e-9, n_points=3)


def test_an_interrupted_write_leaves_no_partial_file(tmp_path, torque_system, monkeypatch):
    """Ctrl-C while a result is written: no file under the final name (write to a temporary
    name, rename at the end)."""
    import csv as csv_module

    res = simulate(torque_system, 0.1, inputs=SPEED, n_points=11)

    class Interrupting:
        def __init__(self, fh):
            self.rows = 0

        def writerow(self, row):
            self.rows += 1

        def writerows(self, rows):
            raise KeyboardInterrupt

    monkeypatch.setattr(csv_module, "writer", Interrupting)
    with pytest.raises(KeyboardInterrupt):
        res.to_csv(tmp_path / "run.csv")
    assert list(tmp_path.iterdir()) == []
    monkeypatch.undo()
    assert res.to_csv(tmp_path / "run.csv").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["run.csv"]


# ------------------------------------------------------------------ budgets and BDF stalls
def _duplex_step_scene(arrangement: str, fz: float):
    from pathlib import Path

    from bearingsim.scenes.runner import prepare
    from bearingsim.scenes.scene import load_scene

    scene = load_scene(Path(__file__).parents[2] / "scenes" / "duplex_pair_axial.toml")
    scene = scene.replace(args={**scene.args, "arrangement": arrangement},
                          inputs={**scene.inputs, "shaft.Fz": f"{fz} * step(0.002)"})
    return prepare(scene)


@pytest.mark.parametrize(("arrangement", "fz"), [("DF", 2000.0), ("DB", 1000.0)])
def test_bdf_finishes_the_duplex_load_step_that_stalled_it(arrangement, fz):
    """scipy's BDF refused every step once the damped shaft had settled to round-off (its
    Newton test took corrections 1e-9 of the tolerance that stopped shrinking for divergence):
    DF 2000 N stalled at t = 1.4966 ms with steps of 1e-12 s. With the stagnation rule the run
    ends in under 3 000 steps and agrees with LSODA."""
    from bearingsim.scenes.scene_simulation import run_simulation

    prep = _duplex_step_scene(arrangement, fz)
    bdf = run_simulation(prep, method="BDF", max_steps=3000)
    lsoda = run_simulation(prep, method="LSODA")
    assert bdf.stats["n_steps"] <= 3000
    for name in ("shaft.z", "shaft.x", "shaft.ty"):
        np.testing.assert_allclose(bdf[name][-1], lsoda[name][-1], rtol=1e-5,
                                   atol=1e-6 * np.max(np.abs(lsoda[name])))


def test_bdf_newton_accepts_corrections_stagnating_at_round_off():
    """A damped oscillator at rest whose right-hand side carries 1e-10 round-off noise: scipy's
    BDF refuses Newton solve after Newton solve until its step is below the spacing of floats
    (status -1 after ~3 000 steps); the stagnation rule runs through in ~250 steps."""
    import scipy.integrate

    from bearingsim.simulation.scipy_solvers import StagnationTolerantBDF

    def steps(solver):
        rng = np.random.default_rng(0)
        counted = [0]

        class Counted(solver):
            def _step_impl(self):
                counted[0] += 1
                return super()._step_impl()

        sol = scipy.integrate.solve_ivp(
            lambda t, y: np.array([y[1], -1e6 * y[0] - 2e2 * y[1]
                                   + 1e-10 * rng.standard_normal()]),
            (0.0, 0.04), [0.0, 0.0], method=Counted, rtol=1e-6, atol=1e-12,
            jac=lambda t, y: np.array([[0.0, 1.0], [-1e6, -2e2]]))
        return sol, counted[0]

    ours, n_ours = steps(StagnationTolerantBDF)
    assert ours.status == 0 and n_ours < 500
    assert np.max(np.abs(ours.y[0])) < 1e-12  # stays at rest to the noise level
    scipys, n_scipys = steps(scipy.integrate.BDF)
    assert scipys.status == -1 or n_scipys > 2000


@pytest.mark.parametrize("method", ["BDF", "LSODA", "RK45", "compiled_bdf", "cvodes"])
def test_step_budget_ends_the_run_with_the_time_reached(torque_system, method):
    from bearingsim.errors import BudgetExceededError, SimulationError

    with pytest.raises(SimulationError, match=r"stopped at t = .* s of 50 s|CVODES failed "
                       r"between t = 0 s") as info:
        simulate(torque_system, 50.0, inputs=SPEED, method=method, max_steps=20, max_step=1e-3)
    if method != "cvodes":  # CVODES reports its own max_num_steps failure
        assert isinstance(info.value, BudgetExceededError)
        assert 0.0 < info.value.t_reached < 50.0
        assert "step budget of 20 steps (max_steps)" in str(info.value)


def test_wall_time_budget_ends_the_run(torque_system):
    from bearingsim.errors import BudgetExceededError

    with pytest.raises(BudgetExceededError, match=r"wall-time budget of 0.001 s \(timeout\)"):
        simulate(torque_system, 1e3, inputs=SPEED, method="RK45", timeout=1e-3,
                 max_steps=10**9, max_step=1e-3)


@pytest.mark.parametrize("method", ["cvodes", "idas"])
def test_wall_time_budget_stops_sundials_inside_its_call(torque_system, method, capfd):
    """CVODES and IDAS integrate the whole run in one call; the progress clock in their
    oracle checks the wall-time budget and ends the call, reporting the time reached, with
    nothing from the failed evaluation on standard error."""
    from bearingsim.errors import BudgetExceededError

    with pytest.raises(BudgetExceededError, match=r"wall-time budget of 0.05 s \(timeout\)") \
            as info:
        simulate(torque_system, 50.0, inputs=SPEED, method=method, timeout=0.05,
                 max_steps=10**9, max_step=1e-5, n_points=3)
    assert 0.0 < info.value.t_reached < 50.0
    assert capfd.readouterr().err == ""


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"max_steps": 0}, r"max_steps = 0 \[-\] is outside the valid range \[1, inf\)"),
    ({"max_steps": 2.5}, "max_steps must be a whole number >= 1"),
    ({"max_steps": "many"}, "max_steps must be a whole number >= 1"),
    ({"timeout": -1.0}, r"timeout = -1.0 \[s\] is outside"),
    ({"timeout": float("nan")}, "timeout must be finite"),
])
def test_budget_arguments_are_checked(torque_system, kwargs, match):
    with pytest.raises(ParameterError, match=match):
        simulate(torque_system, 0.1, inputs=SPEED, **kwargs)


def test_scipy_failure_before_the_first_output_time_reports_the_time_reached(
        torque_system, monkeypatch):
    """solve_ivp leaves ``sol.t`` an empty list when it fails before the first output time:
    the failure path raised AttributeError ('list' object has no attribute 'size')."""
    import scipy.integrate

    real = scipy.integrate.solve_ivp

    def failing(fun, t_span, y0, **kwargs):
        sol = real(fun, t_span, y0, **{**kwargs, "t_eval": kwargs["t_eval"][-1:]})
        sol.status, sol.message, sol.t = -1, "Required step size is less than spacing", []
        return sol

    monkeypatch.setattr(scipy.integrate, "solve_ivp", failing)
    for method in ("BDF", "LSODA"):
        with pytest.raises(SimulationError, match=rf"{method} failed at t = .* s of 0.1 s: "
                           "Required step size"):
            simulate(torque_system, 0.1, inputs=SPEED, method=method)


def test_end_time_of_1e308_is_refused_by_the_budget_not_run_for_ever(torque_system):
    from bearingsim.errors import BudgetExceededError

    with pytest.raises((ParameterError, BudgetExceededError)):
        simulate(torque_system, 1e308, inputs=SPEED, method="BDF", max_steps=200, n_points=2)


# ------------------------------------------------------------------ SKF bistability
@pytest.fixture(scope="module")
def skf_system():
    return assemble(double_layer_bearing("61905", "61907", fidelity="torque",
                                         friction_model="skf"), outputs=["Rs", "M_shaft"])


@pytest.mark.parametrize("start", [0.0, 50.0, 99.9])
def test_skf_bistable_speed_ratio_is_named_and_the_branch_is_the_one_a_run_reaches(
        skf_system, start):
    """The SKF model at 100 rad/s, Fr = 1000 N has stable steady states at Rs = 0.0013 and
    0.998 and an unstable one at 0.560; steady_ratio used to return one of them silently by
    start guess. Now it warns with all three and returns the one a run from the start settles
    on (checked by integrating from the same start)."""
    from bearingsim.errors import MultipleSteadyStatesWarning

    with pytest.warns(MultipleSteadyStatesWarning,
                      match=r"3 steady states, Rs = 0.001346 \(stable\), Rs = 0.5602 "
                            r"\(unstable\), Rs = 0.9981 \(stable\); returned Rs = ") as info:
        rs, _, _ = steady_ratio(skf_system, 100.0, loads=(1000.0, 0.0),
                                x_guess=np.array([start]))
    assert f"returned Rs = {rs:.4g}" in str(info[0].message)
    run = simulate(skf_system, 20.0, inputs={"shaft_speed": 100.0, "Fr": 1000.0, "Fa": 0.0},
                   x0={"middle.sleeve.w": start}, method="cvodes", n_points=3)
    assert run.final("Rs") == pytest.approx(rs, rel=1e-3, abs=1e-5)


def test_palmgren_speed_ratio_has_one_branch_and_no_warning(torque_system):
    import warnings

    from bearingsim.studies.double_layer import steady_branches

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        steady_ratio(torque_system, 100.0, loads=(1000.0, 0.0))
    branches = steady_branches(torque_system, {"shaft_speed": 100.0, "Fr": 1000.0, "Fa": 0.0},
                               torque_system.p0())
    assert len(branches) == 1 and branches[0].stable


def test_scene_budgets_are_read_checked_and_end_the_run():
    from bearingsim.errors import BudgetExceededError
    from bearingsim.scenes.preparation import prepare
    from bearingsim.scenes.scene import SceneError, scene_from_dict
    from bearingsim.scenes.scene_simulation import run_simulation

    base = {"assembly": {"name": "double_layer_bearing", "fidelity": "torque"},
            "inputs": {"shaft_speed": 100.0}, "outputs": ["Rs"]}
    for bad in ({"timeout": -1.0}, {"timeout": "10 N"}, {"max_steps": 0},
                {"max_steps": 2.5}, {"atol": 1e300}, {"rtol": 0.5}):
        with pytest.raises(SceneError, match=f"simulation.{next(iter(bad))}"):
            scene_from_dict({**base, "simulation": {"t_end": 1.0, **bad}})
    assert scene_from_dict({**base, "simulation": {"t_end": 1.0, "timeout": "10 min"}}
                           ).simulation.timeout == 600.0  # a time with a unit
    scene = scene_from_dict({**base, "simulation": {"t_end": 50.0, "max_step": 1e-3,
                                                    "max_steps": 30, "timeout": 60.0}})
    assert (scene.simulation.max_steps, scene.simulation.timeout) == (30, 60.0)
    assert scene.replace(title="again").simulation.timeout == 60.0  # survives to_dict
    with pytest.raises(BudgetExceededError, match=r"step budget of 30 steps"):
        run_simulation(prepare(scene))


def test_steady_ratio_takes_numbers_with_units_as_simulate_does(torque_system):
    """``steady_ratio(s, "1000 rpm")`` was refused ("speed must be float") and loads as text
    too, while simulate's inputs and System.p0 convert them (docs/units.md)."""
    with_units = steady_ratio(torque_system, "1000 rpm", ("0.2 kN", "0 N"))
    in_si = steady_ratio(torque_system, 1000 * np.pi / 30, (200.0, 0.0))
    assert with_units[0] == pytest.approx(in_si[0], rel=1e-12)
    assert with_units[1] == pytest.approx(in_si[1], rel=1e-12)
    with pytest.raises(ParameterError, match=r"steady_ratio: speed: 'kN' is not a unit of "
                                             r"rad/s quantities"):
        steady_ratio(torque_system, "3 kN")
    with pytest.raises(ParameterError, match=r"steady_ratio: loads\[1\]: 'rpm' is not a unit "
                                             r"of N quantities"):
        steady_ratio(torque_system, 100.0, (200.0, "5 rpm"))


@pytest.mark.parametrize(("speeds", "match"), [
    ([100.0, 0.0], r"speed_ratio_sweep: speeds = array with min 0, max 100 \[rad/s\] is "
                   r"outside the valid range \(0, inf\)"),  # was steady_ratio's message
    (["fast"], r"speed_ratio_sweep: speeds: 'fast' is not a number with a unit"),  # ValueError
    (["5000 kg"], r"speed_ratio_sweep: speeds: 'kg' is not a unit of rad/s quantities"),
    ([], r"speed_ratio_sweep: speeds must be a non-empty list"),  # was an empty sweep
    ([100.0, float("nan")], r"speed_ratio_sweep: speeds must be finite"),
])
def test_speed_ratio_sweep_checks_its_speeds_before_assembling(speeds, match):
    with pytest.raises(ParameterError, match=match):
        speed_ratio_sweep(speeds)


def test_speed_ratio_sweep_takes_speeds_with_units(torque_system):
    """As steady_ratio takes "3000 rpm" (docs/units.md); the sweep refused ["1000 rpm"]: "speeds
    must be numbers [rad/s]"."""
    with_units = speed_ratio_sweep(["1000 rpm", "5000 rpm"], system=torque_system)
    in_si = speed_ratio_sweep([1000 * np.pi / 30, 5000 * np.pi / 30], system=torque_system)
    np.testing.assert_allclose(with_units.speeds, in_si.speeds, rtol=1e-15)
    np.testing.assert_allclose(with_units.rs, in_si.rs, rtol=1e-12)


@pytest.mark.parametrize("study", ["deep_groove_statics", "roller_statics"])
def test_statics_loads_must_be_a_mapping(study):
    """A list of loads raised a TypeError from inside dict()."""
    from bearingsim.studies.deep_groove_statics import deep_groove_statics
    from bearingsim.studies.roller_statics import roller_statics

    run = {"deep_groove_statics": deep_groove_statics, "roller_statics": roller_statics}[study]
    with pytest.raises(ParameterError, match=rf"{study}: loads must be a dict of load names "
                                             r"\(Fx, Fy.*\) -> values, got list \[1000\]"):
        run(loads=[1000])
