"""Command line: ``bearingsim run | validate | sweep | cache | list | demo | export-fmu``.

Exit status: 0 success; 1 a simulation (or a sweep point) or a plot failed; 2 an invalid scene,
command line or a file that cannot be read or written.
"""

from __future__ import annotations

import argparse
import inspect
import math
import os
import re
import signal
import sys
import warnings

__all__ = ["main", "printable"]


def _components() -> dict[str, list[str]]:
    """Component classes defined in each ``bearingsim.components`` module."""
    import importlib
    import pkgutil

    import bearingsim.components as pkg
    from bearingsim.language import Component

    out: dict[str, list[str]] = {}
    for info in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + "."):
        try:
            mod = importlib.import_module(info.name)
        except Exception:  # noqa: BLE001 - a module being written must not break `list`
            continue
        names = [n for n, obj in vars(mod).items()
                 if inspect.isclass(obj) and issubclass(obj, Component)
                 and obj.__module__ == mod.__name__ and not n.startswith("_")]
        if names:
            out[info.name.removeprefix(pkg.__name__ + ".")] = sorted(names)
    return out


_TERMINAL_CODES = re.compile(r"\x1b(\[[0-?]*[ -/]*[@-~]|\][^\x07\x1b]*(\x07|\x1b\\)?|.)?"
                             r"|\x9b[0-?]*[ -/]*[@-~]")
"""ANSI/VT sequences: CSI (colours, cursor moves), OSC (window title) and two-byte escapes."""
_CONTROLS = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f\u200b-\u200f\u202a-\u202e\u2066-\u2069]")


def printable(text: object) -> str:
    """``text`` without terminal escape sequences and control characters (newlines and tabs
    kept): user text (a scene title, a file name, an error quoting them) cannot move the
    cursor, recolour or retitle the terminal.

    Parameters
    ----------
    text : object
        Anything; its ``str``.

    Returns
    -------
    str
        The text without escape sequences and control characters.
    """
    return _CONTROLS.sub("", _TERMINAL_CODES.sub("", str(text)))


def _say(text: object, err: bool = False) -> None:
    print(printable(text), file=sys.stderr if err else sys.stdout)


def _warning_printer(command: str):
    """A ``warnings.showwarning`` that prints a warning as a line of the command
    (``bearingsim run: warning: SpeedLimitWarning: ...``) on standard error, each text once,
    instead of Python's file, line number and source line."""
    shown: set[str] = set()

    def show(message, category, filename, lineno, file=None, line=None) -> None:  # noqa: ARG001
        text = f"{category.__name__}: {message}"
        if text not in shown:
            shown.add(text)
            _say(f"bearingsim {command}: warning: {text}", err=True)

    return show


LIST_SECTIONS = ("assemblies", "components", "bearings", "lubricants", "scenes")


def _bearing_row(g) -> str:
    """One catalogue bearing: dimensions, ball set, angle, ratings, speeds, preload classes."""
    from bearingsim.units import rad_s_to_rpm

    c, c0 = g.dynamic_load_rating, g.static_load_rating
    rating = "C/C0 -" if c is None else f"C/C0 {c * 1e-3:5.2f}/{(c0 or 0.0) * 1e-3:5.2f} kN"
    speeds = ("" if g.limiting_speed is None else
              f"  n_lim {rad_s_to_rpm(g.limiting_speed):6.0f} r/min")
    preload = ("" if g.preload is None else
               f"  preload L/M/H {g.preload.light:g}/{g.preload.medium:g}/{g.preload.heavy:g} N")
    return (f"  {g.designation:8s} d={g.bore * 1e3:5.1f} D={g.outside_diameter * 1e3:5.1f} "
            f"B={g.width * 1e3:4.1f} mm  Z={g.ball_count:2d} Dw={g.ball_diameter * 1e3:6.3f} mm"
            f"  dm={g.pitch_diameter * 1e3:6.2f} mm  a={math.degrees(g.contact_angle):4.1f} deg"
            f"  {rating}{speeds}{preload}")


def _roller_bearing_row(g) -> str:
    """One catalogue roller bearing: dimensions, roller set, ratings, limiting speed."""
    from bearingsim.units import rad_s_to_rpm

    return (f"  {g.designation:8s} d={g.bore * 1e3:5.1f} D={g.outside_diameter * 1e3:5.1f} "
            f"B={g.width * 1e3:4.1f} mm  Z={g.roller_count:2d} Dw={g.roller_diameter * 1e3:5.2f}"
            f" Lwe={g.roller_length * 1e3:5.2f} mm  dm={g.pitch_diameter * 1e3:6.2f} mm  C/C0 "
            f"{g.dynamic_load_rating * 1e-3:5.1f}/{g.static_load_rating * 1e-3:5.1f} kN  n_lim "
            f"{rad_s_to_rpm(g.limiting_speed):6.0f} r/min")


