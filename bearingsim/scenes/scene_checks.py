"""The checks of a scene's sections: every value against its kind, unit and range, collected so
that one error lists every problem with its key and line."""

from __future__ import annotations

import difflib
import functools
import math
from pathlib import Path
from typing import Any

import numpy as np

from bearingsim.assemblies.spec import ArgSpec, AssemblySpec
from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.files import PathOutsideError, confined_path
from bearingsim.scenes.expression_units import expression_unit
from bearingsim.scenes.expressions import ExpressionError, compile_expression, constant_value
from bearingsim.scenes.scene_types import (
    POINT_HEADS,
    STATICS_METHODS,
    TABLE_KEYS,
    Output,
    SceneError,
    Settling,
    Simulation,
    TableInput,
    line_of,
)
from bearingsim.scenes.tables import (
    SceneFileError,
    check_table_memory,
    output_base,
    read_table_file,
)
from bearingsim.units import parse_quantity
from bearingsim.units.registry import UnitError, quantity_to_si, same_quantity, split_quantity


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
            integer=False, si_unit: str | None = None) -> float | None:
    """``v`` checked (a number, in range; ``unit`` names its unit in messages), or None with
    the problem recorded. Given ``si_unit``, a number with a unit (``"1.5 kN"``, ``"50 ms"``)
    is taken in that SI unit."""
    if si_unit is not None and isinstance(v, str) and split_quantity(v) is not None:
        try:
            v = quantity_to_si(v, si_unit, key)
        except UnitError as exc:
            c.add(key, str(exc).removeprefix(f"{key}: "), f"a number in {unit}, or a number "
                                                           "with a unit of that quantity")
            return None
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


def _unit_text(spec: ArgSpec) -> str:
    """The SI unit of a number argument as a message names it (``N``, ``rad/s``; ``-`` for a
    dimensionless one)."""
    return "-" if spec.unit == "1" else spec.unit


def _check_arg(c: _Collector, key: str, spec: ArgSpec, v: Any) -> Any:
    from bearingsim.catalog import BEARINGS, list_bearings
    from bearingsim.catalog.rollers import ROLLER_BEARINGS
    from bearingsim.physics.lubricant import as_lubricant, known_lubricants

    if v is None:
        return None
    if spec.kind == "bearing":  # as the catalogue reads it ("7020c", "NU 206"), spelled its way
        found = spec.designation(v)
        if found is None:
            # the other catalogue's kind (each catalogue knows the other as its sibling)
            other = BEARINGS.in_sibling(v) or ROLLER_BEARINGS.in_sibling(v)
            elsewhere = f" ({v!r} is {other}: not one of this assembly's bearings)" if other \
                else ""
            c.add(key, f"unknown bearing designation {v!r}{elsewhere}",
                  ", ".join(spec.known() if spec.known is not None else list_bearings()))
            return v
        return found
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
    if spec.kind == "signal":  # "0.1 N m" in its SI unit, or an expression of t
        if isinstance(v, str) and split_quantity(v) is None:
            try:
                compile_expression(v, key)
                unit = expression_unit(v, key)
            except ExpressionError as exc:
                c.add(key, str(exc).split(": ", 1)[1].split(". Allowed:")[0],
                      str(exc).split("Allowed: ", 1)[-1])
                return v
            if unit is not None and not same_quantity(unit, spec.unit):
                c.add(key, f"{key} is in {_unit_text(spec)}, but its expression {v!r} gives "
                      f"{unit} (rpm() converts r/min to rad/s, deg() degrees to rad)",
                      f"an expression of t in {_unit_text(spec)}")
            return v
        return _number(c, key, v, _unit_text(spec), si_unit=spec.unit)
    if spec.kind == "float":  # "1.5 kN", "4000 rpm": in the argument's SI unit
        return _number(c, key, v, _unit_text(spec), low=spec.low, high=spec.high,
                       strict_low=spec.low is not None and not spec.low_inclusive,
                       si_unit=spec.unit)
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
        checked = {}
        for k, item in v.items():
            if k not in (spec.table or {}):
                _unknown(c, key, k, spec.table or {})
                checked[k] = item
            else:
                checked[k] = _check_arg(c, f"{key}.{k}", spec.table[k], item)
        return checked
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
    rule = "at least two rows, equally many times and values, times strictly increasing"
    if t.size < 2 or t.size != y.size:
        c.add(key, f"a table needs at least two rows and a value per time; got {t.size} "
              f"time(s) and {y.size} value(s)", rule)
        return None
    back = np.flatnonzero(np.diff(t) <= 0)
    if back.size:  # rows counted from 1 among the data rows (a file's header not counted)
        k = int(back[0])
        c.add(key, f"times must increase strictly: data row {k + 2} has t = {t[k + 1]:g} s after "
              f"t = {t[k]:g} s in row {k + 1}", rule)
        return None
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        c.add(key, "table values must be finite")
        return None
    return TableInput(t.tolist(), y.tolist(), source)


