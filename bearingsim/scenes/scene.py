"""The scene model (a dataclass) and its TOML loader and validator.

A scene names an assembly and its arguments, a fidelity (or ``"auto"``), input signals
(numbers, expressions of ``t`` or CSV tables), parameter and initial-state overrides, the
requested outputs, the time span and solver settings, and the output folder. See
``docs/scenes.md`` for the format.

Errors name the key (dotted, e.g. ``simulation.rtol``), the line in the file and the allowed
values.
"""

from __future__ import annotations

import difflib
import math
import re
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.assemblies.spec import ArgSpec, AssemblySpec
from bearingsim.checks import ATOL_RANGE, RTOL_RANGE
from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.files import (
    FileAccessError,
    PathOutsideError,
    confined_path,
    open_regular,
    os_reason,
)
from bearingsim.scenes.expressions import ExpressionError, compile_expression, constant_value
from bearingsim.scenes.library import builtin_scene_path, builtin_scenes
from bearingsim.scenes.lubricant_table import load_lubricants_table
from bearingsim.scenes.registry import REGISTRY
from bearingsim.scenes.tables import (
    SceneFileError,
    check_table_memory,
    load_bearings_files,
    output_base,
    read_table_file,
    scene_folder,
)
from bearingsim.simulation.budget import DEFAULT_MAX_STEPS, MAX_TIMEOUT
from bearingsim.simulation.integrators import METHODS
from bearingsim.units import parse_quantity

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

TOP_KEYS = ("title", "description", "analysis", "outputs", "tolerance", "bearings", "lubricants",
            "assembly",
            "inputs", "parameters", "initial", "grid", "cases", "settling",
            "transient_on_purpose", "statics", "simulation", "output")
ANALYSES = ("transient", "steady", "modes", "statics")
"""What a scene asks (key ``analysis``): a run in time (``transient``, the default), the
settled operating point (``steady``), natural frequencies and mode names at the equilibrium
(``modes``) or quasi-static ball loads, stiffness, contact pressure and life (``statics``); the
last three for each point of ``grid`` or ``cases`` (:mod:`bearingsim.scenes.analyses`)."""
POINT_HEADS = ("inputs", "parameters", "assembly")
"""Key heads of an operating grid or load case (``inputs.shaft_speed``, ``parameters.<name>``,
``assembly.<argument>``)."""
STATICS_METHODS = ("exact", "iso_ts_16281")
DEFAULT_TOLERANCE = 0.05
"""Largest relative error of the requested outputs a scene accepts from ``fidelity = "auto"``
when it gives no ``tolerance`` [-]."""
TABLE_KEYS = ("file", "column", "time_column", "times", "values")
MAX_SCENE_BYTES = 50_000_000
"""Largest scene file read [bytes] (a scene with inline tables of 10^6 rows is about 30 MB;
larger tables belong in CSV files)."""


class SceneError(ParameterError):
    """A scene file or scene object is invalid.

    Attributes
    ----------
    key : str
        Dotted key (``simulation.rtol``).
    line : int or None
        1-based line in the scene file, when known.
    allowed : str
        The allowed values.
    problems : list of SceneError
        All problems found (the first one is this error itself when several are reported).
    """

    def __init__(self, message: str, key: str = "", line: int | None = None, allowed: str = "",
                 path: str | None = None, problems: list | None = None):
        self.key, self.line, self.allowed, self.path = key, line, allowed, path
        self.reason = message
        self.problems = problems or [self]
        super().__init__(self._format())

    def _format(self) -> str:
        if len(self.problems) > 1:
            return f"{len(self.problems)} problems in the scene:\n  " + "\n  ".join(
                p._format() for p in self.problems)
        where = self.path or "scene"
        if self.line is not None:
            where += f":{self.line}"
        text = f"{where}: {self.key}: {self.reason}" if self.key else f"{where}: {self.reason}"
        if self.allowed:
            text += f"; allowed: {self.allowed}"
        return text