def _list(args: argparse.Namespace) -> int:
    from bearingsim.catalog import get_bearing, list_bearings
    from bearingsim.catalog.rollers import get_roller_bearing, list_roller_bearings
    from bearingsim.physics.lubricant import known_lubricants
    from bearingsim.scenes.library import builtin_scenes
    from bearingsim.scenes.registry import REGISTRY

    shown = LIST_SECTIONS if args.what == "all" else (args.what,)
    pattern = (args.filter or "").lower()

    def keep(name: str) -> bool:
        return pattern in name.lower()

    if "assemblies" in shown:
        print("assemblies (scene [assembly] name):")
        for spec in REGISTRY.values():
            if not keep(spec.name):
                continue
            print(f"  {spec.name}: {spec.description}")
            if spec.fidelity_arg is not None:
                print(f"    fidelity: auto, {', '.join(spec.fidelities)}")
            print("    arguments:")
            for name, arg in spec.args.items():
                value = arg.default
                default = ("" if value is None else "; default " + (
                    ", ".join(map(str, value)) if isinstance(value, (list, tuple)) else str(value)))
                print(f"      {name}: {arg.doc}; {arg.allowed}{default}")
            print(f"    default outputs: {', '.join(spec.default_outputs)}")
            post = spec.post(spec.with_defaults({}))
            if post:
                print(f"    post-processed outputs: {', '.join(post)}")
    if "components" in shown:
        print("components:")
        for module, names in _components().items():
            names = [n for n in names if keep(n)]
            if names:
                print(f"  {module}: {', '.join(names)}")
    if "bearings" in shown:
        print("bearings:")
        for d in list_bearings():
            if keep(d):
                print(_bearing_row(get_bearing(d)))
        rollers = [d for d in list_roller_bearings() if keep(d)]
        if rollers:
            print("cylindrical roller bearings (cylindrical_roller_bearing, spindle):")
            for d in rollers:
                print(_roller_bearing_row(get_roller_bearing(d)))
    if "lubricants" in shown:
        print("lubricants: " + ", ".join(n for n in known_lubricants() if keep(n)))
    if "scenes" in shown:
        print("built-in scenes (bearingsim run NAME): "
              + ", ".join(n for n in builtin_scenes() if keep(n)))
    return 0


def _demo(args: argparse.Namespace) -> int:
    from bearingsim.scenes.library import DEMO_SCENES, builtin_scene_path

    for name in DEMO_SCENES:
        _run(argparse.Namespace(scene=builtin_scene_path(name), out=args.out,
                                overwrite=args.overwrite, no_progress=args.no_progress,
                                allow_path=[]))
    return 0


def _run(args: argparse.Namespace) -> int:
    from bearingsim.scenes import run_scene
    from bearingsim.scenes.runner import console_lines

    run = run_scene(args.scene, out=args.out, overwrite=args.overwrite,
                    progress=False if args.no_progress else None, allow_paths=args.allow_path)
    s = run.summary
    _say(f"{s['title']}: {s['assembly']} at fidelity {s['fidelity']['chosen']} "
          f"({s['fidelity']['reason']})")
    for text in s["fidelity"].get("rejected", []):
        _say(f"  rejected {text}")
    _say(f"  {s['system']['states']} states; "
         + ", ".join(f"{k} {v:.2f} s" for k, v in s["timings_s"].items()))
    for kind, items in s.get("skipped", {}).items():
        for item in items:
            text = item if isinstance(item, str) else f"{item['name']}: {item['note']}"
            _say(f"  skipped ({kind}): {text}")
    for line in console_lines(s):
        _say(line)
    result = getattr(run, "result", None)
    for name, echo in (result.input_echo() if result is not None else {}).items():
        _say(f"  input {name} = {echo['shown']} at t_end")
    for f in run.files:
        _say(f"  wrote {f}")
    for failure in s.get("plot_failures", []):
        _say(f"bearingsim run: plot failed: {failure['plot']}: {failure['error']} (the "
             f"simulation succeeded; its CSV and summary are written)", err=True)
    return 1 if s.get("plot_failures") or s.get("failed") else 0


