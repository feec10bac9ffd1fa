"""Benchmark: what an operating point of a shipped analysis scene costs, this code against
baseline commits side by side, run alone and in a sweep.

Every shipped scene whose analysis is ``steady``, ``modes`` or ``statics`` is run as a user
runs it, ``bearingsim run <scene> --out <temporary folder> --no-progress``, each run a fresh
Python process on a warm cache (its systems and kernels stored by a first run of each package,
not timed). Per run: the scene's own timings (``timings_s`` of its summary: ``assemble``, the
model built or loaded, and ``solve``, the operating points) and the CPU time of the process
and its children. The baseline runs from a ``git archive`` export of its package; the two
alternate over :data:`ROUNDS` rounds and the table shows the medians (the machine is shared:
compare the columns of one run, not runs of other days).

The same packages also run :data:`SWEEP`, ``bearingsim sweep`` of ``duplex_modes`` over its
preload and speed on a LocalCluster of 2 workers (a fresh process each, alternating): the
phases of its summary (``plan``: points validated, model loaded; ``points``) and the wall
time of the command.

Command: ``python -m bench.analysis_points [--baseline COMMIT ...]``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys

from bench.common import (
    ROOT,
    Section,
    exported_package,
    fmt,
    markdown_table,
    scene_command,
    sweep_command,
)

__all__ = ["BASELINES", "ROUNDS", "SWEEP", "analysis_scenes", "measure", "section"]

BASELINES = ("101d468", "2c41f1d", "89e8352")
"""``101d468``: before :func:`~bearingsim.components.ball_row.axial_approach` solved one ball
instead of the whole row (a duplex pair's preload offset, solved per operating point), a row's
Hertz constants were kept and :func:`~bearingsim.simulation.steady_state` shortened its
Newton steps. ``2c41f1d``: before the physics functions' finite checks were cut to one pass
per argument and a sweep's plan stopped building the assembly for every parametric point.
``89e8352``: before the package imported its modeling language on first use and the sweep
command's parser stopped importing the scenes package (the sweep's fork server started after
both)."""
SWEEP = ("duplex_modes", ["assembly.preload_force=250,500,1000,1500,2000,2500,3000,4000",
                          "assembly.speed=0,419"], 2)
"""The sweep timed: scene, grid (16 points) and workers."""
ROUNDS = 3
"""Rounds of the baseline and this code, alternating."""
ANALYSES = ("steady", "modes", "statics")


def analysis_scenes() -> list[str]:
    """The shipped scenes that solve operating points (not a run in time), by name.

    Returns
    -------
    list of str
        Scene names, sorted.
    """
    from bearingsim.scenes import parse_scene

    names = []
    for path in sorted((ROOT / "scenes").glob("*.toml")):
        if parse_scene(path.read_text(encoding="utf-8")).analysis in ANALYSES:
            names.append(path.stem)
    return names


def _run(env: dict, scene: str) -> dict[str, float]:
    """One ``bearingsim run scene`` in a new process: its summary's timings [s] and points,
    the command's wall and CPU time [s]."""
    wall, cpu, summary = scene_command(env, scene)
    return {**summary["timings_s"], "points": summary["points"], "wall": wall, "cpu": cpu}


def _sweep(env: dict) -> dict[str, float]:
    """:data:`SWEEP` in a new process: its summary's ``plan`` and ``points`` phases and the
    command's wall time [s]."""
    scene, grid, workers = SWEEP
    wall, summary, points = sweep_command(
        env, scene, [*(a for g in grid for a in ("--grid", g)), "--workers", str(workers)])
    phases = summary["phases_s"]
    return {"plan": phases["plan"], "cluster": phases["cluster"], "points": phases["points"],
            "slowest": max(points), "wall": wall, "n": summary["points"],
            "ok": summary["ok"]}


WARM_RUNS = 5
"""Runs of each scene in one process after its first (:func:`_warm`)."""
WARM_PROCESSES = 7
"""Processes per package that time the warm runs, alternating between the packages: on this
virtual machine a whole process may run 1.5-1.8 times slower than the next one."""

_WARM_SCRIPT = """
import json, sys, warnings
warnings.simplefilter("ignore")
from bearingsim.scenes.runner import run_scene
out = {}
for scene in sys.argv[2:]:
    run_scene(scene, write=False, progress=False)
    runs = [run_scene(scene, write=False, progress=False).summary for _ in range(int(sys.argv[1]))]
    out[scene] = min(r["timings_s"]["solve"] / r["points"] for r in runs)
print(json.dumps(out))
"""


