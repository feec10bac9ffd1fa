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

A second table runs ros34pw2 and bdf on a small model, the 61905/61907 double-layer bearing
at the torque level (3 states, ``bearing_model()`` of the co-simulation example; shaft speed
ramped to 100 rad/s, radial load 500 N), over 0.5 s at a 1 ms communication step: the
measurements behind ``export_fmu(stepper="auto")``.

Beside them, ``simulate(method="compiled_bdf")`` on the same model with the FMU's error
weights (rtol, atol = rtol / 100), its CPU time (``integrate_cpu_time``, the C loop) spread
over the same communication steps.

A small C program (``bench/fmu_stepper_host.c``, compiled with gcc) dlopens each FMU's binary,
sets the loads of duty condition 1 (1730 r/min, radial load 938 N), ramps the shaft speed from
0 over 5 ms (through ``fmi2SetRealInputDerivatives``, so the ramp is exact), calls
``fmi2DoStep`` with a fixed communication step and prints the mean wall time of one call (no
Python or ctypes in the timed loop): wall time and the CPU time of the thread (the latter is
what counts on a shared machine). Each FMU runs at two communication steps (0.1 ms and 1 ms)
and two tolerances (1e-6, 1e-5) over the same simulated time; runs alternate between the
FMUs; the best of the repeats is reported, with the real-time factor (simulated time / CPU
time). Accuracy: largest deviation of the outputs from ``simulate`` (CVODES, rtol 1e-10) at
the communication points, relative to each output's largest magnitude. Usage::

    python -m bench.fmu_stepper [--quick]
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import tempfile
import zipfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from bearingsim.studies.deep_groove import DUTY_CYCLE
from bearingsim.units import rpm_to_rad_s
from bench.common import Section, markdown_table

__all__ = ["HOST_SOURCE", "run", "section"]

HOST_SOURCE = Path(__file__).with_name("fmu_stepper_host.c")
"""The C timing host."""

COMM_STEPS = (1e-4, 1e-3)
"""Communication steps of the ball-level model [s]."""

T_END = 0.1
"""Simulated time of the ball-level model [s] (``--quick``: a fifth)."""

RAMP = 5e-3
"""Duration of the shaft-speed ramp from rest [s] (a multiple of the communication steps)."""

TOLERANCES = (1e-6, 1e-5)
"""Relative tolerances given to the ball-level FMUs (``fmi2SetupExperiment``); Rodas3 runs at
the first and the first communication step only (it is the slowest by far)."""

SMALL_TOLERANCES = (1e-6, 1e-8)
"""Relative tolerances of the small model."""

STEPPERS = ("rodas3", "ros34pw2", "bdf")


@dataclass(frozen=True)
class Model:
    """A model of the benchmark and how the host drives it."""

    label: str
    build: Callable
    """-> the assembly."""
    outputs: list[str]
    ramp: tuple[str, float]
    """Input ramped from 0 over :data:`RAMP` and its final value."""
    held: dict[str, float] = field(default_factory=dict)
    """Inputs set once (also the FMU's start values)."""
    spiky: tuple[str, ...] = ()
    """Outputs left out of the smooth error (contact loads)."""


def _ball_level():
    from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing

    return deep_groove_ball_bearing("6304", fidelity="dynamic_massive_balls", n_slices=0,
                                    loads={"Fx": None})


def _torque_level():
    from bearingsim.studies.motor_bearing_cosim import bearing_model

    return bearing_model()


BALL_LEVEL = Model(
    "6304 massive balls", _ball_level,
    ["w_cage", *[f"inner[{j}].Q" for j in range(7)], "ring.x_um", "ring.y_um"],
    ("shaft_speed", rpm_to_rad_s(DUTY_CYCLE[0][0])), {"load.Fx": DUTY_CYCLE[0][1]},
    spiky=tuple(f"inner[{j}].Q" for j in range(7)))
"""Compared outputs: cage speed [rad/s], inner contact loads [N], ring displacement [um]."""

SMALL = Model("61905/61907 torque level", _torque_level, ["M_shaft", "w_middle", "Rs"],
              ("shaft_speed", 100.0), {"Fr": 500.0})