@dataclass
class TableInput:
    """An input given as a table: linear interpolation between ``times`` [s] and ``values``."""

    times: list[float]
    values: list[float]
    source: str = ""

    def as_tuple(self) -> tuple[np.ndarray, np.ndarray]:
        """``(times, values)`` as accepted by ``simulate(inputs=...)``."""
        return np.asarray(self.times, dtype=float), np.asarray(self.values, dtype=float)


@dataclass
class Simulation:
    """Time span and solver of a scene."""

    t_end: float = 1.0
    t_start: float = 0.0
    method: str | None = None
    """The integration method; None: ``simulate``'s fastest accurate choice
    (:func:`~bearingsim.simulation.choice.choose_method`)."""
    rtol: float = 1e-6
    atol: float = 1e-8
    n_points: int = 501
    max_step: float = math.inf
    initial: str = "start"
    max_steps: int = DEFAULT_MAX_STEPS
    timeout: float | None = None


@dataclass
class Settling:
    """When a transient scene's outputs count as settled (key ``settling``).

    An output has settled when its range (largest minus smallest value) over the last
    ``window`` of the run is at most ``tolerance`` times its final magnitude (or, for an
    output that ends near zero, ``tolerance`` times its largest magnitude in the run).
    """

    window: float = 0.2
    """Fraction of the run checked, at its end [-], in (0, 1)."""
    tolerance: float = 1e-3
    """Largest relative change over the window [-]."""


@dataclass
class Output:
    """Where and what a scene run writes."""

    folder: str = "results"
    csv: bool = True
    plots: bool = True
    plot_groups: list[list[str]] = field(default_factory=list)


@dataclass
class Scene:
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
    analysis: str = "transient"
    grid: dict[str, list[Any]] = field(default_factory=dict)
    cases: list[dict[str, Any]] = field(default_factory=list)
    settling: Settling = field(default_factory=Settling)
    transient_on_purpose: bool = False
    statics_method: str = "exact"
    path: str | None = None
    text: str | None = field(default=None, repr=False)
    allow_paths: tuple[str, ...] = ()

    @property
    def spec(self) -> AssemblySpec:
        """The registry entry of the assembly."""
        return REGISTRY[self.assembly]

    def to_dict(self) -> dict[str, Any]:
        """The scene as the nested dict of its TOML form."""
        inputs = {}
        for k, v in self.inputs.items():
            inputs[k] = {"times": list(v.times), "values": list(v.values)} if isinstance(
                v, TableInput) else v
        sim = {k: v for k, v in asdict(self.simulation).items() if v is not None}
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
            "output": out,
        }

    def replace(self, **changes) -> Scene:
        """A validated copy with some fields changed."""
        d = {k: getattr(self, k) for k in self.__dataclass_fields__}
        d.update(changes)
        return scene_from_dict(Scene(**d).to_dict(), path=self.path, text=None,
                               allow_paths=self.allow_paths)


# --------------------------------------------------------------------------- line numbers
_KEY_PART = r'(?:"[^"]*"|\'[^\']*\'|[A-Za-z0-9_\-]+)'
_KEY_LINE = re.compile(rf"^\s*({_KEY_PART}(?:\s*\.\s*{_KEY_PART})*)\s*=")
_HEADER = re.compile(rf"^\s*\[\[?\s*({_KEY_PART}(?:\s*\.\s*{_KEY_PART})*)\s*\]\]?")


def _split_key(text: str) -> tuple[str, ...]:
    parts = re.findall(_KEY_PART, text)
    return tuple(p[1:-1] if p[:1] in "\"'" else p for p in parts)


