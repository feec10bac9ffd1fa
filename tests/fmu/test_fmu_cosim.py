"""Motor FMU + double-layer bearing FMU, coupled speed -> bearing and friction torque -> motor,
against the monolithic motor drive: fmpy's SSP master and the Open Simulation Platform's
libcosim (libcosimpy) on the same SSP file."""

from __future__ import annotations

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.ssp.simulation import simulate_ssp

from bearingsim.assembler import assemble
from bearingsim.assemblies.motor_drive import MotorShaft, motor_drive
from bearingsim.simulation import simulate
from bearingsim.studies.motor_bearing_cosim import BEARING_OUTPUTS, MOTOR_OUTPUTS
from tests.fmu.conftest import COSIM_FR, cosim_ramp
from tests.fmu.helpers import open_fmu

T_END = 0.3
BREAKAWAY = 0.01
"""The first 10 ms: the shaft leaves standstill and the friction torque jumps to half its
running value within the first rad/s; a sampled coupling sees that jump one step late."""

REF_OUTPUTS = {"motor.w_shaft": "shaft.w", "bearing.M_shaft": "bearing.M_shaft",
               "bearing.w_middle": "bearing.w_middle"}


@pytest.fixture(scope="module", params=["dc", "pmsm"])
def pair(request, cosim_pair):
    motor = request.param
    paths = cosim_pair(motor)
    system = assemble(motor_drive(motor=motor, speed_ref=cosim_ramp),
                      outputs=list(REF_OUTPUTS.values()))
    ref = simulate(system, T_END, n_points=int(round(T_END / 5e-4)) + 1,
                   inputs={"bearing.Fr": COSIM_FR}, rtol=1e-10, atol=1e-12, progress=False)
    return motor, paths, ref


def errors(ref, t, values: dict[str, np.ndarray]) -> dict[str, tuple[float, float]]:
    """Per signal: largest error relative to the largest reference value, over the whole run
    and after the breakaway."""
    out = {}
    late = ref.t >= BREAKAWAY
    for name, ref_name in REF_OUTPUTS.items():
        r = ref[ref_name]
        v = np.interp(ref.t, t, values[name], left=0.0)
        e = np.abs(v - r) / np.max(np.abs(r))
        out[name] = (float(e.max()), float(e[late].max()))
    return out


def fmpy_run(paths, h):
    """fmpy's SSP master (fixed step, Jacobi: both FMUs step on the last exchanged values)."""
    res = simulate_ssp(str(paths["ssp"]), stop_time=T_END, step_size=h)
    # a row holds the outputs at the end of the step that starts at res["time"]
    return res["time"] + h, {n: res[n] for n in REF_OUTPUTS}


def osp_run(paths, h):
    """libcosim's fixed-step master on the same SSP file."""
    try:
        from libcosimpy._internal import libcosimc

        libcosimc()  # loads libcosimc.so (and what it links, e.g. Debian's libtbb12)
    except OSError as exc:
        pytest.skip(f"libcosimpy's runtime library cannot be loaded: {exc}")
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.WARNING)
    n = int(round(T_END / h))
    execution = CosimExecution.from_ssp_file(str(paths["ssp"]), step_size=int(round(h * 1e9)))
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    refs = []
    for name in REF_OUTPUTS:
        element, var = name.split(".", 1)
        index = execution.slave_index_from_instance_name(element)
        vrs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
        refs.append((index, vrs[var]))
    values = np.empty((n, len(refs)))
    for k in range(n):
        assert execution.step()
        for j, (index, vr) in enumerate(refs):
            values[k, j] = observer.last_real_values(index, [vr])[0]
    t = h * np.arange(1, n + 1)
    return t, {name: values[:, j] for j, name in enumerate(REF_OUTPUTS)}


def test_interfaces(pair):
    _, paths, _ = pair
    motor = read_model_description(str(paths["motor"]))
    bearing = read_model_description(str(paths["bearing"]))
    causal = {v.name: v.causality for v in motor.modelVariables}
    assert [n for n, c in causal.items() if c == "input"] == ["M_bearing"]  # ramp is built in
    assert [n for n, c in causal.items() if c == "output"] == MOTOR_OUTPUTS
    causal = {v.name: v.causality for v in bearing.modelVariables}
    assert sorted(n for n, c in causal.items() if c == "input") == ["Fa", "Fr", "shaft_speed"]
    assert [n for n, c in causal.items() if c == "output"] == BEARING_OUTPUTS
    assert motor.modelExchange is None and bearing.coSimulation is not None


def test_motor_shaft_with_input_reference_has_two_inputs():
    system = assemble(MotorShaft("pmsm"), outputs=MOTOR_OUTPUTS)
    assert sorted(system.input_names) == ["M_bearing", "w_ref"]


