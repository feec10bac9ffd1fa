"""Benchmark: motor + bearing co-simulation in multiples of real time, three masters.

The motor FMU (DC motor on its shaft, speed reference 0 -> 100 rad/s in 0.1 s built in) and the
61905/61907 double-layer bearing FMU at the torque level (imposed shaft speed, 500 N radial),
coupled speed -> bearing and friction torque -> motor
(:mod:`bearingsim.studies.motor_bearing_cosim`),
one SSP file, fixed communication step, Jacobi coupling (both FMUs step on the values exchanged
at the start of the step), run by:

* **C host**: a small C master generated here and compiled with gcc; it ``dlopen``s both FMU
  binaries and calls ``fmi2DoStep`` directly: the cost of the FMUs themselves, the limit any
  master can reach on this machine;
* **libcosim** (``libcosimpy``, the Open Simulation Platform's compiled master):
  ``simulate_until`` on the SSP file, no Python per step;
* **libcosim, ECCO**: the same FMUs under libcosim's adaptive-step algorithm (energy-conservation
  based co-simulation, Sadjina and Pedersen, Engineering with Computers 36, 2020), the speed
  and torque coupling declared as a power bond, tolerance ``ECCO_TOL``;
* **fmpy** (``fmpy.simulate_ssp``): Python drives every step through ctypes.

Reported: wall time, real-time factor (simulated / wall seconds), the share of each FMU's
``doStep`` in the C host, the final motor speed and bearing torque of each master (the fixed-step
masters must agree: same coupling, same steps), and the error of the motor speed over the run
against libcosim at a 100x smaller fixed step (sampled at the master's own communication times,
read one step at a time in a separate run).

``python -m bench.cosim`` prints the section (``--quick``: 0.3 s simulated).
"""

from __future__ import annotations

import argparse
import subprocess
import tempfile
import time
from pathlib import Path

import casadi as ca
import numpy as np

from bench.common import Section, fmt, markdown_table

__all__ = ["run", "section"]

T_END = 2.0
STEP = 1e-3
FR = 500.0
ECCO_TOL = 1e-5
"""Relative and absolute tolerance of the ECCO algorithm's energy residual."""


def _ramp(t):
    return 100.0 * ca.fmin(t / 0.1, 1.0)


_HOST = r"""
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "fmi2Functions.h"

typedef struct {
    fmi2InstantiateTYPE *instantiate;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2SetRealTYPE *set_real;
    fmi2GetRealTYPE *get_real;
    fmi2DoStepTYPE *do_step;
    fmi2TerminateTYPE *terminate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2Component c;
    double step_s;
} Fmu;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)env; (void)category;
    if (status > fmi2Warning) fprintf(stderr, "%s: %s\n", name, message);
}

static const fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};

static void *sym(void *lib, const char *name) {
    void *f = dlsym(lib, name);
    if (!f) { fprintf(stderr, "missing %s\n", name); exit(2); }
    return f;
}

static void load(Fmu *f, const char *so, const char *name, const char *guid, const char *res) {
    void *lib = dlopen(so, RTLD_NOW | RTLD_LOCAL);
    if (!lib) { fprintf(stderr, "%s\n", dlerror()); exit(2); }
    f->instantiate = (fmi2InstantiateTYPE *)sym(lib, "fmi2Instantiate");
    f->setup = (fmi2SetupExperimentTYPE *)sym(lib, "fmi2SetupExperiment");
    f->enter = (fmi2EnterInitializationModeTYPE *)sym(lib, "fmi2EnterInitializationMode");
    f->exit_init = (fmi2ExitInitializationModeTYPE *)sym(lib, "fmi2ExitInitializationMode");
    f->set_real = (fmi2SetRealTYPE *)sym(lib, "fmi2SetReal");
    f->get_real = (fmi2GetRealTYPE *)sym(lib, "fmi2GetReal");
    f->do_step = (fmi2DoStepTYPE *)sym(lib, "fmi2DoStep");
    f->terminate = (fmi2TerminateTYPE *)sym(lib, "fmi2Terminate");
    f->free_instance = (fmi2FreeInstanceTYPE *)sym(lib, "fmi2FreeInstance");
    f->c = f->instantiate(name, fmi2CoSimulation, guid, res, &callbacks, fmi2False, fmi2False);
    if (!f->c) { fprintf(stderr, "cannot instantiate %s\n", name); exit(2); }
    f->step_s = 0.0;
}

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void step(Fmu *f, double t, double h) {
    double t0 = now();
    if (f->do_step(f->c, t, h, fmi2True) > fmi2Warning) { fprintf(stderr, "doStep\n"); exit(3); }
    f->step_s += now() - t0;
}

int main(int argc, char **argv) {
    Fmu motor, bearing;
    const fmi2ValueReference w_shaft = W_SHAFT, m_bearing = M_BEARING;
    const fmi2ValueReference shaft_speed = SHAFT_SPEED, m_shaft = M_SHAFT;
    double t = 0.0, h = STEP_S, w, m, t0, wall;
    long k, n = (long)(T_END_S / STEP_S + 0.5);
    (void)argc; (void)argv;
    load(&motor, MOTOR_SO, "motor", MOTOR_GUID, MOTOR_RES);
    load(&bearing, BEARING_SO, "bearing", BEARING_GUID, BEARING_RES);
    t0 = now();
    motor.setup(motor.c, fmi2False, 0.0, 0.0, fmi2True, T_END_S);
    bearing.setup(bearing.c, fmi2False, 0.0, 0.0, fmi2True, T_END_S);
    motor.enter(motor.c); bearing.enter(bearing.c);
    motor.exit_init(motor.c); bearing.exit_init(bearing.c);
    for (k = 0; k < n; ++k) {
        motor.get_real(motor.c, &w_shaft, 1, &w);
        bearing.get_real(bearing.c, &m_shaft, 1, &m);
        bearing.set_real(bearing.c, &shaft_speed, 1, &w);
        motor.set_real(motor.c, &m_bearing, 1, &m);
        step(&motor, t, h);
        step(&bearing, t, h);
        t = (k + 1) * h;
    }
    wall = now() - t0;
    motor.get_real(motor.c, &w_shaft, 1, &w);
    bearing.get_real(bearing.c, &m_shaft, 1, &m);
    printf("%.9g %.9g %.9g %.17g %.17g\n", wall, motor.step_s, bearing.step_s, w, m);
    motor.terminate(motor.c); bearing.terminate(bearing.c);
    motor.free_instance(motor.c); bearing.free_instance(bearing.c);
    return 0;
}
"""


