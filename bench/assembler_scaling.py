"""Benchmark 1: how assembling a torsional chain scales with its size N, in time and memory.

For N inertia / spring-damper pairs, each N assembled in a fresh Python process (so that one
size's heap does not serve the next): wall and CPU time of ``assemble`` and of each pass, the
peak resident memory of the process (``resource.getrusage`` maxrss, imports included), the rise
of the peak RSS above the RSS before ``assemble`` (``/proc/self/status`` VmHWM, reset through
``/proc/self/clear_refs``; it sees CasADi's C++ heap, which ``tracemalloc`` does not), the peak
RSS rise of each pass (the counter reset before each pass by a probe pass that ``assemble``
runs after every built-in pass, ``extra_passes``), the number of states, and the cost of one
evaluation of the compiled right-hand side and Jacobian called from Python with numbers.

Command of one size: ``python -m bench.assembler_scaling N`` (prints its row as JSON).
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

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

__all__ = ["SIZES", "LARGE_SIZES", "QUICK_SIZES", "run", "measure_one", "measure_in_process"]

SIZES = (10, 30, 100, 300, 1000)
"""Chain sizes of a normal run."""
LARGE_SIZES = (3000, 10000)
"""Sizes added by ``--large-chain`` (N = 10 000: about a minute of assembly alone)."""
QUICK_SIZES = (10, 20, 50)

ROOT = Path(__file__).resolve().parents[1]
MIN_MIB = 0.1
"""Memory rises below this [MiB] are taken as this in the log-log slopes (page-size noise)."""


class _Probe:
    """A pass run after a built-in pass: records that pass's CPU time and peak RSS rise, then
    resets the peak counter for the next pass."""

    def __init__(self, after: str, log: dict):
        self.NAME = f"probe after {after}"
        self.after, self.log = after, log

    def run(self, state) -> None:  # noqa: ARG002 - a pass's signature
        rss, hwm = peak_rss_kib()
        cpu = time.process_time()
        self.log[self.after] = {"cpu_s": cpu - self.log["_cpu"],
                                "rise_mib": (hwm - self.log["_rss"]) / 1024,
                                "hwm_kib": hwm}
        peak_rss_reset()
        self.log["_rss"], _ = peak_rss_kib()
        self.log["_cpu"] = time.process_time()


def measure_in_process(n: int, n_calls: int = 200) -> dict:
    """Assemble one chain of ``n`` pairs in this process and measure it.

    Parameters
    ----------
    n : int
        Number of inertia / spring-damper pairs.
    n_calls : int
        Calls per timing batch of the right-hand side and Jacobian.

    Returns
    -------
    dict
        ``n``, ``build_s``, ``assemble_s`` (wall), ``assemble_cpu_s``, ``passes`` (name ->
        wall s), ``pass_cpu`` (name -> CPU s), ``pass_rise_mib`` (name -> peak RSS rise during
        the pass [MiB]), ``rss_rise_mib`` (peak RSS during ``assemble`` minus RSS before it),
        ``maxrss_mib`` (peak RSS of the process), ``states``, ``rhs_s``, ``jac_s``,
        ``jac_nnz``.
    """
    from bearingsim.assembler import PASS_NAMES, assemble
    from bench.models import TorsionChain, sine_torque

    t0 = time.perf_counter()
    model = TorsionChain(n, torque=sine_torque(), fixed=True)
    build = time.perf_counter() - t0
    log: dict = {}
    probes = {name: _Probe(name, log) for name in PASS_NAMES}
    peak_rss_reset()
    rss0, _ = peak_rss_kib()
    log["_rss"], log["_cpu"] = rss0, time.process_time()
    cpu0, t0 = log["_cpu"], time.perf_counter()
    system = assemble(model, extra_passes=probes)
    total, total_cpu = time.perf_counter() - t0, time.process_time() - cpu0
    passes = {name: dt for name, dt in system.timings if name in probes}
    f, jac = system.functions["ode"], system.functions["jac_x"]
    rng = np.random.default_rng(0)
    x = system.x0() + 1e-3 * rng.standard_normal(system.n_states)
    u, p = system.u_default(), system.p0()
    return {
        "n": n,
        "build_s": build,
        "assemble_s": total,
        "assemble_cpu_s": total_cpu,
        "passes": passes,
        "pass_cpu": {name: log[name]["cpu_s"] for name in passes},
        "pass_rise_mib": {name: log[name]["rise_mib"] for name in passes},
        "rss_rise_mib": (max(log[name]["hwm_kib"] for name in passes) - rss0) / 1024,
        "maxrss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "states": system.n_states,
        "rhs_s": median_call_time(lambda: f(0.1, x, u, p), n_calls),
        "jac_s": median_call_time(lambda: jac(0.1, x, u, p), n_calls),
        "jac_nnz": jac.sparsity_out(0).nnz(),
    }


def measure_one(n: int, n_calls: int = 200) -> dict:
    """:func:`measure_in_process` in a fresh Python process (``python -m
    bench.assembler_scaling n``); same keys."""
    env = {**os.environ,
           "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH"))
                                         if p)}
    out = subprocess.run([sys.executable, "-m", "bench.assembler_scaling", str(n),
                          "--calls", str(n_calls)], check=True, capture_output=True, text=True,
                         env=env, cwd=str(ROOT)).stdout
    return json.loads(out.strip().splitlines()[-1])


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
        log=print, large: bool = False) -> Section:
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
    large : bool
        Add :data:`LARGE_SIZES` (N = 3000 and 10 000).

    Returns
    -------
    Section
    """
    sizes = QUICK_SIZES if quick else SIZES + (LARGE_SIZES if large else ())
    rows: list[dict] = []
    skipped: list[tuple[int, float]] = []
    for n in sizes:
        predicted = _predict(rows, n)
        if predicted > max_assemble_s:
            skipped.append((n, predicted))
            log(f"  N={n}: skipped, predicted assemble time {predicted:.0f} s")
            continue
        row = measure_one(n, n_calls=50 if quick else 200)
        rows.append(row)
        log(f"  N={n}: assemble {row['assemble_s']:.3f} s ({row['assemble_cpu_s']:.3f} CPU-s), "
            f"peak RSS rise {row['rss_rise_mib']:.0f} MiB, {row['states']} states")
    return _report(rows, skipped, img_dir, out_md, max_assemble_s)


