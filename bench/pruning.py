"""Benchmark: pruning to the requested outputs against the full model, same outputs.

The model is a machine with a PMSM spindle drive (motor, speed and current controllers, shaft,
61905/61907 double-layer bearing) and ``N`` further spindles that run independently, each a
torque-level double-layer bearing with its own speed ramp. A scene that asks only for the
drive's speed ratio and shaft speed needs none of the other spindles: ``assemble(..., outputs=)``
drops their equations and states. Both models are integrated with the same solver and tight
tolerances; the outputs must agree to 1e-9 (relative to their scale) and the report gives the
measured assemble and simulate times and their ratios.

Usage: ``python -m bench.pruning [--quick]``; ``run(quick) -> str`` returns the Markdown body.
"""

from __future__ import annotations

import argparse
import time

import casadi as ca
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing, motor_drive
from bearingsim.language import Assembly
from bearingsim.simulation import simulate
from bearingsim.units import rpm_to_rad_s

__all__ = ["Machine", "run", "section", "OUTPUTS"]

OUTPUTS = ["drive.bearing.Rs", "drive.shaft.w"]
PAIRS = (("61905", "61907"), ("61905", "61908"), ("61905", "61909"))


class Machine(Assembly):
    """A PMSM spindle drive and ``n_spindles`` independent speed-driven spindles."""

    def __init__(self, n_spindles: int, name=None):
        super().__init__(name)
        w = rpm_to_rad_s(10_000)
        self.drive = motor_drive(
            double_layer_bearing("61905", "61907", drive="flange"), motor="pmsm",
            speed_ref=lambda t: w * ca.fmin(t / 0.5, 1.0), load_torque=0.0,
            motor_options={"kp_w": 0.05, "ki_w": 0.5})
        for k in range(n_spindles):
            inner, outer = PAIRS[k % len(PAIRS)]
            wk = rpm_to_rad_s(2_000 + 500 * k)
            self.add(f"spindle{k}", double_layer_bearing(
                inner, outer, speed=lambda t, wk=wk: wk * ca.fmin(t / 0.3, 1.0)))


def _best(fn, repeats: int) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def measure(n_spindles: int, t_end: float, repeats: int) -> dict:
    """Assemble and simulate the full and the pruned model; compare the outputs."""
    kw = {"rtol": 1e-11, "atol": 1e-12, "n_points": 201, "progress": False}
    t_full_asm, full = _best(lambda: assemble(Machine(n_spindles)), repeats)
    t_pr_asm, pruned = _best(lambda: assemble(Machine(n_spindles), outputs=OUTPUTS), repeats)
    t_full_sim, r_full = _best(lambda: simulate(full, t_end, **kw), repeats)
    t_pr_sim, r_pr = _best(lambda: simulate(pruned, t_end, **kw), repeats)
    err = max(float(np.max(np.abs(r_full[n] - r_pr[n])) / max(1.0, np.max(np.abs(r_full[n]))))
              for n in OUTPUTS)
    return {
        "spindles": n_spindles, "states_full": full.n_states, "states_pruned": pruned.n_states,
        "skipped": pruned.skipped, "assemble_full": t_full_asm, "assemble_pruned": t_pr_asm,
        "simulate_full": t_full_sim, "simulate_pruned": t_pr_sim, "max_rel_error": err,
        "finals": {n: r_pr.final(n) for n in OUTPUTS},
    }


def run(quick: bool) -> str:
    """Run the benchmark; returns the Markdown body of its report section.

    Parameters
    ----------
    quick : bool
        Fewer spindles, a shorter run and one repetition.
    """
    sizes = (2, 8) if quick else (2, 8, 24)
    t_end, repeats = (1.0, 1) if quick else (2.0, 3)
    rows = [measure(n, t_end, repeats) for n in sizes]
    lines = [
        "A PMSM spindle drive with a 61905/61907 double-layer bearing plus N independent "
        "speed-driven double-layer spindles; the scene asks only for "
        + ", ".join(f"`{n}`" for n in OUTPUTS) + ". Full model: `assemble(machine)`; pruned: "
        "`assemble(machine, outputs=...)`. Both with BDF, rtol 1e-11, atol 1e-12, 201 output "
        f"points over {t_end:g} s; best of {repeats}.",
        "",
        "| N spindles | states full → pruned | assemble full / pruned [s] | ratio "
        "| simulate full / pruned [s] | ratio | max rel. output difference |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['spindles']} | {r['states_full']} → {r['states_pruned']} "
            f"| {r['assemble_full']:.3f} / {r['assemble_pruned']:.3f} "
            f"| {r['assemble_full'] / r['assemble_pruned']:.2f}× "
            f"| {r['simulate_full']:.3f} / {r['simulate_pruned']:.3f} "
            f"| {r['simulate_full'] / r['simulate_pruned']:.1f}× "
            f"| {r['max_rel_error']:.1e} |")
    ok = all(r["max_rel_error"] <= 1e-9 for r in rows)
    lines += [
        "",
        f"Outputs agree to 1e-9: **{'yes' if ok else 'NO'}**. Pruning keeps the same equations "
        "for what the outputs need, so the difference is only the integrator's step sequence "
        "(the full model's error control also watches the other spindles). Skipped in the "
        f"largest case: {'; '.join(x.split(':')[0] for x in rows[-1]['skipped'])}.",
    ]
    return "\n".join(lines)


def section(quick: bool, *_args, **_kwargs):
    """:class:`bench.common.Section` for ``bench.run_all``."""
    from bench.common import Section

    return Section("Pruning to the requested outputs", run(quick))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(run(parser.parse_args().quick))