def line_of(text: str | None, key: tuple[str, ...] | str) -> int | None:
    """1-based line of a (dotted) key in TOML text: the longest prefix of the key found.

    Keys may be written as table headers (``[simulation]``), plain or dotted keys
    (``rtol = ...``, ``"inner_layer.nu" = ...``) or inside inline tables (the line of the
    enclosing key is returned).
    """
    if not text:
        return None
    if isinstance(key, str):
        key = tuple(key.split("."))
    best, best_len = None, 0
    table: tuple[str, ...] = ()
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0] if '"' not in raw and "'" not in raw else raw
        m = _HEADER.match(line)
        if m and not _KEY_LINE.match(line):
            table = _split_key(m.group(1))
            full = table
        else:
            m = _KEY_LINE.match(line)
            if not m:
                continue
            full = table + _split_key(m.group(1))
        # match both nested keys and quoted dotted names ("inner_layer.nu")
        flat = ".".join(full)
        target = ".".join(key)
        length = 0
        if target == flat or target.startswith(flat + "."):
            length = len(flat)
        if length > best_len:
            best, best_len = n, length
    return best


# --------------------------------------------------------------------------- validation
class _Collector:
    def __init__(self, text: str | None, path: str | None):
        self.text, self.path, self.problems = text, path, []

    def add(self, key: str, message: str, allowed: str = "") -> None:
        self.problems.append(SceneError(message, key, line_of(self.text, key), allowed,
                                        self.path))

    def raise_if_any(self) -> None:
        if self.problems:
            self.problems.sort(key=lambda p: (p.line is None, p.line or 0))
            first = self.problems[0]
            raise SceneError(first.reason, first.key, first.line, first.allowed, first.path,
                             problems=list(self.problems))


def _section(c: _Collector, d: dict[str, Any], section: str,
             fields: Any) -> list[tuple[str, Any, str]]:
    """The known keys of a scene table as ``(key, value, dotted key)``; a table that is not a
    table and unknown keys are reported to ``c``."""
    raw = d.get(section, {})
    if not isinstance(raw, dict):
        c.add(section, "must be a table", ", ".join(fields))
        return []
    known = []
    for k, v in raw.items():
        if k in fields:
            known.append((k, v, f"{section}.{k}"))
        else:
            _unknown(c, section, k, fields)
    return known


def _is_number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _unknown(c: _Collector, section: str, key: str, allowed) -> None:
    allowed = list(allowed)
    close = difflib.get_close_matches(key, allowed, n=3)
    hint = f" (did you mean {', '.join(close)}?)" if close else ""
    c.add(f"{section}.{key}" if section else key, f"unknown key{hint}", ", ".join(allowed))


def _number(c: _Collector, key: str, v: Any, unit: str, low=None, high=None, strict_low=False,
            integer=False) -> float | None:
    if isinstance(v, str):
        c.add(key, f"must be a number in {unit}, got the text {v!r}",
              f"a number in {unit}" + ("; write r/min as a number in rad/s" if "rpm" in v.lower()
                                       else ""))
        return None
    if not _is_number(v) or (integer and not isinstance(v, int)):
        kind = "an integer" if integer else "a number"
        c.add(key, f"must be {kind} in {unit}, got {v!r} ({type(v).__name__})",
              f"{kind} in {unit}")
        return None
    if not math.isfinite(v) and not (high is None and v == math.inf and key.endswith("max_step")):
        c.add(key, f"must be finite, got {v!r}", f"a finite number in {unit}")
        return None
    rng = f"{'(' if strict_low else '['}{low if low is not None else '-inf'}, " \
          f"{high if high is not None else 'inf'}] {unit}"
    if low is not None and (v < low or (strict_low and v <= low)):
        c.add(key, f"{v!r} is out of range", rng)
        return None
    if high is not None and v > high:
        c.add(key, f"{v!r} is out of range", rng)
        return None
    return v