def _unpacked(fmu: Path, into: Path) -> dict[str, str]:
    """Unzip ``fmu``; its binary, GUID, resources URI and value references by name."""
    from fmpy import extract, platform, read_model_description, sharedLibraryExtension

    md = read_model_description(str(fmu))
    where = Path(extract(str(fmu), unzipdir=str(into / fmu.stem)))
    so = where / "binaries" / platform / (md.coSimulation.modelIdentifier
                                          + sharedLibraryExtension)
    refs = {v.name: v.valueReference for v in md.modelVariables}
    return {"so": str(so), "guid": md.guid, "res": (where / "resources").as_uri(), "refs": refs}


def _c_host(paths: dict[str, Path], work: Path, t_end: float) -> dict[str, float]:
    import fmpy

    motor, bearing = _unpacked(paths["motor"], work), _unpacked(paths["bearing"], work)
    defines = {
        "W_SHAFT": motor["refs"]["w_shaft"], "M_BEARING": motor["refs"]["M_bearing"],
        "SHAFT_SPEED": bearing["refs"]["shaft_speed"], "M_SHAFT": bearing["refs"]["M_shaft"],
        "STEP_S": repr(STEP), "T_END_S": repr(t_end),
        "MOTOR_SO": f'"{motor["so"]}"', "MOTOR_GUID": f'"{motor["guid"]}"',
        "MOTOR_RES": f'"{motor["res"]}"', "BEARING_SO": f'"{bearing["so"]}"',
        "BEARING_GUID": f'"{bearing["guid"]}"', "BEARING_RES": f'"{bearing["res"]}"',
    }
    source = work / "host.c"
    source.write_text(_HOST, encoding="utf-8")
    exe = work / "host"
    headers = Path(fmpy.__file__).parent / "c-code"
    subprocess.run(["gcc", "-O2", "-I", str(headers), *(f"-D{k}={v}" for k, v in defines.items()),
                    str(source), "-o", str(exe), "-ldl"], check=True)
    best = None
    for _ in range(3):
        out = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
        wall, motor_s, bearing_s, w, m = (float(v) for v in out.split())
        if best is None or wall < best["wall"]:
            best = {"wall": wall, "motor": motor_s, "bearing": bearing_s, "w": w, "M": m}
    return best