def _validate(args: argparse.Namespace) -> int:
    from bearingsim.scenes import validate_scene

    if args.variables:
        return _variables(args)
    prep = validate_scene(args.scene, assemble_model=not args.no_assemble,
                          allow_paths=args.allow_path)
    if args.no_assemble:
        _say(f"{args.scene}: valid ({prep.assembly}; names not checked against the model)")
        return 0
    modes = prep.scene.analysis == "modes"  # its outputs are modes, not the model's outputs
    _say(f"{args.scene}: valid; {prep.spec.name} at fidelity {prep.fidelity or '-'} "
          f"({prep.fidelity_reason}); {prep.system.n_states} states; "
          + (f"modes {', '.join(prep.scene.outputs) or '(every mode)'}" if modes
             else "outputs " + ", ".join(prep.outputs)))
    for item in prep.system.skipped:
        _say(f"  pruned: {item}")
    for name in prep.post:
        _say(f"  post-processed after the integration: {name}")
    return 0


def _variables(args: argparse.Namespace) -> int:
    """``bearingsim validate --variables``: the names a scene's outputs may ask for."""
    from bearingsim.scenes import load_scene
    from bearingsim.scenes.scene_variables import model_variables

    scene = load_scene(args.scene, args.allow_path)
    listed = model_variables(scene)
    if listed.columns:  # what a statics or modes scene's outputs name, not the variables
        _say(f"{scene.analysis} columns (this scene's outputs name these):")
        for name, unit, description in listed.columns:
            _say(f"  {name} [{unit or '-'}]: {description}")
    _say(f"{scene.assembly} at fidelity {listed.fidelity}: {len(listed.variables)} variables")
    for name, unit, description in listed.variables:
        _say(f"  {name} [{unit or '-'}]: {description}")
    if listed.post:
        _say("post-processed (computed after the run):")
        for name, unit, description in listed.post:
            _say(f"  {name} [{unit or '-'}]: {description}")
    if listed.parameters:
        from bearingsim.units import engineering

        _say("parameters ([parameters] sets them, a sweep varies them as parameters.<name>):")
        for name, unit, value, allowed, description in listed.parameters:
            shown = unit if unit not in ("", "1") else "-"
            _say(f"  {name} [{shown}]: {description}; {engineering(value, unit, both=True)}"
                 + (f"; {allowed}" + (f" {shown}" if shown != "-" else "") if allowed else ""))
    return 0


def _sweep(args: argparse.Namespace) -> int:
    if args.scheduler is None:  # the LocalCluster's workers import meanwhile, on another core
        from bearingsim.sweep_preloads import learned_preloads, scene_file
        from bearingsim.sweep_server import start_worker_server

        start_worker_server(learned_preloads(scene_file(args.scene)))
    from bearingsim.scenes.sweep import (
        SweepError,
        crossed_points,
        describe_failures,
        describe_points,
        grid_points,
        parse_sample,
        run_sweep,
        sample_points,
    )
    from bearingsim.scenes.sweep_grid import parse_grid

    if not args.grid and not args.sample:
        raise SweepError("give at least one --grid key=v1,v2,... or --sample key=low:high")
    points = grid_points(parse_grid(args.grid)) if args.grid else [{}]
    if args.sample:
        samples = sample_points(parse_sample(args.sample), args.samples, args.seed,
                                method=args.sampler, scramble=not args.no_scramble)
        points = crossed_points(points, samples)
    from bearingsim.scenes import load_scene
    from bearingsim.scenes.tables import scene_output_folder

    scene = load_scene(args.scene, args.allow_path)
    out = args.out if args.out is not None else scene_output_folder(scene)
    try:
        res = run_sweep(scene, points, scheduler=args.scheduler, n_workers=args.workers,
                        out=out, progress=False if args.no_progress else None, resume=args.resume,
                        timeout=args.timeout, chunk=args.chunk, overwrite=args.overwrite)
    except KeyboardInterrupt:
        _say(f"bearingsim sweep: interrupted; the finished points are in {out}; add --resume "
             "to run the others", err=True)
        return 130
    ran = len(res.rows) - res.resumed
    _say(describe_points(res)
         + (f" ({res.resumed} from the earlier run)" if res.resumed else "")
         + (f"; {res.models_built} model(s) built and sent to the workers, up to "
            f"{res.chunk_size} point(s) per batch" if ran else "; nothing left to run")
         + f"; {res.wall_s:.1f} s")
    if res.failures:
        _say(describe_failures(res), err=True)
    for f in res.files:
        _say(f"  wrote {f}")
    for failure in res.plot_failures:
        _say(f"bearingsim sweep: plot failed: {failure['plot']}: {failure['error']} (the "
             f"table and summary are written)", err=True)
    return 1 if res.failures or res.plot_failures else 0


