"""Benchmark: a sweep over input expressions, this code against a baseline commit side by side.

``bearingsim sweep deep_groove_duty1`` over :data:`LOADS` x the shaft speed written as the
scene writes it, ``rpm(N) * ramp(0, 0.02)`` with :data:`SPEEDS` r/min (32 points of
:data:`T_END`, 2 workers). Each sweep's speeds are new: ``N`` plus a fraction drawn per sweep, so
that no earlier sweep's compiled inputs are on disk (what a user's next sweep over other speeds
meets). The reference is the same sweep with the speeds as numbers [rad/s] (constant speeds:
inputs of one structure whatever their values). Each sweep is a fresh process; the packages
alternate over :data:`ROUNDS` rounds after a warm-up sweep of each (its assembled system and
kernels stored); the table shows the medians.

Command: ``python -m bench.expression_sweep [--baseline COMMIT] [--rounds N]``.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import random
import statistics
import time

from bench.common import ROOT, Section, exported_package, fmt, markdown_table, sweep_command

__all__ = ["BASELINE", "LOADS", "ROUNDS", "SPEEDS", "T_END", "measure", "section"]

BASELINE = "1d31d9e"
"""Before the inputs' C became a library of its own (the integrator was compiled again with
each new input structure) and before scene expressions lifted their numbers (each expression
with other numbers was a new structure)."""
SCENE = "deep_groove_duty1"
LOADS = (200, 500, 800, 1100)
"""Radial loads [N]."""
SPEEDS = (1000, 1500, 2000, 2500, 3000, 3500, 4000, 4500)
"""Shaft speeds [r/min] (each plus a fraction drawn per sweep)."""
T_END = 0.01
"""Simulated time of a point [s]."""
ROUNDS = 3
"""Rounds of the two packages, alternating."""
WORKERS = 2
SLOW = 5.0
"""A point slower than this many times the sweep's median point is counted as slow."""


def _speeds(kind: str, rng: random.Random) -> str:
    """The ``--grid`` value of the speeds: expressions, or numbers [rad/s]."""
    speeds = [n + round(rng.random(), 6) for n in SPEEDS]
    if kind == "expressions":
        return "inputs.shaft_speed=" + ";".join(f"rpm({n}) * ramp(0, 0.02)" for n in speeds)
    return "inputs.shaft_speed=" + ",".join(f"{n * 3.141592653589793 / 30:.6f}" for n in speeds)


def _sweep(env: dict, kind: str, rng: random.Random, loads=LOADS) -> dict[str, float]:
    """One ``bearingsim sweep`` in a new process: its points phase, the mean, median and
    slowest point's wall [s], the points over :data:`SLOW` times the median, the command's
    wall [s]."""
    wall, summary, points = sweep_command(env, SCENE, [
        "--grid", "inputs.load.Fx=" + ",".join(str(f) for f in loads),
        "--grid", _speeds(kind, rng), "--grid", f"simulation.t_end={T_END}",
        "--workers", str(WORKERS)])
    median = statistics.median(points)
    return {"points": summary["phases_s"]["points"], "mean": statistics.fmean(points),
            "median": median, "slowest": max(points),
            "slow": sum(p > SLOW * median for p in points), "wall": wall,
            "n": summary["points"], "ok": summary["ok"]}


def measure(baseline: str = BASELINE, rounds: int = ROUNDS) -> dict:
    """Medians over ``rounds`` alternating rounds, per package (``baseline`` and ``"now"``)
    and kind of speed (``"expressions"``, ``"numbers"``): ``{package: {kind: {quantity:
    median}}}`` (quantities of :func:`_sweep`)."""
    rng = random.Random(time.time_ns())  # new speeds in every sweep, on every run
    runs: dict[str, dict[str, list[dict]]] = {}
    with contextlib.ExitStack() as stack:
        envs = {baseline: stack.enter_context(exported_package(baseline)),
                "now": {**os.environ, "PYTHONPATH": str(ROOT)}}
        for env in envs.values():  # warm: the package's system, kernels and integrator
            _sweep(env, "numbers", rng, loads=LOADS[:1])
        for _ in range(rounds):
            for name, env in envs.items():
                for kind in ("expressions", "numbers"):
                    runs.setdefault(name, {}).setdefault(kind, []).append(
                        _sweep(env, kind, rng))
    return {name: {kind: {k: statistics.median(r[k] for r in rs) for k in rs[0]}
                   for kind, rs in by_kind.items()} for name, by_kind in runs.items()}


