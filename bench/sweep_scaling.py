"""Benchmark: sweep scaling and the warm load of a cached model.

Two measurements:

* **Warm load.** The nested ball-level double-layer bearing (61905/61907, ``dynamic``, 270
  states) assembled into an empty system cache, then loaded from it in a fresh Python process
  (modules imported, nothing in memory): build of the component tree, structure key and load,
  against the assembly it replaces.
* **Sweep scaling.** The shipped ball-level scene ``deep_groove_duty1`` (6304, massive balls,
  75 states) over load x speed, ``t_end`` 300 ms, ``N_POINTS`` points on a LocalCluster of 1
  worker, then of ``--workers``, each in a new Python process in the order of
  ``bearingsim sweep`` (the fork server of the workers started first, then the imports, the
  scene and two sweeps: the second forks its workers from the running server), also timed
  from the launch of the process (the whole command). Each worker times every point it runs
  (:func:`bearingsim.scenes.sweep_worker.run_job`: the simulation and its outputs, what
  ``bearingsim run`` does for the point); the per-point overhead is the rest of the workers'
  time in the points phase (``workers x points phase - sum of point times``, per point),
  measured side by side with the work it adds to. The fixed cost is the sweep's wall time
  outside the points phase (planning with the model loaded from the cache, cluster start,
  shipping the model, closing). The speed-up of the whole sweep gives the serial fraction
  ``s`` of Amdahl's law, ``S(p) = 1 / (s + (1 - s) / p)``.

Registered in ``bench/run_all.py`` ("sweep scaling"); ``python -m bench.sweep_scaling
[--workers N]`` prints the section (rerun with ``--workers 16`` on a 16-core machine).
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bench.common import ROOT, Section, byte_compiled, fmt, markdown_table

__all__ = ["run", "section"]

N_POINTS = 64
ROUNDS = 5
"""Rounds of the 1-worker and the many-worker sweeps, alternating (odd: the median is one)."""
T_END = 0.3
"""Simulated time of each sweep point [s] (as in the measurement of issue 32)."""

WARM_LOAD = """
import json, sys, time
t0 = time.perf_counter()
from bearingsim.assembler import assemble, cache
from bearingsim.assembler.fingerprint import structure_key
from bearingsim.assemblies import double_layer_bearing
from bearingsim.physics.lubricant import Oil
t_import = time.perf_counter() - t0
t0 = time.perf_counter()
bearing = double_layer_bearing("61905", "61907", fidelity="dynamic",
                               lubrication=Oil.from_iso_vg(32, method="oil_mist"),
                               loads={"Fx": 0.0, "Fy": 0.0, "Fz": 100.0, "Mx": 0.0, "My": 0.0})
t_build = time.perf_counter() - t0
t0 = time.perf_counter()
key = structure_key(bearing)
t_key = time.perf_counter() - t0
t0 = time.perf_counter()
if sys.argv[1] == "no cache":
    system = assemble(bearing)
    size = 0
else:
    system = cache.assemble_cached(bearing, cache_dir=sys.argv[1])
    size = cache.LAST["path"].stat().st_size
t_call = time.perf_counter() - t0
t_kernel = None
if sys.argv[1] != "no cache":
    import shutil
    from bearingsim.cache_paths import KERNEL_NAMES
    from bearingsim.simulation.kernels import kernel
    if sys.argv[2] == "forget names":
        shutil.rmtree(f"{sys.argv[1]}/{KERNEL_NAMES}", ignore_errors=True)
    t0 = time.perf_counter()
    kernel(system, "ode", True, cache_dir=sys.argv[1])
    t_kernel = time.perf_counter() - t0
print(json.dumps({"import": t_import, "build": t_build, "key": t_key, "call": t_call,
                  "kernel": t_kernel, "states": system.n_states, "bytes": size}))
