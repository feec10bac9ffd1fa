"""Benchmark: work-precision of the bearing assemblies' time integration.

For the torque-level double-layer bearing (spin-up of the shaft, the middle ring follows) and the
PMSM motor drive (speed ramp and a load step), each method's wall time is set against its largest
error in the chosen outputs relative to a tight CVODES reference. The duplex pair is a static
study (its benchmark compares exact and finite-difference stiffness) and the deep-groove bearing
has its own work-precision section.
"""

from __future__ import annotations

import time
from pathlib import Path

import casadi as ca
import matplotlib.pyplot as plt
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing, motor_drive
from bearingsim.simulation import simulate
from bench.common import Section, fmt, image_link, interp_loglog, markdown_table

__all__ = ["run", "CASES"]

METHODS = ("BDF", "Radau", "LSODA", "cvodes")


def _double_layer():
    system = assemble(double_layer_bearing("61905", "61907"), outputs=["w_middle", "M_shaft"])
    inputs = {"shaft_speed": lambda t: 1047.0 * ca.fmin(t / 0.5, 1.0), "Fr": 200.0}
    return system, inputs, 3.0, ["w_middle", "M_shaft"]


def _motor_drive():
    drive = motor_drive(double_layer_bearing(drive="flange"), motor="pmsm",
                        speed_ref=lambda t: 300.0 * ca.fmin(t / 0.2, 1.0),
                        load_torque=lambda t: -0.05 * ca.if_else(t >= 0.6, 1.0, 0.0))
    system = assemble(drive, outputs=["shaft.w", "bearing.M_shaft", "motor.motor.iq"])
    return system, {}, 1.0, ["shaft.w", "bearing.M_shaft"]


CASES = {"double-layer bearing spin-up (61905/61907, torque level)": _double_layer,
         "PMSM drive + double-layer bearing (ramp, load step)": _motor_drive}


def _error(res, ref, names) -> float:
    return max(float(np.max(np.abs(res[n] - ref[n])) / np.max(np.abs(ref[n]))) for n in names)


def run(quick: bool, img_dir: Path, out_md: Path, log=print) -> Section:
    """Measure wall time against error for every case and method.

    Parameters
    ----------
    quick : bool
        Three tolerances instead of five.
    img_dir, out_md : Path
        Plot folder and report file.
    log : callable
        Progress printer.
    """
    rtols = [1e-4, 1e-6, 1e-8] if quick else [1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    body, data = [], {}
    fig, axes = plt.subplots(1, len(CASES), figsize=(11, 4))
    for ax, (label, build) in zip(axes, CASES.items(), strict=True):
        log(f"  {label}")
        system, inputs, t_end, names = build()
        ref = simulate(system, t_end, inputs=inputs, method="cvodes", rtol=1e-11, atol=1e-13,
                       n_points=201, progress=False)
        rows, curves = [], {}
        for method in METHODS:
            for rtol in rtols:
                t0 = time.perf_counter()
                res = simulate(system, t_end, inputs=inputs, method=method, rtol=rtol,
                               atol=rtol * 1e-3, n_points=201, progress=False)
                wall = time.perf_counter() - t0
                err = _error(res, ref, names)
                curves.setdefault(method, []).append((err, wall))
                rows.append([method, f"{rtol:g}", fmt(wall), fmt(err, 2)])
        for method, pts in curves.items():
            ax.loglog([p[1] for p in pts], [p[0] for p in pts], "o-", label=method)
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel("max relative error")
        ax.set_title(label, fontsize=8)
        ax.grid(alpha=0.3, which="both")
        ratios = []
        for method in ("BDF", "Radau", "LSODA"):
            for level in (1e-4, 1e-6):
                a = interp_loglog(level, *zip(*curves[method], strict=True))
                b = interp_loglog(level, *zip(*curves["cvodes"], strict=True))
                if np.isfinite(a) and np.isfinite(b):
                    ratios.append([method, f"{level:g}", fmt(a / b)])
        body += [f"**{label}** ({system.n_states} states, t = 0 .. {t_end:g} s; outputs "
                 f"{', '.join(names)}; reference CVODES rtol 1e-11):", "",
                 markdown_table(["method", "rtol", "wall [s]", "error"], rows), "",
                 "Wall time relative to CVODES at matched error:", "",
                 markdown_table(["method", "error", "ratio"], ratios) if ratios
                 else "(no overlapping error range)", ""]
        data[label] = curves
    axes[0].legend()
    fig.tight_layout()
    img = img_dir / "assembly_work_precision.png"
    fig.savefig(img, dpi=110)
    plt.close(fig)
    body.append(image_link(img, out_md, "work-precision of the bearing assemblies"))
    return Section("Work-precision of the bearing assemblies", "\n".join(body), data)