@pytest.mark.parametrize("master", ["fmpy", "libcosim"])
def test_cosimulation_matches_the_monolithic_drive(master, pair):
    """1 ms: within 1 % on speed, friction torque and middle-ring speed (torque after the
    breakaway); 0.5 ms halves every error (first-order coupling)."""
    _, paths, ref = pair
    run = fmpy_run if master == "fmpy" else osp_run
    e1 = errors(ref, *run(paths, 1e-3))
    e2 = errors(ref, *run(paths, 5e-4))
    assert e1["motor.w_shaft"][0] < 1e-3, e1
    assert e1["bearing.M_shaft"][1] < 1e-2, e1
    assert e1["bearing.w_middle"][0] < 1e-2, e1
    # the breakaway is resolved one step late, but only there, and it converges too
    assert e1["bearing.M_shaft"][0] < 0.25, e1
    for name in REF_OUTPUTS:
        assert e1[name][1] / e2[name][1] > 1.8, (name, e1, e2)
        assert e1[name][0] / e2[name][0] > 1.8, (name, e1, e2)


def derivative_run(paths, h, tmp_path, derivatives=True):
    """A Jacobi master that passes derivatives (fmpy's low-level API): at each communication
    point it reads every coupled output and its time derivative
    (``fmi2GetRealOutputDerivatives``) and gives them to the other FMU as input and input
    slope (``fmi2SetRealInputDerivatives``), so each FMU ramps its input through the step
    instead of holding it."""
    motor, _, mv = open_fmu(paths["motor"], tmp_path, "CS")
    bearing, _, bv = open_fmu(paths["bearing"], tmp_path, "CS")
    fmus = (motor, bearing)
    links = ((motor, mv["w_shaft"], bearing, bv["shaft_speed"]),
             (bearing, bv["M_shaft"], motor, mv["M_bearing"]))
    for fmu in fmus:
        fmu.setupExperiment(tolerance=1e-8, startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
    n = int(round(T_END / h))
    values = np.empty((n, 3))
    for k in range(n):
        for source, out, target, inp in links:  # motor first: the bearing's dM/dt needs dw/dt
            target.setReal([inp], source.getReal([out]))
            if derivatives:
                target.setRealInputDerivatives([inp], [1],
                                               source.getRealOutputDerivatives([out], [1]))
        for fmu in fmus:
            fmu.doStep(k * h, h)
        values[k] = [*motor.getReal([mv["w_shaft"]]),
                     *bearing.getReal([bv["M_shaft"], bv["w_middle"]])]
    for fmu in fmus:
        fmu.terminate()
        fmu.freeInstance()
    return h * np.arange(1, n + 1), {name: values[:, j] for j, name in enumerate(REF_OUTPUTS)}


def test_output_derivatives_equal_the_slope_of_the_trajectory(cosim_pair, tmp_path):
    """dM_shaft/dt and dw_middle/dt from fmi2GetRealOutputDerivatives (dy/dx der(x) + dy/du du
    + partial dy/dt) against the forward difference of the outputs over a 1 us doStep along
    the same input ramp."""
    bearing, _, v = open_fmu(cosim_pair("dc")["bearing"], tmp_path, "CS")
    bearing.setupExperiment(tolerance=1e-10, startTime=0.0)
    bearing.enterInitializationMode()
    bearing.exitInitializationMode()
    bearing.setReal([v["shaft_speed"]], [50.0])
    bearing.doStep(0.0, 0.05)  # settle the middle ring
    slope, h = 200.0, 1e-6
    bearing.setRealInputDerivatives([v["shaft_speed"]], [1], [slope])
    d_m, d_w = bearing.getRealOutputDerivatives([v["M_shaft"], v["w_middle"]], [1, 1])
    m0, w0 = bearing.getReal([v["M_shaft"], v["w_middle"]])
    bearing.doStep(0.05, h)
    m1, w1 = bearing.getReal([v["M_shaft"], v["w_middle"]])
    fd_m, fd_w = (m1 - m0) / h, (w1 - w0) / h
    assert d_m == pytest.approx(fd_m, rel=1e-3, abs=1e-9)
    assert d_w == pytest.approx(fd_w, rel=1e-3, abs=1e-9)
    bearing.freeInstance()


def test_master_passing_derivatives_matches_within_0_1_percent(pair, tmp_path):
    """With output derivatives passed on as input slopes, the 1 ms co-simulation of the speed
    ramp is within 0.1 % of the monolithic drive on shaft speed, middle-ring speed and (after
    the breakaway) friction torque; holding the inputs (the same master without derivatives)
    is several times further off."""
    _, paths, ref = pair
    with_slopes = errors(ref, *derivative_run(paths, 1e-3, tmp_path))
    held = errors(ref, *derivative_run(paths, 1e-3, tmp_path, derivatives=False))
    for name in REF_OUTPUTS:
        assert with_slopes[name][1] < 1e-3, (name, with_slopes)
        assert with_slopes[name][1] < held[name][1], (name, with_slopes, held)
