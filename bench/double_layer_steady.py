"""Benchmark 3: steady states of a double-layer bearing — time stepping vs ``steady_state``.

For 61905/61907 at 10 000 r/min the speed ratio ``Rs`` is found by integrating until it stops
changing and by solving ``dx/dt = 0`` directly; then ``Rs`` is swept over the shaft speed with one
assembled system (parameters and inputs change without recompilation) and, for comparison, with
a fresh assembly per point. The 100-point sweep on one system is also timed on a baseline
commit of the package (:data:`BASELINE`, in a subprocess), alternating with this code, side by
side (``python -m bench.double_layer_steady --sweep-json`` prints this code's times).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.simulation import simulate, steady_state
from bearingsim.units import rpm_to_rad_s
from bench.common import Section, fmt, image_link, markdown_table

__all__ = ["BASELINE", "run", "steady_rs", "sweep_times", "PAIRINGS"]

PAIRINGS = (("61905", "61907", None), ("61905", "61908", None), ("61905", "61909", "I"))
"""(inner, outer, structure) of the swept pairings; None lets the assembly choose."""
SPEED_RPM = 10_000.0
T_END = 30.0
SETTLED = 1e-10
BASELINE = "da2b26e"
"""The commit before the work on the sweep's fixed costs (buffered Newton, vectorised input
bounds)."""
SWEEP_POINTS = 100
SWEEP_ROUNDS = 5
"""Sweeps timed per measurement (the fastest counts: the machine is shared)."""


def _bearing(inner: str, outer: str, structure: str | None):
    return double_layer_bearing(inner, outer, structure=structure)


def steady_rs(system, w: float) -> float:
    """``Rs`` at the steady state for shaft speed ``w`` [rad/s] (no re-assembly)."""
    x = steady_state(system, inputs={"shaft_speed": w})
    u = system.u_default()
    u[system.input_names.index("shaft_speed")] = w
    return float(system.observe(0.0, x, u)["Rs"])


def sweep_times(rounds: int = SWEEP_ROUNDS) -> dict:
    """The fastest of ``rounds`` 100-point sweeps of 61905/61907 on one assembled system
    (after one warm-up point): process CPU and wall time [s].

    Returns
    -------
    dict
        ``cpu_s``, ``wall_s``, and ``package``, the folder of the package timed.
    """
    import bearingsim

    system = assemble(_bearing("61905", "61907", None))
    speeds = rpm_to_rad_s(np.linspace(0.0, SPEED_RPM, SWEEP_POINTS + 1)[1:])
    steady_rs(system, float(speeds[0]))
    cpu, wall = [], []
    for _ in range(rounds):
        t0, c0 = time.perf_counter(), time.process_time()
        for w in speeds:
            steady_rs(system, float(w))
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - t0)
    return {"cpu_s": min(cpu), "wall_s": min(wall),
            "package": str(Path(bearingsim.__file__).parent)}


def _side_by_side(baseline: str, rounds: int = 2) -> dict[str, dict]:
    """:func:`sweep_times` of ``baseline`` (in a subprocess) and of this code, alternating
    ``rounds`` times; the fastest of each."""
    from bench.per_call import output_on_commit

    best: dict[str, dict] = {}
    for _ in range(rounds):
        then = json.loads(output_on_commit(baseline, ["bench.double_layer_steady",
                                                      "--sweep-json"]).splitlines()[-1])[0]
        for name, row in (("before", then), ("now", sweep_times())):
            kept = best.setdefault(name, row)
            for key in ("cpu_s", "wall_s"):
                kept[key] = min(kept[key], row[key])
    return best


def _settle_time(t: np.ndarray, rs: np.ndarray, tol: float) -> float:
    """First output time after which successive ``Rs`` samples differ by less than ``tol``."""
    moving = np.nonzero(np.abs(np.diff(rs)) >= tol)[0]
    if moving.size == 0:
        return float(t[0])
    k = moving[-1] + 1
    return float(t[k]) if k < t.size - 1 else float("nan")


def run(quick: bool, img_dir: Path, out_md: Path, log=print) -> Section:
    """Run the steady-state benchmark and return its report section.

    Parameters
    ----------
    quick : bool
        10 s of time stepping, 20 sweep points.
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
    w = rpm_to_rad_s(SPEED_RPM)
    t_end = 10.0 if quick else T_END
    t0 = time.perf_counter()
    system = assemble(_bearing("61905", "61907", None))
    t_asm = time.perf_counter() - t0

    stepping = {}
    for method in ("BDF", "cvodes"):
        t0 = time.perf_counter()
        res = simulate(system, t_end, inputs={"shaft_speed": w}, method=method, rtol=1e-10,
                       atol=1e-12, n_points=int(100 * t_end) + 1, progress=False)
        wall = time.perf_counter() - t0
        rs = res["Rs"]
        stepping[method] = {"wall_s": wall, "rs": float(rs[-1]),
                            "settle_s": _settle_time(res.t, rs, SETTLED),
                            "last_change": float(abs(rs[-1] - rs[-2]))}
    ss_times = []
    for _ in range(3 if quick else 11):
        t0 = time.perf_counter()
        rs_ss = steady_rs(system, w)
        ss_times.append(time.perf_counter() - t0)
    t_ss = statistics.median(ss_times)
    log(f"  10 000 r/min: steady_state {t_ss * 1e3:.1f} ms, BDF {stepping['BDF']['wall_s']:.2f} s")

    n_points = 20 if quick else 100
    rpm = np.linspace(0.0, SPEED_RPM, n_points + 1)[1:]
    sweeps: dict[str, np.ndarray] = {}
    sweep_time, sweep_cpu = {}, {}
    for inner, outer, structure in PAIRINGS:
        sys_k = system if (inner, outer) == ("61905", "61907") else assemble(
            _bearing(inner, outer, structure))
        t0, c0 = time.perf_counter(), time.process_time()
        sweeps[f"{inner}/{outer}"] = np.array([steady_rs(sys_k, rpm_to_rad_s(r)) for r in rpm])
        sweep_time[f"{inner}/{outer}"] = time.perf_counter() - t0
        sweep_cpu[f"{inner}/{outer}"] = time.process_time() - c0
    t0, c0 = time.perf_counter(), time.process_time()
    rs_fresh = np.array([steady_rs(assemble(_bearing("61905", "61907", None)), rpm_to_rad_s(r))
                         for r in rpm])
    t_fresh, cpu_fresh = time.perf_counter() - t0, time.process_time() - c0
    sweep_diff = float(np.max(np.abs(rs_fresh - sweeps["61905/61907"])))
    log(f"  sweep of {n_points}: {sweep_time['61905/61907']:.2f} s reused, {t_fresh:.2f} s "
        "re-assembled")

    side = _side_by_side(BASELINE)
    log(f"  sweep CPU before {side['before']['cpu_s']:.3f} s, now {side['now']['cpu_s']:.3f} s")
    img = img_dir / "double_layer_rs_vs_speed.png"
    _plot(rpm, sweeps, img)
    return _report(locals(), img, out_md)