def _host(folder: Path) -> Path:
    from bearingsim.fmu.build import fmi_header_dir

    if shutil.which("gcc") is None:
        raise RuntimeError("bench.fmu_stepper needs gcc")
    exe = folder / "fmu_stepper_host"
    subprocess.run(["gcc", "-O2", "-std=c99", "-D_POSIX_C_SOURCE=199309L",
                    f"-I{fmi_header_dir()}", str(HOST_SOURCE), "-o", str(exe), "-ldl"],
                   check=True)
    return exe


def _run_host(exe: Path, fmu: Path, folder: Path, model: Model, tol: float, h: float, n: int):
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
    ramp, value = model.ramp
    args = [str(exe), str(lib), md.guid, repr(tol), repr(h), str(n), str(vr[ramp]),
            repr(value), repr(RAMP), ",".join(str(vr[o]) for o in model.outputs),
            *[f"{vr[k]}={v!r}" for k, v in model.held.items()]]
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


def _simulate(system, model: Model, t_end: float, n: int, **options):
    """``simulate`` over ``t_end`` with ``n`` communication points; (rows, stats)."""
    from bearingsim.simulation import simulate

    ramp, value = model.ramp
    res = simulate(system, t_end, n_points=n + 1,
                   inputs={ramp: ([0.0, RAMP], [0.0, value]), **model.held},
                   progress=False, **options)
    return (np.column_stack([res.t[1:], *[np.asarray(res[o])[1:] for o in model.outputs]]),
            res.stats)


def _error(rows: np.ndarray, ref: np.ndarray, model: Model, smooth: bool = False) -> float:
    """Largest deviation over outputs, each relative to the largest magnitude of its
    reference; ``smooth``: without the model's spiky outputs (the contact loads, whose onsets
    make spikes of a step's timing)."""
    columns = [k + 1 for k, name in enumerate(model.outputs)
               if not (smooth and name in model.spiky)]
    return max(float(np.max(np.abs(rows[:, k] - ref[:, k])) / max(np.max(np.abs(ref[:, k])),
                                                                  1e-300))
               for k in columns)


def _export(system, model: Model, folder: Path, steppers) -> dict[str, Path]:
    from bearingsim.fmu import export_fmu

    tag = model.build.__name__.strip("_")
    return {s: export_fmu(system, folder / f"{tag}_{s}.fmu", kinds=("CS",), inputs=model.held,
                          stepper=s, model_name=f"{tag}_{s}") for s in steppers}


def _compare(exe: Path, fmus: dict, steppers: list[str], folder: Path, system, model: Model,
             ref: np.ndarray, tol: float, h: float, n: int, repeats: int, log,
             compiled_bdf: bool = True) -> list[list]:
    """Table rows of the FMUs (best CPU time of ``repeats`` alternating runs) and of
    ``compiled_bdf`` at one tolerance and communication step."""
    best = {s: (np.inf, np.inf) for s in steppers}
    results = {}
    for r in range(repeats):
        for stepper in steppers:
            ns, rows, counts = _run_host(exe, fmus[stepper], folder, model, tol, h, n)
            log(f"{model.label}, tol {tol:g}, h {h:g}, run {r + 1}/{repeats} {stepper}: "
                f"{ns[0] / 1e3:.1f} us wall, {ns[1] / 1e3:.1f} us CPU per doStep, {counts}")
            best[stepper] = min(best[stepper], ns, key=lambda v: v[1])
            results[stepper] = (rows, counts)
    table = []
    for stepper in steppers:
        rows, c = results[stepper]
        np.testing.assert_allclose(rows[:, 0], ref[:, 0], rtol=1e-12)
        cpu_us = best[stepper][1] / 1e3
        table.append([f"FMU {stepper}", f"{tol:g}", f"{h * 1e3:g}", f"{cpu_us:.1f}",
                      f"{best[stepper][0] / 1e3:.1f}", f"{h * 1e6 / cpu_us:.2f}",
                      f"{_error(rows, ref, model):.2e}",
                      f"{_error(rows, ref, model, smooth=True):.2e}",
                      c["steps"], c["rejected"], c["jacobians"], c["lu"]])
    if not compiled_bdf:
        return table
    cpu = np.inf
    for _ in range(repeats):
        rows, stats = _simulate(system, model, n * h, n, method="compiled_bdf", rtol=tol,
                                atol=tol / 100)
        cpu = min(cpu, stats["integrate_cpu_time"])
    table.append(["compiled_bdf", f"{tol:g}", f"{h * 1e3:g}", f"{cpu / n * 1e6:.1f}", "-",
                  f"{n * h / cpu:.2f}", f"{_error(rows, ref, model):.2e}",
                  f"{_error(rows, ref, model, smooth=True):.2e}", stats["nsteps"],
                  stats["netfails"] + stats["nncfails"], stats["njevals"], stats["nlinsetups"]])
    return table


