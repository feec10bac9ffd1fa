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
from bearingsim.fmu.cosim_models import BEARING_OUTPUTS, MOTOR_OUTPUTS
from bearingsim.simulation import simulate
from tests.fmu.conftest import COSIM_FR, cosim_ramp

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
