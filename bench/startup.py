"""Benchmark: the start-up of a command, this code against a baseline commit side by side.

Two measurements, each in a fresh Python process:

* **imports**: ``import bearingsim.cli, bearingsim.scenes.runner`` (what ``bearingsim run``
  and ``bearingsim sweep`` import before they read the scene), wall time inside the process;
* **whole command**: ``bearingsim run <scene> --out <temporary folder> --no-progress`` of a
  shipped scene on a warm cache (its system and kernels stored by a first run of each
  package, not timed), from the launch of the process to its exit: wall time, and CPU time
  (user + system of the process and its children).

The baseline (:data:`BASELINE`, the commit before the imports moved to where they are used)
runs from a ``git archive`` export of its package; the two alternate over :data:`ROUNDS`
rounds and the table shows the medians (the machine is shared: compare the columns of one
run, not runs of other days).

Command: ``python -m bench.startup [--baseline COMMIT]``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys

from bench.common import ROOT, Section, exported_package, fmt, markdown_table, scene_command

__all__ = ["BASELINE", "ROUNDS", "SCENES", "measure", "section"]

BASELINE = "fd189b3"
"""The commit before scipy.optimize, scipy.integrate, networkx and the assembler's passes
were imported where they are used, and before the units library kept pint's conversions on
disk."""
ROUNDS = 5
"""Rounds of the baseline and this code, alternating."""
SCENES = ("deep_groove_duty1", "double_layer_friction", "spindle_radial")
"""Shipped scenes whose whole command is timed: a ball-level model on CVODES, a torque-level
model on CVODES, and a model run with LSODA (scipy.integrate) whose start point needs
scipy.optimize (nothing saved there)."""

IMPORTS = ("import time; t0 = time.perf_counter(); import bearingsim.cli, "
           "bearingsim.scenes.runner; print(time.perf_counter() - t0)")


def _imports(env: dict) -> float:
    out = subprocess.run([sys.executable, "-c", IMPORTS], check=True, capture_output=True,
                         text=True, env=env, cwd=ROOT).stdout
    return float(out.strip().splitlines()[-1])


def _command(env: dict, scene: str) -> tuple[float, float]:
    """Wall and CPU time [s] of ``bearingsim run scene`` in a new process."""
    return scene_command(env, scene)[:2]


def measure(baseline: str = BASELINE, rounds: int = ROUNDS) -> dict:
    """Medians over ``rounds`` alternating rounds, for ``"baseline"`` and ``"now"``: the
    imports' wall time [s] and, per scene of :data:`SCENES`, the whole command's wall and CPU
    time [s].

    Parameters
    ----------
    baseline : str
        The commit to compare with.
    rounds : int
        Alternating rounds.

    Returns
    -------
    dict
        ``{"baseline" | "now": {"imports": s, scene: (wall s, cpu s), ...}}``.
    """
    times: dict[str, dict] = {"baseline": {}, "now": {}}
    with exported_package(baseline) as then_env:
        now_env = {**os.environ, "PYTHONPATH": str(ROOT)}
        envs = {"baseline": then_env, "now": now_env}
        for env in envs.values():  # warm: each package's systems and kernels stored
            for scene in SCENES:
                _command(env, scene)
        for _ in range(rounds):
            for name, env in envs.items():
                times[name].setdefault("imports", []).append(_imports(env))
                for scene in SCENES:
                    times[name].setdefault(scene, []).append(_command(env, scene))
    return {name: {key: (statistics.median(v) if key == "imports" else
                         tuple(statistics.median(x[i] for x in v) for i in range(2)))
                   for key, v in t.items()} for name, t in times.items()}


def section(quick: bool = False, baseline: str = BASELINE) -> Section:
    """The run_all section: imports and whole commands, this code against ``baseline``."""
    rounds = 3 if quick else ROUNDS
    m = measure(baseline, rounds)
    then, now = m["baseline"], m["now"]
    rows = [["imports", fmt(then["imports"]), fmt(now["imports"]), "-", "-",
             fmt(then["imports"] / now["imports"])]]
    for scene in SCENES:
        rows.append([f"`bearingsim run {scene}`", fmt(then[scene][0]), fmt(now[scene][0]),
                     fmt(then[scene][1]), fmt(now[scene][1]),
                     fmt(then[scene][0] / now[scene][0])])
    body = (
        f"Each a fresh Python process; medians of {rounds} rounds, the baseline {baseline} "
        "(before scipy.optimize, scipy.integrate, networkx and the assembler's passes were "
        "imported where they are used, and before pint's conversions were kept on disk) and "
        "this code alternating. *imports*: wall time of "
        "`import bearingsim.cli, bearingsim.scenes.runner` inside the process; *run*: "
        "`bearingsim run <scene> --out <temporary folder> --no-progress` on a warm cache "
        "(assembled systems and kernels stored by a first run of each package), launch to "
        "exit, wall time and CPU time of the process and its children (plots, CSV and "
        "summary written). A model loaded from the cache and run on SUNDIALS needs none of "
        "the four, nor pint once its units' conversions are kept (the warm-up run keeps "
        "them), nor, since 5d83818, scipy.linalg and scipy.sparse (imported on use too): "
        "`double_layer_friction` imports no scipy at all, `deep_groove_duty1` scipy.special "
        "(the contacts' elliptic integrals, with scipy's common base); `spindle_radial` runs "
        "LSODA (scipy.integrate) from a start point solved by scipy.optimize, so it imports "
        "them on use.\n\n"
        f"Command: `python -m bench.startup --baseline {baseline}`\n\n"
        + markdown_table(["", "wall before [s]", "wall now [s]", "CPU before [s]",
                          "CPU now [s]", "wall before / now"], rows))
    return Section("24. Start-up of a command", body, m)


def main() -> None:
    """Print the section (``--baseline COMMIT``)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default=BASELINE)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    s = section(args.quick, args.baseline)
    print(json.dumps(s.data))
    print(s.body)


if __name__ == "__main__":
    main()