def _inputs(c: _Collector, d: dict[str, Any], base: Path, allowed: tuple[str, ...],
            carried_units: dict[str, str] | None
            ) -> tuple[dict[str, Any], dict[str, str]]:
    """The ``[inputs]`` of a scene, checked (numbers and quantities in SI, expressions,
    tables), and the SI unit of each given with a unit (also those ``carried_units`` names,
    by input name, for an input given as a number or table: the unit of a copy's SI
    value)."""
    inputs: dict[str, Any] = {}
    input_units: dict[str, str] = {}
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
                if (unit := expression_unit(v, key)) is not None:
                    input_units[k] = unit  # rpm(), deg(): the unit the model must read
            except ExpressionError as exc:
                c.add(key, str(exc).split(": ", 1)[1].split(". Allowed:")[0],
                      str(exc).split("Allowed: ", 1)[-1])
        elif isinstance(v, TableInput):
            inputs[k] = v
        elif _number(c, key, v, "SI units") is not None:
            inputs[k] = float(v)
    for k, unit in (carried_units or {}).items():
        if k in inputs and not isinstance(inputs[k], str):
            input_units.setdefault(k, unit)
    return inputs, input_units


@functools.lru_cache(maxsize=1024)
def _first_non_finite(text: str, t_start: float, t_end: float, n: int) -> float | None:
    """The first of ``n`` evenly spaced times in ``[t_start, t_end]`` [s] where the expression
    ``text`` is not finite; None when it is finite at all of them or does not compile (the
    syntax check reports that). Kept per arguments: a sweep checks each point's scene, and its
    points share few expressions and time spans."""
    import casadi as ca

    t = ca.SX.sym("t")
    grid = np.linspace(t_start, t_end, n)
    try:
        fn = ca.Function("u", [t], [ca.SX(compile_expression(text)(t))])
        vals = np.asarray(fn.map(grid.size)(grid[None, :]), dtype=float).ravel()
    except Exception:  # noqa: BLE001 - reported by the syntax check already
        return None
    bad = ~np.isfinite(vals)
    return float(grid[np.argmax(bad)]) if np.any(bad) else None


def _check_signals(c: _Collector, inputs: dict[str, Any], sim: Simulation,
                   section: str = "inputs") -> None:
    """Expressions must be finite over the time span (checked on a fine grid)."""
    for name, v in inputs.items():
        if not isinstance(v, str):
            continue
        bad = _first_non_finite(v, float(sim.t_start), float(sim.t_end),
                                max(2 * sim.n_points, 201))
        if bad is not None:
            c.add(f"{section}.{name}", f"the expression {v!r} is not finite at t = "
                  f"{bad:.6g} s (in the time span "
                  f"[{sim.t_start:g}, {sim.t_end:g}] s)", "an expression finite for all t")