def _libcosim(ssp: Path, t_end: float) -> dict[str, float]:
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.WARNING)
    best = None
    for _ in range(3):
        execution = CosimExecution.from_ssp_file(str(ssp), step_size=int(round(STEP * 1e9)))
        observer = CosimObserver.create_last_value()
        execution.add_observer(observer)
        ref = {}
        for element, var in (("motor", "w_shaft"), ("bearing", "M_shaft")):
            index = execution.slave_index_from_instance_name(element)
            vrs = {v.name.decode(): v.reference for v in execution.slave_variables(index)}
            ref[var] = (index, vrs[var])
        t0 = time.perf_counter()
        execution.simulate_until(int(round(t_end * 1e9)))
        wall = time.perf_counter() - t0
        values = {k: observer.last_real_values(i, [vr])[0] for k, (i, vr) in ref.items()}
        if best is None or wall < best["wall"]:
            best = {"wall": wall, "w": values["w_shaft"], "M": values["M_shaft"]}
    return best


def _local_execution(paths: dict[str, Path], algorithm=None, step: float = STEP):
    """A libcosim execution of the two FMUs coupled as in the SSP file (ECCO ``algorithm``
    with the coupling as its power bond, else fixed ``step``), with a last-value observer;
    and the (slave, reference) of w_shaft and M_shaft."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    execution = (CosimExecution.from_algorithm(algorithm) if algorithm is not None
                 else CosimExecution.from_step_size(int(round(step * 1e9))))
    index, refs = {}, {}
    for name in ("motor", "bearing"):
        index[name] = execution.add_local_slave(CosimLocalSlave(fmu_path=str(paths[name]),
                                                                instance_name=name))
        refs[name] = {v.name.decode(): v.reference
                      for v in execution.slave_variables(index[name])}
    m, b = index["motor"], index["bearing"]
    w, mb = refs["motor"]["w_shaft"], refs["motor"]["M_bearing"]
    speed, torque = refs["bearing"]["shaft_speed"], refs["bearing"]["M_shaft"]
    execution.connect_real_variables(m, w, b, speed)
    execution.connect_real_variables(b, torque, m, mb)
    if algorithm is not None:
        algorithm.add_power_bond(m, w, mb, b, torque, speed)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    return execution, observer, (m, w), (b, torque)


def _ecco(paths: dict[str, Path], t_end: float, speed_error) -> dict[str, float]:
    """libcosim's ECCO algorithm: wall time (best of 3), steps, final values, speed error."""
    from libcosimpy.CosimAlgorithm import CosimAlgorithm, EccoParams

    def execution():
        # step sizes around the fixed step; each step may change it by 0.2x .. 1.5x
        params = EccoParams(step_size=STEP / 10, min_step_size=STEP / 100,
                            max_step_size=50 * STEP, min_change_rate=0.2, max_change_rate=1.5,
                            abs_tolerance=ECCO_TOL, rel_tolerance=ECCO_TOL)
        algorithm = CosimAlgorithm.create_ecco_algorithm(params)
        return algorithm, *_local_execution(paths, algorithm)

    best = None
    for _ in range(3):
        _, run, observer, w_at, m_at = execution()
        t0 = time.perf_counter()
        run.simulate_until(int(round(t_end * 1e9)))
        wall = time.perf_counter() - t0
        if best is None or wall < best["wall"]:
            best = {"wall": wall, "t_end": run.status().current_time * 1e-9,
                    "w": observer.last_real_values(w_at[0], [w_at[1]])[0],
                    "M": observer.last_real_values(m_at[0], [m_at[1]])[0]}
    _, run, observer, w_at, _ = execution()
    times, speeds = _speeds_per_step(run, observer, w_at, t_end)
    best["steps"] = len(times)
    best["speed_error"] = speed_error(times, speeds)
    return best


def _speeds_per_step(run, observer, w_at: tuple[int, int], t_end: float) -> tuple[list, list]:
    """Run one communication step at a time to ``t_end``: the times [s] and motor speeds."""
    times, speeds = [], []
    while not times or times[-1] < t_end:
        run.step(1)
        times.append(run.status().current_time * 1e-9)
        speeds.append(observer.last_real_values(w_at[0], [w_at[1]])[0])
    return times, speeds