def _report(v: dict, img: Path, out_md: Path) -> Section:
    stepping, t_ss, rs_ss = v["stepping"], v["t_ss"], v["rs_ss"]
    rows = [["`steady_state` (Newton, exact Jacobian)", fmt(t_ss * 1e3, 3), "—", "—",
             f"{rs_ss:.12f}", "—", "1"]]
    for method, s in stepping.items():
        rows.append([f"`simulate` {method} to t = {v['t_end']:g} s, rtol 1e-10, atol 1e-12",
                     fmt(s["wall_s"] * 1e3, 4), fmt(s["settle_s"], 3), fmt(s["last_change"], 2),
                     f"{s['rs']:.12f}", fmt(abs(s["rs"] - rs_ss), 2),
                     fmt(s["wall_s"] / t_ss, 3)])
    table1 = markdown_table(["method", "wall [ms]", "Rs settled (Δ < 1e-10) at t [s]",
                             "last Δ Rs", "Rs", "abs(Rs − Rs_steady)", "time / steady_state"],
                            rows)
    n = v["n_points"]
    t_one, t_fresh = v["sweep_time"]["61905/61907"], v["t_fresh"]
    cpu_one, cpu_fresh = v["sweep_cpu"]["61905/61907"], v["cpu_fresh"]
    table2 = markdown_table(
        ["sweep of 61905/61907", "points", "total wall [s]", "total CPU [s]",
         "per point CPU [ms]"],
        [["one assembled system, `steady_state` per point", n, fmt(t_one), fmt(cpu_one),
          fmt(cpu_one / n * 1e3)],
         ["assemble + `steady_state` per point", n, fmt(t_fresh), fmt(cpu_fresh),
          fmt(cpu_fresh / n * 1e3)],
         ["ratio (re-assembled / reused)", "", fmt(t_fresh / t_one), fmt(cpu_fresh / cpu_one),
          ""]],
    )
    rs_rows = []
    for key, rs in v["sweeps"].items():
        rs_rows.append([key, fmt(v["sweep_time"][key]), f"{rs[0]:.6f}",
                        f"{rs[len(rs) // 2 - 1]:.6f}", f"{rs[-1]:.6f}"])
    rpm = v["rpm"]
    table3 = markdown_table(
        ["pairing", "sweep [s]", f"Rs at {rpm[0]:g} r/min", f"Rs at {rpm[len(rpm) // 2 - 1]:g} "
         "r/min", f"Rs at {rpm[-1]:g} r/min"], rs_rows)
    text = [
        "Model: `double_layer_bearing(inner, outer)` at the torque fidelity with default options "
        "(Palmgren friction, ISO VG 32 in both layers, no load), driven through the input "
        f"`shaft_speed`. Assembling 61905/61907 took {v['t_asm'] * 1e3:.0f} ms. `steady_state` "
        "times are the median of repeated calls (each includes binding the inputs over the "
        "system); `simulate` times are one call, wall-clock, including setup. The sweeps "
        "report wall and process CPU time (CPU is what this code costs when other processes "
        "share the machine). Goal: the 100-point sweep on one system <= 0.1 s. Load average "
        f"at the end of the run: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores.",
        "",
        table1,
        "",
        f"**Rs difference, time stepping (BDF) vs steady_state: "
        f"{abs(stepping['BDF']['rs'] - rs_ss):.2g}** (target 1e-8); speed-up of "
        f"`steady_state` over BDF time stepping: {stepping['BDF']['wall_s'] / t_ss:.0f}×.",
        "",
        f"Speed sweep, {n} points from {rpm[0]:g} to {rpm[-1]:g} r/min:",
        "",
        table2,
        "",
        f"The {SWEEP_POINTS}-point sweep on one system, the fastest of {SWEEP_ROUNDS} sweeps "
        f"in each of 2 rounds, alternating with the package of commit {BASELINE} (before the "
        "work on the sweep's fixed costs) in a subprocess of this run (the machine is "
        "shared: compare the columns, not runs on other days):",
        "",
        markdown_table(
            ["package", "CPU [s]", "wall [s]"],
            [[f"{BASELINE} (before)", fmt(v["side"]["before"]["cpu_s"]),
              fmt(v["side"]["before"]["wall_s"])],
             ["this code", fmt(v["side"]["now"]["cpu_s"]), fmt(v["side"]["now"]["wall_s"])],
             ["ratio (before / now)",
              fmt(v["side"]["before"]["cpu_s"] / v["side"]["now"]["cpu_s"]),
              fmt(v["side"]["before"]["wall_s"] / v["side"]["now"]["wall_s"])]]),
        "",
        f"Command: `python -m bench.double_layer_steady --sweep-json` (this code's times; "
        f"the section runs it on {BASELINE} too).",
        "",
        f"Largest Rs difference between the reused and the re-assembled sweeps: "
        f"{v['sweep_diff']:.2g}.",
        "",
        table3,
        "",
        image_link(img, out_md, "Rs vs shaft speed"),
    ]
    data = {"t_ss": t_ss, "rs_ss": rs_ss, "stepping": stepping, "sweep_reused_s": t_one,
            "sweep_reused_cpu_s": cpu_one,
            "sweep_fresh_s": t_fresh, "n_points": n, "side_by_side": v["side"]}
    return Section("3. Double-layer steady state", "\n".join(text), data)


def _plot(rpm: np.ndarray, sweeps: dict[str, np.ndarray], path: Path) -> None:
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, rs in sweeps.items():
        label = key + (" (I)" if key.endswith("61909") else " (Z)")
        ax.plot(rpm, rs, label=label)
    ax.set_xlabel("shaft speed [r/min]")
    ax.set_ylabel("Rs = n_middle / n_shaft")
    ax.set_title("double-layer bearing: steady speed ratio")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    """Command line: ``--sweep-json`` prints :func:`sweep_times` as a JSON row."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sweep-json", action="store_true",
                        help="time the 100-point sweep and print it as JSON")
    args = parser.parse_args()
    if args.sweep_json:
        print(json.dumps([sweep_times()]))
    else:
        parser.print_help()


if __name__ == "__main__":
    main()
