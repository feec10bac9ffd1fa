"""The scene model (a dataclass) and its TOML loader and validator.

A scene names an assembly and its arguments, a fidelity (or ``"auto"``), input signals
(numbers, expressions of ``t`` or CSV tables), parameter and initial-state overrides, the
requested outputs, the time span and solver settings, and the output folder. See
``docs/scenes.md`` for the format.

Errors name the key (dotted, e.g. ``simulation.rtol``), the line in the file and the allowed
values.
"""

from __future__ import annotations

import csv
import difflib
import math
import re
import sys
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.assemblies.spec import ArgSpec, AssemblySpec
from bearingsim.checks import ATOL_RANGE, RTOL_RANGE
from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.scenes.expressions import ExpressionError, compile_expression
from bearingsim.scenes.library import builtin_scene_path, builtin_scenes
from bearingsim.scenes.registry import REGISTRY
from bearingsim.simulation.budget import DEFAULT_MAX_STEPS, MAX_TIMEOUT
from bearingsim.simulation.integrators import METHODS
from bearingsim.units import parse_quantity

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = [
    "Scene",
    "Simulation",
    "Output",
    "TableInput",
    "SceneError",
    "load_scene",
    "parse_scene",
    "scene_from_dict",
    "line_of",
]

TOP_KEYS = ("title", "description", "outputs", "tolerance", "bearings", "assembly", "inputs",
            "parameters", "initial", "simulation", "output")
