"""Generated parameters and inputs within the valid ranges never give NaN and never hang (bounded
solver work: few output points, a largest step, a wall-clock limit); extremes: start from rest,
speed steps, load steps to zero and large, lubricant swaps without re-assembly, long runs."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing, motor_drive
from bearingsim.catalog import get_bearing
from bearingsim.physics.lubricant import as_lubricant, known_lubricants
from bearingsim.scenes import Scene, Simulation, run_scene
from bearingsim.simulation import simulate, steady_state
from bearingsim.units import rpm_to_rad_s
from tests.stress.conftest import valid_case

SETTINGS = settings(max_examples=25, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])
W_LIMIT = rpm_to_rad_s(15_000)  # below the 61905's limiting speed
PAIRS = [("61905", "61907"), ("61905", "61908"), ("61905", "61909")]


@cache
def system(inner="61905", outer="61907", fidelity="torque", friction_model="palmgren"):
    return assemble(double_layer_bearing(inner, outer, fidelity=fidelity,
                                         friction_model=friction_model),
                    outputs=["Rs", "M_shaft", "w_middle", "w_shaft"]
                    + (["inner_layer.P_loss"] if fidelity == "torque" else []))


@cache
def drive(motor="dc"):
    return assemble(motor_drive(double_layer_bearing(drive="flange"), motor=motor,
                                speed_ref=None, load_torque=0.0),
                    outputs=["shaft.w", "bearing.Rs", "bearing.M_shaft"])


def lubricant_parameters(name: str) -> dict[str, float]:
    """Viscosity of a named lubricant as parameters of both layers (no re-assembly)."""
    nu = float(as_lubricant(name).kinematic_viscosity())
    return {"inner_layer.nu": nu, "outer_layer.nu": nu}


def profile(kind: str, w: float, t_end: float):
    import casadi as ca

    if kind == "constant":
        return w
    if kind == "step":
        return lambda t: w * ca.if_else(t >= 0.3 * t_end, 1.0, 0.0)
    if kind == "ramp":
        return lambda t: w * ca.fmin(t / (0.5 * t_end), 1.0)
    return lambda t: w * (0.5 + 0.5 * ca.sin(20.0 * t))


def finite_or_documented(run):
    """A valid operating point: the run must succeed (any error, named or not, fails the test;
    the bad inputs are in test_stress_generated.py) with finite values. Counted as valid."""
    with valid_case():
        res = run()
        assert np.all(np.isfinite(res.values)), "NaN or inf in the result"
    return res


@SETTINGS
@given(
    pair=st.sampled_from(PAIRS),
    kind=st.sampled_from(["constant", "step", "ramp", "sine"]),
    w=st.floats(0.0, W_LIMIT),
    fr=st.floats(0.0, 5000.0),
    fa=st.floats(0.0, 2000.0),
    lub=st.sampled_from(known_lubricants()),
    friction_model=st.sampled_from(["palmgren", "skf"]),
)
def test_torque_level_never_gives_nan(pair, kind, w, fr, fa, lub, friction_model):
    s = system(*pair, "torque", friction_model)
    params = lubricant_parameters(lub) if friction_model == "palmgren" else {}
    res = finite_or_documented(lambda: simulate(
        s, 0.4, inputs={"shaft_speed": profile(kind, w, 0.4), "Fr": fr, "Fa": fa},
        parameters=params, n_points=9, max_step=0.02, progress=False))
    rs = res["Rs"][res["w_shaft"] > 1.0]
    assert np.all((rs > -0.05) & (rs < 1.0))


@SETTINGS
@given(pair=st.sampled_from(PAIRS), kind=st.sampled_from(["constant", "step", "ramp"]),
       w=st.floats(0.0, W_LIMIT), fidelity=st.sampled_from(["kinematic", "kinematic_approx"]))
def test_kinematic_levels_never_give_nan(pair, kind, w, fidelity):
    s = system(*pair, fidelity)
    finite_or_documented(lambda: simulate(s, 0.4, inputs={"shaft_speed": profile(kind, w, 0.4)},
                                          n_points=9, max_step=0.02, progress=False))


@settings(max_examples=6, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(motor=st.sampled_from(["dc", "pmsm"]), w=st.floats(0.0, rpm_to_rad_s(6000)),
       fr=st.floats(0.0, 2000.0))
def test_motor_drive_never_gives_nan(motor, w, fr):
    s = drive(motor)
    finite_or_documented(lambda: simulate(
        s, 0.3, inputs={"motor.w_ref": w, "bearing.Fr": fr}, n_points=7, max_step=0.01,
        progress=False))


# ----------------------------------------------------------------------------- extremes
@pytest.mark.parametrize("fidelity", ["kinematic", "torque"])
def test_start_from_rest_and_stay_at_rest(fidelity):
    res = simulate(system(fidelity=fidelity), 1.0, inputs={"shaft_speed": 0.0}, n_points=11,
                   progress=False)
    assert np.all(np.isfinite(res.values))
    np.testing.assert_allclose(res["w_middle"], 0.0, atol=1e-12)
    np.testing.assert_allclose(res["Rs"], 0.0, atol=1e-12)


@pytest.mark.parametrize("w", [1.0, 100.0, W_LIMIT])
def test_speed_step_from_rest(w):
    import casadi as ca

    res = simulate(system(), 0.5, inputs={"shaft_speed": lambda t: w * ca.if_else(
        t >= 0.1, 1.0, 0.0), "Fr": 100.0}, n_points=51, max_step=0.01, progress=False)
    assert np.all(np.isfinite(res.values))
    assert 0.0 <= res.final("Rs") < 0.5
    if w >= 100.0:
        assert res.final("Rs") > 0.1


@pytest.mark.parametrize("load", [0.0, 1.0, 5_000.0, 0.5 * get_bearing("61905").static_load_rating])
def test_load_steps_to_zero_and_large(load):
    res = simulate(system(), 0.6, inputs={"shaft_speed": 500.0, "Fr": (
        [0.0, 0.3, 0.30001, 0.6], [1000.0, 1000.0, load, load]), "Fa": load / 4},
        n_points=31, max_step=0.01, progress=False)
    assert np.all(np.isfinite(res.values))
    assert res.final("M_shaft") < 0  # friction opposes the shaft's motion


def test_lubricant_swap_between_runs_without_reassembly_matches_reassembly():
    s = system()
    for lub in ("ISO VG 10", "ISO VG 460", "ISO VG 32"):
        x_swap = steady_state(s, inputs={"shaft_speed": 1000.0},
                              parameters=lubricant_parameters(lub))
        fresh = assemble(double_layer_bearing(lubrication=lub),
                         outputs=["Rs", "M_shaft", "w_middle", "w_shaft", "inner_layer.P_loss"])
        x_new = steady_state(fresh, inputs={"shaft_speed": 1000.0})
        np.testing.assert_allclose(x_swap, x_new, rtol=1e-10, atol=1e-12)


def test_grease_and_oil_alternate_on_one_system():
    s = system()
    out = []
    for lub in ("lithium grease", "ISO VG 68", "lithium grease"):
        res = simulate(s, 0.2, inputs={"shaft_speed": 300.0},
                       parameters=lubricant_parameters(lub), n_points=5, progress=False)
        out.append(res.final("M_shaft"))
    assert out[0] == out[2]
    assert out[0] != out[1]


@pytest.mark.parametrize("fidelity", ["kinematic", "torque"])
def test_long_run_does_not_drift(fidelity):
    s = system(fidelity=fidelity)
    w = 1000.0
    res = simulate(s, 300.0, inputs={"shaft_speed": w}, n_points=31, rtol=1e-9, atol=1e-11,
                   progress=False)
    assert np.all(np.isfinite(res.values))
    x = steady_state(s, inputs={"shaft_speed": w})
    u = np.array([w if n == "shaft_speed" else 0.0 for n in s.input_names])
    rs_steady = s.observe(0.0, x, u)["Rs"]
    tail = res["Rs"][-10:]
    np.testing.assert_allclose(tail, rs_steady, rtol=1e-7)
    assert np.ptp(tail) < 1e-9


def test_long_scene_run_with_pruning_and_bounded_steps(tmp_path):
    scene = Scene("double_layer_bearing", outputs=["Rs", "M_shaft"],
                  inputs={"shaft_speed": "rpm(8000) * ramp(0, 1) + 50 * sin(2 * pi * t)"},
                  simulation=Simulation(t_end=60.0, n_points=121, max_step=0.25))
    run = run_scene(scene, out=tmp_path)
    assert all(np.all(np.isfinite(y)) for y in run.series.values())
    assert run.summary["skipped"]["pruned"]
