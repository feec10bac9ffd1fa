"""Benchmark: accuracy and cost of the motor + bearing co-simulation per master and step.

The motor FMU and the double-layer bearing FMU of ``tests/fmu`` (speed ramp 0 -> 100 rad/s in
0.1 s, 500 N radial, 0.3 s), coupled by the Jacobi masters of ``tests/fmu/cosim_masters.py``
(one exchange per communication step):

* **held**: FMI 2.0, each input held over the communication step (also fmpy's
  ``simulate_ssp`` and libcosim's fixed-step master on the pair's SSP file);
* **input derivatives**: FMI 2.0, each output's time derivative passed on as the partner's input
  derivative (``fmi2SetRealInputDerivatives``), the input a ramp through the step;
* **intermediate update**: FMI 3.0, the same ramp given through the ``intermediateUpdate``
  callback at every time the FMU asks for it;

and by the strong-coupling master :func:`bearingsim.studies.strong_coupling.run_coupled` (each
step iterated with rollback until the coupled values converge, tolerance 1e-4):

* **iterated, linear input derivatives**: FMI 2.0, each input the line from its value at the
  start to the current iterate's value at the end (a first-order input derivative);
* **iterated, cubic input derivatives**: FMI 2.0, each input the cubic Hermite polynomial
  through the values and time derivatives at both ends, as input derivatives of order 1 to 3;
* **iterated, cubic intermediate update**: FMI 3.0, the same cubic given through the
  intermediate-update callback.

Error: the largest deviation from ``simulate`` of the monolithic drive (rtol 1e-10) at the
communication points, relative to the signal's largest value, over the whole run and after
the 10 ms breakaway. Cost: ``doStep`` calls of both FMUs, and the real-time factor (simulated
over wall time) of the Python master through fmpy.

``python -m bench.cosim_coupling`` prints the section (``--quick``: DC motor, 1 ms only).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from bench.common import Section, markdown_table

__all__ = ["run", "section"]

OMEGA_REG = 0.1
"""Regularization speed of the bearing's friction sign [rad/s] (the default of
:class:`bearingsim.components.bearing_torque.PalmgrenBearing`)."""

STEPS = (1e-3, 5e-4, 2.5e-4, 1.25e-4)
"""Communication steps of the input-derivative coupling [s]."""


def _iterated(paths: dict[str, Path], h: float, _unzip: Path, interpolation: str):
    """The strong-coupling master on the pair: communication points, outputs, doStep calls."""
    from bearingsim.studies.motor_bearing_cosim import MOTOR_BEARING_CONNECTIONS
    from bearingsim.studies.strong_coupling import run_coupled
    from tests.fmu.cosim_masters import REF_OUTPUTS, T_END

    run = run_coupled({name: paths[name] for name in ("motor", "bearing")},
                      MOTOR_BEARING_CONNECTIONS, T_END, h, record=list(REF_OUTPUTS),
                      interpolation=interpolation)
    return run.t, run.values, run.do_steps


def _jacobi(master, on_ssp: bool = False):
    """A Jacobi master of ``tests/fmu/cosim_masters.py`` with its doStep count (one per FMU
    and communication step); ``on_ssp``: one that runs the SSP file."""
    def run(paths, h, unzip, **options):
        t, values = master(paths, h) if on_ssp else master(paths, h, unzip, **options)
        return t, values, 2 * len(t)
    return run


def _pair(directory: Path, motor: str, fmi_version: str) -> dict[str, Path]:
    from bearingsim.studies.motor_bearing_cosim import export_motor_bearing
    from tests.fmu.conftest import COSIM_FR, cosim_ramp

    return export_motor_bearing(directory / f"{motor}_{fmi_version}", motor=motor,
                                speed_ref=cosim_ramp, Fr=COSIM_FR, fmi_version=fmi_version,
                                ssp=fmi_version == "2.0")


def run(quick: bool = False, log=print) -> tuple[str, list[dict]]:
    """Export the pairs, run every coupling; return the Markdown body and the rows."""
    from tests.fmu.cosim_masters import (
        REF_OUTPUTS,
        T_END,
        derivative_run,
        errors,
        intermediate_update_run,
        libcosim_run,
        monolithic_reference,
        ssp_run,
    )

    rows, starts = [], []
    with tempfile.TemporaryDirectory(prefix="bench_cosim_coupling_") as tmp:
        work = Path(tmp)
        for motor in ("dc",) if quick else ("dc", "pmsm"):
            log(f"  {motor}: export, reference")
            fmi2, fmi3 = _pair(work, motor, "2.0"), _pair(work, motor, "3.0")
            ref = monolithic_reference(motor)
            w = np.asarray(ref["shaft.w"])
            starts.append(f"{motor.upper()}: {np.interp(1e-3, ref.t, w):.2e} rad/s at 1 ms, "
                          f"{np.interp(2e-3, ref.t, w):.2e} at 2 ms, above {OMEGA_REG:g} rad/s "
                          f"from {ref.t[np.argmax(w > OMEGA_REG)] * 1e3:g} ms")
            jacobi_fmi2, jacobi_fmi3 = _jacobi(derivative_run), _jacobi(intermediate_update_run)
            runs = [("held", 1e-3, jacobi_fmi2, fmi2, {"derivatives": False}),
                    *((f"held, {name}", h, _jacobi(master, on_ssp=True), fmi2, {})
                      for name, master in (("fmpy simulate_ssp", ssp_run),
                                           ("libcosim", libcosim_run))
                      for h in (() if quick else (1e-3, 5e-4))),
                    *(("input derivatives", h, jacobi_fmi2, fmi2, {})
                      for h in (STEPS[:1] if quick else STEPS)),
                    ("intermediate update", 1e-3, jacobi_fmi3, fmi3, {}),
                    ("iterated, linear input derivatives", 1e-3, _iterated, fmi2,
                     {"interpolation": "linear"}),
                    ("iterated, cubic input derivatives", 1e-3, _iterated, fmi2,
                     {"interpolation": "cubic"}),
                    ("iterated, cubic intermediate update", 1e-3, _iterated, fmi3,
                     {"interpolation": "cubic"})]
            unzip = work / f"{motor}_unzipped"  # the FMUs of both motors share file names
            for coupling, h, master, paths, options in runs:
                log(f"  {motor}: {coupling}, {h * 1e3:g} ms")
                start = time.perf_counter()
                try:
                    t, values, do_steps = master(paths, h, unzip, **options)
                except OSError as exc:  # libcosimpy's runtime library not loadable here
                    log(f"  {motor}: {coupling} skipped: {exc}")
                    continue
                wall = time.perf_counter() - start
                e = errors(ref, t, values)
                rows.append({"motor": motor, "coupling": coupling, "H": h,
                             "do_steps": do_steps, "real_time_factor": T_END / wall,
                             **{name: e[name] for name in REF_OUTPUTS}})
    names = list(REF_OUTPUTS)
    table = markdown_table(
        ["motor", "coupling", "H [ms]", "shaft speed", "middle-ring speed",
         "friction torque after 10 ms", "friction torque, whole run", "doStep calls",
         "real-time factor"],
        [[r["motor"].upper(), r["coupling"], f"{r['H'] * 1e3:g}",
          f"{r[names[0]][0]:.2e}", f"{r[names[2]][0]:.2e}", f"{r[names[1]][1]:.2e}",
          f"{r[names[1]][0]:.2e}", r["do_steps"], f"{r['real_time_factor']:.2g}"]
         for r in rows])
    body = "\n".join([
        "The motor and bearing FMUs of `tests/fmu` (speed ramp 0 -> 100 rad/s in 0.1 s, 500 N "
        "radial, 0.3 s) under the Jacobi masters of `tests/fmu/cosim_masters.py` (one "
        "exchange per step): inputs held over the step (FMI 2.0; also fmpy's `simulate_ssp` "
        "and libcosim's fixed-step master on the pair's SSP file), output derivatives passed on "
        "as input derivatives (FMI 2.0), or the same ramp given through the "
        "intermediate-update callback (FMI 3.0); and under the strong-coupling master "
        "`bearingsim.studies.strong_coupling.run_coupled` (each step iterated with rollback "
        "until the coupled values change by less than 1e-4 of their largest value), the "
        "inputs inside the step a line to the iterate's end value (FMI 2.0, first-order input "
        "derivatives) or the cubic Hermite polynomial through the values and derivatives at "
        "both ends (FMI 2.0 input derivatives of order 1 to 3, or FMI 3.0 intermediate "
        "update). Largest error against `simulate` of the "
        "monolithic drive (rtol 1e-10) at the communication points, relative to the signal's "
        "largest value; shaft and middle-ring speed over the whole run. Cost: `doStep` calls "
        "of both FMUs, and the real-time factor of the Python master through fmpy (one run "
        "each on a shared machine: ratios within a motor's rows are indicative; the FMI 3.0 "
        "rows pay a Python callback at every stage of the FMU's stepper).",
        "",
        "Shaft speed of the monolithic run at the start (the breakaway: the friction torque "
        "rises while the slip is below the regularization speed omega_reg): "
        + "; ".join(starts) + ".",
        "",
        "Command: `python -m bench.cosim_coupling`",
        "",
        table,
        "",
    ])
    return body, rows


def section(quick: bool = False) -> Section:
    """The run_all section."""
    body, rows = run(quick)
    return Section("Co-simulation coupling accuracy: held inputs, input derivatives, "
                   "intermediate update, iterated steps", body, {"rows": rows})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(run(parser.parse_args().quick)[0])


if __name__ == "__main__":
    main()