def _check_arg(c: _Collector, key: str, spec: ArgSpec, v: Any) -> Any:
    from bearingsim.catalog import list_bearings
    from bearingsim.physics.lubricant import as_lubricant, known_lubricants

    if v is None:
        return None
    if spec.kind == "bearing":
        names = list_bearings()
        if not isinstance(v, str) or v not in names:
            c.add(key, f"unknown bearing designation {v!r}", ", ".join(names))
        return v
    if spec.kind == "lubricant":
        values = v if isinstance(v, list) else [v]
        if isinstance(v, list) and len(v) != 2:
            c.add(key, f"give one lubricant or a list of two (inner, outer), got {len(v)}",
                  ", ".join(known_lubricants()))
            return v
        for item in values:
            try:
                as_lubricant(item, key)
            except BearingsimError:
                c.add(key, f"unknown lubricant {item!r}", ", ".join(known_lubricants()))
        return v
    if spec.kind == "choice":
        if v not in spec.choices:
            c.add(key, f"{v!r} is not allowed", ", ".join(map(str, spec.choices)))
        return v
    if spec.kind == "bool":
        if not isinstance(v, bool):
            c.add(key, f"must be true or false, got {v!r}", "true, false")
        return v
    if spec.kind == "signal":
        if isinstance(v, str):
            try:
                compile_expression(v, key)
            except ExpressionError as exc:
                c.add(key, str(exc).split(": ", 1)[1].split(". Allowed:")[0],
                      str(exc).split("Allowed: ", 1)[-1])
            return v
        return _number(c, key, v, "SI units")
    if spec.kind == "float":
        return _number(c, key, v, "SI units", low=spec.low, strict_low=spec.low is not None)
    if spec.kind == "floats":
        if not isinstance(v, dict):
            c.add(key, "must be a table of numbers", "a table name = number")
            return v
        for k, item in v.items():
            _number(c, f"{key}.{k}", item, "SI units")
        return v
    if spec.kind == "table":
        if not isinstance(v, dict):
            c.add(key, f"must be a table, got {v!r}", ", ".join(spec.table or {}))
            return v
        for k, item in v.items():
            if k not in (spec.table or {}):
                _unknown(c, key, k, spec.table or {})
            else:
                _check_arg(c, f"{key}.{k}", spec.table[k], item)
        return v
    raise AssertionError(spec.kind)  # pragma: no cover


def _flatten(d: dict[str, Any], prefix: str = "", keep_tables: bool = False) -> dict[str, Any]:
    """Nested TOML tables to dotted names (``inner_layer.nu``); input tables are kept."""
    out = {}
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict) and not (keep_tables and set(v) & set(TABLE_KEYS)):
            out.update(_flatten(v, name + ".", keep_tables))
        else:
            out[name] = v
    return out


def _table_input(c: _Collector, key: str, v: dict, base: Path, allowed: tuple[str, ...],
                 units: dict[str, str]) -> TableInput | None:
    bad = set(v) - set(TABLE_KEYS)
    if bad:
        _unknown(c, key, sorted(bad)[0], TABLE_KEYS)
        return None
    if "file" in v:
        try:
            times, vals, source, unit = read_table_file(key, v, base, allowed)
        except SceneFileError as exc:
            c.add(exc.key, exc.reason, exc.allowed)
            return None
        if unit is not None:
            units[key.removeprefix("inputs.")] = unit
    else:
        if "times" not in v or "values" not in v:
            c.add(key, "a table input needs 'file' and 'column', or 'times' and 'values'",
                  ", ".join(TABLE_KEYS))
            return None
        times, vals, source = v["times"], v["values"], "inline"
        if not all(_is_number(x) for x in list(times) + list(vals)):
            c.add(key, "times and values must be numbers", "lists of numbers in SI units")
            return None
        try:
            check_table_memory(len(times), f"the inline table {key}")
        except ParameterError as exc:
            c.add(key, str(exc))
            return None
    t, y = np.asarray(times, dtype=float), np.asarray(vals, dtype=float)
    if t.size < 2 or t.size != y.size or np.any(np.diff(t) <= 0):
        c.add(key, "a table needs at least two rows, equally many times and values, times "
              "strictly increasing")
        return None
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        c.add(key, "table values must be finite")
        return None
    return TableInput(t.tolist(), y.tolist(), source)


