"""Benchmark: the FMU's co-simulation stepper, cost per ``fmi2DoStep`` measured from a C host.

The 6304 deep-groove bearing with massive balls (``dynamic_massive_balls``, no slices; 75
states) is exported as an FMI 2.0 co-simulation FMU once per stepper of the C runtime
(``export_fmu(stepper=...)``):

* **rodas3**: Rodas3 (the stepper of earlier versions): exact Jacobian and a new LU
  factorisation at every internal step;
* **ros34pw2**: the Rosenbrock-W method ROS34PW2, which keeps the Jacobian and its LU
  factorisation over many steps;
* **bdf**: the BDF stepping core of ``method="compiled_bdf"`` (``bsm_bdf.c``), its history kept
  across doSteps, equal steps to each communication point.

Beside them, ``simulate(method="compiled_bdf")`` on the same model with the FMU's error
weights (rtol, atol = rtol / 100), its CPU time (``integrate_cpu_time``, the C loop) spread
over the same communication steps.

A small C program (``bench/fmu_stepper_host.c``, compiled with gcc) dlopens each FMU's binary,
sets the loads of duty condition 1 (1730 r/min, radial load 938 N), ramps the shaft speed from
0 over 5 ms (through ``fmi2SetRealInputDerivatives``, so the ramp is exact), calls
``fmi2DoStep`` with a fixed communication step and prints the mean wall time of one call (no
Python or ctypes in the timed loop): wall time and the CPU time of the thread (the latter is
what counts on a shared machine). Each FMU runs at two communication steps (0.1 ms and 1 ms)
over the same simulated time; runs alternate between the FMUs; the best of the repeats is
reported, with the real-time factor (simulated time / CPU time). Accuracy: largest deviation
of the outputs from ``simulate`` (CVODES, rtol 1e-10) at the communication points, relative
to each output's largest magnitude. Usage::

    python -m bench.fmu_stepper [--quick]
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import tempfile
import zipfile
from pathlib import Path

import numpy as np

from bearingsim.studies.deep_groove import DUTY_CYCLE
from bearingsim.units import rpm_to_rad_s
from bench.common import Section, markdown_table

__all__ = ["HOST_SOURCE", "run", "section"]

HOST_SOURCE = Path(__file__).with_name("fmu_stepper_host.c")
"""The C timing host."""

COMM_STEPS = (1e-4, 1e-3)
"""Communication steps [s]."""

T_END = 0.1
"""Simulated time [s] (``--quick``: a fifth)."""

RAMP = 5e-3
"""Duration of the shaft-speed ramp from rest [s] (a multiple of the communication steps)."""

TOLERANCE = 1e-6
"""Relative tolerance given to both FMUs (``fmi2SetupExperiment``)."""

OUTPUTS = ["w_cage", *[f"inner[{j}].Q" for j in range(7)], "ring.x_um", "ring.y_um"]
"""Compared outputs: cage speed [rad/s], inner contact loads [N], ring displacement [um]."""

STEPPERS = ("rodas3", "ros34pw2", "bdf")


def _system():
    from bearingsim.assembler import assemble
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing

    bearing = deep_groove_ball_bearing("6304", fidelity="dynamic_massive_balls", n_slices=0,
                                       loads={"Fx": None})
    return assemble(bearing, outputs=OUTPUTS)


def _host(folder: Path) -> Path:
    from bearingsim.fmu.build import fmi_header_dir

    if shutil.which("gcc") is None:
        raise RuntimeError("bench.fmu_stepper needs gcc")
    exe = folder / "fmu_stepper_host"
    subprocess.run(["gcc", "-O2", "-std=c99", "-D_POSIX_C_SOURCE=199309L",
                    f"-I{fmi_header_dir()}", str(HOST_SOURCE), "-o", str(exe), "-ldl"],
                   check=True)
    return exe


def _run_host(exe: Path, fmu: Path, folder: Path, h: float, n: int, w: float, load: float):
    """Wall and CPU time per doStep [ns], the output rows (t, y...) and the stepper's
    counters."""
    from fmpy import read_model_description

    unzip = folder / fmu.stem
    if not unzip.exists():
        with zipfile.ZipFile(fmu) as z:
            z.extractall(unzip)
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    lib = unzip / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
    args = [str(exe), str(lib), md.guid, repr(TOLERANCE), repr(h), str(n),
            str(vr["shaft_speed"]), repr(w), repr(RAMP), ",".join(str(vr[o]) for o in OUTPUTS),
            f"{vr['load.Fx']}={load!r}"]
    proc = subprocess.run(args, capture_output=True, text=True, env={}, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{fmu.name}: host failed ({proc.returncode}): {proc.stderr[-2000:]}")
    lines = proc.stdout.splitlines()
    ns = (float(lines[0].split()[1]), float(lines[0].split()[2]))
    rows = np.loadtxt(lines[1:], ndmin=2)
    m = re.search(r"after (\d+) internal steps \((\d+) rejected\), (\d+) Jacobians, (\d+) LU",
                  proc.stderr)
    counts = dict(zip(("steps", "rejected", "jacobians", "lu"), map(int, m.groups()),
                      strict=True))
    return ns, rows, counts


def _simulate(system, t_end: float, n: int, w: float, load: float, **options):
    """``simulate`` over ``t_end`` with ``n`` communication points; (rows, stats)."""
    from bearingsim.simulation import simulate

    res = simulate(system, t_end, n_points=n + 1,
                   inputs={"shaft_speed": ([0.0, RAMP], [0.0, w]), "load.Fx": load},
                   progress=False, **options)
    return (np.column_stack([res.t[1:], *[np.asarray(res[o])[1:] for o in OUTPUTS]]),
            res.stats)


def _error(rows: np.ndarray, ref: np.ndarray) -> float:
    """Largest deviation over outputs, each relative to the largest magnitude of its
    reference."""
    return max(float(np.max(np.abs(rows[:, k] - ref[:, k])) / max(np.max(np.abs(ref[:, k])),
                                                                  1e-300))
               for k in range(1, ref.shape[1]))


def run(quick: bool, log=print) -> str:
    """Export the FMUs, time them from the C host, run ``compiled_bdf`` and compare all with
    ``simulate`` (CVODES, rtol 1e-10).

    Returns the Markdown section (title line first).
    """
    from bearingsim.fmu import export_fmu

    t_end = T_END / 5 if quick else T_END
    repeats = 2 if quick else 3
    n_rpm, load = DUTY_CYCLE[0]
    w = rpm_to_rad_s(n_rpm)
    system = _system()
    table = []
    with tempfile.TemporaryDirectory(prefix="bench_fmu_stepper_") as tmp:
        folder = Path(tmp)
        exe = _host(folder)
        fmus = {}
        for stepper in STEPPERS:
            log(f"exporting the {stepper} FMU")
            fmus[stepper] = export_fmu(system, folder / f"dgbb_{stepper}.fmu", kinds=("CS",),
                                       inputs={"load.Fx": load}, stepper=stepper,
                                       model_name=f"dgbb_{stepper}")
        for h in COMM_STEPS:
            n = int(round(t_end / h))
            log(f"reference (CVODES, rtol 1e-10), {n} points")
            ref, _ = _simulate(system, t_end, n, w, load, method="cvodes", rtol=1e-10,
                               atol=1e-12)
            best = {s: (np.inf, np.inf) for s in STEPPERS}
            results = {}
            for r in range(repeats):
                for stepper in STEPPERS:
                    ns, rows, counts = _run_host(exe, fmus[stepper], folder, h, n, w, load)
                    log(f"h {h:g}, run {r + 1}/{repeats} {stepper}: {ns[0] / 1e3:.1f} us wall, "
                        f"{ns[1] / 1e3:.1f} us CPU per doStep, {counts}")
                    best[stepper] = min(best[stepper], ns, key=lambda v: v[1])
                    results[stepper] = (rows, counts)
            for stepper in STEPPERS:
                rows, c = results[stepper]
                np.testing.assert_allclose(rows[:, 0], ref[:, 0], rtol=1e-12)
                cpu_us = best[stepper][1] / 1e3
                table.append([f"FMU {stepper}", f"{h * 1e3:g}", f"{cpu_us:.1f}",
                              f"{best[stepper][0] / 1e3:.1f}", f"{h * 1e6 / cpu_us:.2f}",
                              f"{_error(rows, ref):.2e}", c["steps"], c["rejected"],
                              c["jacobians"], c["lu"]])
            cpu = np.inf
            for _ in range(repeats):
                rows, stats = _simulate(system, t_end, n, w, load, method="compiled_bdf",
                                        rtol=TOLERANCE, atol=TOLERANCE / 100)
                cpu = min(cpu, stats["integrate_cpu_time"])
            table.append(["compiled_bdf", f"{h * 1e3:g}", f"{cpu / n * 1e6:.1f}", "-",
                          f"{t_end / cpu:.2f}", f"{_error(rows, ref):.2e}", stats["nsteps"],
                          stats["netfails"] + stats["nncfails"], stats["njevals"],
                          stats["nlinsetups"]])
    header = ["stepper", "communication step [ms]", "CPU µs per doStep", "wall µs per doStep",
              "real-time factor (CPU)", "error vs CVODES", "internal steps", "rejected",
              "Jacobians", "LU factorisations"]
    return (
        "## FMU stepper: cost per doStep from a C host\n\n"
        f"6304 bearing, massive balls ({system.n_states} states), duty condition 1 "
        f"({n_rpm:g} r/min after a {RAMP * 1e3:g} ms ramp from rest, Fx = {load:g} N); FMI 2.0 "
        f"CS, {t_end:g} s simulated at each communication step, FMU tolerance {TOLERANCE:g} "
        "(error weights rtol |x| + rtol / 100); the CPU and wall time of the fmi2DoStep calls "
        f"in a C host (dlopen), the run of least CPU time of {repeats}. *compiled_bdf*: "
        "`simulate(method=\"compiled_bdf\")` with the same error weights, its C loop's CPU time "
        "per communication step (output points at the communication points). Real-time "
        "factor: simulated time / CPU time. Error: largest deviation of w_cage, the inner "
        "contact loads and the ring displacement from `simulate` (CVODES, rtol 1e-10) at the "
        "communication points, relative to each output's largest magnitude. Shared machine: "
        "compare rows of one run.\n\n" + markdown_table(header, table) + "\n"
    )


def section(quick: bool, log=print) -> Section:
    """:func:`run` as a :class:`bench.common.Section` (the signature of ``bench.run_all``)."""
    text = run(quick, log)
    title, _, body = text.partition("\n")
    return Section(title.lstrip("# ").strip(), body.strip())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a fifth of the simulated time")
    args = parser.parse_args(argv)
    print(run(args.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