def _speed_error_against_fine_steps(paths: dict[str, Path], t_end: float):
    """A function of (times, motor speeds) -> the largest error over max |speed|, against
    libcosim at STEP / 100 (linear interpolation between its samples)."""
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimObserver import CosimObserver

    run, _, (m, w), _ = _local_execution(paths, step=STEP / 100)
    n = int(round(t_end / (STEP / 100))) + 1
    series = CosimObserver.create_time_series(n)
    run.add_observer(series)
    series.start_time_series(m, w, CosimVariableType.REAL)
    run.simulate_until(int(round(t_end * 1e9)))
    t_ref, _, w_ref = (np.asarray(v, dtype=float) for v in series.time_series_real_samples(
        m, w, 0, n))
    t_ref *= 1e-9

    def error(times, speeds) -> float:
        t, v = np.asarray(times), np.asarray(speeds)
        inside = t <= t_ref[-1]
        return float(np.max(np.abs(v[inside] - np.interp(t[inside], t_ref, w_ref)))
                     / np.max(np.abs(w_ref)))

    return error


def _fmpy(ssp: Path, t_end: float) -> dict[str, float]:
    from fmpy.ssp.simulation import simulate_ssp

    t0 = time.perf_counter()
    res = simulate_ssp(str(ssp), stop_time=t_end, step_size=STEP)
    wall = time.perf_counter() - t0
    return {"wall": wall, "w": float(res["motor.w_shaft"][-1]),
            "M": float(res["bearing.M_shaft"][-1])}


def run(quick: bool = False) -> tuple[str, dict]:
    """Export the pair, run the three masters; return the Markdown body and the numbers."""
    from bearingsim.studies.motor_bearing_cosim import export_motor_bearing

    t_end = 0.3 if quick else T_END
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        t0 = time.perf_counter()
        paths = export_motor_bearing(work, motor="dc", speed_ref=_ramp, Fr=FR)
        export_s = time.perf_counter() - t0
        results = {"C host": _c_host(paths, work, t_end)}
        try:
            results["libcosim"] = _libcosim(paths["ssp"], t_end)
            speed_error = _speed_error_against_fine_steps(paths, t_end)
            run, observer, w_at, _ = _local_execution(paths)
            results["libcosim"]["speed_error"] = speed_error(
                *_speeds_per_step(run, observer, w_at, t_end))
            results["libcosim, ECCO"] = _ecco(paths, t_end, speed_error)
        except OSError as exc:  # libcosimc.so cannot be loaded on this machine
            results["libcosim"] = {"note": str(exc)}
        results["fmpy"] = _fmpy(paths["ssp"], t_end)
    host = results["C host"]
    fixed_error = results["libcosim"].get("speed_error")
    rows = []
    for name, r in results.items():
        if "wall" not in r:
            rows.append([name, "", "", "", "", "", "", r["note"]])
            continue
        steps = r.get("steps", round(t_end / STEP))
        simulated = r.get("t_end", t_end)
        error = r.get("speed_error", fixed_error)
        rows.append([name, str(steps), fmt(r["wall"]), fmt(simulated / r["wall"]),
                     fmt(r["wall"] / host["wall"]), "" if error is None else fmt(error),
                     f"{r['w']:.9g}", f"{r['M']:.9g}"])
    n = round(t_end / STEP)
    body = "\n".join([
        f"DC motor + 61905/61907 torque-level bearing (500 N radial), FMI 2.0 co-simulation, "
        f"{t_end:g} s at a {STEP * 1e3:g} ms communication step ({n} steps), Jacobi coupling; "
        "*libcosim, ECCO*: libcosim's adaptive-step algorithm on the same FMUs, the speed and "
        f"torque coupling as a power bond, tolerance {ECCO_TOL:g} (its last step ends past "
        f"{t_end:g} s; RTF over the time it reached). "
        f"Both FMUs exported in {export_s:.1f} s. *RTF*: simulated seconds per wall second "
        "(goal >= 100 at the torque level); *x C host*: wall time over the C host's, whose "
        "doStep calls are the limit of any fixed-step master here: motor "
        f"{host['motor'] / n * 1e6:.3g} us and bearing {host['bearing'] / n * 1e6:.3g} us per "
        f"doStep ({(host['motor'] + host['bearing']) / host['wall'] * 100:.0f} % of its wall "
        "time). *speed error*: the largest error of w_shaft at the master's communication times "
        "against libcosim at a 100x smaller fixed step, over max |w_shaft| (the fixed-step "
        "masters take the same steps: libcosim's value).", "",
        "Command: `python -m bench.cosim`", "",
        markdown_table(["master", "steps", "wall [s]", "RTF", "x C host", "speed error",
                        "final w_shaft [rad/s]", "final M_shaft [N m]"], rows), ""])
    return body, results


def section(quick: bool = False) -> Section:
    """The run_all section."""
    body, results = run(quick)
    return Section("Motor + bearing co-simulation: real-time factors of three masters", body,
                   results)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(run(parser.parse_args().quick)[0])


if __name__ == "__main__":
    main()
