"""Speed distribution ratio of double-layer bearings (docs/studies.md, section A).

For the pairings 61905/61907 (Z), 61905/61908 (Z) and 61905/61909 (I) from 0 to 10 000 r/min:
pure rolling (exact and approximate), the Palmgren Dp^4.5 law, the torque-level simulation with
Palmgren and with SKF friction, and the four lubrication combinations (oil/oil, grease/grease,
oil/grease, grease/oil), all under a 200 N radial load. Writes plots and a table to the output
folder. With ``--dynamic``, also the ball-level (dynamic) ratio of 61905/61907 at a few speeds
for oil/oil and grease/oil (same base oil) under a 100 N axial load, next to the torque level
at that load (assembly about 2 min, then some 20-40 s per speed and lubrication).

    python examples/double_layer_speed_ratio.py --out out/double_layer [--dynamic]
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from bearingsim.assembler import assemble  # noqa: E402
from bearingsim.assemblies import double_layer_bearing  # noqa: E402
from bearingsim.physics.double_layer_theory import (  # noqa: E402
    design_report,
    speed_ratio_palmgren,
    speed_ratio_pure_rolling,
)
from bearingsim.physics.lubricant import Grease, Oil  # noqa: E402
from bearingsim.simulation import steady_state  # noqa: E402
from bearingsim.studies.double_layer import speed_ratio, speed_ratio_sweep  # noqa: E402
from bearingsim.units import rad_s_to_rpm, rpm_to_rad_s  # noqa: E402

PAIRINGS = (("61905", "61907", "Z"), ("61905", "61908", "Z"), ("61905", "61909", "I"))
OIL = Oil.from_iso_vg(32, method="oil_mist")
GREASE = Grease(Oil.from_iso_vg(100), fill_fraction=1.0 / 3.0)
LOADS = (200.0, 0.0)
"""Radial and axial load through both layers [N]; the SKF moments vanish without load."""
LUBRICATIONS = {"oil/oil": (OIL, OIL), "grease/grease": (GREASE, GREASE),
                "oil/grease": (OIL, GREASE), "grease/oil": (GREASE, OIL)}


DYNAMIC_SPEEDS_RPM = (1000.0, 2865.0, 5000.0)
DYNAMIC_LOADS = {"Fx": 0.0, "Fy": 0.0, "Fz": 100.0, "Mx": 0.0, "My": 0.0}
DYNAMIC_GREASE = Grease(Oil.from_iso_vg(32), fill_fraction=0.5)
"""Grease on the dynamic runs' base oil (ISO VG 32), so the swap is the ring drag's f0."""


def _torque_level_rs(lubrication, w: float) -> float:
    system = assemble(double_layer_bearing("61905", "61907", lubrication=lubrication))
    inputs = {"shaft_speed": w, "Fa": DYNAMIC_LOADS["Fz"]}
    x = steady_state(system, inputs=inputs)
    u = np.array([inputs.get(n, 0.0) for n in system.input_names])
    return float(system.observe(0.0, x, u, system.p0())["Rs"])


def dynamic_rows() -> list[list]:
    """Ball-level speed ratio of 61905/61907 at :data:`DYNAMIC_SPEEDS_RPM`, oil/oil and
    grease/oil, from runs at the torque level's ratio +- 5 % (``bracketed``: the result lies
    between them)."""
    oil = Oil.from_iso_vg(32, method="oil_mist")
    bearing = double_layer_bearing("61905", "61907", fidelity="dynamic", lubrication=(oil, oil),
                                   loads=DYNAMIC_LOADS, layer_options={"n_slices": 0})
    system = assemble(bearing, outputs=["Rs", "M_middle"])
    cases = {"oil/oil": ((oil, oil), None),
             "grease/oil": ((DYNAMIC_GREASE, oil),
                            {"inner_layer.ring_drag.f0": DYNAMIC_GREASE.palmgren_f0(
                                "deep_groove_ball")})}
    rows = []
    for label, (lubrication, parameters) in cases.items():
        for rpm in DYNAMIC_SPEEDS_RPM:
            w = float(rpm_to_rad_s(rpm))
            rs_torque = _torque_level_rs(lubrication, w)
            est = speed_ratio(bearing, system, w, (0.95 * rs_torque, 1.05 * rs_torque),
                                      parameters)
            rows.append([label, rpm, est.rs, rs_torque, est.bracketed])
            print(f"61905/61907 dynamic {label:<11s} {rpm:6g} r/min  Rs {est.rs:.4f}  "
                  f"(torque level {rs_torque:.4f})", flush=True)
    return rows


def main() -> None:
    """Run the study."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/double_layer")
    parser.add_argument("--points", type=int, default=40)
    parser.add_argument("--dynamic", action="store_true",
                        help="also the ball-level ratio at a few speeds (several minutes)")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    speeds = rpm_to_rad_s(np.linspace(250.0, 10_000.0, args.points))
    rows = []
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    for ax, (inner, outer, structure) in zip(axes, PAIRINGS, strict=True):
        rpm = rad_s_to_rpm(speeds)
        ax.axhline(speed_ratio_pure_rolling(inner, outer), c="gray", ls=":", label="pure rolling")
        ax.axhline(speed_ratio_pure_rolling(inner, outer, exact=False), c="gray", ls="-.",
                   label="Dp1/(Dp1+Dp2)")
        ax.axhline(speed_ratio_palmgren(inner, outer), c="k", ls="--", label="Dp^4.5 law")
        for model in ("palmgren", "skf"):
            for label, lub in LUBRICATIONS.items():
                if model == "skf" and label != "oil/oil":
                    continue
                sweep = speed_ratio_sweep(speeds, inner, outer, loads=LOADS,
                                          structure=structure, lubrication=lub,
                                          friction_model=model)
                ax.plot(rpm, sweep.rs, label=f"{model}, {label}")
                rows.append([inner, outer, f"torque ({model}), {label}", *sweep.rs[[0, -1]]])
        rep = design_report(inner, outer)
        ax.set_title(f"{inner}/{outer} ({structure}-type), PDR {rep.pitch_diameter_ratio:.2f}")
        ax.set_xlabel("shaft speed [r/min]")
        ax.grid(alpha=0.3)
        rows.append([inner, outer, "optimal (limiting speeds)", rep.rs_optimal, rep.rs_optimal])
    axes[0].set_ylabel("Rs = n_z / n_i [1]")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "speed_ratio_theories.png", dpi=120)
    plt.close(fig)
    if args.dynamic:
        with (out / "speed_ratio_dynamic.csv").open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["lubrication (inner/outer)", "shaft speed [r/min]", "Rs dynamic",
                        "Rs torque level (M0 + M1)", "bracketed"])
            w.writerows(dynamic_rows())
    with (out / "speed_ratio_table.csv").open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["inner", "outer", "model", "Rs at 250 r/min", "Rs at 10000 r/min"])
        w.writerows(rows)
    for r in rows:
        print(f"{r[0]}/{r[1]}  {r[2]:<34s} {r[3]:.4f}  {r[4]:.4f}")


if __name__ == "__main__":
    main()