DEFAULT_TOLERANCE = 0.05
"""Largest relative error of the requested outputs a scene accepts from ``fidelity = "auto"``
when it gives no ``tolerance`` [-]."""
TABLE_KEYS = ("file", "column", "time_column", "times", "values")


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
    method: str = "BDF"
    rtol: float = 1e-6
    atol: float = 1e-8
    n_points: int = 501
    max_step: float = math.inf
    initial: str = "start"
    max_steps: int = DEFAULT_MAX_STEPS
    timeout: float | None = None


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
    tolerance : float
        Largest relative error [-] of the requested outputs that ``fidelity = "auto"`` may
        accept from a lower level (its measured error against the reference level,
        :attr:`~bearingsim.assemblies.spec.AssemblySpec.level_errors`); default
        :data:`DEFAULT_TOLERANCE`.
    path : str, optional
        The scene file (for error messages and relative table paths).
    text : str, optional
        The scene file text (for line numbers in error messages).
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
    path: str | None = None
    text: str | None = field(default=None, repr=False)

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
        return {
            "title": self.title,
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
        return scene_from_dict(Scene(**d).to_dict(), path=self.path, text=None)


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


def _table_input(c: _Collector, key: str, v: dict, base: Path) -> TableInput | None:
    bad = set(v) - set(TABLE_KEYS)
    if bad:
        _unknown(c, key, sorted(bad)[0], TABLE_KEYS)
        return None
    if "file" in v:
        path = Path(v["file"])
        path = path if path.is_absolute() else base / path
        col = v.get("column")
        tcol = v.get("time_column", "time")
        if not path.is_file():
            c.add(f"{key}.file", f"table file {str(path)!r} not found",
                  "a CSV file with a header row, relative to the scene file")
            return None
        try:
            with path.open(newline="") as fh:
                rows = list(csv.reader(fh))
        except OSError as exc:
            c.add(f"{key}.file", f"cannot read {str(path)!r}: {exc}")
            return None
        # "name [unit]" headers (bearingsim's own CSVs) match the name alone
        header = [re.sub(r"\s*\[[^\]]*\]$", "", h.strip()) for h in rows[0]] if rows else []
        if tcol not in header or col not in header:
            missing = "time_column" if tcol not in header else "column"
            c.add(f"{key}.{missing}", f"column {(tcol if missing == 'time_column' else col)!r} "
                  f"not in {path.name}", ", ".join(header))
            return None
        it, iv = header.index(tcol), header.index(col)
        times, vals = [], []
        for k, row in enumerate(rows[1:], start=2):
            try:
                times.append(float(row[it]))
                vals.append(float(row[iv]))
            except (ValueError, IndexError):
                if k == 2:  # a unit row
                    continue
                c.add(f"{key}.file", f"{path.name} line {k}: not a number in {tcol!r} or "
                      f"{col!r}", "numbers in SI units")
                return None
        source = f"{path.name}:{col}"
    else:
        if "times" not in v or "values" not in v:
            c.add(key, "a table input needs 'file' and 'column', or 'times' and 'values'",
                  ", ".join(TABLE_KEYS))
            return None
        times, vals, source = v["times"], v["values"], "inline"
        if not all(_is_number(x) for x in list(times) + list(vals)):
            c.add(key, "times and values must be numbers", "lists of numbers in SI units")
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


def _load_bearings(c: _Collector, files: Any, path: str | None) -> None:
    """Register the bearings of the scene's datasheet file(s) (key ``bearings``, relative to
    the scene file) before the assembly's bearing names are checked."""
    if files is None:
        return
    from bearingsim.catalog import load_datasheet

    base = Path(path).resolve().parent if path else Path.cwd()
    for item in files if isinstance(files, list) else [files]:
        if not isinstance(item, str):
            c.add("bearings", f"{item!r} is not a file name", "a datasheet file or a list of them")
            continue
        file = Path(item) if Path(item).is_absolute() else base / item
        try:
            load_datasheet(file, replace=True)
        except BearingsimError as exc:
            c.add("bearings", str(exc), "a CSV or TOML datasheet in catalogue units")


def scene_from_dict(d: dict[str, Any], path: str | None = None,
                    text: str | None = None) -> Scene:
    """Validate a scene in its nested-dict (TOML) form and build a :class:`Scene`.

    Raises
    ------
    SceneError
        Listing every problem with its key, line and allowed values.
    """
    c = _Collector(text, path)
    for k in d:
        if k not in TOP_KEYS:
            _unknown(c, "", k, TOP_KEYS)
    _load_bearings(c, d.get("bearings"), path)
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
    base = Path(path).resolve().parent if path else Path.cwd()
    raw_inputs = d.get("inputs", {})
    if not isinstance(raw_inputs, dict):
        c.add("inputs", "must be a table", "name = number, expression or table")
        raw_inputs = {}
    for k, v in _flatten(raw_inputs, keep_tables=True).items():
        key = f"inputs.{k}"
        if isinstance(v, dict):
            tab = _table_input(c, key, v, base)
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
    if "t_end" not in (d.get("simulation") if isinstance(d.get("simulation"), dict) else {}):
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
                out.folder = v
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
    c.raise_if_any()
    return Scene(
        assembly=name, args=args, fidelity=fidelity, inputs=inputs, input_units=input_units,
        parameters=values["parameters"], initial=values["initial"], outputs=list(outputs),
        simulation=sim, output=out, title=title or (Path(path).stem if path else name),
        tolerance=float(tolerance), path=path, text=text,
    )


def parse_scene(text: str, path: str | None = None) -> Scene:
    """Parse and validate scene TOML text (without assembling the model)."""
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise SceneError(f"not valid TOML: {exc}", "", int(m.group(1)) if m else None,
                         "TOML syntax (https://toml.io)", path) from None
    return scene_from_dict(d, path=path, text=text)


def load_scene(path: str | Path) -> Scene:
    """Read, parse and validate a scene file (without assembling the model).

    Parameters
    ----------
    path : str or Path
        A scene TOML file, or the name of a built-in scene
        (:func:`~bearingsim.scenes.library.builtin_scenes`, e.g. ``"double_layer_rs"``) when no
        such file exists.

    Raises
    ------
    SceneError
        Naming the key, the line and the allowed values; for a missing file, the built-in
        scene names.
    """
    p = Path(path)
    if not p.exists():
        p = builtin_scene_path(str(path)) or p
    try:
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneError(f"scene file {str(p)!r} not found; built-in scenes: "
                         f"{', '.join(builtin_scenes())}", path=str(p)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneError(f"cannot read scene file: {exc}", path=str(p)) from None
    return parse_scene(text, str(p))
