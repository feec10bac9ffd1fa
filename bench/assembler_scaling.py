"""Benchmark 1: how assembling a torsional chain scales with its size N.

For N inertia / spring-damper pairs: total and per-pass assemble time (``system.timings``),
peak memory during ``assemble`` (``tracemalloc`` peak of Python allocations, in a separate run so
that tracing does not distort the timings, and the rise of the process's peak RSS, which also sees
CasADi's C++ heap), number of states, and the cost of one evaluation of the compiled right-hand
side and Jacobian called from Python with numbers.
"""

from __future__ import annotations

import gc
import time
import tracemalloc
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from bearingsim.assembler import assemble
from bench.common import (
    Section,
    fmt,
    image_link,
    loglog_slope,
    markdown_table,
    median_call_time,
    peak_rss_kib,
    peak_rss_reset,
)
from bench.models import TorsionChain, sine_torque

__all__ = ["run", "measure_one"]

SIZES = (10, 30, 100, 300, 1000)
QUICK_SIZES = (10, 20, 50)


def _chain(n: int) -> TorsionChain:
    return TorsionChain(n, torque=sine_torque(), fixed=True)


def _predict(rows: list[dict], n: int) -> float:
    """Extrapolate the assemble time to ``n`` from the last (up to) three sizes."""
    last = rows[-3:]
    if len(last) < 2:
        return 0.0
    ns = [r["n"] for r in last]
    ts = [r["assemble_s"] for r in last]
    k = loglog_slope(ns, ts)
    return ts[-1] * (n / ns[-1]) ** k


def run(quick: bool, img_dir: Path, out_md: Path, max_assemble_s: float = 150.0,
        log=print) -> Section:
    """Run the scaling benchmark and return its report section.

    Parameters
    ----------
    quick : bool
        Sizes 10, 20, 50 only, fewer timing calls.
    img_dir : Path
        Folder for the plot.
    out_md : Path
        The report file (for relative image links).
    max_assemble_s : float
        Skip a size whose assemble time, extrapolated from the smaller sizes, exceeds this [s].
    log : callable
        Progress printer.

    Returns
    -------
    Section
    """
    sizes = QUICK_SIZES if quick else SIZES
    rows: list[dict] = []
    skipped: list[tuple[int, float]] = []
    for n in sizes:
        predicted = _predict(rows, n)
        if predicted > max_assemble_s:
            skipped.append((n, predicted))
            log(f"  N={n}: skipped, predicted assemble time {predicted:.0f} s")
            continue
        row = measure_one(n, memory=True, n_calls=50 if quick else 200)
        rows.append(row)
        log(f"  N={n}: assemble {row['assemble_s']:.3f} s, {row['states']} states")
    return _report(rows, skipped, img_dir, out_md, max_assemble_s)


def measure_one(n: int, memory: bool = True, n_calls: int = 200) -> dict:
    """Assemble one chain of ``n`` pairs and measure it.

    Parameters
    ----------
    n : int
        Number of inertia / spring-damper pairs.
    memory : bool
        Also assemble a second time under ``tracemalloc`` for the Python peak memory.
    n_calls : int
        Calls per timing batch of the right-hand side and Jacobian.

    Returns
    -------
    dict
        ``n``, ``build_s``, ``assemble_s``, ``passes`` (name -> s), ``states``, ``rss_peak_mib``,
        ``py_peak_mib`` (NaN without ``memory``), ``rhs_s``, ``jac_s``, ``jac_nnz``.
    """
    gc.collect()
    t0 = time.perf_counter()
    model = _chain(n)
    build = time.perf_counter() - t0
    gc.collect()
    have_rss = peak_rss_reset()
    rss0, _ = peak_rss_kib()
    t0 = time.perf_counter()
    system = assemble(model)
    total = time.perf_counter() - t0
    _, hwm = peak_rss_kib()
    passes = dict(system.timings)
    f, jac = system.functions["ode"], system.functions["jac_x"]
    rng = np.random.default_rng(0)
    x = system.x0() + 1e-3 * rng.standard_normal(system.n_states)
    u, p = system.u_default(), system.p0()
    rhs_s = median_call_time(lambda: f(0.1, x, u, p), n_calls)
    jac_s = median_call_time(lambda: jac(0.1, x, u, p), n_calls)
    row = {
        "n": n,
        "build_s": build,
        "assemble_s": total,
        "passes": passes,
        "states": system.n_states,
        "rss_peak_mib": (hwm - rss0) / 1024 if have_rss else float("nan"),
        "py_peak_mib": float("nan"),
        "rhs_s": rhs_s,
        "jac_s": jac_s,
        "jac_nnz": jac.sparsity_out(0).nnz(),
    }
    if memory:
        del system, f, jac
        model = _chain(n)
        gc.collect()
        tracemalloc.start()
        try:
            assemble(model)
            row["py_peak_mib"] = tracemalloc.get_traced_memory()[1] / 2**20
        finally:
            tracemalloc.stop()
    return row