HEADER = ["stepper", "tolerance", "communication step [ms]", "CPU µs per doStep",
          "wall µs per doStep", "real-time factor (CPU)", "error vs CVODES",
          "error w/o contact loads", "internal steps", "rejected", "Jacobians",
          "LU factorisations"]


def run(quick: bool, log=print) -> str:
    """Export the FMUs, time them from the C host, run ``compiled_bdf`` and compare all with
    ``simulate`` (CVODES, rtol 1e-10).

    Returns the Markdown section (title line first).
    """
    from bearingsim.assembler import assemble

    t_end = T_END / 5 if quick else T_END
    repeats = 2 if quick else 3
    system = assemble(BALL_LEVEL.build(), outputs=BALL_LEVEL.outputs)
    small_system = assemble(SMALL.build(), outputs=SMALL.outputs)
    table, small_table = [], []
    with tempfile.TemporaryDirectory(prefix="bench_fmu_stepper_") as tmp:
        folder = Path(tmp)
        exe = _host(folder)
        log("exporting the FMUs")
        fmus = _export(system, BALL_LEVEL, folder, STEPPERS)
        for h in COMM_STEPS:
            n = int(round(t_end / h))
            log(f"reference (CVODES, rtol 1e-10), {n} points")
            ref, _ = _simulate(system, BALL_LEVEL, t_end, n, method="cvodes", rtol=1e-10,
                               atol=1e-12)
            for tol in TOLERANCES:
                steppers = [s for s in STEPPERS
                            if s != "rodas3" or (tol, h) == (TOLERANCES[0], COMM_STEPS[0])]
                table += _compare(exe, fmus, steppers, folder, system, BALL_LEVEL, ref, tol,
                                  h, n, repeats, log)
        small_fmus = _export(small_system, SMALL, folder, STEPPERS[1:])
        n = int(round(5 * t_end / COMM_STEPS[1]))
        ref, _ = _simulate(small_system, SMALL, 5 * t_end, n, method="cvodes", rtol=1e-10,
                           atol=1e-12)
        for tol in SMALL_TOLERANCES:
            small_table += _compare(exe, small_fmus, list(STEPPERS[1:]), folder, small_system,
                                    SMALL, ref, tol, COMM_STEPS[1], n, repeats, log,
                                    compiled_bdf=False)
    (n_rpm, load), w = DUTY_CYCLE[0], BALL_LEVEL.ramp[1]
    return (
        "## FMU stepper: cost per doStep from a C host\n\n"
        f"6304 bearing, massive balls ({system.n_states} states), duty condition 1 "
        f"({n_rpm:g} r/min = {w:.4g} rad/s after a {RAMP * 1e3:g} ms ramp from rest, "
        f"Fx = {load:g} N); FMI 2.0 CS, {t_end:g} s simulated at each communication step and "
        "FMU tolerance (error weights rtol |x| + rtol / 100); the CPU and wall time of the "
        f"fmi2DoStep calls in a C host (dlopen), the run of least CPU time of {repeats}. "
        "*compiled_bdf*: `simulate(method=\"compiled_bdf\")` with the same error weights, its "
        "C loop's CPU time per communication step (output points at the communication "
        "points). Real-time factor: simulated time / CPU time. Error: largest deviation of "
        "w_cage, the inner contact loads and the ring displacement from `simulate` (CVODES, "
        "rtol 1e-10) at the communication points, relative to each output's largest "
        "magnitude; *w/o contact loads*: of w_cage and the ring displacement. Shared "
        "machine: compare rows of one run.\n\n" + markdown_table(HEADER, table) + "\n\n"
        f"Small model: {SMALL.label} ({small_system.n_states} states, shaft speed ramped to "
        f"{SMALL.ramp[1]:g} rad/s in {RAMP * 1e3:g} ms, Fr = {SMALL.held['Fr']:g} N), "
        f"{5 * t_end:g} s at a {COMM_STEPS[1] * 1e3:g} ms communication step; error of "
        f"{', '.join(SMALL.outputs)}.\n\n" + markdown_table(HEADER, small_table) + "\n"
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