def _slope(ns: list[int], values: list[float], floor: float) -> float:
    """Log-log slope over the largest three sizes (values below ``floor`` count as it)."""
    if len(ns) < 3:
        return float("nan")
    return loglog_slope(ns[-3:], [max(v, floor) for v in values[-3:]])


def _report(rows: list[dict], skipped: list[tuple[int, float]], img_dir: Path, out_md: Path,
            max_assemble_s: float) -> Section:
    ns = [r["n"] for r in rows]
    totals = [r["assemble_s"] for r in rows]
    cpus = [r["assemble_cpu_s"] for r in rows]
    rises = [r["rss_rise_mib"] for r in rows]
    pass_names = list(rows[0]["passes"])
    slope_cpu = loglog_slope(ns, cpus)
    slope_cpu_top = _slope(ns, cpus, 1e-7)
    slope_mem_top = _slope(ns, rises, MIN_MIB)

    main = markdown_table(
        ["N", "states", "model build [s]", "assemble [s]", "assemble CPU [s]",
         "peak RSS rise [MiB]", "process peak RSS [MiB]", "ode call [µs]", "jac_x call [µs]",
         "jac nnz"],
        [[r["n"], r["states"], fmt(r["build_s"]), fmt(r["assemble_s"]),
          fmt(r["assemble_cpu_s"]), fmt(r["rss_rise_mib"]), fmt(r["maxrss_mib"]),
          fmt(r["rhs_s"] * 1e6), fmt(r["jac_s"] * 1e6), r["jac_nnz"]] for r in rows],
    )
    time_rows, mem_rows = [], []
    time_slopes, mem_slopes = {}, {}
    for name in pass_names:
        ts = [r["pass_cpu"][name] for r in rows]
        ms = [r["pass_rise_mib"][name] for r in rows]
        time_slopes[name] = _slope(ns, ts, 1e-4)
        mem_slopes[name] = _slope(ns, ms, MIN_MIB)
        time_rows.append([name] + [fmt(t * 1e3) for t in ts]
                         + [fmt(time_slopes[name], 2), f"{ts[-1] / cpus[-1]:.0%}"])
        mem_rows.append([name] + [fmt(m) for m in ms] + [fmt(mem_slopes[name], 2)])
    pass_time = markdown_table(
        ["pass"] + [f"N={n} [ms]" for n in ns] + ["slope (last 3 N)", f"share at N={ns[-1]}"],
        time_rows)
    pass_mem = markdown_table(["pass"] + [f"N={n} [MiB]" for n in ns] + ["slope (last 3 N)"],
                              mem_rows)
    steepest_time = max(time_slopes, key=lambda k: np.nan_to_num(time_slopes[k]))
    steepest_mem = max(mem_slopes, key=lambda k: np.nan_to_num(mem_slopes[k]))
    img = img_dir / "assembler_scaling.png"
    _plot(rows, pass_names, img)

    lines = [
        "Model: `bench.models.TorsionChain` — a `TorqueSource` with a symbolic `10 sin(5 t)` "
        "torque, N × (`Inertia` J = 1, `SpringDamper` c = 1e4, d = 50), last spring to `Fixed`. "
        "2 N states. Each N is assembled once in a fresh process (`python -m "
        "bench.assembler_scaling N`). Times: wall clock of `assemble` (`time.perf_counter`) "
        "and its CPU time (`time.process_time`; on this shared machine the wall time can be "
        "several times the CPU time when other jobs run, the CPU time much less so). Memory: "
        "the rise of the process's peak RSS during `assemble` above the RSS before it "
        "(`/proc/self/status` VmHWM after resetting it via `/proc/self/clear_refs`; it sees "
        "CasADi's C++ heap, which `tracemalloc` does not), and the process's peak RSS "
        "(`getrusage` maxrss, imports of numpy, scipy, CasADi and bearingsim included). Per "
        "pass: its CPU time and the rise of the peak RSS during it above the RSS at its "
        "start, from a probe pass after each built-in pass (`assemble(..., extra_passes=...)`). "
        "`ode`/`jac_x` call times are medians of batches of calls from Python with numpy "
        "arguments, so they include the CasADi Python-call overhead (~tens of µs).",
        "",
        main,
        "",
        f"**Log-log slope of assemble CPU time vs N: {slope_cpu:.2f} over all N, "
        f"{slope_cpu_top:.2f} over the largest three N; of the peak RSS rise: "
        f"{slope_mem_top:.2f} over the largest three N** (1 = linear). Slope of the wall "
        f"time over all N: {loglog_slope(ns, totals):.2f}.",
        "",
        "CPU time per pass (slope fitted over the largest three N):",
        "",
        pass_time,
        "",
        f"Steepest pass in time: **{steepest_time}** (slope {time_slopes[steepest_time]:.2f}).",
        "",
        f"Peak RSS rise per pass (slope fitted over the largest three N; rises below "
        f"{MIN_MIB} MiB count as {MIN_MIB}):",
        "",
        pass_mem,
        "",
        f"Steepest pass in memory: **{steepest_mem}** (slope {mem_slopes[steepest_mem]:.2f}).",
    ]
    if ns[-1] < LARGE_SIZES[-1]:
        lines += ["", f"N = {', '.join(map(str, LARGE_SIZES))} are added by "
                  "`python -m bench.run_all --only 'assembler scaling' --large-chain`."]
    for n, pred in skipped:
        lines += ["", f"N = {n} was skipped: its assemble time extrapolated from the measured "
                  f"sizes is ~{pred:.0f} s, over the {max_assemble_s:.0f} s limit of this run "
                  "(`--max-assemble-s`)."]
    lines += ["", image_link(img, out_md, "assemble time and memory vs N")]
    data = {"rows": rows, "slope_cpu": slope_cpu, "slope_cpu_top": slope_cpu_top,
            "slope_mem_top": slope_mem_top, "time_slopes": time_slopes,
            "mem_slopes": mem_slopes, "skipped": skipped}
    return Section("1. Assembler scaling", "\n".join(lines), data)