def _check_signals(c: _Collector, inputs: dict[str, Any], sim: Simulation,
                   section: str = "inputs") -> None:
    """Expressions must be finite over the time span (checked on a fine grid)."""
    import casadi as ca

    t = ca.SX.sym("t")
    grid = np.linspace(sim.t_start, sim.t_end, max(2 * sim.n_points, 201))
    for name, v in inputs.items():
        if not isinstance(v, str):
            continue
        try:
            fn = ca.Function("u", [t], [ca.SX(compile_expression(v, name)(t))])
            vals = np.asarray(fn.map(grid.size)(grid[None, :]), dtype=float).ravel()
        except Exception:  # noqa: BLE001 - reported by the syntax check already
            continue
        bad = ~np.isfinite(vals)
        if np.any(bad):
            c.add(f"{section}.{name}", f"the expression {v!r} is not finite at t = "
                  f"{grid[np.argmax(bad)]:.6g} s (in the time span "
                  f"[{sim.t_start:g}, {sim.t_end:g}] s)", "an expression finite for all t")


def _point_value(c: _Collector, key: str, where: str, v: Any, spec: AssemblySpec | None,
                 units: dict[str, str]) -> Any:
    """One value of an operating grid or load case, checked against its key; inputs in SI."""
    head, _, rest = key.partition(".")
    if head not in POINT_HEADS or not rest:
        c.add(where, f"{key!r} is not an operating-point key",
              "inputs.<input>, parameters.<parameter>, assembly.<argument>")
        return None
    if head == "assembly":
        if spec is None:
            return None
        arg = spec.args.get(rest)
        if arg is None:
            _unknown(c, where.rsplit(".", 1)[0], key, [f"assembly.{a}" for a in spec.args])
            return None
        if arg.kind == "float" and isinstance(v, str) and (q := parse_quantity(v)) is not None:
            v = q[0]  # "4000 rpm": the argument's documented SI unit
        return _check_arg(c, where, arg, v)
    if head == "inputs" and isinstance(v, str) and (quantity := parse_quantity(v)) is not None:
        units[rest] = quantity[1]
        return quantity[0]
    value = _number(c, where, v, "SI units or a number with a unit ('10000 rpm')"
                    if head == "inputs" else "SI units")
    return None if value is None else float(value)


def _operating_points(c: _Collector, d: dict[str, Any], spec: AssemblySpec | None,
                      units: dict[str, str]) -> tuple[dict[str, list[Any]], list[dict[str, Any]]]:
    """The ``grid`` (key -> values) and ``cases`` (list of points) of a scene, checked."""
    grid: dict[str, list[Any]] = {}
    raw = d.get("grid", {})
    if not isinstance(raw, dict):
        c.add("grid", "must be a table", "key = [values]")
        raw = {}
    for key, values in _flatten(raw).items():
        where = f"grid.{key}"
        if not isinstance(values, list) or not values:
            c.add(where, "must be a non-empty list of values", "a list, e.g. [0, 200, 500]")
            continue
        grid[key] = [_point_value(c, key, where, v, spec, units) for v in values]
    cases: list[dict[str, Any]] = []
    raw_cases = d.get("cases", [])
    if not isinstance(raw_cases, list) or not all(isinstance(x, dict) for x in raw_cases):
        c.add("cases", "must be a list of tables ([[cases]])", "[[cases]] name = ..., key = value")
        raw_cases = []
    for k, case in enumerate(raw_cases):
        point: dict[str, Any] = {}
        for key, v in _flatten(case).items():
            where = f"cases.{key}"
            if key == "name":
                if not isinstance(v, str):
                    c.add(where, f"case {k + 1}: the name must be text", "a string")
                point["name"] = str(v)
            else:
                point[key] = _point_value(c, key, where, v, spec, units)
        point.setdefault("name", f"case {k + 1}")
        cases.append(point)
    if grid and cases:
        c.add("cases", "give the operating points either as a grid or as cases, not both",
              "[grid] or [[cases]]")
    return grid, cases


