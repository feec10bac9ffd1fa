"""The scene model (a dataclass) and its TOML loader and validator.

A scene names an assembly and its arguments, a fidelity (or ``"auto"``), input signals
(numbers, expressions of ``t`` or CSV tables), parameter and initial-state overrides, the
requested outputs, the time span and solver settings, and the output folder. See
``docs/scenes.md`` for the format.

Errors name the key (dotted, e.g. ``simulation.rtol``), the line in the file and the allowed
values.

The scene's parts are in :mod:`.scene_types`, the checks of its sections in
:mod:`.scene_checks`; this module holds :class:`Scene` and its readers.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from bearingsim.assemblies.spec import AssemblySpec
from bearingsim.checks import ATOL_RANGE, RTOL_RANGE, checked
from bearingsim.files import (
    FileAccessError,
    open_regular,
    os_reason,
)
from bearingsim.scenes.library import builtin_scene_path, builtin_scenes
from bearingsim.scenes.lubricant_table import load_lubricants_table
from bearingsim.scenes.registry import REGISTRY
from bearingsim.scenes.scene_checks import (
    _analysis_options,
    _check_arg,
    _check_signals,
    _Collector,
    _flatten,
    _inputs,
    _number,
    _operating_points,
    _output,
    _quantity_value,
    _section,
    _settling,
    _unknown,
)
from bearingsim.scenes.scene_types import (
    ANALYSES,
    DEFAULT_TOLERANCE,
    MAX_SCENE_BYTES,
    TOP_KEYS,
    Output,
    SceneError,
    Settling,
    Simulation,
    TableInput,
    line_of,
)
from bearingsim.scenes.tables import load_bearings_files, scene_folder
from bearingsim.simulation.budget import MAX_TIMEOUT
from bearingsim.simulation.integrators import METHODS

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


__all__ = [
    "ANALYSES",
    "Scene",
    "Settling",
    "Simulation",
    "Output",
    "TableInput",
    "SceneError",
    "load_scene",
    "parse_scene",
    "scene_from_dict",
    "line_of",
]

@dataclass
class Scene:  # numpydoc ignore=PR02
    """A simulation scene (the same content as a scene TOML file).

    Parameters
    ----------
    assembly : str
        Registered assembly name (``bearingsim list``).
    args : dict
        Arguments of the assembly factory (allowed keys depend on the assembly).
    fidelity : str
        A fidelity level of the assembly or ``"auto"`` (the lowest level that provides every
        requested output, input and parameter).
    inputs : dict
        Input name -> number, expression of ``t`` (text) or :class:`TableInput`.
    parameters : dict
        Parameter dotted name -> value (SI units).
    initial : dict
        State dotted name -> initial value.
    outputs : list of str
        Requested outputs (model variables or post-processed quantities); empty: the assembly's
        defaults.
    simulation, output : Simulation, Output
    title : str
    input_units : dict
        SI unit of each input given as a number with a unit (``"10000 rpm"`` -> ``rad/s``),
        checked against the model's input when assembled.
    value_units : dict
        SI unit of each parameter and initial value given as a number with a unit, by key
        (``parameters.spring.Fz``: ``"1.5 kN"`` -> ``N``; also from a grid or cases), checked
        against the model's when assembled.
    analysis : str
        One of :data:`ANALYSES`.
    grid : dict
        Operating grid of a ``steady``, ``modes`` or ``statics`` scene: key (``inputs.<name>``,
        ``parameters.<name>``, ``assembly.<argument>``) -> list of values (SI, inputs also
        as ``"10000 rpm"``); every combination is one operating point, the first key varying
        fastest (the x axis of the plot; the second key gives one curve per value).
    cases : list of dict
        Operating points given one by one (load cases), each a table of the same keys and an
        optional ``name``.
    settling : Settling
        The criterion of settled outputs (transient scenes).
    transient_on_purpose : bool
        The scene reports a transient on purpose: its final values are not checked for
        settling.
    statics_method : str
        ``statics`` scenes: ``"exact"`` or ``"iso_ts_16281"`` kinematics
        (:func:`~bearingsim.studies.deep_groove_statics.deep_groove_statics`).
    tolerance : float
        Largest relative error [-] of the requested outputs that ``fidelity = "auto"`` may
        accept from a lower level (its measured error against the reference level,
        :attr:`~bearingsim.assemblies.spec.AssemblySpec.level_errors`); default
        :data:`DEFAULT_TOLERANCE`.
    path : str, optional
        The scene file (for error messages and relative table paths).
    text : str, optional
        The scene file text (for line numbers in error messages).
    allow_paths : tuple of str
        Folders outside the scene's folder that its files may be in (``--allow-path``).
    lubricants : dict
        The scene's ``[lubricants]`` table (registered again when the scene is prepared).
    bearings : list of str
        Its bearing datasheet files (key ``bearings``), registered when the scene is read and
        again when it is prepared (:meth:`register_own`).
    """

    assembly: str
    args: dict[str, Any] = field(default_factory=dict)
    fidelity: str = "auto"
    inputs: dict[str, Any] = field(default_factory=dict)
    parameters: dict[str, float] = field(default_factory=dict)
    initial: dict[str, float] = field(default_factory=dict)
    outputs: list[str] = field(default_factory=list)
    simulation: Simulation = field(default_factory=Simulation)
    output: Output = field(default_factory=Output)
    title: str = ""
    tolerance: float = DEFAULT_TOLERANCE
    input_units: dict[str, str] = field(default_factory=dict)
    value_units: dict[str, str] = field(default_factory=dict)
    analysis: str = "transient"
    grid: dict[str, list[Any]] = field(default_factory=dict)
    cases: list[dict[str, Any]] = field(default_factory=list)
    settling: Settling = field(default_factory=Settling)
    transient_on_purpose: bool = False
    statics_method: str = "exact"
    path: str | None = None
    text: str | None = field(default=None, repr=False)
    allow_paths: tuple[str, ...] = ()
    lubricants: dict[str, Any] = field(default_factory=dict)
    bearings: list[str] = field(default_factory=list)

    @property
    def spec(self) -> AssemblySpec:
        """The registry entry of the assembly.

        Returns
        -------
        AssemblySpec
            The scene's assembly.
        """
        return REGISTRY[self.assembly]

    def to_dict(self) -> dict[str, Any]:
        """The scene as the nested dict of its TOML form.

        Returns
        -------
        dict
            Sections and keys as in a scene file.
        """
        inputs = {}
        for k, v in self.inputs.items():
            inputs[k] = {"times": list(v.times), "values": list(v.values)} if isinstance(
                v, TableInput) else v
        sim = {k: v for k, v in asdict(self.simulation).items() if v is not None
               and (self.analysis == "transient" or k == "timeout")}
        out = asdict(self.output)
        kind = ({"settling": asdict(self.settling),
                 "transient_on_purpose": self.transient_on_purpose}
                if self.analysis == "transient" else
                {"grid": {k: list(v) for k, v in self.grid.items()},
                 "cases": [dict(c) for c in self.cases],
                 "statics": {"method": self.statics_method}})
        return {
            "title": self.title,
            "analysis": self.analysis,
            **kind,
            "outputs": list(self.outputs),
            "tolerance": self.tolerance,
            "assembly": {"name": self.assembly, "fidelity": self.fidelity, **self.args},
            "inputs": inputs,
            "parameters": dict(self.parameters),
            "initial": dict(self.initial),
            "simulation": sim,
            "output": out, **({"lubricants": self.lubricants} if self.lubricants else {}),
            **({"bearings": list(self.bearings)} if self.bearings else {}),
        }

    def register_own(self) -> None:
        """Register the scene's datasheet bearings and lubricants again (replacing those of
        their names that scenes read since registered): a scene runs with its own.

        Raises
        ------
        SceneError
            When a datasheet file cannot be read any more, naming the key ``bearings``.
        """
        for problem in [*load_bearings_files(self.bearings or None, scene_folder(self.path),
                                             self.allow_paths),
                        *load_lubricants_table(self.lubricants)]:
            raise SceneError(problem.reason, problem.key, line_of(self.text, problem.key),
                             problem.allowed, self.path)

    @property
    def given_units(self) -> dict[str, str]:
        """The SI unit of every value given as a number with a unit, by key:
        ``inputs.<name>`` (:attr:`input_units`), ``parameters.<name>``, ``initial.<state>``
        (:attr:`value_units`). A copy through :meth:`to_dict` holds SI numbers only;
        :func:`scene_from_dict` takes these back as ``carried_units``.

        Returns
        -------
        dict of str to str
            SI unit by key.
        """
        return {**{f"inputs.{n}": u for n, u in self.input_units.items()},
                **self.value_units}

    def replace(self, **changes) -> Scene:
        """A validated copy with some fields changed.

        Parameters
        ----------
        **changes
            Fields of :class:`Scene` and their new values.

        Returns
        -------
        Scene
            The changed scene, checked as a scene file is.
        """
        d = {k: getattr(self, k) for k in self.__dataclass_fields__}
        d.update(changes)
        new = Scene(**d)

        def value(scene: Scene, key: str) -> Any:
            section, name = key.split(".", 1)
            return getattr(scene, section).get(name)

        # a value set anew is in SI: only an unchanged one keeps the unit it was given in
        units = {k: u for k, u in new.given_units.items() if value(new, k) == value(self, k)}
        return scene_from_dict(new.to_dict(), path=self.path, text=None,
                               allow_paths=self.allow_paths, carried_units=units)


def scene_from_dict(d: dict[str, Any], path: str | None = None,
                    text: str | None = None, allow_paths: Sequence[str | Path] = (),
                    carried_units: dict[str, str] | None = None) -> Scene:
    """Validate a scene in its nested-dict (TOML) form and build a :class:`Scene`.

    Files it names (tables, ``bearings``, ``output.folder``) must be inside the folder of
    ``path`` (the current folder without one) or of ``allow_paths``.

    Parameters
    ----------
    d : dict
        The scene's sections and keys, as a TOML file gives them.
    path : str, optional
        The scene file (for messages and the folder files are read from).
    text : str, optional
        The file's text (for the line numbers in messages).
    allow_paths : sequence of path
        Folders outside the scene's folder that its files may be in.
    carried_units : dict of str to str, optional
        The SI unit a value was given in before, by key (:attr:`Scene.given_units` of the
        scene ``d`` was made from, whose :meth:`Scene.to_dict` holds SI numbers): kept for
        the inputs, parameters and initial values ``d`` gives as numbers (or tables), so that
        the model's check of their quantity still applies (a copy of a scene, a sweep
        point).

    Returns
    -------
    Scene
        The checked scene.

    Raises
    ------
    SceneError
        Listing every problem with its key, line and allowed values.
    """
    c = _Collector(text, path)
    for k in d:
        if k not in TOP_KEYS:
            _unknown(c, "", k, TOP_KEYS)
    analysis = d.get("analysis", "transient")
    if analysis not in ANALYSES:
        c.add("analysis", f"{analysis!r} is not an analysis", ", ".join(ANALYSES))
        analysis = "transient"
    on_purpose = d.get("transient_on_purpose", False)
    if not isinstance(on_purpose, bool):
        c.add("transient_on_purpose", f"must be true or false, got {on_purpose!r}",
              "true, false")
        on_purpose = False
    allowed = tuple(str(a) for a in allow_paths)
    for problem in [*load_bearings_files(d.get("bearings"), scene_folder(path), allowed),
                    *load_lubricants_table(d.get("lubricants"))]:
        c.add(problem.key, problem.reason, problem.allowed)
    # assembly
    asm = d.get("assembly")
    name, fidelity, args = None, "auto", {}
    if not isinstance(asm, dict) or "name" not in asm:
        c.add("assembly.name", "missing: every scene names its assembly", ", ".join(REGISTRY))
    else:
        name = asm["name"]
        if not isinstance(name, str) or name not in REGISTRY:
            c.add("assembly.name", f"unknown assembly {name!r}", ", ".join(REGISTRY))
            name = None
    if name is not None:
        spec = REGISTRY[name]
        fidelity = asm.get("fidelity", "auto")
        if not isinstance(fidelity, str) or (fidelity != "auto"
                                             and fidelity not in spec.fidelities):
            c.add("assembly.fidelity", f"{fidelity!r} is not a fidelity of {name}",
                  ", ".join(("auto",) + spec.fidelities))
        for k, v in asm.items():
            if k in ("name", "fidelity"):
                continue
            if k not in spec.args:
                _unknown(c, "assembly", k, ["name", "fidelity", *spec.args])
                continue
            args[k] = _check_arg(c, f"assembly.{k}", spec.args[k], v)
    # outputs
    outputs = d.get("outputs", [])
    if not isinstance(outputs, list) or not all(isinstance(o, str) for o in outputs):
        c.add("outputs", "must be a list of variable names", "a list of dotted names")
        outputs = []
    # inputs
    base = scene_folder(path)
    carried = carried_units or {}
    inputs, input_units = _inputs(c, d, base, allowed, {
        k.removeprefix("inputs."): u for k, u in carried.items() if k.startswith("inputs.")})
    # parameters and initial values
    values: dict[str, dict[str, float]] = {}
    value_units: dict[str, str] = {}
    for section in ("parameters", "initial"):
        raw = d.get(section, {})
        values[section] = {}
        if not isinstance(raw, dict):
            c.add(section, "must be a table", "dotted name = number")
            continue
        for k, v in _flatten(raw).items():
            key = f"{section}.{k}"
            value = _quantity_value(c, key, key, v, value_units)
            if value is not None:
                values[section][k] = value
                if key in carried:
                    value_units.setdefault(key, carried[key])
    # simulation
    sim = Simulation()
    for k, v, key in _section(c, d, "simulation", Simulation.__dataclass_fields__):
        if k == "method":
            if not (isinstance(v, str) and v in METHODS):
                c.add(key, f"{v!r} is not a solver", ", ".join(METHODS))
            else:
                sim.method = v
        elif k == "initial":
            if v not in ("start", "steady"):
                c.add(key, f"{v!r} is not allowed", "start, steady")
            else:
                sim.initial = v
        elif k == "n_points":
            if _number(c, key, v, "points", 2, 1_000_000, integer=True) is not None:
                sim.n_points = int(v)
        elif k == "max_steps":
            if _number(c, key, v, "steps", 1, None, integer=True) is not None:
                sim.max_steps = int(v)
        elif k == "timeout":  # (a time with a unit, "50 ms", too)
            if (v := _number(c, key, v, "s", 0.0, MAX_TIMEOUT, True, si_unit="s")) is not None:
                sim.timeout = float(v)
        else:
            low, strict, high = {"t_end": (None, False, None), "t_start": (None, False, None),
                                 "rtol": (RTOL_RANGE[0], False, RTOL_RANGE[1]),
                                 "atol": (ATOL_RANGE[0], False, ATOL_RANGE[1]),
                                 "max_step": (0.0, True, None)}[k]
            time = k in ("t_end", "t_start", "max_step")
            if (v := _number(c, key, v, "s" if time else "[1]", low, high, strict,
                             si_unit="s" if time else None)) is not None:
                setattr(sim, k, float(v))
    if analysis != "transient":
        pass  # no time span: the operating points are solved directly
    elif "t_end" not in (d.get("simulation") if isinstance(d.get("simulation"), dict) else {}):
        c.add("simulation.t_end", "missing: the end time of the run", "a number in s > t_start")
    elif sim.t_end <= sim.t_start:
        c.add("simulation.t_end", f"{sim.t_end!r} must be after t_start = {sim.t_start!r}",
              f"a number in s > {sim.t_start!r}")
    out = _output(c, d, path, allowed)
    _check_signals(c, inputs, sim)
    for k in ("load_torque",):
        if isinstance(args.get(k), str):
            _check_signals(c, {k: args[k]}, sim, "assembly")
    title = d.get("title", "")
    if not isinstance(title, str):
        c.add("title", "must be text", "a string")
        title = ""
    tolerance = d.get("tolerance", DEFAULT_TOLERANCE)
    if _number(c, "tolerance", tolerance, "[1] (relative error)", 0.0, 10.0, True) is None:
        tolerance = DEFAULT_TOLERANCE
    grid, cases = _operating_points(c, d, REGISTRY[name] if name is not None else None,
                                    input_units, value_units)
    settling = _settling(c, d)
    statics_method = _analysis_options(c, d, analysis, inputs)
    c.raise_if_any()
    files = d.get("bearings")  # None: none
    return Scene(
        assembly=name, args=args, fidelity=fidelity, inputs=inputs, input_units=input_units,
        value_units=value_units,
        parameters=values["parameters"], initial=values["initial"], outputs=list(outputs),
        simulation=sim, output=out, title=title or (Path(path).stem if path else name),
        tolerance=float(tolerance), analysis=analysis, grid=grid, cases=cases,
        settling=settling, transient_on_purpose=on_purpose, statics_method=statics_method,
        path=path, text=text, allow_paths=allowed, lubricants=d.get("lubricants") or {},
        bearings=[b for b in (files if isinstance(files, list) else [files])
                  if isinstance(b, str)],
    )


@checked
def parse_scene(text: str, path: str | None = None,
                allow_paths: Sequence[str | Path] = ()) -> Scene:
    """Parse and validate scene TOML text (without assembling the model).

    Parameters
    ----------
    text : str
        The scene in TOML.
    path : str, optional
        Its file (for messages and the folder files are read from).
    allow_paths : sequence of path
        As :func:`scene_from_dict` takes it.

    Returns
    -------
    Scene
        The checked scene.
    """
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise SceneError(f"not valid TOML: {exc}", "", int(m.group(1)) if m else None,
                         "TOML syntax (https://toml.io)", path) from None
    return scene_from_dict(d, path=path, text=text, allow_paths=allow_paths)


@checked
def load_scene(path: str | Path, allow_paths: Sequence[str | Path] = ()) -> Scene:
    """Read, parse and validate a scene file (without assembling the model).

    Parameters
    ----------
    path : str or Path
        A scene TOML file, or the name of a built-in scene
        (:func:`~bearingsim.scenes.library.builtin_scenes`, e.g. ``"double_layer_rs"``) when no
        such file exists.
    allow_paths : sequence of path
        Folders outside the scene file's folder that its tables, datasheets and output folder
        may be in (none by default: everything inside the scene file's folder).

    Returns
    -------
    Scene
        The checked scene.

    Raises
    ------
    SceneError
        Naming the key, the line and the allowed values; for a missing file, the built-in
        scene names.
    """
    p = Path(path)
    if not p.is_file():  # a folder named like a built-in scene (its output, say) is not one
        p = builtin_scene_path(str(path)) or p
    if not p.exists():
        raise SceneError(f"scene file {str(p)!r} not found; built-in scenes: "
                         f"{', '.join(builtin_scenes())}", path=str(p))
    try:
        with open_regular(p, "scene file", MAX_SCENE_BYTES) as fh:
            text = fh.read()
    except FileAccessError as exc:
        raise SceneError(str(exc), path=str(p)) from None
    except UnicodeDecodeError:
        raise SceneError("the scene file is not UTF-8 text", path=str(p)) from None
    except OSError as exc:
        raise SceneError(f"cannot read the scene file: {os_reason(exc)}", path=str(p)) from None
    return parse_scene(text, str(p), allow_paths)
