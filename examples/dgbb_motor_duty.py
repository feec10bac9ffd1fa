"""Motor duty cycle of a 6304 deep-groove ball bearing (docs/studies.md, section C).

For the four working conditions: cage slip ratio against time, ball-cage collision forces,
contact loads, minimum film thickness and L10 lives (Lundberg-Palmgren per contact, ISO 281,
ISO/TS 16281 from the load distribution), the start-up (slip settling time, collision force
level and peak, :func:`~bearingsim.studies.deep_groove.start_up`), plus the validation case
(500 N, 500 rad/s^2 spin-up, dry mu = 0.02). Writes ``dgbb_motor_duty.png`` and prints a
Markdown table. A short ``--ramp`` (2 ms) gives the hard start of docs/dgbb.md under which the
start-up trends of docs/studies.md, section C appear; ``--dry`` uses the study's dry friction.

Usage::

    python examples/dgbb_motor_duty.py [--t-end 0.1] [--ramp 0.02] [--dry]
"""

from __future__ import annotations

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from bearingsim.physics.ball_equilibrium import static_state  # noqa: E402
from bearingsim.physics.lubricant import Dry  # noqa: E402
from bearingsim.studies.deep_groove import (  # noqa: E402
    DUTY_CYCLE,
    VALIDATION,
    duty_condition,
    largest_pocket_force,
    post_process,
    start_up,
    validation_case,
)


def main(t_end: float, ramp: float, dry: bool) -> None:
    lubricant = Dry(VALIDATION["mu"]) if dry else "ISO VG 32"
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 9))
    rows = []
    for k, (n_rpm, load) in enumerate(DUTY_CYCLE, start=1):
        # saved every 10 us: the collisions last some 10 us
        res, design = duty_condition(k, t_end=t_end, ramp=ramp, n_slices=1,
                                     lubricant=lubricant, n_points=int(t_end / 1e-5) + 1)
        s = post_process(res, design, lubricant, load)
        su = start_up(res, design)
        label = f"{k}: {n_rpm:g} r/min, {load:g} N"
        axes[0].plot(res.t, res["slip"], label=label)
        axes[1].plot(res.t, largest_pocket_force(res, 7))
        axes[2].plot(res.t, np.max([res[f"inner[{j}].Q"] for j in range(7)], axis=0))
        rows.append([k, n_rpm, load, f"{s.slip:.4f}", f"{1e3 * su.slip_settling:.1f}",
                     f"{su.collision_level:.1f}", f"{su.collision_peak:.0f}",
                     f"{s.q_inner_max:.0f}", f"{s.pocket_force_max:.2f}",
                     f"{s.h_min * 1e6:.3f}", f"{s.life_lp:.0f}", f"{s.life_iso281:.0f}",
                     f"{s.life_ts16281:.0f}", f"{s.life_hours_iso281:.0f}"])
    axes[0].set_ylabel("cage slip [-]")
    axes[0].set_ylim(-0.1, 0.3)
    axes[1].set_ylabel("max ball-cage force [N]")
    axes[2].set_ylabel("max inner contact load [N]")
    axes[2].set_xlabel("time [s]")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig("dgbb_motor_duty.png", dpi=110)
    head = ["cond", "n [r/min]", "Fr [N]", "slip", "slip settles [ms]",
            "start-up collision level [N]", "peak [N]", "Qi max [N]",
            "pocket F max [N]", "h_min [um]", "L10 LP [Mrev]", "L10 ISO 281 [Mrev]",
            "L10r TS 16281 [Mrev]", "L10h ISO 281 [h]"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        print("| " + " | ".join(str(v) for v in r) + " |")
    res, design = validation_case(t_end=t_end)
    qs = static_state(design, {"Fx": VALIDATION["load"]}).q_inner.max()
    tail = res.t > 0.5 * t_end
    q_dyn = np.max([res[f"inner[{j}].Q"][tail] for j in range(7)])
    print(f"\nvalidation: max inner load {q_dyn:.1f} N (quasi-static {qs:.1f} N, "
          f"{100 * (q_dyn / qs - 1):+.1f} %), final slip {res.final('slip'):.4f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-end", type=float, default=0.1, help="simulated time [s]")
    parser.add_argument("--ramp", type=float, default=0.02, help="run-up time to speed [s]")
    parser.add_argument("--dry", action="store_true", help="dry friction mu = 0.02")
    args = parser.parse_args()
    main(args.t_end, args.ramp, args.dry)
