"""Masters of the motor/bearing co-simulation tests (fmpy's low-level API), the monolithic
reference and the error measure, shared by the tests and ``bench/cosim_coupling.py``."""

from __future__ import annotations

import numpy as np
from fmpy import read_model_description
from fmpy.ssp.simulation import simulate_ssp

from bearingsim.assembler import assemble
from bearingsim.assemblies.motor_drive import motor_drive
from bearingsim.simulation import simulate
from tests.fmu.conftest import COSIM_FR, cosim_ramp
from tests.fmu.helpers import open_fmu, open_fmu3

T_END = 0.3
BREAKAWAY = 0.01
"""The first 10 ms [s]: the shaft leaves standstill and the friction torque rises from zero to
its running value while the slip is inside the regularization band (omega_reg = 0.1 rad/s,
the first 4 ms); a sampled coupling follows that fast transient with a lag."""

REF_STEP = 1.25e-4
"""Sampling of the monolithic reference [s]: every communication point of the runs (steps of
0.125 ms and multiples) is one of its samples."""

REF_OUTPUTS = {"motor.w_shaft": "shaft.w", "bearing.M_shaft": "bearing.M_shaft",
               "bearing.w_middle": "bearing.w_middle"}


def monolithic_reference(motor: str):
    """``simulate`` of the monolithic drive with the ramp of the co-simulation tests (rtol
    1e-10), sampled every REF_STEP over T_END."""
    system = assemble(motor_drive(motor=motor, speed_ref=cosim_ramp),
                      outputs=list(REF_OUTPUTS.values()))
    return simulate(system, T_END, n_points=int(round(T_END / REF_STEP)) + 1,
                    inputs={"bearing.Fr": COSIM_FR}, rtol=1e-10, atol=1e-12, progress=False)


def value_reference(path, name: str) -> int:
    """Value reference of the variable ``name`` of the FMU at ``path``."""
    return next(v.valueReference for v in read_model_description(str(path)).modelVariables
                if v.name == name)


def errors(ref, t, values: dict[str, np.ndarray]) -> dict[str, tuple[float, float]]:
    """Per signal: largest error at the communication points ``t`` (where a co-simulation has
    values) relative to the largest reference value, over the whole run and after the
    breakaway."""
    t = np.asarray(t)
    index = np.rint(t / REF_STEP).astype(int)
    if np.any(np.abs(index * REF_STEP - t) > 1e-9) or index.max() >= len(ref.t):
        raise ValueError("errors: the communication points must be samples of the reference "
                         f"(multiples of {REF_STEP} s up to {T_END} s)")
    late = t >= BREAKAWAY
    out = {}
    for name, ref_name in REF_OUTPUTS.items():
        r = np.asarray(ref[ref_name])
        e = np.abs(np.asarray(values[name]) - r[index]) / np.max(np.abs(r))
        out[name] = (float(e.max()), float(e[late].max()))
    return out


def ssp_run(paths, h):
    """fmpy's SSP master (fixed step, Jacobi: both FMUs step on the last exchanged values)."""
    res = simulate_ssp(str(paths["ssp"]), stop_time=T_END, step_size=h)
    # a row holds the outputs at the end of the step that starts at res["time"]
    return res["time"] + h, {n: res[n] for n in REF_OUTPUTS}


def libcosim_run(paths, h):
    """libcosim's fixed-step master on the same SSP file (``OSError`` where libcosimpy's
    runtime library cannot be loaded)."""
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


def intermediate_update_run(paths, h, tmp_path):
    """The Jacobi master of :func:`derivative_run` in FMI 3.0: at each
    communication point it reads every coupled output y and its total time derivative (the
    output derivative plus the directional derivative along the partner's rate, as FMI 3.0
    has no input derivatives) and, through the intermediate-update callback, gives the other
    FMU y + dy/dt (t - t0) at every time it asks for inside the step."""
    ramps = {}
    fmus = {}

    def callback_for(name, input_name):
        def callback(env, t, *_):
            y, dy, t0 = ramps[name]
            fmu, vr = fmus[name]
            fmu.setFloat64([vr[input_name]], [y + dy * (t - t0)])
        return callback

    for name, path, input_name in (("motor", paths["motor"], "M_bearing"),
                                   ("bearing", paths["bearing"], "shaft_speed")):
        callback = callback_for(name, input_name)
        fmu, _, vr = open_fmu3(path, tmp_path, intermediate_update=callback,
                               required=[value_reference(path, input_name)])
        fmu._keep = callback  # fmpy keeps the ctypes wrapper; the closure must outlive it too
        fmus[name] = (fmu, vr)
    (motor, mv), (bearing, bv) = fmus["motor"], fmus["bearing"]
    for fmu, _ in fmus.values():
        fmu.enterInitializationMode(tolerance=1e-8)
        fmu.exitInitializationMode()
    n = int(round(T_END / h))
    values = np.empty((n, 3))
    for k in range(n):
        t0 = k * h
        w = motor.getFloat64([mv["w_shaft"]])[0]
        dw = motor.getOutputDerivatives([mv["w_shaft"]], [1])[0]
        bearing.setFloat64([bv["shaft_speed"]], [w])
        m = bearing.getFloat64([bv["M_shaft"]])[0]
        dm = (bearing.getOutputDerivatives([bv["M_shaft"]], [1])[0]
              + bearing.getDirectionalDerivative([bv["M_shaft"]], [bv["shaft_speed"]], [dw])[0])
        motor.setFloat64([mv["M_bearing"]], [m])
        ramps["bearing"], ramps["motor"] = (w, dw, t0), (m, dm, t0)
        motor.doStep(t0, h)
        bearing.doStep(t0, h)
        values[k] = [*motor.getFloat64([mv["w_shaft"]]),
                     *bearing.getFloat64([bv["M_shaft"], bv["w_middle"]])]
    for fmu, _ in fmus.values():
        fmu.terminate()
        fmu.freeInstance()
    return h * np.arange(1, n + 1), {name: values[:, j] for j, name in enumerate(REF_OUTPUTS)}
