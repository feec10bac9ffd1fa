"""Benchmark: exported FMUs — cost per ``doStep`` and real-time factor, native C against Python.

Each assembly is exported twice as an FMI 2.0 co-simulation FMU and run side by side in one
process with fmpy's ``FMU2Slave`` at a 1 ms communication step:

* **native**: :func:`bearingsim.fmu.export_fmu` (CasADi C code + the C runtime with its adaptive
  ROS34PW2 stepper, tolerance 1e-6);
* **pythonfmu**: a ``pythonfmu.Fmi2Slave`` (:class:`BearingsimPythonSlave`) built with
  ``pythonfmu build``; its ``do_step`` calls the system's compiled CasADi functions
  (:func:`bearingsim.simulation.compile.compile_system`, zero-copy ``Function.buffer`` calls) with a
  simple implicit stepper: backward Euler, one step per millisecond, Newton with the exact
  Jacobian.

Both are checked against ``simulate`` (CVODES-class accuracy, rtol 1e-10) so the cost is read
next to the accuracy it buys. Usage::

    python -m bench.fmu [--quick]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import zipfile
from functools import partial
from pathlib import Path

import numpy as np

from bearingsim import Assembly, Input, connect
from bearingsim.components.rotational import Damper, Fixed, Inertia, SpringDamper, TorqueSource

__all__ = ["BearingsimPythonSlave", "EXPORTS", "MODELS", "PythonStepper", "RotationalDrive",
           "export_section", "export_times", "run", "section"]

COMM_STEP = 1e-3
"""Communication step of every run [s]."""


class RotationalDrive(Assembly):
    """A torque input drives a motor inertia, a spring-damper coupling and a damped load."""

    def __init__(self):
        super().__init__("rotational_drive")
        self.tau = Input(1.0, "N.m", "driving torque")
        self.src = TorqueSource(None)
        self.rotor = Inertia(2e-3)
        self.coupling = SpringDamper(200.0, 0.05)
        self.load = Inertia(1e-2)
        self.friction = Damper(0.02)
        self.ground = Fixed()
        connect(self.src.flange, self.rotor.flange_a)
        connect(self.rotor.flange_b, self.coupling.flange_a)
        connect(self.coupling.flange_b, self.load.flange_a)
        connect(self.load.flange_b, self.friction.flange_a)
        connect(self.friction.flange_b, self.ground.flange)

    def equations(self):
        return [self.src.tau_in == self.tau]


def _bearing():
    from bearingsim.studies.motor_bearing_cosim import bearing_model

    return bearing_model()


def _motor():
    from bearingsim.assemblies.motor_drive import motor_drive

    return motor_drive(motor="pmsm", speed_ref=None)


MODELS = {
    "rotational": ("rotational drive (2 inertias, coupling)", RotationalDrive, {"tau": 1.0},
                   ["load.w", "coupling.tau"]),
    "bearing": ("double-layer bearing 61905/61907 at 100 rad/s", _bearing,
                {"shaft_speed": 100.0, "Fr": 500.0}, ["M_shaft", "w_middle", "Rs"]),
    "motor": ("PMSM drive + double-layer bearing", _motor,
              {"motor.w_ref": 100.0, "bearing.Fr": 500.0},
              ["shaft.w", "bearing.w_middle", "bearing.M_shaft"]),
}
"""key -> (label, assembly factory, input start values, outputs)."""


def _system(key: str):
    from bearingsim.assembler import assemble

    _, factory, inputs, outputs = MODELS[key]
    return assemble(factory(), outputs=outputs), inputs, outputs


class _Call:
    """A CasADi function of (t, x, u, p) evaluated into preallocated buffers."""

    def __init__(self, fn):
        self._buf, self._eval = fn.buffer()
        self.args = [np.zeros(fn.nnz_in(k)) for k in range(fn.n_in())]
        for k, arr in enumerate(self.args):
            self._buf.set_arg(k, memoryview(arr))
        self.out = np.zeros(fn.nnz_out(0))
        self._buf.set_res(0, memoryview(self.out))
        sp = fn.sparsity_out(0)
        rows, cols = sp.get_triplet()
        self.rows, self.cols, self.shape = np.array(rows), np.array(cols), (sp.size1(),
                                                                           sp.size2())

    def __call__(self, t, x, u, p) -> np.ndarray:
        self.args[0][:] = t
        self.args[1][:] = x
        self.args[2][:] = u
        self.args[3][:] = p
        self._eval()
        return self.out

    def dense(self, t, x, u, p) -> np.ndarray:
        m = np.zeros(self.shape)
        m[self.rows, self.cols] = self(t, x, u, p)
        return m


class PythonStepper:
    """Backward Euler on a system's compiled functions: ``x1 = x0 + h f(t1, x1, u, p)``, solved
    by Newton's method with the exact Jacobian (a step whose iteration fails is halved).

    Parameters
    ----------
    key : str
        A key of :data:`MODELS`.
    h_max : float
        Largest internal step [s]; a communication step is cut into equal steps no longer.
    """

    def __init__(self, key: str, h_max: float = 1e-3):
        from bearingsim.simulation.compile import compile_system

        system, inputs, outputs = _system(key)
        compiled = compile_system(system)
        fns = compiled.functions
        self.ode, self.jac, self.out = _Call(fns["ode"]), _Call(fns["jac_x"]), _Call(
            fns["output"])
        self.input_names = list(system.input_names)
        self.output_names = list(system.output_names)
        self.u = system.u_default()
        for name, value in inputs.items():
            self.u[self.input_names.index(name)] = value
        self.p = system.p0()
        self.x0 = system.x0()
        self.x = self.x0.copy()
        self.t = 0.0
        self.h_max = h_max
        self.n = len(self.x)
        self.y = np.zeros(len(self.output_names))
        self._update_outputs()

    def reset(self, t0: float) -> None:
        self.t, self.x = t0, self.x0.copy()
        self._update_outputs()

    def _update_outputs(self) -> None:
        self.y[:] = self.out(self.t, self.x, self.u, self.p)

    def get_u(self, k: int) -> float:
        return float(self.u[k])

    def set_u(self, k: int, value: float) -> None:
        self.u[k] = value

    def get_y(self, k: int) -> float:
        return float(self.y[k])

    def _euler(self, t1: float, x: np.ndarray, h: float) -> np.ndarray | None:
        """One backward Euler step to t1; Newton with the Jacobian at the current iterate."""
        x1 = x.copy()
        for _ in range(10):
            r = x1 - x - h * self.ode(t1, x1, self.u, self.p)
            m = np.eye(self.n) - h * self.jac.dense(t1, x1, self.u, self.p)
            dx = np.linalg.solve(m, -r)
            x1 += dx
            if np.all(np.abs(dx) <= 1e-10 * (1.0 + np.abs(x1))):
                return x1
        return None

    def _advance(self, t: float, x: np.ndarray, h: float, depth: int = 0) -> np.ndarray | None:
        x1 = self._euler(t + h, x, h)
        if x1 is not None or depth >= 8:
            return x1
        half = self._advance(t, x, h / 2, depth + 1)  # Newton failed: two half steps
        return None if half is None else self._advance(t + h / 2, half, h / 2, depth + 1)

    def step(self, t: float, h: float) -> bool:
        """Integrate over one communication step; False if Newton fails."""
        n_sub = max(1, math.ceil(h / self.h_max - 1e-9))
        hs = h / n_sub
        x = self.x
        for k in range(n_sub):
            x = self._advance(t + k * hs, x, hs)
            if x is None:
                return False
        self.x, self.t = x, t + h
        self._update_outputs()
        return True


try:
    from pythonfmu import Fmi2Causality, Fmi2Slave, Fmi2Variability, Real
except ImportError:  # pragma: no cover - pythonfmu is a test/bench dependency
    Fmi2Slave = object


class BearingsimPythonSlave(Fmi2Slave):
    """pythonfmu co-simulation slave around :class:`PythonStepper`; subclasses set ``MODEL``."""

    MODEL = ""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.stepper = s = PythonStepper(self.MODEL)
        for k, name in enumerate(s.input_names):
            self.register_variable(Real(
                name, start=s.get_u(k), causality=Fmi2Causality.input,
                variability=Fmi2Variability.continuous, getter=partial(s.get_u, k),
                setter=partial(s.set_u, k)))
        for k, name in enumerate(s.output_names):
            self.register_variable(Real(
                name, causality=Fmi2Causality.output, variability=Fmi2Variability.continuous,
                getter=partial(s.get_y, k)))

    def setup_experiment(self, start_time, stop_time, tolerance):
        self.stepper.reset(start_time)

    def do_step(self, current_time, step_size):
        return self.stepper.step(current_time, step_size)


_SLAVE_SCRIPT = '''"""pythonfmu slave generated by bench/fmu.py: bearingsim model {key!r}."""
from bench.fmu import BearingsimPythonSlave


class {cls}(BearingsimPythonSlave):
    MODEL = {key!r}
'''


def build_python_fmu(key: str, directory: Path) -> Path:
    """Write the slave script and build it with ``pythonfmu build`` (a subprocess)."""
    cls = "BsmPy" + key.capitalize()
    script = directory / f"{cls}.py"
    script.write_text(_SLAVE_SCRIPT.format(key=key, cls=cls))
    root = Path(__file__).resolve().parent.parent
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(root), str(directory), os.environ.get("PYTHONPATH", "")]))
    subprocess.run([sys.executable, "-m", "pythonfmu", "build", "-f", str(script), "-d",
                    str(directory)], check=True, capture_output=True, env=env, cwd=root)
    return directory / f"{cls}.fmu"


def _open(path: Path, unzip: Path):
    from fmpy import read_model_description
    from fmpy.fmi2 import FMU2Slave

    with zipfile.ZipFile(path) as z:
        z.extractall(unzip)
    md = read_model_description(str(path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(unzip),
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bench")
    fmu.instantiate()
    return fmu, {v.name: v.valueReference for v in md.modelVariables}


def _run_here(path: Path, unzip: Path, inputs: dict, outputs: list[str], t_end: float):
    """Step an FMU at COMM_STEP in this process; (seconds per doStep, outputs per step)."""
    fmu, vr = _open(path, unzip)
    fmu.setupExperiment(startTime=0.0, tolerance=1e-6)
    fmu.enterInitializationMode()
    fmu.setReal([vr[k] for k in inputs], list(inputs.values()))
    fmu.exitInitializationMode()
    refs = [vr[n] for n in outputs]
    n = int(round(t_end / COMM_STEP))
    out = np.empty((n, len(refs)))
    spent = 0.0
    for k in range(n):
        t0 = time.perf_counter()
        fmu.doStep(k * COMM_STEP, COMM_STEP)
        spent += time.perf_counter() - t0
        out[k] = fmu.getReal(refs)
    fmu.terminate()
    return spent / n, out


def _worker(argv: list[str]) -> None:
    """Entry of the subprocess of :func:`_run`: time one FMU, print JSON, exit at once."""
    path, unzip, spec = argv
    spec = json.loads(spec)
    cost, out = _run_here(Path(path), Path(unzip), spec["inputs"], spec["outputs"],
                          spec["t_end"])
    sys.stdout.write(json.dumps({"cost": cost, "out": out.tolist()}))
    sys.stdout.flush()
    os._exit(0)


def _run(path: Path, unzip: Path, inputs: dict, outputs: list[str], t_end: float):
    """Step an FMU at COMM_STEP in a fresh Python process (both kinds alike).

    pythonfmu 0.7 embedded in a running interpreter corrupts it (``fmi2FreeInstance`` and the
    garbage collector crash it later), so every FMU is timed in its own process, which exits
    without tearing the interpreter down.
    """
    root = Path(__file__).resolve().parent.parent
    spec = json.dumps({"inputs": inputs, "outputs": outputs, "t_end": t_end})
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(root), str(path.parent), os.environ.get("PYTHONPATH", "")]))
    proc = subprocess.run(
        [sys.executable, "-c", "import sys; from bench.fmu import _worker; _worker(sys.argv[1:])",
         str(path), str(unzip), spec], capture_output=True, text=True, env=env, cwd=root,
        check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"timing {path.name} failed ({proc.returncode}): {proc.stderr[-2000:]}")
    data = json.loads(proc.stdout[proc.stdout.index("{"):])
    return data["cost"], np.array(data["out"])


def _error(system, inputs, outputs, t_end, values) -> float:
    from bearingsim.simulation import simulate

    n = int(round(t_end / COMM_STEP))
    ref = simulate(system, t_end, n_points=n + 1, inputs=inputs, rtol=1e-10, atol=1e-12,
                   progress=False)
    return max(float(np.max(np.abs(values[:, j] - ref[name][1:])) /
                     max(np.max(np.abs(ref[name])), 1e-300))
               for j, name in enumerate(outputs))


def measure(quick: bool, log=print) -> list[dict]:
    """Run every model natively and as a pythonfmu FMU; one dict of numbers per model."""
    from bearingsim.fmu import export_fmu

    t_end = 0.2 if quick else 1.0
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_fmu_") as tmp:
        tmp = Path(tmp)
        for key, (label, _, inputs, outputs) in MODELS.items():
            log(f"  {label}")
            system, _, _ = _system(key)
            t0 = time.perf_counter()
            native = export_fmu(system, tmp / f"{key}.fmu", kinds=("CS",), inputs=inputs)
            t_native = time.perf_counter() - t0
            t0 = time.perf_counter()
            python = build_python_fmu(key, tmp)
            t_python = time.perf_counter() - t0
            row = {"key": key, "label": label, "states": system.n_states,
                   "build native": t_native, "build python": t_python, "t_end": t_end}
            for name, path in (("native", native), ("python", python)):
                cost, values = _run(path, tmp / f"{key}_{name}", inputs, outputs, t_end)
                row[f"{name} step"] = cost
                row[f"{name} rtf"] = COMM_STEP / cost
                row[f"{name} error"] = _error(system, inputs, outputs, t_end, values)
            rows.append(row)
    return rows


def run(quick: bool, log=print) -> str:
    """The benchmark's Markdown section (heading included)."""
    from bench.common import fmt, markdown_table

    rows = measure(quick, log)
    table = markdown_table(
        ["model", "states", "native doStep [µs]", "pythonfmu doStep [µs]", "pythonfmu / native",
         "native real-time factor", "pythonfmu real-time factor", "native max rel. error",
         "pythonfmu max rel. error", "build native / pythonfmu [s]"],
        [[r["label"], r["states"], fmt(r["native step"] * 1e6), fmt(r["python step"] * 1e6),
          fmt(r["python step"] / r["native step"]), fmt(r["native rtf"]),
          fmt(r["python rtf"]), fmt(r["native error"]), fmt(r["python error"]),
          f'{r["build native"]:.1f} / {r["build python"]:.1f}'] for r in rows])
    return "\n".join([
        "## FMU export: cost per doStep, native C against a Python FMU",
        "",
        f"Each model as an FMI 2.0 co-simulation FMU, stepped from Python (fmpy `FMU2Slave`) "
        f"over {rows[0]['t_end']:g} s at a {COMM_STEP * 1e3:g} ms communication step; the time "
        "is that of the `fmi2DoStep` calls only (fmpy's ctypes call included, a few µs). "
        "*native*: `export_fmu` (generated C, adaptive ROS34PW2, tolerance 1e-6). *pythonfmu*: a "
        "`pythonfmu.Fmi2Slave` built with `pythonfmu build` whose `do_step` calls the compiled "
        "CasADi functions of the same system with backward Euler (one step per ms, Newton with "
        "the exact Jacobian). Real-time factor: simulated time / wall time. Error: largest "
        "deviation of the outputs from `simulate` (rtol 1e-10) at the communication points, "
        "relative to the largest value of each output.",
        "",
        table,
        "",
    ])