def _warm(env: dict, scenes: list[str]) -> dict[str, float]:
    """Each scene run :data:`WARM_RUNS` times in one process after a first run (kernels
    loaded, modules imported): the least solve time per operating point [s] of the runs (the
    cost itself; a slower run was interrupted by the machine's other work), by scene."""
    done = subprocess.run([sys.executable, "-c", _WARM_SCRIPT, str(WARM_RUNS), *scenes],
                          check=True, capture_output=True, text=True, env=env, cwd=ROOT)
    return json.loads(done.stdout.strip().splitlines()[-1])


def measure(baselines: tuple[str, ...] = BASELINES, rounds: int = ROUNDS) -> dict:
    """Per package (each baseline commit, and ``"now"``: this checkout) and analysis scene,
    the medians over ``rounds`` alternating rounds of ``assemble``, ``solve``, ``wall``,
    ``cpu`` [s] and ``points``, and of :data:`SWEEP` (key ``"sweep"``: ``plan``, ``points``,
    ``wall`` [s], ``n``, ``ok``): ``{package: {scene: {quantity: median}}}``. A scene that a
    baseline's package cannot read (a newer one: the command exits with status 2) is left
    out."""
    scenes = analysis_scenes()
    names = [*baselines, "now"]
    runs: dict[str, dict[str, list[dict]]] = {name: {} for name in names}
    with contextlib.ExitStack() as stack:
        envs = {b: stack.enter_context(exported_package(b)) for b in baselines}
        envs["now"] = {**os.environ, "PYTHONPATH": str(ROOT)}
        for env in envs.values():  # warm: each package's systems and kernels stored
            for scene in list(scenes):
                try:
                    _run(env, scene)
                except subprocess.CalledProcessError as exc:
                    if exc.returncode != 2:  # 2: a scene a baseline's package cannot read
                        raise
                    scenes.remove(scene)  # (a newer scene): compared where all can run it
            _sweep(env)  # (and the modules the sweep's workers import, where it keeps them)
        for _ in range(rounds):
            for name, env in envs.items():
                for scene in scenes:
                    runs[name].setdefault(scene, []).append(_run(env, scene))
                runs[name].setdefault("sweep", []).append(_sweep(env))
        warm: dict[str, list[dict[str, float]]] = {name: [] for name in names}
        for _ in range(WARM_PROCESSES):
            for name, env in envs.items():
                warm[name].append(_warm(env, scenes))
    out = {name: {scene: {k: statistics.median(r[k] for r in rs) for k in rs[0]}
                  for scene, rs in by_scene.items()} for name, by_scene in runs.items()}
    for name, per_process in warm.items():
        for scene in scenes:
            values = [w[scene] for w in per_process]
            out[name][scene].update(warm=statistics.median(values), warm_low=min(values),
                                    warm_high=max(values))
    return out


