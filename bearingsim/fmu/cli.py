"""Command line: ``bearingsim export-fmu pkg.module:factory model.fmu [options]``.

The factory is ``pkg.module:callable`` (importable, the current folder included),
``path/to/file.py:callable`` or the name of an assembly that scenes know (``bearingsim list``:
built-in or a plug-in's); ``--arg NAME=VALUE`` passes keyword arguments to it (values read as
TOML values: numbers, true/false, quoted or bare text, lists). For an assembly name the
arguments are its scene arguments, plus ``fidelity`` (default: its highest automatic level),
and the FMU's outputs default to the ones its scenes report. ``bearingsim export-fmu`` also
takes a scene file or built-in scene (:mod:`bearingsim.scenes.scene_fmu`, given as
``cli_export``'s ``scene_fmu``).
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from bearingsim.errors import BearingsimError, ParameterError, SimulationError

__all__ = ["build_parser", "cli_export", "scene_outputs"]


def _assignment(text: str) -> tuple[str, float]:
    """NAME=VALUE of a parameter start value: a number."""
    name, value = _input_assignment(text)
    if isinstance(value, str):
        raise argparse.ArgumentTypeError(f"{name}: {value!r} is not a number")
    return name, value


def _input_assignment(text: str) -> tuple[str, float | str]:
    """NAME=VALUE of an input start value: a number, or a number with a unit (``3000rpm``),
    converted and checked by :func:`~bearingsim.fmu.export.export_fmu`."""
    name, sep, value = text.partition("=")
    if not sep:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    try:
        return name.strip(), float(value)
    except ValueError:
        return name.strip(), value.strip()


def _factory_argument(text: str) -> tuple[str, Any]:
    name, sep, value = text.partition("=")
    if not sep or not name.strip().isidentifier():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE with a Python name, got {text!r}")
    try:
        parsed = tomllib.loads(f"v = {value.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()  # bare text, e.g. motor=pmsm
    return name.strip(), parsed


def _csv(text: str) -> list[str]:
    return [s.strip() for s in text.split(",") if s.strip()]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``export-fmu``.

    Returns
    -------
    argparse.ArgumentParser
        The parser of its command line.
    """
    from bearingsim.fmu.model_c import STEPPERS

    parser = argparse.ArgumentParser(
        prog="bearingsim export-fmu",
        description="Export an assembly as an FMU (FMI 2.0 or 3.0, Linux x86_64).",
    )
    parser.add_argument("factory", help="pkg.module:callable or path/to/file.py:callable "
                                        "returning an assembly or a System, an assembly "
                                        "name (bearingsim list), or a scene file or built-in "
                                        "scene (its assembly, level, outputs, parameters and "
                                        "constant inputs)")
    parser.add_argument("output", help="path of the .fmu to write")
    parser.add_argument("--outputs", type=_csv, default=None,
                        help="comma-separated dotted names of the outputs (default: for an "
                        "assembly name, the outputs its scenes report; else every variable)")
    parser.add_argument("--kinds", type=_csv, default=["ME", "CS"],
                        help="ME, CS or ME,CS (default)")
    parser.add_argument("--name", default=None, help="model name (default: the assembly's)")
    parser.add_argument("--param", type=_assignment, action="append", default=[],
                        metavar="NAME=VALUE", help="parameter start value (repeatable)")
    parser.add_argument("--input", type=_input_assignment, action="append", default=[],
                        metavar="NAME=VALUE",
                        help="input start value, a number in the input's unit or with a unit "
                             "(3000rpm); checked against its range (repeatable)")
    parser.add_argument("--arg", type=_factory_argument, action="append", default=[],
                        metavar="NAME=VALUE", help="keyword argument of the factory, e.g. "
                        "motor=pmsm or inner=\"61905\" (repeatable; TOML values)")
    parser.add_argument("--fmi-version", default="2.0", choices=["2.0", "3.0"],
                        help="FMI version (default 2.0)")
    parser.add_argument("--platforms", type=_csv, default=[],
                        help="cross-built binaries besides Linux x86-64, UNTESTED: "
                        "linux-aarch64, darwin-x86_64, darwin-aarch64, windows-x86_64 (aarch64: "
                        "FMI 3.0 only; needs pip install ziglang)")
    parser.add_argument("--stepper", default=STEPPERS[0], choices=list(STEPPERS),
                        help="co-simulation stepper (default auto: bdf, the BDF of "
                        "compiled_bdf, for models of many states, else ros34pw2, a "
                        "Rosenbrock-W method that reuses the Jacobian; rodas3 evaluates it at "
                        "every step)")
    return parser


def scene_outputs(spec, model, fidelity: str) -> list[str]:
    """The outputs a scene of this assembly reports at ``fidelity``: its default outputs that
    the model at that level has, else the plain names its output table assigns to that level
    (the 6304 ball level: ``w_cage``, ``slip``); inputs are never outputs.

    Parameters
    ----------
    spec : AssemblySpec
        The assembly's scene description.
    model : Component
        The assembly built at ``fidelity``.
    fidelity : str
        Its level.

    Returns
    -------
    list of str
        Dotted names (empty when the scene names none the model has).
    """
    from bearingsim.language.declarations import Input, Parameter

    declared = {f"{c.path}.{n}" if c.path else n: d
                for c in model.walk() for n, d in c.declarations.items()}
    reported = {n for n, d in declared.items() if not isinstance(d, (Input, Parameter))}
    names = [n for n in spec.default_outputs if n in reported]
    return names or [pattern for pattern, level in spec.output_fidelity
                     if level == fidelity and pattern in reported]


