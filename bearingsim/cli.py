"""Command line: ``bearingsim list | demo | export-fmu``."""

from __future__ import annotations

import argparse
import sys

__all__ = ["main"]


def _list(_: argparse.Namespace) -> int:
    from bearingsim.catalog import get_bearing, list_bearings
    from bearingsim.physics.lubricant import known_lubricants

    print("assemblies: double_layer_bearing (fidelity: kinematic, kinematic_approx, torque), "
          "motor_drive (motor: dc, pmsm)")
    print("components: rotational (Inertia, Spring, Damper, SpringDamper, Fixed, TorqueSource, "
          "SpeedSource, IdealGear, SpeedSensor, TorqueSensor), bearing_torque (PalmgrenBearing, "
          "SkfBearing, PureRollingLayer), motor (DCMotor, PMSM, DCMotorDrive, PMSMDrive)")
    print("bearings:")
    for d in list_bearings():
        g = get_bearing(d)
        print(f"  {d:8s} d={g.bore * 1e3:5.1f} D={g.outside_diameter * 1e3:5.1f} "
              f"B={g.width * 1e3:4.1f} mm  Z={g.ball_count:2d} Dw={g.ball_diameter * 1e3:6.3f} mm"
              f"  dm={g.pitch_diameter * 1e3:6.2f} mm")
    print("lubricants: " + ", ".join(known_lubricants()))
    return 0


def _demo(args: argparse.Namespace) -> int:
    from bearingsim.demo import main as demo_main

    demo_main(["--out", args.out])
    return 0


def _export(args: argparse.Namespace) -> int:
    from bearingsim.fmu import cli_export

    return cli_export(args.rest) or 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bearingsim`` command."""
    parser = argparse.ArgumentParser(prog="bearingsim", description="bearing system simulator")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("list", help="assemblies, components, catalogue bearings and lubricants")
    p_demo = sub.add_parser("demo", help="run the default scene and write its plots")
    p_demo.add_argument("--out", default="demo_output")
    p_exp = sub.add_parser("export-fmu", help="export an assembly as an FMU",
                           add_help=False)
    p_exp.add_argument("rest", nargs=argparse.REMAINDER)
    args = parser.parse_args(argv)
    handlers = {"list": _list, "demo": _demo, "export-fmu": _export}
    return handlers[args.command](args)


if __name__ == "__main__":
    sys.exit(main())