def _cache(args: argparse.Namespace) -> int:
    from bearingsim.assembler.cache import cache_info, clear_cache
    from bearingsim.cache_paths import cache_root

    root = cache_root()
    if root.exists() and not root.is_dir():  # a misspelt $BEARINGSIM_CACHE, say
        _say(f"bearingsim cache: {root} is not a folder: nothing is kept there, every run "
             "assembles anew; set $BEARINGSIM_CACHE to a folder", err=args.action == "clear")
        return 2 if args.action == "clear" else 0
    info = clear_cache(root) if args.action == "clear" else cache_info(root)
    verb = "removed" if args.action == "clear" else "holds"
    print(f"{info.root} {verb}: {info.systems} assembled system(s), "
          f"{info.systems_bytes / 1e6:.1f} MB; {info.libraries} compiled librar"
          f"{'y' if info.libraries == 1 else 'ies'}, {info.libraries_bytes / 1e6:.1f} MB; "
          f"unit definitions, {info.units_bytes / 1e6:.1f} MB")
    if args.action != "clear":
        from bearingsim.cache_budget import BUDGET_VARIABLE, budget_bytes

        print(f"budget for the systems and libraries: {budget_bytes() / 1e6:.1f} MB "
              f"(${BUDGET_VARIABLE}; the least recently used go first beyond it)")
    return 0


