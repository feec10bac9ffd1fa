"""Benchmark: what an operating point of a shipped analysis scene costs, this code against a
baseline commit side by side.

Every shipped scene whose analysis is ``steady``, ``modes`` or ``statics`` is run as a user
runs it, ``bearingsim run <scene> --out <temporary folder> --no-progress``, each run a fresh
Python process on a warm cache (its systems and kernels stored by a first run of each package,
not timed). Per run: the scene's own timings (``timings_s`` of its summary: ``assemble``, the
model built or loaded, and ``solve``, the operating points) and the CPU time of the process
and its children. The baseline runs from a ``git archive`` export of its package; the two
alternate over :data:`ROUNDS` rounds and the table shows the medians (the machine is shared:
compare the columns of one run, not runs of other days).

Command: ``python -m bench.analysis_points [--baseline COMMIT]``.
"""

from __future__ import annotations

import argparse
import os
import statistics

from bench.common import ROOT, Section, exported_package, fmt, markdown_table, scene_command

__all__ = ["BASELINE", "ROUNDS", "analysis_scenes", "measure", "section"]

BASELINE = "101d468"
"""The commit before :func:`~bearingsim.components.ball_row.axial_approach` solved one ball
instead of the whole row (a duplex pair's preload offset, solved per operating point), a row's
Hertz constants were kept and :func:`~bearingsim.simulation.steady_state` shortened its
Newton steps."""
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


def measure(baseline: str = BASELINE, rounds: int = ROUNDS) -> dict:
    """Per package (``"baseline"``: the commit ``baseline``; ``"now"``: this checkout) and
    analysis scene, the medians over ``rounds`` alternating rounds of ``assemble``,
    ``solve``, ``wall``, ``cpu`` [s] and ``points``: ``{package: {scene: {quantity:
    median}}}``."""
    scenes = analysis_scenes()
    runs: dict[str, dict[str, list[dict]]] = {"baseline": {}, "now": {}}
    with exported_package(baseline) as then_env:
        envs = {"baseline": then_env, "now": {**os.environ, "PYTHONPATH": str(ROOT)}}
        for env in envs.values():  # warm: each package's systems and kernels stored
            for scene in scenes:
                _run(env, scene)
        for _ in range(rounds):
            for name, env in envs.items():
                for scene in scenes:
                    runs[name].setdefault(scene, []).append(_run(env, scene))
    return {name: {scene: {k: statistics.median(r[k] for r in rs) for k in rs[0]}
                   for scene, rs in by_scene.items()} for name, by_scene in runs.items()}


def section(quick: bool = False, baseline: str = BASELINE) -> Section:
    """The run_all section: the analysis scenes, this code against ``baseline``."""
    rounds = 2 if quick else ROUNDS
    m = measure(baseline, rounds)
    then, now = m["baseline"], m["now"]
    rows = []
    for scene in now:
        a, b = then[scene], now[scene]
        rows.append([f"`{scene}`", str(int(b["points"])), fmt(1e3 * a["solve"] / a["points"]),
                     fmt(1e3 * b["solve"] / b["points"]), fmt(a["solve"] / b["solve"]),
                     fmt(a["assemble"]), fmt(b["assemble"]), fmt(a["wall"]), fmt(b["wall"]),
                     fmt(a["cpu"]), fmt(b["cpu"])])
    body = (
        f"Each shipped scene whose analysis is steady, modes or statics, run as a user runs "
        f"it: `bearingsim run <scene> --out <temporary folder> --no-progress`, a fresh Python "
        f"process on a warm cache (assembled systems and kernels stored by a first run of "
        f"each package); medians of {rounds} rounds, the baseline {baseline} (before the "
        "axial approach of a ball row solved one ball instead of all Z, a duplex pair's "
        "preload offset solved per operating point; before a row's Hertz constants were "
        "kept; and before steady_state's Newton steps were shortened where they would raise "
        "the residual, which sent a point of double_layer_rs to MINPACK and its import) and "
        "this code alternating. *solve per "
        "point*: the scene's own solve time (its summary's `timings_s`) over its operating "
        "points, with what the process pays once on first use (kernels loaded, modules "
        "imported on use: most of it for the scenes of a few milliseconds a point); "
        "*assemble*: the model built or loaded from the cache; *wall*, *CPU*: the whole "
        "command, launch to exit (CPU of the process and its children).\n\n"
        f"Command: `python -m bench.analysis_points --baseline {baseline}`\n\n"
        + markdown_table(["scene", "points", "solve per point before [ms]",
                          "solve per point now [ms]", "solve before / now",
                          "assemble before [s]", "assemble now [s]", "wall before [s]",
                          "wall now [s]", "CPU before [s]", "CPU now [s]"], rows))
    return Section("25. Analysis scenes: cost per operating point", body, m)


def main() -> None:
    """Print the section (``--baseline COMMIT``)."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--baseline", default=BASELINE)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    print(section(args.quick, args.baseline).body)


if __name__ == "__main__":
    main()
