"""Benchmark 2: CVODES against scipy's implicit integrators at equal error (work-precision).

A damped torsional chain driven by a symbolic sine torque is integrated to a tight Radau
reference; for a range of tolerances every method's wall time (``Result.stats["wall_time"]``,
which for CVODES includes building the CasADi integrator) is set against the largest error of
one output relative to the reference. BDF, Radau and LSODA get the exact sparse Jacobian.
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.simulation import simulate
from bench.common import Section, fmt, image_link, interp_loglog, markdown_table
from bench.models import TorsionChain, sine_torque

__all__ = ["run", "METHODS"]

METHODS = ("BDF", "Radau", "LSODA", "cvodes")
T_END = 2.0
N_POINTS = 201


def _timed_run(system, method: str, rtol: float, min_total_s: float, max_repeats: int) -> tuple:
    """Best wall time over up to ``max_repeats`` runs (stop once ``min_total_s`` is spent)."""
    best, spent, res = np.inf, 0.0, None
    for _ in range(max_repeats):
        t0 = time.perf_counter()
        res = simulate(system, T_END, method=method, rtol=rtol, atol=rtol * 1e-3,
                       n_points=N_POINTS, progress=False)
        spent += time.perf_counter() - t0
        best = min(best, res.stats["wall_time"])
        if spent > min_total_s:
            break
    return best, res


def run(quick: bool, img_dir: Path, out_md: Path, log=print) -> Section:
    """Run the work-precision benchmark and return its report section.

    Parameters
    ----------
    quick : bool
        A 10-pair chain, three tolerances, a looser reference and no repeats.
    img_dir : Path
        Folder for the plot.
    out_md : Path
        The report file (for relative image links).
    log : callable
        Progress printer.

    Returns
    -------
    Section
    """
    n = 10 if quick else 30
    rtols = [1e-4, 1e-6, 1e-8] if quick else [10.0**-k for k in range(4, 11)]
    ref_rtol = 1e-10 if quick else 1e-12
    repeats = 1 if quick else 3
    system = assemble(TorsionChain(n, c=1.0e4, d=50.0, torque=sine_torque(10.0, 5.0)))
    out = "body[0].w"
    t0 = time.perf_counter()
    ref = simulate(system, T_END, method="Radau", rtol=ref_rtol, atol=ref_rtol * 1e-2,
                   n_points=N_POINTS, progress=False)
    ref_time = time.perf_counter() - t0
    y_ref = ref[out]
    scale = float(np.max(np.abs(y_ref)))
    check = simulate(system, T_END, method="cvodes", rtol=ref_rtol, atol=ref_rtol * 1e-2,
                     n_points=N_POINTS, progress=False)
    ref_check = float(np.max(np.abs(check[out] - y_ref)) / scale)
    log(f"  reference Radau rtol {ref_rtol:g}: {ref_time:.1f} s; CVODES at the same rtol "
        f"differs by {ref_check:.2g}")

    results: dict[str, list[dict]] = {m: [] for m in METHODS}
    for method in METHODS:
        for rtol in rtols:
            wall, res = _timed_run(system, method, rtol, min_total_s=1.0, max_repeats=repeats)
            err = float(np.max(np.abs(res[out] - y_ref)) / scale)
            steps = res.stats.get("nsteps", res.stats.get("nlu", ""))
            nfev = res.stats.get("nfevals", res.stats.get("nfev", ""))
            results[method].append({"rtol": rtol, "wall_s": wall, "error": err, "nfev": nfev,
                                    "steps": steps})
        log(f"  {method}: " + ", ".join(f"{r['wall_s']:.3g} s" for r in results[method]))

    img = img_dir / "work_precision.png"
    _plot(results, img, n)
    return _report(results, rtols, n, out, ref_rtol, ref_time, ref_check, img, out_md, quick)


def matched_ratios(results: dict[str, list[dict]], method: str, base: str = "cvodes",
                   levels: list[float] | None = None) -> list[tuple[float, float]]:
    """Wall-time ratio ``method / base`` at equal error, interpolated in log-log.

    Parameters
    ----------
    results : dict
        Method -> list of ``{"error", "wall_s", ...}``.
    method, base : str
        The two methods compared.
    levels : list of float, optional
        Error levels; default: every decade 1e-2 .. 1e-12 inside both methods' error ranges.

    Returns
    -------
    list of (error, ratio)
    """
    levels = levels or [10.0**-k for k in range(2, 13)]
    ea = [r["error"] for r in results[method]]
    ta = [r["wall_s"] for r in results[method]]
    eb = [r["error"] for r in results[base]]
    tb = [r["wall_s"] for r in results[base]]
    out = []
    for e in levels:
        a, b = interp_loglog(e, ea, ta), interp_loglog(e, eb, tb)
        if np.isfinite(a) and np.isfinite(b):
            out.append((e, a / b))
    return out


def _report(results, rtols, n, out, ref_rtol, ref_time, ref_check, img, out_md, quick) -> Section:
    header = ["rtol"] + [f"{m} time [s]" for m in METHODS] + [f"{m} error" for m in METHODS]
    rows = []
    for k, rtol in enumerate(rtols):
        rows.append([f"{rtol:g}"] + [fmt(results[m][k]["wall_s"]) for m in METHODS]
                    + [fmt(results[m][k]["error"], 2) for m in METHODS])
    work = markdown_table(["rtol"] + [f"{m} RHS evals" for m in METHODS],
                          [[f"{rtol:g}"] + [results[m][k]["nfev"] for m in METHODS]
                           for k, rtol in enumerate(rtols)])
    ratio_rows, summary = [], {}
    for method in ("BDF", "Radau", "LSODA"):
        pairs = matched_ratios(results, method)
        summary[method] = pairs
        for e, r in pairs:
            ratio_rows.append([method, f"{e:g}", fmt(r)])
    ratios = markdown_table(["method", "matched error", "wall time / CVODES wall time"],
                            ratio_rows)
    bdf = summary["BDF"]
    geo = float(np.exp(np.mean(np.log([r for _, r in bdf])))) if bdf else float("nan")
    text = [
        f"Model: `TorsionChain` with N = {n} pairs ({2 * n} states), c = 1e4 N m/rad, "
        "d = 50 N m s/rad, J = 1 kg m², torque `10 sin(5 t)` N m, last spring fixed; t = 0 .. "
        f"{T_END:g} s, {N_POINTS} output points, atol = 1e-3 · rtol. Error: max over the output "
        f"points of |`{out}` − reference| / max |reference|. Reference: Radau, rtol "
        f"{ref_rtol:g} ({ref_time:.1f} s); CVODES at the same rtol differs from it by "
        f"{ref_check:.2g} (the floor below which errors are not resolved). Time: "
        "`Result.stats['wall_time']` "
        + ("(one run)" if quick else "(best of up to 3 runs, fewer when a run takes > 1 s)")
        + "; it excludes closing the inputs over the system and the initial-state solve, and "
        "for CVODES includes building the CasADi integrator. scipy's BDF/Radau get the exact "
        "sparse Jacobian `jac_x`, LSODA its dense form.",
        "",
        markdown_table(header, rows),
        "",
        "Right-hand-side evaluations (scipy `nfev`, CVODES `nfevals`):",
        "",
        work,
        "",
        "Wall-time ratio at matched error (log-log interpolation of time vs error between "
        "the measured tolerances):",
        "",
        ratios,
        "",
        f"**BDF (scipy) / CVODES wall time at matched error: geometric mean {fmt(geo)}** over "
        f"{len(bdf)} error level(s).",
        "",
        image_link(img, out_md, "error vs wall time"),
    ]
    return Section("2. CVODES vs solve_ivp at equal error", "\n".join(text),
                   {"results": results, "ratios": summary, "bdf_over_cvodes": geo})


def _plot(results: dict[str, list[dict]], path: Path, n: int) -> None:
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for method in METHODS:
        rs = results[method]
        ax.loglog([r["wall_s"] for r in rs], [r["error"] for r in rs], "o-", label=method)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("max relative error of body[0].w")
    ax.set_title(f"work-precision, torsional chain N = {n}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