"""


def _nested(cache_dir: str, names: str = "keep names") -> dict:
    """One fresh process running :data:`WARM_LOAD` (timings in seconds): the system, then
    (with a cache) the first kernel look-up, compiling the library if it is not in the cache;
    ``names="forget names"`` removes the kept library names first."""
    out = subprocess.run([sys.executable, "-c", WARM_LOAD, cache_dir, names],
                         capture_output=True, text=True, check=True, env={**os.environ})
    return json.loads(out.stdout.strip().splitlines()[-1])


def warm_load() -> dict:
    """Plain assembly, cold (empty cache: assemble and store, compile the kernel), warm (load,
    find the kernel library by its kept name) and warm without the kept names (the library
    found by generating its C source), each in a fresh process, the warm ones alternating
    (the fastest of two each)."""
    plain = _nested("no cache")
    with tempfile.TemporaryDirectory() as cache_dir:
        cold = _nested(cache_dir)
        runs = [_nested(cache_dir, names) for _ in range(2)
                for names in ("keep names", "forget names")]
    warm = min(runs[0::2], key=lambda r: r["call"] + r["kernel"])
    unnamed = min(runs[1::2], key=lambda r: r["call"] + r["kernel"])
    return {"plain": plain, "cold": cold, "warm": warm, "unnamed": unnamed}


SIDE_BY_SIDE = """
import json, sys, time, warnings
warnings.simplefilter("ignore")
from bearingsim.scenes import load_scene
from bearingsim.scenes.library import builtin_scene_path
from bearingsim.scenes.preparation import prepare
from bearingsim.scenes.scene_simulation import simulate_inputs
from bearingsim.simulation import simulate
prep = prepare(load_scene(builtin_scene_path("deep_groove_duty1")))
s = prep.scene.simulation
args = dict(t_start=s.t_start, method=s.method, rtol=s.rtol, atol=s.atol, n_points=51,
            inputs=simulate_inputs(prep.scene.inputs), progress=False)
simulate(prep.system, T_END, **args)
time.sleep(max(0.0, float(sys.argv[1]) - time.time()))
cpu = []
for _ in range(RUNS):
    t0 = time.thread_time()
    simulate(prep.system, T_END, **args)
    cpu.append(time.thread_time() - t0)