EXPORTS = {
    "double-layer bearing (torque level)": ["double_layer_bearing"],
    "motor drive (torque level)": ["motor_drive"],
    "duplex pair": ["duplex_pair"],
    "duplex pair, damped": ["duplex_pair", "--arg", "damping_ratio=0.05"],
    "6304 ball level (massive balls)": ["deep_groove_ball_bearing", "--arg", "bearing=6304",
                                        "--arg", "fidelity=dynamic_massive_balls"],
    "cylindrical roller NU206 (quasi-static, 10 slices)": ["cylindrical_roller_bearing"],
    "cylindrical roller NU206 (torque level)": ["cylindrical_roller_bearing", "--arg",
                                                "fidelity=torque"],
    "spindle (duplex pair + NU roller bearing)": ["spindle"],
}
"""The shipped assemblies as ``bearingsim export-fmu`` arguments (scene names: the scene's
outputs)."""


def export_times(log=print) -> list[dict]:
    """Export every shipped assembly as ME+CS, FMI 2.0 and 3.0, each in a fresh process with
    an empty cache folder (``$BEARINGSIM_CACHE``; cold: imports, assembly, code generation and
    compilation): wall time and the CPU time of the process and its compilers."""
    import os
    import resource

    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_fmu_export_") as tmp:
        for k, (label, args) in enumerate(EXPORTS.items()):
            row = {"label": label}
            for version in ("2.0", "3.0"):
                log(f"  export {label}, FMI {version}")
                env = {**os.environ, "BEARINGSIM_CACHE": str(Path(tmp) / f"cache_{k}_{version}")}
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                t0 = time.perf_counter()
                subprocess.run([sys.executable, "-m", "bearingsim.cli", "export-fmu", *args,
                                str(Path(tmp) / "m.fmu"), "--kinds", "ME,CS", "--fmi-version",
                                version], check=True, capture_output=True, env=env)
                wall = time.perf_counter() - t0
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
                row[version] = (wall, cpu)
            rows.append(row)
    return rows