def _report(rows: list[dict], skipped: list[tuple[int, float]], img_dir: Path, out_md: Path,
            max_assemble_s: float) -> Section:
    ns = [r["n"] for r in rows]
    totals = [r["assemble_s"] for r in rows]
    pass_names = list(rows[0]["passes"])
    slope = loglog_slope(ns, totals)
    slope_top = loglog_slope(ns[-3:], totals[-3:]) if len(ns) >= 3 else slope

    main = markdown_table(
        ["N", "states", "model build [s]", "assemble [s]", "tracemalloc peak [MiB]",
         "peak RSS rise [MiB]", "ode call [µs]", "jac_x call [µs]", "jac nnz"],
        [[r["n"], r["states"], fmt(r["build_s"]), fmt(r["assemble_s"]), fmt(r["py_peak_mib"]),
          fmt(r["rss_peak_mib"]), fmt(r["rhs_s"] * 1e6), fmt(r["jac_s"] * 1e6), r["jac_nnz"]]
         for r in rows],
    )
    pass_rows = []
    pass_slopes = {}
    for name in pass_names:
        ts = [max(r["passes"][name], 1e-7) for r in rows]
        k = loglog_slope(ns[-3:], ts[-3:]) if len(ns) >= 3 else float("nan")
        pass_slopes[name] = k
        share = ts[-1] / totals[-1]
        pass_rows.append([name] + [fmt(t * 1e3) for t in ts] + [fmt(k, 2), f"{share:.0%}"])
    passes = markdown_table(
        ["pass"] + [f"N={n} [ms]" for n in ns] + ["slope (last 3 N)", f"share at N={ns[-1]}"],
        pass_rows,
    )
    worst = max(pass_slopes, key=lambda k: (np.nan_to_num(pass_slopes[k]), 0))
    img = img_dir / "assembler_scaling.png"
    _plot(rows, pass_names, img)

    lines = [
        "Model: `bench.models.TorsionChain` — a `TorqueSource` with a symbolic `10 sin(5 t)` "
        "torque, N × (`Inertia` J = 1, `SpringDamper` c = 1e4, d = 50), last spring to `Fixed`. "
        "2 N states. Times are wall-clock from one assemble per N (`time.perf_counter`); pass "
        "times from `system.timings`. The memory columns come from separate runs: the "
        "`tracemalloc` peak counts only Python allocations (it is a second assemble under "
        "tracing), the peak-RSS rise (`/proc/self/status` VmHWM after resetting it via "
        "`/proc/self/clear_refs`) also sees CasADi's C++ heap but counts pages the allocator "
        "had already freed as reused, so small values are noise. `ode`/`jac_x` call times are "
        "medians of batches of calls from Python with numpy arguments "
        "(`system.functions[...](t, x, u, p)`), so they include the CasADi Python-call "
        "overhead (~tens of µs).",
        "",
        main,
        "",
        f"**Log-log slope of assemble time vs N: {slope:.2f} over all N, {slope_top:.2f} over "
        f"the largest three N** (1 = linear).",
        "",
        "Per pass (slope fitted over the largest three N):",
        "",
        passes,
        "",
        f"Steepest pass: **{worst}** (slope {pass_slopes[worst]:.2f}).",
    ]
    for n, pred in skipped:
        lines += ["", f"N = {n} was skipped: its assemble time extrapolated from the measured "
                  f"sizes is ~{pred:.0f} s, over the {max_assemble_s:.0f} s limit of this run "
                  "(`--max-assemble-s`)."]
    lines += ["", image_link(img, out_md, "assemble time vs N")]
    data = {"rows": rows, "slope": slope, "slope_top": slope_top, "pass_slopes": pass_slopes,
            "skipped": skipped}
    return Section("1. Assembler scaling", "\n".join(lines), data)


def _plot(rows: list[dict], pass_names: list[str], path: Path) -> None:
    ns = np.array([r["n"] for r in rows], float)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.loglog(ns, [r["assemble_s"] for r in rows], "ko-", lw=2, label="assemble (total)")
    for name in pass_names:
        ts = np.array([r["passes"][name] for r in rows])
        if ts.max() > 1e-3:
            ax.loglog(ns, ts, ".-", lw=1, label=name)
    t_ref = rows[0]["assemble_s"]
    ax.loglog(ns, t_ref * ns / ns[0], "k:", lw=1, label="∝ N")
    ax.loglog(ns, t_ref * (ns / ns[0]) ** 2, "k--", lw=1, label="∝ N²")
    ax.set_xlabel("N (inertia-spring pairs)")
    ax.set_ylabel("time [s]")
    ax.set_title("assemble time of a torsional chain")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)

