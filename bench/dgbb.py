"""Benchmark: work-precision of the deep-groove dynamic model (duty conditions 1 and 4).

For each condition a run from rest (speed ramp) is integrated to a tight CVODES reference; BDF and
Radau (scipy, exact sparse Jacobian), CVODES, and the study's own method -- fixed-step classical
RK4 with Newton-Raphson for the quasi-static ball positions inside every stage (the ``dynamic``
fidelity, whose Newton blocks the assembler generates) -- are timed against the error in the cage
speed and in the largest inner contact load at the end. Reported: wall time, error, the ratio to
the RK4 baseline at matched error and simulated seconds per wall second.

Not registered in ``bench/run_all.py``; call ``run(quick)``.
"""

from __future__ import annotations

import time

import casadi as ca
import numpy as np

from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.solver import assemble, simulate
from bearingsim.solver.simulate import close_inputs
from bearingsim.studies.deep_groove import DUTY_CYCLE
from bearingsim.units import rpm_to_rad_s
from bench.common import fmt, interp_loglog, markdown_table

__all__ = ["run"]

RAMP = 0.005


def _system(k: int, fidelity: str):
    n_rpm, load = DUTY_CYCLE[k - 1]
    w = rpm_to_rad_s(n_rpm)
    outputs = ["w_cage"] + [f"inner[{j}].Q" for j in range(7)]
    bearing = deep_groove_ball_bearing("6304", fidelity, speed=lambda t: w * ca.fmin(t / RAMP, 1),
                                       loads={"Fx": load}, n_slices=0)
    return assemble(bearing, outputs=outputs)


def _errors(res, ref) -> float:
    e_w = abs(res.final("w_cage") - ref["w_cage"]) / abs(ref["w_cage"])
    q = max(res.final(f"inner[{j}].Q") for j in range(7))
    return max(e_w, abs(q - ref["q"]) / ref["q"])


def _rk4(system, t_end: float, dt: float):
    """Classical RK4 with a fixed step on the compiled right-hand side (Newton inside)."""
    closed = close_inputs(system, None)
    p, x = system.p0(), system.x0()
    f = closed.f
    n = int(round(t_end / dt))
    t = 0.0
    for _ in range(n):
        k1 = np.asarray(f(t, x, p)).ravel()
        k2 = np.asarray(f(t + dt / 2, x + dt / 2 * k1, p)).ravel()
        k3 = np.asarray(f(t + dt / 2, x + dt / 2 * k2, p)).ravel()
        k4 = np.asarray(f(t + dt, x + dt * k3, p)).ravel()
        x = x + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t += dt
    obs = system.observe(t, x)
    return obs["w_cage"], max(obs[f"inner[{j}].Q"] for j in range(7))


def run(quick: bool) -> str:
    """Run the benchmark; return a Markdown section."""
    t_end = 0.002 if quick else 0.01
    rtols = [1e-3, 1e-4, 1e-5] if quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7]
    steps = [2e-6, 1e-6] if quick else [4e-6, 2e-6, 1e-6, 5e-7]
    lines = [f"Model: 6304, `dynamic_massive_balls` for the adaptive methods and `dynamic` "
             f"(quasi-static balls, Newton blocks) for RK4, one slice per contact, speed ramp "
             f"over {RAMP * 1e3:g} ms, t = 0 .. {t_end:g} s. Error: max of the relative errors of "
             "the final cage speed and largest inner contact load against CVODES at rtol 1e-9.",
             ""]
    for k in (1, 4):
        system = _system(k, "dynamic_massive_balls")
        ref_res = simulate(system, t_end, method="cvodes", rtol=1e-9, atol=1e-9, n_points=3,
                           progress=False)
        ref = {"w_cage": ref_res.final("w_cage"),
               "q": max(ref_res.final(f"inner[{j}].Q") for j in range(7))}
        rows, curves = [], {}
        for method in ("BDF", "Radau", "cvodes"):
            for rtol in rtols:
                t0 = time.perf_counter()
                res = simulate(system, t_end, method=method, rtol=rtol, atol=rtol * 0.1,
                               n_points=3, progress=False)
                wall = time.perf_counter() - t0
                err = _errors(res, ref)
                curves.setdefault(method, []).append((err, wall))
                rows.append([method, f"rtol {rtol:g}", fmt(wall), fmt(err, 2),
                             fmt(t_end / wall)])
        qs_system = _system(k, "dynamic")
        for dt in steps:
            t0 = time.perf_counter()
            w_c, q = _rk4(qs_system, t_end, dt)
            wall = time.perf_counter() - t0
            err = max(abs(w_c - ref["w_cage"]) / abs(ref["w_cage"]), abs(q - ref["q"]) / ref["q"])
            curves.setdefault("RK4+Newton", []).append((err, wall))
            rows.append(["RK4+Newton", f"dt {dt:g} s", fmt(wall), fmt(err, 2), fmt(t_end / wall)])
        base = curves["RK4+Newton"]
        ratio_rows = []
        for method in ("BDF", "Radau", "cvodes"):
            for level in (1e-2, 1e-3, 1e-4):
                a = interp_loglog(level, [e for e, _ in curves[method]],
                                  [w for _, w in curves[method]])
                b = interp_loglog(level, [e for e, _ in base], [w for _, w in base])
                if np.isfinite(a) and np.isfinite(b):
                    ratio_rows.append([method, f"{level:g}", fmt(a / b)])
        n_rpm, load = DUTY_CYCLE[k - 1]
        lines += [f"### Condition {k}: {n_rpm:g} r/min, {load:g} N", "",
                  markdown_table(["method", "setting", "wall [s]", "error", "sim s / wall s"],
                                 rows), "",
                  "Wall time / RK4+Newton wall time at matched error:", "",
                  markdown_table(["method", "error", "ratio"], ratio_rows) if ratio_rows
                  else "(no overlapping error range)", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run(quick=True))