def section(quick: bool = False, baseline: str = BASELINE, rounds: int | None = None
            ) -> Section:
    """The run_all section: the expression sweep and its reference, this code against
    ``baseline`` (``rounds``: default 2 quick, else :data:`ROUNDS`)."""
    rounds = rounds or (2 if quick else ROUNDS)
    m = measure(baseline, rounds)
    rows = [[name if name == "now" else f"`{name}`", kind,
             f"{int(m[name][kind]['ok'])} of {int(m[name][kind]['n'])}",
             *(fmt(m[name][kind][k]) for k in ("points", "mean", "median", "slowest")),
             str(int(m[name][kind]["slow"])), fmt(m[name][kind]["wall"])]
            for kind in ("expressions", "numbers") for name in (baseline, "now")]
    ratio = m[baseline]["expressions"]["points"] / m["now"]["expressions"]["points"]
    extra = {name: m[name]["expressions"]["points"] - m[name]["numbers"]["points"]
             for name in (baseline, "now")}
    body = (
        f"`bearingsim sweep {SCENE} --grid inputs.load.Fx={','.join(map(str, LOADS))} --grid "
        f"\"inputs.shaft_speed=rpm(N1) * ramp(0, 0.02);...\" --grid simulation.t_end={T_END} "
        f"--workers {WORKERS}`: {len(LOADS)} loads x {len(SPEEDS)} speeds "
        f"({len(LOADS) * len(SPEEDS)} points), the speeds N = "
        f"{', '.join(map(str, SPEEDS))} r/min each plus a fraction drawn per sweep, so that "
        "every sweep's expressions are new to the disk cache (a user's next sweep over other "
        "speeds). *numbers*: the same sweep with the speeds as numbers [rad/s] (constant "
        "speeds), the reference. A fresh process per sweep on a warm cache (each package's "
        f"system and kernels stored by a warm-up sweep); medians of {rounds} rounds, the "
        f"packages alternating. `{baseline}`: before the inputs' C became a library of its "
        "own (the compiled BDF's library, integrator and inputs, was compiled again for "
        "every new input structure) and before scene expressions lifted their numbers into "
        "the run's values (each expression with other numbers was a new structure). "
        f"*points*: the sweep's points phase; *mean*, *median*, *slowest*: a point's wall "
        f"time; *slow*: the points over {SLOW:g} times the median; *wall*: the command.\n\n"
        f"Command: `python -m bench.expression_sweep --baseline {baseline}`\n\n"
        + markdown_table(["package", "speeds", "points ok", "points phase [s]",
                          "point mean [s]", "point median [s]", "slowest point [s]",
                          "slow points", "wall [s]"], rows)
        + f"\n\nThe points phase of the expression sweep: {ratio:.1f}x shorter now than at "
        f"`{baseline}`. The expression sweep's points phase less the number sweep's (what the "
        f"new expressions cost): {extra[baseline]:.2f} s at `{baseline}`, "
        f"{extra['now']:.2f} s now.\n")
    return Section("26. Sweeps over input expressions", body, m)


def main() -> None:
    """Print the section."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", default=BASELINE)
    parser.add_argument("--rounds", type=int, default=ROUNDS)
    args = parser.parse_args()
    print(section(baseline=args.baseline, rounds=args.rounds).body)


if __name__ == "__main__":
    main()
