"""Benchmark: work-precision of the deep-groove dynamic model (duty conditions 1 and 4).

For each condition a run from rest (speed ramp) is integrated to a tight CVODES reference; BDF and
Radau (scipy, exact sparse Jacobian), CVODES and fixed-step classical RK4 are timed against the
error in the cage speed and in the largest inner contact load at the end, on the
``dynamic_massive_balls`` model (a pure ODE). The study's own method -- Newton-Raphson for the
quasi-static ball positions inside every stage of fixed-step RK4 -- is timed on the ``dynamic``
model (quasi-static balls: a Newton block per ball in every right-hand side), with CVODES on the
same model beside it, against that model's own tight reference. RK4 is stable only for
``dt < 2.78 / |lambda|_max`` (the real-axis limit of its stability region), ``lambda`` the
eigenvalues of the Jacobian along the reference trajectory; it is run at fractions of that step.
Reported: wall time, error, the ratio to the RK4 baselines at matched error and simulated
seconds per wall second.

Registered in ``bench/run_all.py``; ``python -m bench.dgbb`` prints the section.
"""

from __future__ import annotations

import time

import casadi as ca
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.simulation import simulate
from bearingsim.simulation.closed import close_inputs
from bearingsim.simulation.fastcall import BufferedFunction
from bearingsim.studies.deep_groove import DUTY_CYCLE
from bearingsim.units import rpm_to_rad_s
from bench.common import fmt, interp_loglog, markdown_table

__all__ = ["run"]

RAMP = 0.005


def _system(k: int, fidelity: str, rootfinder: str | None = None):
    n_rpm, load = DUTY_CYCLE[k - 1]
    w = rpm_to_rad_s(n_rpm)
    outputs = ["w_cage"] + [f"inner[{j}].Q" for j in range(7)]
    bearing = deep_groove_ball_bearing("6304", fidelity, speed=lambda t: w * ca.fmin(t / RAMP, 1),
                                       loads={"Fx": load}, n_slices=0)
    return assemble(bearing, outputs=outputs, rootfinder=rootfinder)


RK4_REAL_LIMIT = 2.785
"""Classical RK4 is stable on the negative real axis for ``h |lambda| < 2.785``."""


def stable_step(system, res) -> tuple[float, float]:
    """Largest |eigenvalue| of the Jacobian over the saved states of ``res`` and the RK4 step
    limit ``2.785 / |lambda|`` [s]."""
    jac = system.functions["jac_x"]
    u, p = np.zeros(len(system.inputs)), system.p0()
    lam = 0.0
    for k in range(res.t.size):
        x = np.array([res[n][k] for n in system.state_names])
        lam = max(lam, float(np.max(np.abs(np.linalg.eigvals(
            np.asarray(jac(res.t[k], x, u, p).full()))))))
    return lam, RK4_REAL_LIMIT / lam


def _errors(res, ref) -> float:
    e_w = abs(res.final("w_cage") - ref["w_cage"]) / abs(ref["w_cage"])
    q = max(res.final(f"inner[{j}].Q") for j in range(7))
    return max(e_w, abs(q - ref["q"]) / ref["q"])


def _rk4(system, t_end: float, dt: float):
    """Classical RK4 with a fixed step (zero-copy buffered calls of the right-hand side)."""
    closed = close_inputs(system, None)
    p, x = system.p0(), system.x0()
    f = BufferedFunction(closed.f).vector
    n = int(np.ceil(t_end / dt))  # at most dt, ending exactly at t_end
    dt = t_end / n
    t = 0.0
    for _ in range(n):
        k1 = f(t, x, p)
        k2 = f(t + dt / 2, x + dt / 2 * k1, p)
        k3 = f(t + dt / 2, x + dt / 2 * k2, p)
        k4 = f(t + dt, x + dt * k3, p)
        x = x + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t += dt
    obs = system.observe(t, x)
    return obs["w_cage"], max(obs[f"inner[{j}].Q"] for j in range(7)), dt


def _reference(system, t_end: float, method: str = "cvodes") -> dict[str, float]:
    res = simulate(system, t_end, method=method, rtol=1e-9, atol=1e-9, n_points=11,
                   progress=False)
    return {"w_cage": res.final("w_cage"),
            "q": max(res.final(f"inner[{j}].Q") for j in range(7)), "res": res}


