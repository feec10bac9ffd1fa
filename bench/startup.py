"""Benchmark: the start-up of a command, this code against baseline commits side by side.

Two measurements, each in a fresh Python process:

* **imports**: ``import bearingsim.cli, bearingsim.scenes.runner`` (what ``bearingsim run``
  and ``bearingsim sweep`` import before they read the scene), wall time inside the process;
* **whole command**: ``bearingsim run <scene> --out <temporary folder> --no-progress`` of a
  shipped scene on a warm cache (its system and kernels stored by a first run of each
  package, not timed), from the launch of the process to its exit: wall time, and CPU time
  (user + system of the process and its children).

The baselines (:data:`BASELINES`: the commit before the imports moved to where they are
used, and the one before a ball bearing's design and a compiled run stopped importing
scipy.special and scipy.sparse) run from a ``git archive`` export of their package; the
packages alternate over :data:`ROUNDS` rounds and the table shows the medians (the machine
is shared: compare the columns of one run, not runs of other days).

Command: ``python -m bench.startup [--baseline COMMIT ...]``.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys

from bench.common import ROOT, Section, exported_package, fmt, markdown_table, scene_command

__all__ = ["BASELINES", "BASELINE_WORDS", "ROUNDS", "SCENES", "measure", "section"]

BASELINES = ("fd189b3", "8b21674")
BASELINE_WORDS = (
    "before scipy.optimize, scipy.integrate, networkx and the assembler's passes were "
    "imported where they are used, and before pint's conversions were kept on disk",
    "before a bearing's design computed the contacts' complete elliptic integrals by the "
    "arithmetic-geometric mean of the generated models instead of scipy.special, and before "
    "the fill-reducing order of a compiled kernel's Newton matrix was kept beside its library "
    "instead of computed by SuperLU (scipy.sparse) in every process")
"""What each of :data:`BASELINES` is before, for the section's text."""
ROUNDS = 5
"""Rounds of the baseline and this code, alternating."""
SCENES = ("deep_groove_duty1", "double_layer_friction", "spindle_radial")
"""Shipped scenes whose whole command is timed: a ball-level model on compiled_bdf, a
torque-level model on CVODES, and a model run with LSODA (scipy.integrate) whose start point needs
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


def measure(baselines: tuple[str, ...] = BASELINES, rounds: int = ROUNDS) -> dict:
    """Medians over ``rounds`` alternating rounds, for each baseline and ``"now"``: the
    imports' wall time [s] and, per scene of :data:`SCENES`, the whole command's wall and CPU
    time [s].

    Parameters
    ----------
    baselines : tuple of str
        The commits to compare with.
    rounds : int
        Alternating rounds.

    Returns
    -------
    dict
        ``{commit | "now": {"imports": s, scene: (wall s, cpu s), ...}}``.
    """
    times: dict[str, dict] = {name: {} for name in (*baselines, "now")}
    with contextlib.ExitStack() as stack:
        envs = {b: stack.enter_context(exported_package(b)) for b in baselines}
        envs["now"] = {**os.environ, "PYTHONPATH": str(ROOT)}
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


def section(quick: bool = False, baselines: tuple[str, ...] = BASELINES) -> Section:
    """The run_all section: imports and whole commands, this code against ``baselines``."""
    rounds = 3 if quick else ROUNDS
    m = measure(baselines, rounds)
    names = (*baselines, "now")
    rows = [["imports", *(fmt(m[n]["imports"]) for n in names), *("-" for _ in names),
             *(fmt(m[b]["imports"] / m["now"]["imports"]) for b in baselines)]]
    for scene in SCENES:
        rows.append([f"`bearingsim run {scene}`", *(fmt(m[n][scene][0]) for n in names),
                     *(fmt(m[n][scene][1]) for n in names),
                     *(fmt(m[b][scene][0] / m["now"][scene][0]) for b in baselines)])
    words = "; ".join(f"{b}: {w}" for b, w in zip(BASELINES, BASELINE_WORDS, strict=True)
                      if b in baselines)
    body = (
        f"Each a fresh Python process; medians of {rounds} rounds, the baselines and this "
        f"code alternating. Baselines: {words}. *imports*: wall time of "
        "`import bearingsim.cli, bearingsim.scenes.runner` inside the process; *run*: "
        "`bearingsim run <scene> --out <temporary folder> --no-progress` on a warm cache "
        "(assembled systems and kernels stored by a first run of each package), launch to "
        "exit, wall time and CPU time of the process and its children (plots, CSV and "
        "summary written). A model loaded from the cache needs none of scipy.optimize, "
        "scipy.integrate, networkx and the passes, nor pint once its units' conversions "
        "are kept (the warm-up run keeps them), nor, since 5d83818, scipy.linalg and "
        "scipy.sparse on SUNDIALS; at 8b21674 `deep_groove_duty1` (compiled_bdf) still "
        "imported scipy.special for the contacts' elliptic integrals and scipy.sparse for "
        "the order of its Newton matrix, and now imports no scipy at all, as "
        "`double_layer_friction`; `spindle_radial` runs LSODA (scipy.integrate) from a "
        "start point solved by scipy.optimize, so it imports them on use.\n\n"
        f"Command: `python -m bench.startup --baseline {' --baseline '.join(baselines)}`\n\n"
        + markdown_table(["", *(f"wall {n} [s]" for n in names),
                          *(f"CPU {n} [s]" for n in names),
                          *(f"wall {b} / now" for b in baselines)], rows))
    return Section("24. Start-up of a command", body, m)


def main() -> None:
    """Print the section (``--baseline COMMIT``, repeated for more)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", action="append",
                        help=f"a baseline commit (repeat for more; default {BASELINES})")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    s = section(args.quick, tuple(args.baseline or BASELINES))
    print(json.dumps(s.data))
    print(s.body)


if __name__ == "__main__":
    main()
