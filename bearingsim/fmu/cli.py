"""Command line: ``bearingsim export-fmu pkg.module:factory model.fmu [options]``."""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

__all__ = ["build_parser", "cli_export"]


def _assignment(text: str) -> tuple[str, float]:
    name, sep, value = text.partition("=")
    if not sep:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    try:
        return name.strip(), float(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{name}: {value!r} is not a number") from None


def _csv(text: str) -> list[str]:
    return [s.strip() for s in text.split(",") if s.strip()]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``export-fmu``."""
    parser = argparse.ArgumentParser(
        prog="bearingsim export-fmu",
        description="Export an assembly as an FMU (FMI 2.0, Linux x86_64).",
    )
    parser.add_argument("factory", help="pkg.module:callable returning an assembly or a System")
    parser.add_argument("output", help="path of the .fmu to write")
    parser.add_argument("--outputs", type=_csv, default=None,
                        help="comma-separated dotted names of the outputs")
    parser.add_argument("--kinds", type=_csv, default=["ME", "CS"],
                        help="ME, CS or ME,CS (default)")
    parser.add_argument("--name", default=None, help="model name (default: the assembly's)")
    parser.add_argument("--param", type=_assignment, action="append", default=[],
                        metavar="NAME=VALUE", help="parameter start value (repeatable)")
    parser.add_argument("--input", type=_assignment, action="append", default=[],
                        metavar="NAME=VALUE", help="input start value (repeatable)")
    parser.add_argument("--fmi-version", default="2.0", choices=["2.0", "3.0"],
                        help="FMI version (default 2.0)")
    return parser


def _load(spec: str):
    module, sep, attr = spec.partition(":")
    if not sep or not module or not attr:
        raise SystemExit(f"export-fmu: expected pkg.module:callable, got {spec!r}")
    try:
        obj = importlib.import_module(module)
    except ImportError as exc:
        raise SystemExit(f"export-fmu: cannot import {module}: {exc}") from None
    for part in attr.split("."):
        if not hasattr(obj, part):
            raise SystemExit(f"export-fmu: {module} has no attribute {attr!r}")
        obj = getattr(obj, part)
    return obj() if callable(obj) else obj


def cli_export(argv: Sequence[str] | None = None) -> int:
    """Run ``export-fmu`` with command-line arguments.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.

    Returns
    -------
    int
        Exit status (0 on success).
    """
    from bearingsim.errors import BearingsimError
    from bearingsim.fmu.export import export_fmu

    args = build_parser().parse_args(argv)
    model = _load(args.factory)
    try:
        path = export_fmu(
            model, args.output, inputs=dict(args.input), outputs=args.outputs,
            parameters=dict(args.param), fmi_version=args.fmi_version, kinds=args.kinds,
            model_name=args.name,
        )
    except BearingsimError as exc:
        print(f"export-fmu: {exc}", file=sys.stderr)
        return 1
    print(path)
    return 0