def _timed_runs(system, t_end, ref, dt_stable, methods, rtols, fractions, label=""):
    """Rows (method, setting, wall, error, sim s / wall s) and curves {method: [(err, wall)]};
    RK4 at ``fractions`` of ``dt_stable``."""
    rows, curves = [], {}
    for method in methods:
        for rtol in rtols:
            t0 = time.perf_counter()
            res = simulate(system, t_end, method=method, rtol=rtol, atol=rtol * 0.1,
                           n_points=3, progress=False)
            wall = time.perf_counter() - t0
            err = _errors(res, ref)
            curves.setdefault(method + label, []).append((err, wall))
            rows.append([method + label, f"rtol {rtol:g}", fmt(wall), fmt(err, 2),
                         fmt(t_end / wall)])
    for frac in fractions:
        t0 = time.perf_counter()
        w_c, q, dt = _rk4(system, t_end, frac * dt_stable)
        wall = time.perf_counter() - t0
        err = max(abs(w_c - ref["w_cage"]) / abs(ref["w_cage"]), abs(q - ref["q"]) / ref["q"])
        curves.setdefault("RK4" + label, []).append((err, wall))
        rows.append(["RK4" + label, f"dt {dt:.3g} s", fmt(wall), fmt(err, 2), fmt(t_end / wall)])
    return rows, curves


def _ratios(curves, baseline: str) -> list[list[str]]:
    """Wall time of every other method over the baseline's at the baseline's errors."""
    out = []
    for method, points in curves.items():
        if method == baseline:
            continue
        for level, b in curves[baseline]:
            a = interp_loglog(level, [e for e, _ in points], [w for _, w in points])
            if np.isfinite(a):
                out.append([method, fmt(level, 2), fmt(a / b)])
    return out


def _ratio_table(rows: list[list[str]]) -> str:
    return (markdown_table(["method", "error", "ratio"], rows) if rows
            else "(no overlapping error range)")


def run(quick: bool) -> str:
    """Run the benchmark; return a Markdown section."""
    t_end = 0.002 if quick else 0.01
    rtols = [1e-4, 1e-6, 1e-8, 1e-10] if quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    fractions = [0.9, 0.45] if quick else [0.9, 0.45, 0.225]
    lines = [f"Model: 6304, one slice per contact, speed ramp over {RAMP * 1e3:g} ms, "
             f"t = 0 .. {t_end:g} s. Error: max of the relative errors of the final cage speed "
             "and largest inner contact load against CVODES at rtol 1e-9 on the same model. "
             "RK4 at fractions of its stable step 2.785/|lambda|_max (largest Jacobian "
             "eigenvalue over the reference run). *qs*: the `dynamic` model (quasi-static "
             "balls, a Newton block per ball with a line search inside every right-hand side); "
             "*RK4 qs* is the study's own method (Newton-Raphson inside fixed-step RK4).", ""]
    for k in (1, 4):
        system = _system(k, "dynamic_massive_balls")
        ref = _reference(system, t_end)
        lam, dt_stable = stable_step(system, ref["res"])
        rows, curves = _timed_runs(system, t_end, ref, dt_stable, ("BDF", "Radau", "cvodes"),
                                   rtols, fractions)
        qs = _system(k, "dynamic")
        ref_qs = _reference(qs, t_end)
        lam_qs, dt_qs = stable_step(qs, ref_qs["res"])
        rows_qs, curves_qs = _timed_runs(qs, t_end, ref_qs, dt_qs, ("cvodes",), rtols[:3],
                                         fractions[:2], " qs")
        study = {"RK4 qs": curves_qs["RK4 qs"], **curves, "cvodes qs": curves_qs["cvodes qs"]}
        n_rpm, load = DUTY_CYCLE[k - 1]
        lines += [f"### Condition {k}: {n_rpm:g} r/min, {load:g} N", "",
                  f"Largest |eigenvalue| {lam:.3g} 1/s: RK4 stable for dt < {dt_stable:.3g} s "
                  f"(qs: {lam_qs:.3g} 1/s, dt < {dt_qs:.3g} s).", "",
                  markdown_table(["method", "setting", "wall [s]", "error", "sim s / wall s"],
                                 rows + rows_qs), "",
                  "Wall time / RK4 wall time at matched error (massive balls):", "",
                  _ratio_table(_ratios(curves, "RK4")), "",
                  "Wall time / the study's method (RK4 qs) at matched error:", "",
                  _ratio_table(_ratios(study, "RK4 qs")), ""]
    return "\n".join(lines)


if __name__ == "__main__":
    print(run(quick=True))
