"""Natural frequencies of a 7020 duplex pair (docs/studies.md, section B).

Reproduces the three studies of the source for 7020C, 7020A5 and 7020A at the light, medium and
heavy preload classes: frequencies against preload, against contact angle (one preload) and
against the ball position angle, plus a speed sweep with centrifugal and gyroscopic ball
effects. Writes ``duplex_7020_table.md`` and PNG plots into the output folder.

The shaft is the default :class:`~bearingsim.assemblies.duplex.ShaftSpec` (solid steel,
100 mm x 400 mm, rows 300 mm apart): the source does not give it.

Usage::

    python examples/duplex_7020.py [--out DIR] [--arrangement DF]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from bearingsim.physics.shaft_modes import MODE_NAMES  # noqa: E402
from bearingsim.studies.duplex import DuplexModel  # noqa: E402
from bearingsim.studies.duplex_sweep import plot_sweep, sweep  # noqa: E402
from bearingsim.units import deg, rpm_to_rad_s  # noqa: E402

DESIGNATIONS = ("7020C", "7020A5", "7020A")
LEVELS = ("light", "medium", "heavy")


def frequency_table(model: DuplexModel) -> tuple[str, dict]:
    """Markdown table of the five frequencies for every designation and preload class."""
    header = "| bearing | preload | preload [N] | " + " | ".join(MODE_NAMES) + " |"
    lines = [header, "|" + "---|" * (3 + len(MODE_NAMES))]
    data = {}
    for d in DESIGNATIONS:
        for level in LEVELS:
            modes = model.modes(preload=level, bearing=d)
            f = modes.by_name()
            data[(d, level)] = f
            force = model.preload_force(level, d)
            lines.append(f"| {d} | {level} | {force:g} | "
                         + " | ".join(f"{f[n]:.0f}" for n in MODE_NAMES) + " |")
    return "\n".join(lines), data


def main(argv: list[str] | None = None) -> int:
    """Run the studies; return the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("duplex_7020_out"))
    parser.add_argument("--arrangement", default="DF", choices=("DF", "DB", "DT"))
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    model = DuplexModel("7020C", args.arrangement)  # one system for all three bearings
    table, _ = frequency_table(model)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4), sharey=True)
    for ax, d in zip(axes, DESIGNATIONS, strict=True):
        plot_sweep(sweep(model, "preload", LEVELS, bearing=d, label=d), ax=ax)
        ax.set_title(f"{d} {args.arrangement}: frequencies vs preload")
    fig.tight_layout()
    fig.savefig(args.out / "frequencies_vs_preload.png", dpi=120)

    angles = deg(np.linspace(10.0, 35.0, 11))
    by_angle = sweep(model, "contact_angle", angles, preload=1270.0, label="1270 N")
    ax = plot_sweep(by_angle)
    ax.set_title(f"7020 {args.arrangement}: frequencies vs contact angle (preload 1270 N)")
    ax.figure.savefig(args.out / "frequencies_vs_contact_angle.png", dpi=120)

    psi = np.linspace(0.0, 2 * np.pi / 20, 9)
    by_psi = sweep(model, "ball_position_angle", psi, preload="light")
    ax = plot_sweep(by_psi)
    ax.set_title("7020C: frequencies vs ball position angle (light preload)")
    ax.figure.savefig(args.out / "frequencies_vs_ball_position.png", dpi=120)

    fast = DuplexModel("7020C", args.arrangement, {"speed_effects": True})
    speeds = rpm_to_rad_s(np.linspace(0.0, 12_000.0, 7))
    by_speed = sweep(fast, "speed", speeds, preload="light", label="Jones-Harris")
    ax = plot_sweep(by_speed)
    ax.set_title("7020C: frequencies vs speed (centrifugal and gyroscopic ball effects)")
    ax.figure.savefig(args.out / "frequencies_vs_speed.png", dpi=120)

    change = dict(zip(MODE_NAMES, by_angle.relative_change(), strict=True))
    text = [
        f"# 7020 duplex pair ({args.arrangement}): natural frequencies [Hz]", "", table, "",
        "Relative change over contact angles 10-35 deg at 1270 N: "
        + ", ".join(f"{k} {v:.1%}" for k, v in change.items()),
        "",
        "Largest relative change over ball position angles: "
        f"{by_psi.relative_change().max():.2e}",
        "",
        "Relative change over 0-12 000 r/min (Jones-Harris rows): "
        + ", ".join(f"{k} {v:.1%}" for k, v in zip(MODE_NAMES, by_speed.relative_change(),
                                                    strict=True)),
    ]
    (args.out / "duplex_7020_table.md").write_text("\n".join(text) + "\n", encoding="utf-8")
    print("\n".join(text))
    print(f"plots and table written to {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