def section(quick: bool = False, baselines: tuple[str, ...] = BASELINES) -> Section:
    """The run_all section: the analysis scenes and :data:`SWEEP`, this code against
    ``baselines``."""
    rounds = 2 if quick else ROUNDS
    m = measure(baselines, rounds)
    names = [*baselines, "now"]
    head = [f"{b} [ms]" for b in baselines]
    rows = []
    for scene in m["now"]:
        if scene == "sweep":
            continue
        per = [m[n][scene] for n in names]
        rows.append([f"`{scene}`", str(int(per[-1]["points"])),
                     *(fmt(1e3 * r["solve"] / r["points"]) for r in per),
                     fmt(per[-2]["solve"] / per[-1]["solve"]),
                     *(f"{fmt(1e3 * r['warm'])} ({fmt(1e3 * r['warm_low'])}-"
                       f"{fmt(1e3 * r['warm_high'])})" for r in per),
                     fmt(per[-2]["warm"] / per[-1]["warm"]),
                     *(fmt(r["wall"]) for r in per), *(fmt(r["cpu"]) for r in per)])
    scene, grid, workers = SWEEP
    sweep_rows = [[n if n == "now" else f"`{n}`", f"{int(m[n]['sweep']['ok'])} of "
                   f"{int(m[n]['sweep']['n'])}",
                   *(fmt(m[n]["sweep"][k]) for k in ("plan", "cluster", "points", "slowest",
                                                      "wall"))] for n in names]
    body = (
        f"Each shipped scene whose analysis is steady, modes or statics (that every package "
        f"compared can read), run as a user runs "
        f"it: `bearingsim run <scene> --out <temporary folder> --no-progress`, a fresh Python "
        f"process on a warm cache (assembled systems and kernels stored by a first run of "
        f"each package); medians of {rounds} rounds, the packages of the baselines "
        f"({', '.join(baselines)}) and this code alternating. Baselines: "
        + " ".join(f"{b}: {w}" for b, w in zip(BASELINES, BASELINE_WORDS, strict=True)
                   if b in baselines) +
        " *solve per point*: the scene's own solve time (its summary's `timings_s`) over its "
        "operating points, with what the process pays once on first use (kernels loaded, "
        "modules imported on use: most of it for the scenes of a few milliseconds a point); "
        f"*warm process*: the same per point in one process that ran the scene before, the "
        f"fastest of {WARM_RUNS} runs; the median of {WARM_PROCESSES} such processes per "
        "package, alternating, and in brackets the fastest and slowest process (a whole process "
        "may run up to 1.8 times slower than the next here) (what a point costs in a "
        "sweep or a repeated run, without the first-use costs that dominate the fresh command); "
        f"*ratio*: solve of {baselines[-1]} over now; *wall*, *CPU*: the whole command, launch "
        "to exit (CPU of the process and its children).\n\n"
        f"Command: `python -m bench.analysis_points --baseline {' --baseline '.join(baselines)}`"
        "\n\n"
        + markdown_table(["scene", "points", *(f"solve per point {h}" for h in head),
                          "solve per point now [ms]", f"solve {baselines[-1]} / now",
                          *(f"warm process: per point {h}" for h in head),
                          "warm process: now [ms]", f"warm {baselines[-1]} / now",
                          *(f"wall {b} [s]" for b in baselines), "wall now [s]",
                          *(f"CPU {b} [s]" for b in baselines), "CPU now [s]"], rows)
        + f"\n\n**A modes sweep**: `bearingsim sweep {scene} "
        + " ".join(f"--grid {g}" for g in grid)
        + f" --workers {workers}` ({len(grid[0].split(',')) * len(grid[1].split(','))} points), "
        "a fresh process each, the same rounds (medians), after a sweep of each package to warm "
        "its caches. *plan*: the summary's phase that validates the points and loads the model "
        "(at both baselines it also built the pair for every point, to read the preload's "
        "parameter values); *cluster*: the wait for the workers after it (the fork server's "
        "imports: now also the modules the workers of the scene's earlier sweeps imported at "
        "their first point, `bearingsim.sweep_preloads`); *points*: the phase the workers run "
        "them; *slowest point*: the longest point's wall time (a worker's first, which at the "
        "baselines imported scipy.linalg and scipy.optimize); *wall*: the command.\n\n"
        + markdown_table(["package", "points ok", "plan [s]", "cluster [s]", "points [s]",
                          "slowest point [s]", "wall [s]"], sweep_rows))
    return Section("25. Analysis scenes: cost per operating point", body, m)


BASELINE_WORDS = (
    "before the axial approach of a ball row solved one ball instead of all Z (a duplex "
    "pair's preload offset, solved per operating point), before a row's Hertz constants were "
    "kept and before steady_state's Newton steps were shortened where they would raise the "
    "residual (which sent a point of double_layer_rs to MINPACK and its import);",
    "before the finite checks of the physics functions looked at each argument once and "
    "worked out their message only when raising, and before a sweep's plan stopped building "
    "the assembly for every point of a parametric argument;",
    "before the package imported its modeling language on first use: `bearingsim sweep` "
    "started its workers' fork server after CasADi, numpy and beartype were imported, and "
    "after its parser imported the scenes package.")
"""What each of :data:`BASELINES` is before, for the section's text."""


def main() -> None:
    """Print the section (``--baseline COMMIT``)."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--baseline", action="append",
                        help=f"a baseline commit (repeat for more; default {BASELINES})")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    print(section(args.quick, tuple(args.baseline or BASELINES)).body)


if __name__ == "__main__":
    main()
