"""Benchmark: the cylindrical roller bearing's quasi-static level against its number of slices.

An NU 206 at 0.5 mrad misalignment under a radial load ramp to 10 kN (21 save points). For each
number of slices per roller: the time to assemble and to simulate (best of the repeats), and
the error of the final largest roller load, largest contact pressure and shaft moment against
the numeric equilibrium with 40 slices (:func:`~bearingsim.components.roller_row.
roller_row_equilibrium`). The physical limit of the slice count: the tilt changes a roller's
approach by ``ty Lwe`` = 4.8 um along its length against a mean approach of about 10 um, so a
few slices already resolve the load's linear part; the pressure (the end slice's load) and the
moment converge more slowly, with the slice width.

Usage: ``python -m bench.roller [--quick]``; ``section(quick)`` returns the report section.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies import cylindrical_roller_bearing
from bearingsim.components.roller_row import roller_row_equilibrium, roller_row_parameters
from bearingsim.simulation import simulate
from bench.common import Section

__all__ = ["measure", "section"]

TILT = 5e-4
LOAD = 10_000.0
OUTPUTS = [f"row.Q[{j}]" for j in range(12)] + [f"row.p_max[{j}]" for j in range(12)] + [
    "guide.frame.My"]


def _best(fn, repeats: int):
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def measure(n_slices: int, repeats: int, reference) -> dict:
    """Assemble and simulate at ``n_slices``; errors against the 40-slice equilibrium."""
    t_asm, system = _best(lambda: assemble(
        cylindrical_roller_bearing("NU206", misalignment=(0.0, TILT), n_slices=n_slices),
        outputs=OUTPUTS), repeats)
    t_sim, result = _best(lambda: simulate(system, 1.0, inputs={"load.Fx": lambda t: LOAD * t},
                                           n_points=21, progress=False), repeats)
    q = max(result.final(f"row.Q[{j}]") for j in range(12))
    p = max(result.final(f"row.p_max[{j}]") for j in range(12))
    m = result.final("guide.frame.My")
    return {"slices": n_slices, "assemble_s": t_asm, "simulate_s": t_sim,
            "err_Q": abs(q / max(reference.contacts.Q) - 1.0),
            "err_p": abs(p / max(reference.contacts.p_max) - 1.0),
            "err_M": abs(-m / reference.moment[1] - 1.0)}


def section(quick: bool) -> Section:
    """Run the benchmark; returns its report section."""
    reference = roller_row_equilibrium(roller_row_parameters("NU206"), 12, 40, (LOAD, 0.0),
                                       (0.0, TILT))
    slices = (1, 5, 10) if quick else (1, 2, 5, 10, 20)
    rows = [measure(n, 1 if quick else 2, reference) for n in slices]
    lines = ["NU 206, 0.5 mrad misalignment, radial load ramp to 10 kN, 21 save points; "
             "errors of the final values against the numeric equilibrium with 40 slices. "
             "One slice cannot resolve the tilt (no moment: error 100 %); the moment error "
             "falls as 1/n^2 (the slices are a midpoint rule over the roller length), the "
             "pressure error as 1/n (it is the end slice's mean load).", "",
             "| slices | assemble [s] | simulate [s] | Q_max error | p_max error | "
             "moment error |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['slices']} | {r['assemble_s']:.2f} | {r['simulate_s']:.3f} | "
                     f"{r['err_Q']:.1e} | {r['err_p']:.1e} | {r['err_M']:.1e} |")
    return Section("Cylindrical roller bearing: slices per roller", "\n".join(lines),
                   {"rows": rows})


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(section(parser.parse_args().quick).body)