def _folder(text: str) -> str:
    """An output folder given on the command line: not empty (``--out "$UNSET"`` wrote into
    the current folder)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty folder name; give . for the current folder")
    return text


def _parser() -> argparse.ArgumentParser:
    from bearingsim import __version__
    from bearingsim.sweep_samplers import SAMPLERS  # (not the scenes package: see there)

    parser = argparse.ArgumentParser(prog="bearingsim", description="bearing system simulator")
    parser.add_argument("--version", action="version", version=f"bearingsim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    p_run = sub.add_parser("run", help="run a scene file: CSV, JSON summary and PNG plots")
    p_run.add_argument("scene", help="scene TOML file or built-in scene name (bearingsim list)")
    p_run.add_argument("--out", type=_folder,
                       help="output folder (default: the scene's output.folder)")
    p_run.add_argument("--overwrite", action="store_true",
                       help="replace the files of an earlier run of this scene in the folder")
    p_run.add_argument("--no-progress", action="store_true",
                       help="no progress bar (shown on a terminal for runs longer than 2 s)")
    p_val = sub.add_parser("validate", help="check a scene file without running it")
    p_sw = sub.add_parser("sweep", help="run a scene over a grid or sample (dask.distributed)")
    for p in (p_run, p_val, p_sw):
        p.add_argument("--allow-path", action="append", default=[], metavar="DIR",
                       help="let the scene read and write in DIR too (by default only inside "
                            "the scene file's folder); repeat for several")
    p_val.add_argument("scene", help="scene TOML file or built-in scene name (bearingsim list)")
    p_val.add_argument("--no-assemble", action="store_true",
                       help="only check the file, not its names against the model")
    p_val.add_argument("--variables", action="store_true",
                       help="list every variable of the scene's model (name [unit]: "
                            "description) and the post-processed quantities, the names "
                            "'outputs' may ask for, and the parameters [parameters] may set "
                            "(value and range); the scene's outputs are not checked")
    p_sw.add_argument("scene", help="scene TOML file or built-in scene name (bearingsim list)")
    p_sw.add_argument("--grid", action="append", default=[], metavar="KEY=V1,V2,...",
                      help="grid values of a key (inputs.X, parameters.X, initial.X, "
                           "simulation.X, assembly.X): numbers in SI units or with a unit "
                           "('2 kN'), names, expressions of t; repeat for a Cartesian "
                           "product; separate expressions with ';'")
    p_sw.add_argument("--sample", action="append", default=[], metavar="KEY=LOW:HIGH",
                      help="quasi-random sample of a numeric key, low and high in SI units "
                           "or with a unit ('1 kN:3 kN'; see --sampler)")
    p_sw.add_argument("--samples", type=int, default=8,
                      help="number of samples (default 8; Sobol: a power of two)")
    p_sw.add_argument("--seed", type=int, default=0, help="seed of the sample (default 0)")
    p_sw.add_argument("--sampler", choices=SAMPLERS, default="lhs",
                      help="Latin hypercube (default), LHS with optimal permutations, or Sobol "
                           "(scipy.stats.qmc)")
    p_sw.add_argument("--no-scramble", action="store_true",
                      help="unscrambled sample (LHS cell centres, Sobol from the origin)")
    p_sw.add_argument("--resume", action="store_true",
                      help="keep the rows of an earlier run of this sweep in the output folder "
                           "and run only the other points")
    p_sw.add_argument("--overwrite", action="store_true",
                      help="replace the files of an earlier sweep of this scene in the folder")
    p_sw.add_argument("--timeout", type=float, metavar="SECONDS",
                      help="time budget of one point: a point still running after it is "
                           "recorded as failed (default: the scene's simulation.timeout)")
    p_sw.add_argument("--chunk", type=int, metavar="N",
                      help="points per task (default: sized from one point measured first)")
    p_sw.add_argument("--scheduler", help="address of a dask scheduler (default: a "
                                          "LocalCluster)")
    p_sw.add_argument("--workers", type=int, default=2,
                      help="LocalCluster workers (default 2)")
    p_sw.add_argument("--out", type=_folder,
                      help="output folder (default: the scene's output.folder)")
    p_sw.add_argument("--no-progress", action="store_true",
                      help="no progress bar (shown on a terminal)")
    p_cache = sub.add_parser("cache", help="size of the cache of assembled systems and "
                             "compiled kernels ($BEARINGSIM_CACHE), or clear it")
    p_cache.add_argument("action", nargs="?", default="show", choices=("show", "clear"),
                         help="show (the default): what the cache holds and its size budget; "
                              "clear: delete it (rebuilt on the next runs)")
    p_list = sub.add_parser("list", help="assemblies, components, catalogue bearings, "
                            "lubricants and built-in scenes")
    p_list.add_argument("what", nargs="?", default="all", choices=("all", *LIST_SECTIONS),
                        help="one section (default: all)")
    p_list.add_argument("--filter", help="only names containing this text (any letter case)")
    p_demo = sub.add_parser("demo", help="run the built-in demo scenes, one per study question "
                            "(double-layer Rs against speed and load, duplex-pair modes against "
                            "preload, deep-groove life per duty condition) and a PMSM spin-up")
    p_demo.add_argument("--out", default="demo_output", type=_folder,
                        help="output folder (default demo_output)")
    p_demo.add_argument("--overwrite", action="store_true",
                        help="replace the files of an earlier demo run in the folder")
    p_demo.add_argument("--no-progress", action="store_true", help="no progress bar")
    p_exp = sub.add_parser("export-fmu", add_help=False,
                           help="export an assembly, or the model a scene runs, as an FMU")
    p_exp.add_argument("rest", nargs=argparse.REMAINDER)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bearingsim`` command.

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status (0 on success).
    """
    from bearingsim.errors import BearingsimError, SimulationError

    argv = sys.argv[1:] if argv is None else list(argv)
    command = argv[0] if argv and not argv[0].startswith("-") else "bearingsim"
    try:
        if command == "export-fmu":  # its own parser, its own --help
            from bearingsim.fmu import cli_export
            from bearingsim.scenes.scene_fmu import scene_fmu

            return cli_export(argv[1:], scene_fmu) or 0
        args = _parser().parse_args(argv)
        command = args.command
        handlers = {"list": _list, "demo": _demo, "run": _run,
                    "validate": _validate, "sweep": _sweep, "cache": _cache}
        with warnings.catch_warnings():  # warnings as lines of the command, each once
            warnings.showwarning = _warning_printer(args.command)
            status = handlers[args.command](args)
        sys.stdout.flush()  # here, where a closed pipe is caught, not at the exit
        return status
    except KeyboardInterrupt:  # Ctrl-C: outputs are written whole or not at all
        _say(f"bearingsim {command}: interrupted", err=True)
        return 130
    except SimulationError as exc:
        _say(f"bearingsim {command}: simulation failed: {exc}", err=True)
        return 1
    except BearingsimError as exc:
        _say(f"bearingsim {command}: {exc}", err=True)
        return 2
    except BrokenPipeError:  # a reader that stopped early (| head): quiet, as other tools
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 128 + signal.SIGPIPE
    except OSError as exc:  # a file the command reads or writes (folder missing, disk full)
        from bearingsim.files import os_reason

        where = f"{exc.filename}: " if exc.filename else ""
        _say(f"bearingsim {command}: {where}{os_reason(exc)}", err=True)
        return 2


if __name__ == "__main__":
    sys.exit(main())