print(json.dumps(cpu))
""".replace("RUNS", "8")


def side_by_side(processes: int = 2, rounds: int = ROUNDS) -> dict:
    """CPU time [s] of one sweep point's run (the scene's start-up to ``T_END``), 8 runs in one
    process alone, then in ``processes`` processes at once (started together), alternating
    over ``rounds`` rounds: what running side by side costs each run on this machine, with no
    sweep code involved.

    Returns
    -------
    dict
        ``alone`` and ``together``: the median CPU seconds of a run over all rounds;
        ``ratios``: together over alone in each round.
    """
    script = SIDE_BY_SIDE.replace("T_END", repr(T_END))

    def start(at: float) -> subprocess.Popen:
        return subprocess.Popen([sys.executable, "-c", script, repr(at)],
                                stdout=subprocess.PIPE, text=True)

    def medians(procs: list[subprocess.Popen]) -> float:
        runs = [t for p in procs for t in json.loads(p.communicate()[0].splitlines()[-1])]
        return float(np.median(runs))

    alone, together = [], []
    for _ in range(rounds):
        alone.append(medians([start(time.time() + 8.0)]))
        together.append(medians([start(time.time() + 8.0) for _ in range(processes)]))
    return {"alone": float(np.median(alone)), "together": float(np.median(together)),
            "ratios": [b / a for a, b in zip(alone, together, strict=True)]}


def _points(n: int) -> list[dict]:
    """``n`` points over radial load x shaft speed (start-up ramps as in the scene)."""
    loads = np.linspace(500.0, 1500.0, 8)
    speeds = np.linspace(1000.0, 3000.0, max(1, n // 8))
    pts = [{"inputs.load.Fx": float(f), "inputs.shaft_speed": f"rpm({s:.0f}) * ramp(0, 0.02)",
            "simulation.t_end": T_END} for s in speeds for f in loads]
    return pts[:n]


def timeline(spans: dict[int, tuple[int, float, float]]) -> dict:
    """From a sweep's :attr:`~bearingsim.scenes.sweep.SweepResult.spans`: the workers' idle
    time at the end (summed over the workers: the last point's end less each worker's last
    end [s]), the mean gap between two points on one worker (end to next start [s]: a
    task's cost on the worker and, between tasks, the wait for the next) and the mean wall
    time of the last point each worker ran [s] (what the others may wait for)."""
    by_worker: dict[int, list[tuple[float, float]]] = {}
    for pid, start, wall in spans.values():
        by_worker.setdefault(pid, []).append((start, start + wall))
    ends = {pid: max(e for _, e in v) for pid, v in by_worker.items()}
    gaps = [b[0] - a[1] for v in by_worker.values()
            for a, b in zip(sorted(v), sorted(v)[1:], strict=False)]
    last = [e - s for s, e in (max(v) for v in by_worker.values())]
    return {"idle_end_s": sum(max(ends.values()) - e for e in ends.values()),
            "gap_s": float(np.mean(gaps)) if gaps else float("nan"),
            "last_s": float(np.mean(last))}


def steal_seconds() -> float:
    """CPU time the virtual machine's host has taken from this machine's processors since it
    started (the ``steal`` column of ``/proc/stat``, summed over the processors) [s]; NaN
    where the system does not say."""
    try:
        fields = Path("/proc/stat").read_text().splitlines()[0].split()
        return int(fields[8]) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return float("nan")


class _GarbageCollections:
    """Time this process spends in Python's cyclic garbage collector while the context is
    open (:data:`gc.callbacks`): ``seconds`` in all collections, ``full`` the number of
    collections of the oldest generation."""

    def __init__(self):
        self.seconds, self.full, self._start = 0.0, 0, 0.0

    def _note(self, phase: str, info: dict) -> None:
        if phase == "start":
            self._start = time.perf_counter()
            return
        self.seconds += time.perf_counter() - self._start
        self.full += info["generation"] == 2

    def __enter__(self):
        gc.callbacks.append(self._note)
        return self

    def __exit__(self, *exc):
        gc.callbacks.remove(self._note)


def _sweep(scene, points, workers: int, longest_first: bool = True) -> dict:
    """One sweep in this process: wall, phases, the workers' busy fraction, the overhead per
    point (and its parts: idle at the end, gaps between points), the CPU time of this process
    (the client and, with a LocalCluster, the scheduler)."""
    from bearingsim.scenes.sweep import run_sweep

    collecting = _GarbageCollections()
    with tempfile.TemporaryDirectory() as out, collecting:
        cpu0, t0, steal0 = time.process_time(), time.perf_counter(), steal_seconds()
        res = run_sweep(scene, points, n_workers=workers, out=out, progress=False,
                        longest_first=longest_first)
        wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
        steal = steal_seconds() - steal0
    if len(res.ok) != len(points):
        raise RuntimeError(res.failures[:3])
    on_workers = [r["wall_s"] for r in res.rows]
    busy = workers * res.phases["points"]
    cpu_of_points = [res.point_cpu[k] for k in sorted(res.point_cpu)]
    return {"wall": wall, "chunk": res.chunk_size, "phases": res.phases, "workers": workers,
            "point_s": float(np.mean(on_workers)), "busy": sum(on_workers) / busy,
            "point_cpu_s": float(np.mean(cpu_of_points)),
            "waiting": 1.0 - sum(cpu_of_points) / sum(on_workers),
            "overhead_s": (busy - sum(on_workers)) / len(on_workers),
            "fixed_s": wall - res.phases["points"], "client_cpu_s": cpu, "steal_s": steal,
            "gc_s": collecting.seconds, "full_gc": collecting.full,
            **timeline(res.spans), "ended": time.time()}


def sweeps_in_a_fresh_process(workers: int, launched: float, n_points: int = N_POINTS,
                              repeats: int = 2) -> list[dict]:
    """``repeats`` sweeps of ``n_points`` on ``workers`` workers in one new Python process
    launched at epoch time ``launched``, in the order of ``bearingsim sweep``: the fork server
    of the workers started first (by :data:`CHILD`, before the process imports anything else;
    with the modules the scene's workers imported in earlier sweeps, as the command), the
    scene loaded, then the sweeps; a repeat forks its workers from the running server. With more
    than one worker, one more sweep runs the points in the given order instead of longest
    first (``longest_first=False``). Each sweep notes the load average after it; the first,
    the time from the launch to its start (``ready_s``: interpreter, imports, scene) and to
    its end (``command_s``, the wall of the whole command)."""
    from bearingsim.scenes import load_scene
    from bearingsim.scenes.library import builtin_scene_path

    scene = load_scene(builtin_scene_path("deep_groove_duty1"))
    ready = time.time() - launched
    out = []
    for longest_first in [True] * repeats + ([False] if workers > 1 else []):
        out.append(_sweep(scene, _points(n_points), workers, longest_first))
        out[-1]["load_after"] = os.getloadavg()[0]
    out[0].update(ready_s=ready, command_s=out[0]["ended"] - launched)
    return out


def _child_overhead(quiet: bool) -> dict:
    """:func:`cluster_overhead` in a new Python process (dask's settings are read once)."""
    root = Path(__file__).resolve().parent.parent
    out = subprocess.run([sys.executable, "-m", "bench.sweep_scaling", "--overhead",
                          "quiet" if quiet else "defaults"], check=True, capture_output=True,
                         text=True, cwd=str(root)).stdout
    return json.loads(out.strip().splitlines()[-1])


CHILD = """
import json, sys
from bearingsim.sweep_preloads import learned_preloads, scene_file
from bearingsim.sweep_server import start_worker_server
start_worker_server(learned_preloads(scene_file("deep_groove_duty1")))
from bench.sweep_scaling import sweeps_in_a_fresh_process
print(json.dumps(sweeps_in_a_fresh_process(int(sys.argv[1]), float(sys.argv[2]))))
"""
"""A fresh process of :func:`_child`: the fork server started as ``bearingsim sweep`` starts
it, before anything else is imported (the benchmark's own modules import matplotlib)."""


def _child(workers: int) -> list[dict]:
    """:func:`sweeps_in_a_fresh_process` in a new Python process (:data:`CHILD`)."""
    root = Path(__file__).resolve().parent.parent
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [str(root), *filter(None, [os.environ.get("PYTHONPATH")])])}
    out = subprocess.run([sys.executable, "-c", CHILD, str(workers), repr(time.time())],
                         capture_output=True, text=True, check=True, env=env, cwd=root)
    return json.loads(out.stdout.strip().splitlines()[-1])


def amdahl_serial_fraction(speedup: float, workers: int) -> float:
    """``s`` of Amdahl's law ``S = 1 / (s + (1 - s) / p)`` from a measured speed-up."""
    return (1.0 / speedup - 1.0 / workers) / (1.0 - 1.0 / workers)


def _busy(seconds: float) -> tuple[float, float]:
    """A task on a worker: ``seconds`` of this thread's CPU time in a Python loop; returns the
    thread's and the worker process's CPU time over it [s]."""
    t0, p0 = time.thread_time(), time.process_time()
    x = 0.0
    while time.thread_time() - t0 < seconds:
        for i in range(1000):
            x += 0.5 * i
    return time.thread_time() - t0, time.process_time() - p0


def cluster_overhead(quiet: bool, seconds: float = 8.0) -> dict:
    """CPU time a one-worker LocalCluster of the sweep spends beside an 8 s task: in the worker
    process's other threads and in this process (scheduler, nanny, client), each relative to
    the task's CPU time; ``quiet``: with :data:`~bearingsim.scenes.sweep_cluster.
    QUIET_CLUSTER`, else with dask's defaults."""
    from unittest import mock

    from bearingsim.scenes import sweep_cluster

    settings = sweep_cluster.QUIET_CLUSTER if quiet else {}
    with mock.patch.object(sweep_cluster, "QUIET_CLUSTER", settings):
        client, cluster = sweep_cluster.connect(None, 1)
    try:
        client.submit(_busy, 0.5, pure=False).result()  # the worker warmed up
        c0 = time.process_time()
        task, worker = client.submit(_busy, seconds, pure=False).result()
        here = time.process_time() - c0
    finally:
        client.close()
        cluster.close()
    return {"worker_other": (worker - task) / task, "client": here / task}


def run(workers: int = 2) -> dict:
    """Measure everything; returns the raw numbers (seconds)."""
    from bearingsim.scenes import load_scene
    from bearingsim.scenes.library import builtin_scene_path
    from bearingsim.scenes.sweep_plan import plan_sweep

    byte_compiled(ROOT)  # each fresh process reads the modules' bytecode, as an install's
    load_before = os.getloadavg()
    nested = warm_load()
    scene = load_scene(builtin_scene_path("deep_groove_duty1"))
    plan_sweep(scene, _points(1))  # the model into the cache: every sweep below loads it
    # alternating rounds, so that both worker counts see the machine's changing speed; the
    # table shows the round of the median fresh-process speed-up
    rounds = [(_child(1), _child(workers)) for _ in range(ROUNDS)]
    ratios = [(one[0]["wall"] / many[0]["wall"], one[-1]["wall"] / many[-2]["wall"])
              for one, many in rounds]
    one, many = rounds[sorted(range(ROUNDS), key=lambda k: ratios[k][0])[ROUNDS // 2]]
    overhead = {"defaults": _child_overhead(False), "quiet": _child_overhead(True)}
    return {"nested": nested, "one": one, "many": many, "workers": workers,
            "rounds": ratios, "overhead": overhead, "side_by_side": side_by_side(workers),
            "load_before": load_before,
            "load_after": os.getloadavg(), "cores": len(os.sched_getaffinity(0))}


def _scaling_row(label: str, sweep: dict) -> list[str]:
    ph = sweep["phases"]
    return ([label, f"{sweep['wall']:.2f}", str(sweep["chunk"]), f"{sweep['point_s'] * 1e3:.0f}",
             f"{sweep['point_cpu_s'] * 1e3:.0f}", f"{sweep['waiting']:.1%}",
             f"{sweep['last_s'] * 1e3:.0f}",
             f"{sweep['busy']:.1%}", f"{sweep['overhead_s'] * 1e3:.1f}",
             f"{sweep['idle_end_s']:.2f}", f"{sweep['gap_s'] * 1e3:.1f}",
             f"{sweep['fixed_s']:.2f}", f"{sweep['client_cpu_s'] / N_POINTS * 1e3:.0f}",
             f"{sweep['gc_s']:.2f} ({sweep['full_gc']})"]
            + [f"{ph.get(k, float('nan')):.2f}" for k in
               ("imports", "plan", "cluster", "ship", "points", "close", "write")]
            + [f"{sweep['load_after']:.1f}", f"{sweep.get('steal_s', float('nan')):.2f}"])


def _scaling_text(r: dict) -> list[str]:
    """The sweep scaling part of the section."""
    p = r["workers"]
    first = (r["one"][0], r["many"][0])
    again = (r["one"][-1], r["many"][-2])
    given = r["many"][-1]
    speedup = first[0]["wall"] / first[1]["wall"]
    speedup_again = again[0]["wall"] / again[1]["wall"]
    points_speedup = first[0]["phases"]["points"] / first[1]["phases"]["points"]
    slowdown = first[1]["point_s"] / first[0]["point_s"]
    cpu_slowdown = first[1]["point_cpu_s"] / first[0]["point_cpu_s"]
    # Amdahl from the 1-worker sweep's own split: what does not run in the points phase
    # (imports, plan, cluster, ship, finish) is serial; the points phase is parallel
    s = first[0]["fixed_s"] / first[0]["wall"]
    predict = {q: 1.0 / (s + (1.0 - s) / q) for q in (2, 4, 16)}
    rows = [_scaling_row("1 worker, fresh process", first[0]),
            _scaling_row(f"{p} workers, fresh process", first[1]),
            _scaling_row("1 worker, again in that process", again[0]),
            _scaling_row(f"{p} workers, again in that process", again[1]),
            _scaling_row(f"{p} workers, given order, again in that process", given)]
    busy = min(first[1]["busy"], again[1]["busy"])
    sbs = r.get("side_by_side")
    command = (first[0]["command_s"], first[1]["command_s"])
    return [
        f"**Sweep scaling**: scene `deep_groove_duty1` (6304, massive balls, 75 states), "
        f"t_end {T_END * 1e3:.0f} ms, {N_POINTS} points over load x speed. Each worker count "
        "runs in a new Python process in the order of `bearingsim sweep`: the fork server of "
        "the workers started first (it imports bearingsim on another core while the process "
        "imports bearingsim's scenes and loads the scene), then a sweep, then a second sweep "
        "in the same process, whose workers fork from the running server (1 worker and "
        f"{p} alternate, {len(r['rounds'])} rounds; the table shows the round of the median "
        "fresh-process speed-up); the points go out "
        "longest first (`longest_first=True`, by their estimated time), and with "
        f"{p} workers a third sweep hands them out in the given order (speed rising: the "
        "longest last), side by side. Point: mean wall of a point on a worker; point CPU: "
        "mean CPU time of the thread that ran it; waiting: the share of the points' wall "
        "time they were not on a core (waiting for one: other processes, the client and "
        "the scheduler among them); last: mean "
        "wall of the last point each worker ran; workers busy: the points' share of the "
        "workers' time in the "
        "points phase; overhead: the rest, per point (target <= 5 ms), made of the workers' "
        "idle time at the end (summed over the workers: the last point's end less each "
        "worker's last end) and the gaps between two points on a worker (mean, end to next "
        "start: a task's cost on the worker); fixed: wall of `run_sweep` outside the points "
        "phase (target <= 2 s + assembly; the model is loaded from the cache here, in "
        "`plan`); client CPU: CPU time of the client's process (client and scheduler) per "
        "point over the whole sweep; client GC: the client process's time in Python's "
        "garbage collector over the sweep (in brackets: full collections; the sweep "
        "freezes the objects alive before its points out of them); steal: processor time "
        "the virtual machine's host took "
        "from this machine during the sweep (`/proc/stat`, summed over its processors: time "
        "the points may have waited for though no process here ran). Phases in seconds "
        "(imports: dask.distributed, in the first sweep of a process).",
        "",
        markdown_table(["sweep", "wall [s]", "points/task", "point [ms]", "point CPU [ms]",
                        "waiting", "last [ms]",
                        "workers busy",
                        "overhead [ms]", "idle at end [s]", "gap [ms]", "fixed [s]",
                        "client CPU [ms/point]", "client GC [s]", "imports", "plan",
                        "cluster", "ship", "points", "close", "write", "load after",
                        "steal [s]"], rows),
        "",
        f"Speed-up of the whole sweep, {p} workers against 1, in each of {len(r['rounds'])} "
        "rounds (fresh process / second sweep): "
        + ", ".join(f"{a:.2f}x / {b:.2f}x" for a, b in r["rounds"])
        + f"; median {float(np.median([a for a, _ in r['rounds']])):.2f}x / "
        f"{float(np.median([b for _, b in r['rounds']])):.2f}x. The table's round: "
        f"{speedup:.2f}x in a fresh "
        f"process, {speedup_again:.2f}x for the second sweep (target >= 1.8x for 2; implied "
        f"serial fractions {fmt(amdahl_serial_fraction(speedup, p))} and "
        f"{fmt(amdahl_serial_fraction(speedup_again, p))}). Longest first against the "
        f"given order, {p} workers in the same process: {again[1]['wall']:.2f} s against "
        f"{given['wall']:.2f} s, the workers idle at the end {again[1]['idle_end_s']:.2f} s "
        f"against {given['idle_end_s']:.2f} s, overhead {again[1]['overhead_s'] * 1e3:.1f} "
        f"against {given['overhead_s'] * 1e3:.1f} ms a point. The points phase alone: "
        f"{points_speedup:.2f}x, with the workers busy {busy:.1%} of it or more; a point took "
        f"{slowdown:.2f}x as long with {p} workers as with 1, its CPU time {cpu_slowdown:.2f}x "
        f"as long, and the points waited for a core {first[0]['waiting']:.1%} and "
        f"{first[1]['waiting']:.1%} of their wall time"
        + (f": {p} workers, the client and the scheduler (and any other process) share "
           f"{r['cores']} cores, so a point runs slower when the workers run side by side; "
           "that limits the speed-up of this machine, not the sweep's feeding, which the "
           "busy fraction measures." if slowdown > 1.05 else ".")
        + (f" The same point's run with no sweep code, in one process and in {p} processes "
           f"at once, alternating over {len(sbs['ratios'])} rounds: {sbs['alone']:.3f} s "
           f"and {sbs['together']:.3f} s of CPU (medians of 8 runs a round), "
           f"{sbs['together'] / sbs['alone']:.2f}x (rounds: "
           + ", ".join(f"{r:.2f}x" for r in sbs["ratios"]) + ")"
           + (f": the processes slow each other down in the caches and memory they share (and "
              "in what the virtual machine's host shares); at that cost "
              f"{p} workers could reach {p * sbs['alone'] / sbs['together']:.2f}x at most. "
              "This is measured after the sweeps, and the machine's capacity moves from "
              f"minute to minute: the sweeps' own points took {slowdown:.2f}x as long with "
              f"{p} workers as with 1 (above)."
              if sbs["together"] > 1.05 * sbs["alone"] else ".") if sbs else "")
        + f" Amdahl's law with the serial fraction of the fresh 1-worker sweep (its fixed "
        f"time over its wall: s = {fmt(s)}) predicts "
        + ", ".join(f"{v:.1f}x on {q}" for q, v in predict.items())
        + f" workers for these {N_POINTS} points; the 16-worker target >= 12x needs s <= "
        f"{fmt(amdahl_serial_fraction(12.0, 16))}, i.e. sweeps of about "
        f"{s / amdahl_serial_fraction(12.0, 16):.0f} times the work (more or longer points) for "
        "the same fixed cost. Rerun with `python -m bench.sweep_scaling --workers 16` on a "
        "machine with 16 free cores.",
        "",
        f"The whole command (launch of the process to the end of its first sweep: interpreter, "
        f"imports, scene, sweep): {command[0]:.2f} s on 1 worker, {command[1]:.2f} s on {p}, "
        f"{command[0] / command[1]:.2f}x (serial fraction "
        f"{fmt(amdahl_serial_fraction(command[0] / command[1], p))}); the process was ready "
        f"to sweep after {first[0]['ready_s']:.2f} s and {first[1]['ready_s']:.2f} s, and the "
        "command's time outside the points phase is "
        f"{command[0] - first[0]['phases']['points']:.2f} s and "
        f"{command[1] - first[1]['phases']['points']:.2f} s.",
        "",
    ]


def _body(r: dict) -> str:
    plain, cold, warm = r["nested"]["plain"], r["nested"]["cold"], r["nested"]["warm"]
    unnamed = r["nested"]["unnamed"]
    lines = [
        f"Machine load average {r['load_before'][0]:.1f} before and {r['load_after'][0]:.1f} "
        f"after the run on {r['cores']} usable cores (and after each sweep in the table): "
        "other processes shared them, so the absolute times are not those of a quiet "
        "machine; overheads are measured side by side with the work in the same sweep.",
        "",
        "**Warm load of the nested ball-level double-layer bearing** (61905/61907 `dynamic`, "
        f"{cold['states']} states; a fresh process each, the cache entry "
        f"{cold['bytes'] / 1e6:.1f} MB):",
        "",
        markdown_table(
            ["", "build tree [s]", "structure key [s]", "assemble / assemble_cached [s]",
             "first kernel look-up [s]"],
            [["`assemble` (no cache)", f"{plain['build']:.2f}", "-", f"{plain['call']:.2f}",
              "-"],
             ["cold: assemble and store, compile", f"{cold['build']:.2f}", f"{cold['key']:.2f}",
              f"{cold['call']:.2f}", f"{cold['kernel']:.2f}"],
             ["warm: load, library by its kept name", f"{warm['build']:.2f}",
              f"{warm['key']:.2f}", f"{warm['call']:.2f}", f"{warm['kernel']:.2f}"],
             ["warm: load, library by its generated source", f"{unnamed['build']:.2f}",
              f"{unnamed['key']:.2f}", f"{unnamed['call']:.2f}",
              f"{unnamed['kernel']:.2f}"]]),
        "",
        f"The warm call (structure key, entry checks, load; functions deserialized on first "
        f"use) takes {fmt(warm['call'] / cold['call'])} of the cold one (target: load <= 1 s; "
        f"with the tree built first {warm['build'] + warm['call']:.2f} s). Storing costs the "
        f"first run {cold['call'] - plain['call']:.1f} s (the right-hand side, observed and "
        "output functions and the mapped kernels are built to be stored). *First kernel "
        "look-up*: `kernel(system, \"ode\", True)`, the compiled right-hand side and Jacobian "
        "a run needs (`bearingsim.simulation.kernel_names`): the cold process compiles the "
        "library; a warm one finds it by the name kept under the hash of the loaded bytes, or, "
        "with the kept names removed, by generating its C source and hashing it, as every new "
        "process did before.",
        "",
        *_scaling_text(r),
        "",
        "**The cluster's own CPU time** beside an 8 s task on a one-worker LocalCluster of "
        "the sweep (each relative to the task's CPU time): dask's defaults serve its "
        "dashboard (a profiler sampling the task thread every 10 ms, a 20 ms event-loop tick, "
        "monitors every 0.1-0.5 s); the sweep's cluster turns them down "
        "(`sweep_cluster.QUIET_CLUSTER`).",
        "",
        markdown_table(
            ["settings", "worker process, other threads", "client process (scheduler, nanny)"],
            [[name, f"{100 * r['overhead'][key]['worker_other']:.1f} %",
              f"{100 * r['overhead'][key]['client']:.1f} %"]
             for name, key in (("dask defaults", "defaults"), ("sweep cluster", "quiet"))]),
    ]
    return "\n".join(lines)


def section(workers: int = 2) -> Section:
    """The run_all section."""
    r = run(workers)
    return Section("Sweep scaling and the warm load of cached models", _body(r), r)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2,
                        help="workers of the scaling run (default 2)")
    parser.add_argument("--overhead", choices=("defaults", "quiet"),
                        help=argparse.SUPPRESS)  # the cluster's own CPU time, as JSON
    args = parser.parse_args()
    if args.overhead:
        print(json.dumps(cluster_overhead(args.overhead == "quiet")))
    else:
        print(section(args.workers).body)
