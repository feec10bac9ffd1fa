"""Benchmark: accuracy of the motor + bearing co-simulation per coupling and communication step.

The motor FMU and the double-layer bearing FMU of ``tests/fmu`` (speed ramp 0 -> 100 rad/s in
0.1 s, 500 N radial, 0.3 s), coupled by the Jacobi masters of ``tests/fmu/cosim_masters.py``:

* **held**: FMI 2.0, each input held over the communication step;
* **input derivatives**: FMI 2.0, each output's time derivative passed on as the partner's input
  derivative (``fmi2SetRealInputDerivatives``), the input a ramp through the step;
* **intermediate update**: FMI 3.0, the same ramp given through the ``intermediateUpdate``
  callback at every time the FMU asks for it.

Error: the largest deviation from ``simulate`` of the monolithic drive (rtol 1e-10) relative to
the signal's largest value, over the whole run and after the 10 ms breakaway.

``python -m bench.cosim_coupling`` prints the section (``--quick``: DC motor, 1 ms only).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from bench.common import Section, markdown_table

__all__ = ["run", "section"]

OMEGA_REG = 0.1
"""Regularization speed of the bearing's friction sign [rad/s] (the default of
:class:`bearingsim.components.bearing_torque.PalmgrenBearing`)."""

STEPS = (1e-3, 5e-4, 2.5e-4, 1.25e-4)
"""Communication steps of the input-derivative coupling [s]."""


def _pair(directory: Path, motor: str, fmi_version: str) -> dict[str, Path]:
    from bearingsim.studies.motor_bearing_cosim import export_motor_bearing
    from tests.fmu.conftest import COSIM_FR, cosim_ramp

    return export_motor_bearing(directory / f"{motor}_{fmi_version}", motor=motor,
                                speed_ref=cosim_ramp, Fr=COSIM_FR, fmi_version=fmi_version,
                                ssp=False)


def run(quick: bool = False, log=print) -> tuple[str, list[dict]]:
    """Export the pairs, run every coupling; return the Markdown body and the rows."""
    from tests.fmu.cosim_masters import (
        REF_OUTPUTS,
        derivative_run,
        errors,
        intermediate_update_run,
        monolithic_reference,
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
            runs = [("held", 1e-3, derivative_run, fmi2, {"derivatives": False}),
                    *(("input derivatives", h, derivative_run, fmi2, {})
                      for h in (STEPS[:1] if quick else STEPS)),
                    ("intermediate update", 1e-3, intermediate_update_run, fmi3, {})]
            unzip = work / f"{motor}_unzipped"  # the FMUs of both motors share file names
            for coupling, h, master, paths, options in runs:
                log(f"  {motor}: {coupling}, {h * 1e3:g} ms")
                e = errors(ref, *master(paths, h, unzip, **options))
                rows.append({"motor": motor, "coupling": coupling, "H": h,
                             **{name: e[name] for name in REF_OUTPUTS}})
    names = list(REF_OUTPUTS)
    table = markdown_table(
        ["motor", "coupling", "H [ms]", "shaft speed", "middle-ring speed",
         "friction torque after 10 ms", "friction torque, whole run"],
        [[r["motor"].upper(), r["coupling"], f"{r['H'] * 1e3:g}",
          f"{r[names[0]][0]:.2e}", f"{r[names[2]][0]:.2e}", f"{r[names[1]][1]:.2e}",
          f"{r[names[1]][0]:.2e}"] for r in rows])
    body = "\n".join([
        "The motor and bearing FMUs of `tests/fmu` (speed ramp 0 -> 100 rad/s in 0.1 s, 500 N "
        "radial, 0.3 s) under the Jacobi masters of `tests/fmu/cosim_masters.py`: inputs held "
        "over the step (FMI 2.0), output derivatives passed on as input derivatives (FMI 2.0), "
        "or the same ramp given through the intermediate-update callback (FMI 3.0). Largest "
        "error against `simulate` of the monolithic drive (rtol 1e-10), relative to the "
        "signal's largest value; shaft and middle-ring speed over the whole run.",
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
                   "intermediate update", body, {"rows": rows})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(run(parser.parse_args().quick)[0])


if __name__ == "__main__":
    main()