def _point_value(c: _Collector, key: str, where: str, v: Any, spec: AssemblySpec | None,
                 units: dict[str, str], value_units: dict[str, str]) -> Any:
    """One value of an operating grid or load case, checked against its key; inputs and
    parameters in SI (the unit of one given with a unit recorded in ``units`` by input name,
    in ``value_units`` by key)."""
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
        return _check_arg(c, where, arg, v)
    if head == "inputs" and isinstance(v, str) and (quantity := parse_quantity(v)) is not None:
        if units.setdefault(rest, quantity[1]) != quantity[1]:
            c.add(where, f"input {rest} is given in {units[rest]} and, as {v!r}, in "
                  f"{quantity[1]}: values of another quantity", f"numbers with units of one "
                  f"quantity ({units[rest]}), or numbers in the input's unit")
            return None
        return quantity[0]
    if head == "parameters":
        return _quantity_value(c, where, key, v, value_units)
    value = _number(c, where, v, "SI units or a number with a unit ('10000 rpm')"
                    if head == "inputs" else "SI units")
    return None if value is None else float(value)


def _quantity_value(c: _Collector, where: str, key: str, v: Any,
                   value_units: dict[str, str]) -> float | None:
    """A parameter's or an initial value: a number in SI units, or a number with a unit
    (``"1.5 kN"``: its SI value; the SI unit recorded in ``value_units`` under ``key``, to
    be checked against the model's when it is assembled); None when invalid."""
    if isinstance(v, str) and (quantity := parse_quantity(v)) is not None:
        if value_units.setdefault(key, quantity[1]) != quantity[1]:
            c.add(where, f"{key} is given in {value_units[key]} and, as {v!r}, in "
                  f"{quantity[1]}: values of another quantity", "numbers with units of one "
                  f"quantity ({value_units[key]})")
            return None
        return quantity[0]
    value = _number(c, where, v, "SI units or a number with a unit ('1.5 kN')")
    return None if value is None else float(value)


def _operating_points(c: _Collector, d: dict[str, Any], spec: AssemblySpec | None,
                      units: dict[str, str], value_units: dict[str, str]
                      ) -> tuple[dict[str, list[Any]], list[dict[str, Any]]]:
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
        grid[key] = [_point_value(c, key, where, v, spec, units, value_units)
                     for v in values]
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
                point[key] = _point_value(c, key, where, v, spec, units, value_units)
        point.setdefault("name", f"case {k + 1}")
        cases.append(point)
    if grid and cases:
        c.add("cases", "give the operating points either as a grid or as cases, not both",
              "[grid] or [[cases]]")
    return grid, cases


def _output(c: _Collector, d: dict[str, Any], path: str | None,
            allowed: tuple[str, ...]) -> Output:
    """The ``[output]`` section: its folder (inside the scene's output base or an allowed
    folder), the CSV and plot switches and the plot groups."""
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
    return out


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
    sim, out = d.get("simulation"), d.get("output")  # were read, then left unused
    for k in sim if isinstance(sim, dict) else {}:
        if k in Simulation.__dataclass_fields__ and k != "timeout":
            c.add(f"simulation.{k}", f"simulation.{k} applies to transient scenes only (a "
                  f"{analysis} analysis solves each point directly, not in time)",
                  "simulation.timeout (a sweep point's time budget)")
    if isinstance(out, dict) and out.get("plot_groups"):
        c.add("output.plot_groups", f"output.plot_groups applies to transient scenes only "
              f"(the {analysis} figure draws its own columns; outputs chooses them)")
    if analysis == "statics":  # its solvers take the bearing by name: model values unused
        cases = [case for case in d.get("cases") or [] if isinstance(case, dict)]
        swept = {"grid": list(d.get("grid") or {}) if isinstance(d.get("grid"), dict) else [],
                 "cases": [k for case in cases for k in case]}
        for key in [*(s for s in ("parameters", "initial") if d.get(s)),
                    *(where for where, keys in swept.items()
                      if any(str(k).startswith("parameters.") for k in keys))]:
            c.add(key, "a statics scene solves its bearing from the designation and the "
                  "assembly arguments, not from the model's parameters or start values, which "
                  "it would leave unused", "the bearing's values in a datasheet (bearings = "
                  "...), assembly arguments, or a steady scene of the quasi-static level")
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