def export_section(log=print):
    """Export time per shipped assembly as a :class:`bench.common.Section`."""
    from bench.common import Section, markdown_table

    rows = export_times(log)
    table = markdown_table(
        ["assembly", "FMI 2.0 wall / CPU [s]", "FMI 3.0 wall / CPU [s]"],
        [[r["label"], *(f"{r[v][0]:.1f} / {r[v][1]:.1f}" for v in ("2.0", "3.0"))]
         for r in rows])
    body = "\n".join([
        "`bearingsim export-fmu NAME model.fmu --kinds ME,CS` per shipped assembly (its scene "
        "name: the scene's outputs), each in a fresh Python process with an empty cache folder "
        "(`BEARINGSIM_CACHE`): imports, assembly, code generation and compilation, nothing "
        "cached. CPU: user + system time of the process "
        "and its C compilers (on a 2-core machine shared with other jobs the wall time can be "
        "several times the CPU time). One C file per model function, compiled in parallel, "
        "the right-hand side at -O2, the state and input Jacobians at -O1, the outputs at -O0 "
        "(`bearingsim.fmu.codegen.OPTIMISATION`).",
        "",
        table,
    ])
    return Section("FMU export time per assembly", body)


def section(quick: bool, img_dir: Path | None = None, out_md: Path | None = None, log=print):
    """:func:`run` as a :class:`bench.common.Section` (the signature of ``bench.run_all``)."""
    from bench.common import Section

    text = run(quick, log)
    title, _, body = text.partition("\n")
    return Section(title.lstrip("# ").strip(), body.strip())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="0.2 s instead of 1 s per run")
    parser.add_argument("--export-times", action="store_true",
                        help="only the export time per shipped assembly")
    args = parser.parse_args(argv)
    if args.export_times:
        s = export_section()
        print(f"## {s.title}\n\n{s.body}")
        return 0
    print(run(args.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