def _settling(c: _Collector, d: dict[str, Any]) -> Settling:
    settling = Settling()
    for k, v, key in _section(c, d, "settling", Settling.__dataclass_fields__):
        low, high = (0.0, 1.0) if k == "window" else (0.0, 0.5)
        if _number(c, key, v, "[1]", low, high, True) is not None:
            setattr(settling, k, float(v))
    return settling


def _analysis_options(c: _Collector, d: dict[str, Any], analysis: str,
                      inputs: dict[str, Any]) -> str:
    """Checks the keys that depend on the analysis kind; returns the statics method."""
    method = "exact"
    for _, v, key in _section(c, d, "statics", ("method",)):
        if v not in STATICS_METHODS:
            c.add(key, f"{v!r} is not a statics method", ", ".join(STATICS_METHODS))
        else:
            method = v
    if analysis == "transient":
        for key in ("grid", "cases", "statics"):
            if key in d:
                c.add(key, f"{key} is for the analyses steady, modes and statics; this scene is "
                      "a transient (analysis = \"transient\")", "analysis = \"steady\", "
                      "\"modes\" or \"statics\" with a grid or cases")
        return method
    for key in ("settling", "transient_on_purpose"):
        if key in d:
            c.add(key, f"{key} applies to transient scenes only (analysis = {analysis!r})")
    for name, v in inputs.items():
        try:
            constant = constant_value(v, f"inputs.{name}")
        except ExpressionError:
            constant = None
        if constant is None:
            c.add(f"inputs.{name}", f"a {analysis} analysis holds every input constant: give a "
                  "number (or a number with a unit), not an expression of t or a table",
                  "a number, a number with a unit or a constant expression (rpm(1000))")
        else:
            inputs[name] = constant  # a constant expression (rpm(1000)) as its SI value
    return method


