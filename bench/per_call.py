"""Benchmark: the fixed cost of a ``simulate`` call on a cached system.

Every shipped scene (``scenes/*.toml``) is prepared once (assembled, its inputs converted,
kernels and integrators cached by a first run); then ``simulate`` of a 1 ms run from its start
time (3 output points, the scene's method, inputs and tolerances) is repeated.
*Total* is the CPU time of the call (this thread,
robust against other processes on the machine); *integrator* the CPU time inside the
integrator alone (``Result.stats["integrate_cpu_time"]``); *per-call cost* their difference:
argument and input checks, input functions, start values, kernel look-up, observed variables
at the output times, the result. The fastest of the repeats (the machine is shared: the
minimum is the cost with the least interference from other processes), over two rounds.

The same runs are timed on a baseline commit of the package in a subprocess (``--baseline``,
default :data:`BASELINE`), side by side in one run (a baseline without
``integrate_cpu_time`` in its stats compares by the totals only).

Command: ``python -m bench.per_call [--baseline COMMIT] [--repeats N]``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import statistics
import subprocess
import sys
import time
import warnings
from collections.abc import Iterator
from pathlib import Path

from bench.common import ROOT, Section, exported_package, fmt, markdown_table

__all__ = ["BASELINE", "clock_loop_penalty", "elapsed_time_penalty", "measure", "output_on_commit",
           "section"]

BASELINE = "da2b26e"
"""The commit before the fourth round of work on fixed costs (buffered integrator and observe
calls; the first three began at 7955f3a, 29a6fd4 and 0877683)."""
RUN_S = 1e-3
"""Length of the timed runs [s]."""
SHORT_RUN_S = 1e-9
"""Length of the runs timed for comparison [s]: a few steps, so that little runs between the
Python before and after the integrator call."""


def measure(repeats: int = 20) -> list[dict]:
    """Time a 1 ms run of every shipped transient scene ``repeats`` times (after 3 warm-up
    runs; scenes the package cannot read, as the baseline's the newer ones, are left out).

    Returns
    -------
    list of dict
        Per scene: ``scene``, ``method``, ``states``, ``total_ms`` and ``overhead_ms``
        (the fastest call's; ``overhead_ms`` NaN where the stats have no
        ``integrate_cpu_time``), ``short_overhead_ms`` (the same for runs of
        :data:`SHORT_RUN_S`), and ``package``, the folder of the package timed.
    """
    import bearingsim
    from bearingsim.simulation import simulate

    rows = []
    for scene, system, t_start, args in _transient_scenes():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            timed = {length: _time_runs(simulate, system, t_start + length, args, repeats)
                     for length in (RUN_S, SHORT_RUN_S)}
        totals, overheads, method = timed[RUN_S]
        rows.append({"scene": scene, "method": method, "states": system.n_states,
                     "total_ms": 1e3 * min(totals),
                     "overhead_ms": 1e3 * min(overheads),
                     "short_overhead_ms": 1e3 * min(timed[SHORT_RUN_S][1]),
                     "package": str(Path(bearingsim.__file__).parent)})
    return rows


def _transient_scenes() -> Iterator[tuple[str, object, float, dict]]:
    """Every shipped transient scene the package can read, prepared: its name, system, start
    time [s] and the arguments of :func:`~bearingsim.simulation.simulate` (the scene's method,
    inputs and tolerances, 3 output points, no progress bar)."""
    from bearingsim.errors import BearingsimError
    from bearingsim.scenes import parse_scene
    try:
        from bearingsim.scenes.preparation import prepare
        from bearingsim.scenes.scene_simulation import simulate_inputs
    except ImportError:  # a baseline's package: the same function where it lived then
        import importlib

        for home in ("bearingsim.scenes.preparation", "bearingsim.scenes.runner"):
            module = importlib.import_module(home)
            if hasattr(module, "simulate_inputs"):
                prepare, simulate_inputs = module.prepare, module.simulate_inputs
                break
    for path in sorted((ROOT / "scenes").glob("*.toml")):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                prep = prepare(parse_scene(path.read_text(encoding="utf-8")))
            except BearingsimError:  # a scene the baseline's package cannot read
                continue
        if getattr(prep.scene, "analysis", "transient") != "transient":
            continue  # steady, modes, statics: no time run to time
        s = prep.scene.simulation
        yield path.stem, prep.system, s.t_start, {
            "t_start": s.t_start, "method": s.method, "rtol": s.rtol, "atol": s.atol,
            "n_points": 3, "max_step": s.max_step, "initial": s.initial,
            "inputs": simulate_inputs(prep.scene.inputs), "parameters": prep.scene.parameters,
            "x0": prep.scene.initial or None, "progress": False}


PROBE_SIZE = 150
"""Numbers the probe of :func:`elapsed_time_penalty` checks (the states at two output times of
the 6304's 75-state model)."""


@contextlib.contextmanager
def _after_integrator(hook):
    """Call ``hook()`` right after every integrator call in C (CVODES and IDAS through
    :class:`~bearingsim.simulation.integrator_calls.IntegratorCall`, and ``compiled_bdf``),
    its CPU time counted as the integrator's (inside ``integrate_cpu_time``); undone at the
    end."""
    from bearingsim.simulation import integrator_calls, integrators

    sundials_call, bdf_run = integrator_calls.IntegratorCall.__call__, integrators.compiled_bdf_run

    def hooked_call(call, *args):
        sundials_call(call, *args)
        hook()

    def hooked_run(*args, **kwargs):
        run = bdf_run(*args, **kwargs)
        start = time.thread_time()
        hook()
        run.stats["integrate_cpu_time"] += time.thread_time() - start
        return run

    integrator_calls.IntegratorCall.__call__ = hooked_call
    integrators.compiled_bdf_run = hooked_run
    try:
        yield
    finally:
        integrator_calls.IntegratorCall.__call__ = sundials_call
        integrators.compiled_bdf_run = bdf_run


def _numpy_call_twice(values) -> tuple[float, float]:
    """CPU time [us] of ``numpy.isfinite(values).all()``, then of the same call again at
    once."""
    import numpy as np

    start = time.thread_time_ns()
    np.isfinite(values).all()
    middle = time.thread_time_ns()
    np.isfinite(values).all()
    return (middle - start) / 1e3, (time.thread_time_ns() - middle) / 1e3


def _spin(seconds: float) -> None:
    """Run the interpreter for ``seconds`` (wall) on almost no memory: a loop reading the
    clock."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass


def elapsed_time_penalty(repeats: int = 20) -> list[dict]:
    """Whether the 1 ms run's larger per-call cost comes from its integration or from the time
    it takes: per shipped scene with states integrated in C (CVODES, IDAS, compiled_bdf),
    the per-call cost (as :func:`measure`) of the
    1 ms run, of the 1 ns run, and of the 1 ns run followed by a loop that only reads the clock
    for as long as the 1 ms run's integration took (its median CPU time; the loop touches
    almost no memory, so it leaves the processor's caches as the 1 ns run left them; its time
    is counted as the integrator's). And in each case the CPU time of one small numpy call
    (``numpy.isfinite(v).all()`` on :data:`PROBE_SIZE` numbers, what the runs check states
    with) right after the integrator, and the same call again at once.

    Returns
    -------
    list of dict
        Per scene and case (``"1 ms run"``, ``"1 ns run"``, ``"1 ns run + clock loop"``):
        ``scene``, ``case``, ``spin_ms`` (the loop's length), ``overhead_ms``, ``first_us``
        and ``again_us`` (the fastest of ``repeats`` runs).
    """
    import numpy as np

    from bearingsim.simulation import simulate

    values = np.ones(PROBE_SIZE)
    timings: list[tuple[float, float]] = []
    spin_s = [0.0]

    def probe():
        _spin(spin_s[0])
        timings.append(_numpy_call_twice(values))

    rows = []
    with _after_integrator(probe), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for scene, system, t_start, args in _transient_scenes():
            if system.n_states == 0:
                continue
            spin_s[0] = 0.0
            long_run = [simulate(system, t_start + RUN_S, **args).stats["integrate_cpu_time"]
                        for _ in range(5)]
            cases = (("1 ms run", RUN_S, 0.0), ("1 ns run", SHORT_RUN_S, 0.0),
                     ("1 ns run + clock loop", SHORT_RUN_S, statistics.median(long_run)))
            for case, length, spin in cases:
                spin_s[0] = spin
                _, overheads, _ = _time_runs(simulate, system, t_start + length, args, repeats,
                                             after_warm_up=timings.clear)
                if not timings:  # scipy's integrators: no call in C to hook
                    break
                rows.append({"scene": scene, "case": case, "spin_ms": 1e3 * spin,
                             "overhead_ms": 1e3 * min(overheads),
                             "first_us": min(t[0] for t in timings),
                             "again_us": min(t[1] for t in timings)})
    return rows


CLOCK_LOOPS_MS = (0.1, 1.0, 4.0, 20.0)
"""Lengths of the clock loops of :func:`clock_loop_penalty` [ms]."""


def clock_loop_penalty(repeats: int = 20) -> list[dict]:
    """The CPU time of one small numpy call (as in :func:`elapsed_time_penalty`) right after a
    loop that only reads the clock, and of the same call again, by the loop's length
    (:data:`CLOCK_LOOPS_MS`): what the machine charges code for the time since it last ran,
    without bearingsim.

    Returns
    -------
    list of dict
        Per loop length: ``loop_ms``, ``first_min_us``, ``first_median_us``,
        ``again_median_us`` and ``slow_share`` (the share of first calls above 5 times the
        repeated call's median).
    """
    import numpy as np

    values = np.ones(PROBE_SIZE)
    rows = []
    for loop_ms in CLOCK_LOOPS_MS:
        first, again = [], []
        for _ in range(2 * repeats):
            _spin(loop_ms / 1e3)
            one, two = _numpy_call_twice(values)
            first.append(one)
            again.append(two)
        again_median = statistics.median(again)
        rows.append({"loop_ms": loop_ms, "first_min_us": min(first),
                     "first_median_us": statistics.median(first),
                     "again_median_us": again_median,
                     "slow_share": sum(f > 5 * again_median for f in first) / len(first)})
    return rows


def _time_runs(simulate, system, t_end: float, args: dict, repeats: int,
               after_warm_up=None) -> tuple[list[float], list[float], str]:
    """CPU times [s] of ``repeats`` runs to ``t_end`` after 3 warm-up runs (then
    ``after_warm_up()``, if given): totals, per-call costs (NaN without
    ``integrate_cpu_time``) and the method the runs used."""
    for _ in range(3):
        result = simulate(system, t_end, **args)
    if after_warm_up is not None:
        after_warm_up()
    totals, overheads = [], []
    for _ in range(repeats):
        start = time.thread_time()
        result = simulate(system, t_end, **args)
        total = time.thread_time() - start
        totals.append(total)
        overheads.append(total - result.stats.get("integrate_cpu_time", float("nan")))
    return totals, overheads, str(result.stats.get("method", "-"))


def _baseline(commit: str, repeats: int) -> list[dict]:
    """:func:`measure` on the package at ``commit`` (in a subprocess)."""
    return json.loads(output_on_commit(commit, ["bench.per_call", "--json", "--repeats",
                                                str(repeats)]).strip().splitlines()[-1])


def output_on_commit(commit: str, module_args: list[str]) -> str:
    """Standard output of ``python -m <module_args>`` run with the package at ``commit``
    (exported from git into a temporary folder) and this checkout's ``bench``.

    Parameters
    ----------
    commit : str
        A commit of this repository.
    module_args : list of str
        The module to run and its arguments; its last output line is JSON rows, each with
        ``package``, the folder of the package it imported.

    Returns
    -------
    str
        What the run printed.

    Raises
    ------
    RuntimeError
        When the run imported another package than the exported one.
    """
    with exported_package(commit) as env:
        out = subprocess.run([sys.executable, "-m", *module_args], check=True,
                             capture_output=True, text=True, env=env, cwd=str(ROOT)).stdout
    tmp = env["PYTHONPATH"].split(os.pathsep)[0]
    rows = json.loads(out.strip().splitlines()[-1])
    if any(not row["package"].startswith(tmp) for row in rows):
        raise RuntimeError(f"the baseline run imported another package: {rows[0]['package']}")
    return out


ROUNDS = 3
"""Rounds of the baseline and this code, alternating."""


def _fastest(into: dict[str, dict], rows: list[dict]) -> None:
    """Keep per scene the row with the smaller total and the smaller per-call cost."""
    for row in rows:
        kept = into.setdefault(row["scene"], dict(row))
        for key in ("total_ms", "overhead_ms", "short_overhead_ms"):
            if row[key] < kept[key] or math.isnan(kept[key]):
                kept[key] = row[key]


def section(quick: bool = False, baseline: str = BASELINE) -> Section:
    """The run_all section: per-call cost per shipped scene, this code and the baseline."""
    repeats = 8 if quick else 40
    then = subprocess.run(["git", "-C", str(ROOT), "ls-tree", "--name-only", baseline,
                           "bearingsim/scenes/library/"], check=True, capture_output=True,
                          text=True).stdout.split()
    shipped_then = {Path(p).stem for p in then}  # a newer scene has no "before"
    old: dict[str, dict] = {}
    new_rows: dict[str, dict] = {}
    for _ in range(ROUNDS):  # alternating, so that both see the machine's changing load
        _fastest(old, [row for row in _baseline(baseline, repeats)
                       if row["scene"] in shipped_then])
        _fastest(new_rows, measure(repeats))
    new = list(new_rows.values())
    penalty = elapsed_time_penalty(repeats)
    loops = clock_loop_penalty(repeats)
    rows = []
    for row in new:
        then_row = old.get(row["scene"], {})
        rows.append([row["scene"], then_row.get("method", "—"), row["method"], row["states"],
                     fmt(then_row.get("total_ms", math.nan)), fmt(row["total_ms"]),
                     fmt(then_row.get("overhead_ms", math.nan)), fmt(row["overhead_ms"]),
                     fmt(then_row.get("short_overhead_ms", math.nan)),
                     fmt(row["short_overhead_ms"])])
    worst = max((row["overhead_ms"] for row in new if math.isfinite(row["overhead_ms"])),
                default=math.nan)
    text = (
        f"A {RUN_S * 1e3:g} ms run of every shipped transient scene on its cached system "
        "(assembled, kernels and integrators built by warm-up runs), the scene's method, "
        f"inputs and tolerances, 3 output points; the fastest of {repeats} calls in each of "
        f"{ROUNDS} rounds. *per-call cost*: "
        "the call's CPU time (this thread) minus the CPU time inside the integrator "
        "(`Result.stats[\"integrate_cpu_time\"]`): "
        "checks, input functions, start values, kernel look-up, observed variables, the "
        f"result. *before*: the same runs on commit {baseline}, in a subprocess of this run, "
        "side by side (the machine is shared: absolute times move with its load, the ratios "
        "less). A scene that states no method runs the method `simulate` chooses "
        "(`method=None`: CVODES on the VM for the tiny torque-level models). Models without "
        "states (quasi-static levels) integrate "
        "nothing: their whole call is the per-call cost plus the solve of the nonlinear blocks "
        "at the output points (*total*). *1 ns run*: the per-call cost of runs of "
        f"{SHORT_RUN_S:g} s (a few steps) timed the same way: the same Python, run right "
        "after the Python before the call instead of after an integration of milliseconds. "
        "Goal: per-call cost <= 0.3 ms.\n\n"
        f"Command: `python -m bench.per_call --baseline {baseline} --repeats {repeats}`\n\n"
        + markdown_table(["scene", "method before", "method now", "states",
                          "total before [ms]", "total now [ms]", "per-call cost before [ms]",
                          "per-call cost now [ms]", "1 ns run: per-call cost before [ms]",
                          "1 ns run: now [ms]"], rows)
        + f"\n\nLargest per-call cost now: {worst:.2f} ms.\n\n"
        "**Why the 1 ms run costs more than the 1 ns run: the time it takes, not what it "
        "runs.** On this machine (a virtual machine sharing its processor) any code that runs "
        "after a few milliseconds of anything pays for loading its code and data into the "
        "processor's caches again, even after a loop that touches almost no memory. First, "
        "per scene with states: the per-call cost of the 1 ms run, of the 1 ns run, and of the "
        "1 ns run followed by a loop that only reads the clock for as long as the 1 ms run's "
        "integration took (its time counted as the integrator's); in each case one small "
        f"numpy call (`numpy.isfinite(v).all()` on {PROBE_SIZE} numbers) hooked right after "
        "the integrator, and the same call again at once (the fastest of the repeats; the "
        "hook's time is counted as the integrator's). The 1 ns run with the loop costs what "
        "the 1 ms run costs: the difference comes from the elapsed time, not from the "
        "integration's use of the caches.\n\n"
        f"Command: `python -c 'from bench.per_call import elapsed_time_penalty; "
        f"print(elapsed_time_penalty({repeats}))'`\n\n"
        + markdown_table(["scene", "case", "clock loop [ms]", "per-call cost [ms]",
                          "first numpy call after the integrator [us]",
                          "the same call again [us]"],
                         [[row["scene"], row["case"], fmt(row["spin_ms"]),
                           fmt(row["overhead_ms"]), fmt(row["first_us"]),
                           fmt(row["again_us"])] for row in penalty])
        + "\n\nSecond, without bearingsim: the same numpy call after a loop that only reads "
        "the clock, by the loop's length (fastest and median of the repeats, and the share of "
        "first calls above 5 times the repeated call's median).\n\n"
        f"Command: `python -c 'from bench.per_call import clock_loop_penalty; "
        f"print(clock_loop_penalty({repeats}))'`\n\n"
        + markdown_table(["clock loop [ms]", "first call, fastest [us]",
                          "first call, median [us]", "share above 5x", "call again, median [us]"],
                         [[fmt(row["loop_ms"]), fmt(row["first_min_us"]),
                           fmt(row["first_median_us"]), f"{row['slow_share']:.2f}",
                           fmt(row["again_median_us"])] for row in loops])
        + f"\n\nLoad average at the end of the run: {os.getloadavg()[0]:.1f} on "
        f"{os.cpu_count()} cores.\n")
    return Section("Per-call cost of simulate", text,
                   {"rows": new, "baseline": old, "elapsed_time_penalty": penalty,
                    "clock_loops": loops})


def main() -> None:
    """Command line: the section's Markdown, or (``--json``) the raw rows of this code."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default=BASELINE)
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--json", action="store_true", help="raw rows of this code only")
    args = parser.parse_args()
    if args.json:
        print(json.dumps(measure(args.repeats)))
    else:
        print(section(args.repeats < 20, args.baseline).body)


if __name__ == "__main__":
    main()
