"""``make demo``: the built-in default scene.

A PMSM with field-oriented speed control spins a spindle shaft running in a Z-type 61905/61907
double-layer bearing (torque fidelity, Palmgren friction, ISO VG 32 oil) up to 10 000 r/min,
then a load torque step hits the shaft. The demo writes the time series (CSV), plots of speeds,
speed ratio and torques, and a steady speed-ratio sweep of the three pairings of models.md
section A against the closed-form theories.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import casadi as ca
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from bearingsim.assembler import assemble  # noqa: E402
from bearingsim.assemblies import double_layer_bearing, motor_drive  # noqa: E402
from bearingsim.physics.double_layer_theory import (  # noqa: E402
    speed_ratio_palmgren,
    speed_ratio_pure_rolling,
)
from bearingsim.simulation import simulate  # noqa: E402
from bearingsim.studies.double_layer import speed_ratio_sweep  # noqa: E402
from bearingsim.units import rad_s_to_rpm, rpm_to_rad_s  # noqa: E402

PAIRINGS = (("61905", "61907", "Z"), ("61905", "61908", "Z"), ("61905", "61909", "I"))


def spin_up(out: Path) -> dict:
    """Motor spin-up with a load step; returns a summary."""
    w_max = rpm_to_rad_s(10_000)
    drive = motor_drive(
        double_layer_bearing("61905", "61907", drive="flange"), motor="pmsm",
        speed_ref=lambda t: w_max * ca.fmin(t / 1.0, 1.0),
        load_torque=lambda t: -0.05 * ca.if_else(t >= 3.0, 1.0, 0.0),
        motor_options={"kp_w": 0.05, "ki_w": 0.5},
    )
    t0 = time.perf_counter()
    system = assemble(drive)
    t_asm = time.perf_counter() - t0
    res = simulate(system, 5.0, rtol=1e-7, atol=1e-9, n_points=1001)
    res.to_csv(out / "spin_up.csv", ["shaft.w", "bearing.middle.w", "bearing.Rs",
                                     "bearing.M_shaft", "motor.motor.tau_em", "motor.motor.iq"])
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 7))
    axes[0].plot(res.t, rad_s_to_rpm(res["shaft.w"]), label="shaft n_i")
    axes[0].plot(res.t, rad_s_to_rpm(res["bearing.middle.w"]), label="middle ring n_z")
    axes[0].set_ylabel("speed [r/min]")
    axes[0].legend()
    axes[1].plot(res.t, res["bearing.Rs"], label="simulated")
    axes[1].axhline(speed_ratio_palmgren("61905", "61907"), ls="--", c="k",
                    label="Palmgren Dp^4.5 law")
    axes[1].axhline(speed_ratio_pure_rolling("61905", "61907"), ls=":", c="gray",
                    label="pure rolling")
    axes[1].set_ylabel("Rs = n_z / n_i [1]")
    axes[1].set_ylim(0, 0.6)
    axes[1].legend(fontsize=8)
    axes[2].plot(res.t, res["motor.motor.tau_em"], label="motor torque")
    axes[2].plot(res.t, -res["bearing.M_shaft"], label="bearing friction torque")
    axes[2].set_ylabel("torque [N m]")
    axes[2].set_xlabel("time [s]")
    axes[2].legend()
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle("PMSM spin-up of a 61905/61907 Z-type double-layer bearing")
    fig.tight_layout()
    fig.savefig(out / "spin_up.png", dpi=120)
    plt.close(fig)
    return {
        "assemble_s": round(t_asm, 3),
        "simulate_s": round(res.stats["wall_time"], 3),
        "states": system.n_states,
        "final_shaft_rpm": round(float(rad_s_to_rpm(res.final("shaft.w"))), 1),
        "final_Rs": round(res.final("bearing.Rs"), 5),
        "final_friction_torque_Nm": round(-res.final("bearing.M_shaft"), 5),
    }


def ratio_sweep(out: Path) -> dict:
    """Steady Rs against shaft speed for the three pairings, with the theories."""
    speeds = rpm_to_rad_s(np.linspace(200.0, 10_000.0, 50))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    table = {}
    for (inner, outer, structure), color in zip(PAIRINGS, ("C0", "C1", "C2"), strict=True):
        sweep = speed_ratio_sweep(speeds, inner, outer, structure=structure)
        ax.plot(rad_s_to_rpm(speeds), sweep.rs, c=color, label=f"{inner}/{outer} torque model")
        pal = speed_ratio_palmgren(inner, outer)
        pr = speed_ratio_pure_rolling(inner, outer)
        ax.axhline(pal, c=color, ls="--", lw=0.8)
        ax.axhline(pr, c=color, ls=":", lw=0.8)
        table[f"{inner}/{outer}"] = {"pure_rolling": round(pr, 4), "palmgren": round(pal, 4),
                                     "torque_model_10000rpm": round(float(sweep.rs[-1]), 4)}
    ax.set_xlabel("shaft speed [r/min]")
    ax.set_ylabel("Rs [1]")
    ax.set_title("Steady speed ratio (dashed: Dp^4.5 law, dotted: pure rolling)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "speed_ratio_sweep.png", dpi=120)
    plt.close(fig)
    return table


def main(argv: list[str] | None = None) -> None:
    """Run the demo and write its outputs."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="demo_output", help="output folder")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    summary = {"spin_up": spin_up(out), "speed_ratio": ratio_sweep(out)}
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary, indent=2))
    print(f"plots and data written to {out.resolve()}")


if __name__ == "__main__":
    main()