def scene_from_dict(d: dict[str, Any], path: str | None = None,
                    text: str | None = None, allow_paths: Sequence[str | Path] = ()) -> Scene:
    """Validate a scene in its nested-dict (TOML) form and build a :class:`Scene`.

    Files it names (tables, ``bearings``, ``output.folder``) must be inside the folder of
    ``path`` (the current folder without one) or of ``allow_paths``.

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
    for problem in load_bearings_files(d.get("bearings"), scene_folder(path), allowed):
        c.add(problem.key, problem.reason, problem.allowed)
    for problem in load_lubricants_table(d.get("lubricants")):
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
    inputs: dict[str, Any] = {}
    input_units: dict[str, str] = {}
    base = scene_folder(path)
    raw_inputs = d.get("inputs", {})
    if not isinstance(raw_inputs, dict):
        c.add("inputs", "must be a table", "name = number, expression or table")
        raw_inputs = {}
    for k, v in _flatten(raw_inputs, keep_tables=True).items():
        key = f"inputs.{k}"
        if isinstance(v, dict):
            tab = _table_input(c, key, v, base, allowed, input_units)
            if tab is not None:
                inputs[k] = tab
        elif isinstance(v, str) and (quantity := parse_quantity(v)) is not None:
            inputs[k], input_units[k] = quantity  # a number with a unit: SI from here on
        elif isinstance(v, str):
            try:
                compile_expression(v, key)
                inputs[k] = v
            except ExpressionError as exc:
                c.add(key, str(exc).split(": ", 1)[1].split(". Allowed:")[0],
                      str(exc).split("Allowed: ", 1)[-1])
        elif isinstance(v, TableInput):
            inputs[k] = v
        elif _number(c, key, v, "SI units") is not None:
            inputs[k] = float(v)
    # parameters and initial values
    values: dict[str, dict[str, float]] = {}
    for section in ("parameters", "initial"):
        raw = d.get(section, {})
        values[section] = {}
        if not isinstance(raw, dict):
            c.add(section, "must be a table", "dotted name = number")
            continue
        for k, v in _flatten(raw).items():
            if _number(c, f"{section}.{k}", v, "SI units") is not None:
                values[section][k] = float(v)
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
        elif k == "timeout":
            if _number(c, key, v, "s", 0.0, MAX_TIMEOUT, strict_low=True) is not None:
                sim.timeout = float(v)
        else:
            low, strict, high = {"t_end": (None, False, None), "t_start": (None, False, None),
                                 "rtol": (RTOL_RANGE[0], False, RTOL_RANGE[1]),
                                 "atol": (ATOL_RANGE[0], False, ATOL_RANGE[1]),
                                 "max_step": (0.0, True, None)}[k]
            if _number(c, key, v, "s" if k in ("t_end", "t_start", "max_step") else "[1]", low,
                       high, strict) is not None:
                setattr(sim, k, float(v))
    if analysis != "transient":
        pass  # no time span: the operating points are solved directly
    elif "t_end" not in (d.get("simulation") if isinstance(d.get("simulation"), dict) else {}):
        c.add("simulation.t_end", "missing: the end time of the run", "a number in s > t_start")
    elif sim.t_end <= sim.t_start:
        c.add("simulation.t_end", f"{sim.t_end!r} must be after t_start = {sim.t_start!r}",
              f"a number in s > {sim.t_start!r}")
    # output
    out = Output()
    for k, v, key in _section(c, d, "output", Output.__dataclass_fields__):
        if k == "folder":
            if not isinstance(v, str) or not v:
                c.add(key, "must be a folder name", "a non-empty text")
            else:
                try:
                    confined_path(v, output_base(path), allowed, "output folder")
                    out.folder = v
                except PathOutsideError as exc:
                    c.add(key, str(exc))
        elif k in ("csv", "plots"):
            if not isinstance(v, bool):
                c.add(key, f"must be true or false, got {v!r}", "true, false")
            else:
                setattr(out, k, v)
        elif k == "plot_groups":
            if not (isinstance(v, list) and all(isinstance(g, list) and g and all(
                    isinstance(n, str) for n in g) for g in v)):
                c.add(key, "must be a list of lists of output names",
                      'e.g. [["w_shaft", "w_middle"], ["Rs"]]')
            else:
                out.plot_groups = v
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
                                    input_units)
    settling = _settling(c, d)
    statics_method = _analysis_options(c, d, analysis, inputs)
    c.raise_if_any()
    return Scene(
        assembly=name, args=args, fidelity=fidelity, inputs=inputs, input_units=input_units,
        parameters=values["parameters"], initial=values["initial"], outputs=list(outputs),
        simulation=sim, output=out, title=title or (Path(path).stem if path else name),
        tolerance=float(tolerance), analysis=analysis, grid=grid, cases=cases,
        settling=settling, transient_on_purpose=on_purpose, statics_method=statics_method,
        path=path, text=text, allow_paths=allowed,
    )


def parse_scene(text: str, path: str | None = None,
                allow_paths: Sequence[str | Path] = ()) -> Scene:
    """Parse and validate scene TOML text (without assembling the model); ``allow_paths`` as
    :func:`scene_from_dict` takes it."""
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise SceneError(f"not valid TOML: {exc}", "", int(m.group(1)) if m else None,
                         "TOML syntax (https://toml.io)", path) from None
    return scene_from_dict(d, path=path, text=text, allow_paths=allow_paths)


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

    Raises
    ------
    SceneError
        Naming the key, the line and the allowed values; for a missing file, the built-in
        scene names.
    """
    p = Path(path)
    if not p.exists():
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