def _from_registry(name: str, kwargs: dict[str, Any]):
    """The assembly a scene would build from ``name`` and the arguments ``kwargs``, and the
    outputs such a scene reports (None when no assembly has that name)."""
    from bearingsim.assemblies.registry import REGISTRY

    if name not in REGISTRY:
        return None
    spec = REGISTRY[name]
    kwargs = dict(kwargs)
    fidelity = kwargs.pop("fidelity", spec.auto_fidelities[-1])
    unknown = sorted(set(kwargs) - set(spec.args))
    if unknown:
        raise ParameterError(f"{name} has no argument {', '.join(unknown)}; "
                             f"arguments: {', '.join(spec.args)}, fidelity")
    if fidelity not in spec.fidelities:
        raise ParameterError(f"{fidelity!r} is not a fidelity of {name}; "
                             f"fidelities: {', '.join(spec.fidelities)}")
    texts = sorted(k for k, v in kwargs.items()
                   if spec.args[k].kind == "signal" and isinstance(v, str))
    if texts:
        raise ParameterError(f"{name}: give {', '.join(texts)} as a number (an "
                             "expression of t is for scenes; the FMU's inputs vary in time)")
    try:
        model = spec.build(spec.with_defaults(kwargs), fidelity)
        return model, scene_outputs(spec, model, fidelity)
    except BearingsimError as exc:  # the assembly's own name said once
        raise ParameterError(f"{name}: {str(exc).removeprefix(f'{name}: ')}") from None


def _load(spec: str, kwargs: dict[str, Any]):
    """The model a factory or assembly name gives, and its default outputs (None: every
    variable)."""
    if ":" not in spec:
        found = _from_registry(spec, kwargs)
        if found is not None:
            return found
    module, sep, attr = spec.rpartition(":")
    if not sep or not module or not attr:
        raise ParameterError(f"expected a scene file (*.toml) or built-in scene, an "
                         f"assembly name (bearingsim list), pkg.module:callable or "
                         f"file.py:callable, got {spec!r}")
    if module.endswith(".py"):
        path = Path(module)
        if not path.is_file():
            raise ParameterError(f"no file {module}")
        spec_obj = importlib.util.spec_from_file_location(path.stem, path)
        obj = importlib.util.module_from_spec(spec_obj)
        try:
            spec_obj.loader.exec_module(obj)
        except Exception as exc:  # noqa: BLE001 - report any failure of the user's file
            raise ParameterError(f"cannot load {module}: {exc}") from None
    else:
        if os.getcwd() not in sys.path:
            sys.path.insert(0, os.getcwd())  # modules in the current folder, as python -m does
        try:
            obj = importlib.import_module(module)
        except ImportError as exc:
            raise ParameterError(f"cannot import {module}: {exc}") from None
    for part in attr.split("."):
        if not hasattr(obj, part):
            raise ParameterError(f"{module} has no attribute {attr!r}")
        obj = getattr(obj, part)
    if not callable(obj):
        if kwargs:
            raise ParameterError(f"{attr} is not callable, so --arg cannot be given")
        return obj, None
    try:
        return obj(**kwargs), None
    except TypeError as exc:
        raise ParameterError(f"{attr}({', '.join(f'{k}={v!r}' for k, v in kwargs.items())})"
                             f" failed: {exc}") from None


def cli_export(argv: Sequence[str] | None = None,
               scene_fmu: Callable[[str], Any] | None = None) -> int:
    """Run ``export-fmu`` with command-line arguments.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name; default ``sys.argv[1:]``.
    scene_fmu : callable, optional
        ``scene_fmu(factory)`` -> the model, outputs, input and parameter start values and
        notes of a scene file or built-in scene, or None for any other factory
        (:func:`bearingsim.scenes.scene_fmu.scene_fmu`, given by ``bearingsim export-fmu``:
        the scenes are a layer above the FMU export).

    Returns
    -------
    int
        Exit status: 0 on success; as the other commands, 2 for bad input and 1 for a build
        that failed (no C compiler), the reason on standard error after ``bearingsim
        export-fmu:``.
    """
    from bearingsim.simulation.c_compiler import CompileError

    args = build_parser().parse_args(argv)
    try:
        path = _export(args, scene_fmu)
    except BearingsimError as exc:  # as the other commands: 2 for bad input, 1 for a failure
        print(f"bearingsim export-fmu: {exc}", file=sys.stderr)
        return 1 if isinstance(exc, (SimulationError, CompileError)) else 2
    print(path)
    return 0


def _export(args: argparse.Namespace, scene_fmu: Callable[[str], Any] | None) -> Path:
    """:func:`cli_export` after parsing: the FMU written."""
    from bearingsim.fmu.export import export_fmu

    inputs, parameters = dict(args.input), dict(args.param)
    scene = scene_fmu(args.factory) if scene_fmu is not None else None
    if scene is not None:
        if args.arg:
            raise ParameterError("a scene's assembly takes its arguments from the scene's "
                                 "[assembly]; --arg is for a factory or an assembly name")
        model, default_outputs = scene.model, scene.outputs
        inputs, parameters = {**scene.inputs, **inputs}, {**scene.parameters, **parameters}
        for note in scene.notes:
            print(f"bearingsim export-fmu: {note}", file=sys.stderr)
    else:
        model, default_outputs = _load(args.factory, dict(args.arg))
    return export_fmu(
        model, args.output, inputs=inputs,
        outputs=args.outputs if args.outputs is not None else default_outputs,
        parameters=parameters, fmi_version=args.fmi_version, kinds=args.kinds,
        model_name=args.name, stepper=args.stepper, platforms=args.platforms,
    )