def _plot(rows: list[dict], pass_names: list[str], path: Path) -> None:
    ns = np.array([r["n"] for r in rows], float)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax.loglog(ns, [r["assemble_cpu_s"] for r in rows], "ko-", lw=2, label="assemble (total)")
    for name in pass_names:
        ts = np.array([r["pass_cpu"][name] for r in rows])
        if ts.max() > 1e-3:
            ax.loglog(ns, np.maximum(ts, 1e-4), ".-", lw=1, label=name)
    t_ref = rows[0]["assemble_cpu_s"]
    ax.loglog(ns, t_ref * ns / ns[0], "k:", lw=1, label="∝ N")
    ax.loglog(ns, t_ref * (ns / ns[0]) ** 2, "k--", lw=1, label="∝ N²")
    ax.set_xlabel("N (inertia-spring pairs)")
    ax.set_ylabel("CPU time [s]")
    ax.set_title("assemble time of a torsional chain")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    bx.loglog(ns, [max(r["rss_rise_mib"], MIN_MIB) for r in rows], "ko-", lw=2,
              label="peak RSS rise (assemble)")
    bx.loglog(ns, [r["maxrss_mib"] for r in rows], "ks--", lw=1, label="process peak RSS")
    for name in pass_names:
        ms = np.array([max(r["pass_rise_mib"][name], MIN_MIB) for r in rows])
        if ms.max() > 1.0:
            bx.loglog(ns, ms, ".-", lw=1, label=name)
    bx.set_xlabel("N (inertia-spring pairs)")
    bx.set_ylabel("memory [MiB]")
    bx.set_title("assemble memory")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend(fontsize=7)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    """Measure one chain size in this process and print its row as JSON."""
    import argparse

    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("n", type=int, help="number of inertia / spring-damper pairs")
    parser.add_argument("--calls", type=int, default=200,
                        help="calls per timing batch of the right-hand side and Jacobian")
    args = parser.parse_args(argv)
    print(json.dumps(measure_in_process(args.n, args.calls)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
