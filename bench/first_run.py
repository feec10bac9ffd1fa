"""Benchmark: the first run of a shipped ball-level scene on a cold cache, with the default
method (``method=None``, :mod:`bearingsim.simulation.choice`).

Each measurement is a fresh process (no kernels in memory) on a kernel-library cache folder of
its own: *cold*, an empty folder (the first run ever on this machine); *warm*, the folder the
cold run left (the library compiled, finished first if the cold run's build was stopped at its
exit); *compile*, another empty folder where the kernel is
compiled and waited for, alone. Times are wall seconds of the ``simulate`` call (assembly
excluded, the same in all three). Goal: cold <= warm + compile, i.e. the first run waits for
the compiler only when that pays, and otherwise loses no more than the compile would cost.

Command: ``python -m bench.first_run [--t-end SECONDS]``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from bench.common import Section, fmt, markdown_table

__all__ = ["SCENES", "section"]

ROOT = Path(__file__).resolve().parents[1]
SCENES = ("deep_groove_duty1",)
"""The shipped scenes with ball-level models."""
T_ENDS = (0.005, 0.05)
"""Run lengths [s]: a short first run (the VM should start) and a longer one."""

_CHILD = """
import json, sys, time, warnings
warnings.simplefilter("ignore")
from bearingsim.scenes import parse_scene
from bearingsim.scenes.preparation import prepare
from bearingsim.scenes.scene_simulation import simulate_inputs
from bearingsim.simulation import simulate
from bearingsim.simulation.kernels import kernel
path, t_end, mode = sys.argv[1], float(sys.argv[2]), sys.argv[3]
prep = prepare(parse_scene(open(path).read()))
s = prep.scene.simulation
start = time.perf_counter()
if mode == "compile":
    kernel(prep.system, "ode", True)
    print(json.dumps({"wall": time.perf_counter() - start}))
else:
    res = simulate(prep.system, s.t_start + t_end, inputs=simulate_inputs(prep.scene.inputs),
                   parameters=prep.scene.parameters, rtol=s.rtol, atol=s.atol, n_points=3,
                   progress=False)
    print(json.dumps({"wall": time.perf_counter() - start, "method": res.stats["method"],
                      "reason": res.stats["method_reason"]}))
"""


def _child(scene: str, t_end: float, mode: str, cache: str) -> dict:
    env = {**os.environ, "BEARINGSIM_CACHE": cache,
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run([sys.executable, "-c", _CHILD, str(ROOT / "scenes" / f"{scene}.toml"),
                          str(t_end), mode], check=True, capture_output=True, text=True,
                         env=env, cwd=str(ROOT)).stdout
    return json.loads(out.strip().splitlines()[-1])


def measure(t_ends=T_ENDS) -> list[list]:
    """Rows: scene, run length, cold / warm / compile wall times, method and reason."""
    rows = []
    for scene in SCENES:
        for t_end in t_ends:
            with tempfile.TemporaryDirectory() as cold, tempfile.TemporaryDirectory() as alone:
                first = _child(scene, t_end, "run", cold)
                compile_s = _child(scene, t_end, "compile", alone)["wall"]
                _child(scene, t_end, "compile", cold)  # a build the cold run left unfinished
                warm = _child(scene, t_end, "run", cold)
            rows.append([scene, fmt(t_end), fmt(first["wall"]), fmt(warm["wall"]),
                         fmt(compile_s), "yes" if first["wall"] <= warm["wall"] + compile_s
                         else "no", first["method"], first["reason"]])
    return rows


def section(quick: bool = False) -> Section:
    """The run_all section (``quick``: the short run only)."""
    t_ends = T_ENDS[:1] if quick else T_ENDS
    text = (__doc__.split("\n\n", 1)[1].rsplit("\n\nCommand", 1)[0].replace("\n", " ")
            + f"\n\nCommand: `python -m bench.first_run --t-end {','.join(map(str, t_ends))}`"
            + "\n\n" + markdown_table(
                ["scene", "run [s]", "cold [s]", "warm [s]", "compile alone [s]",
                 "cold <= warm + compile", "method of the cold run", "why"],
                measure(t_ends)) + "\n")
    return Section("First runs on a cold cache", text)


def main() -> None:
    """Command line: the section's Markdown."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-end", default=",".join(map(str, T_ENDS)))
    args = parser.parse_args()
    print(markdown_table(["scene", "run [s]", "cold [s]", "warm [s]", "compile alone [s]",
                          "cold <= warm + compile", "method", "why"],
                         measure(tuple(float(v) for v in args.t_end.split(",")))))


if __name__ == "__main__":
    main()
