"""Files a scene reads: input tables (CSV) and bearing datasheets (key ``bearings``).

Each reader raises :class:`SceneFileError` naming the scene key it serves (``inputs.load.file``,
``bearings``), so that the scene validator can report it with the line of that key.
"""

from __future__ import annotations

import csv
import math
import re
from array import array
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.files import FileAccessError, confined_path, open_regular, os_reason
from bearingsim.units import parse_quantity

__all__ = ["SceneFileError", "column_label", "read_table_file", "load_bearings_files",
           "column_unit", "check_table_memory", "available_memory",
           "output_base", "scene_folder", "scene_output_folder"]

_COLUMN_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_.\- ]{0,39}(\s*\[[^\]\x00-\x1f]{0,20}\])?")

_SI_SYMBOL = r"(m|kg|s|N|Pa|J|W|K|rad|V|A|Ohm|H|Wb|T|C|F|mol)(\^-?[0-9])?"
_COHERENT_SI = re.compile(rf"{_SI_SYMBOL}([./]{_SI_SYMBOL})*")
_HEADER_UNIT = re.compile(r"(.*?)\s*\[([^\]]*)\]")
BYTES_PER_ROW = 4000
"""Memory a table row costs a run [bytes]: the interpolation expression (13 symbolic nodes a
row) and the interval check on it; measured: peak RSS of a double_layer_bearing run 117 MB with
10^3 rows, 231 MB with 3x10^4 rows (3.9 kB a row)."""


def scene_folder(path: str | None) -> Path:
    """The folder scene file names are relative to: the scene file's folder, or the current
    folder for a scene without a file.

    Parameters
    ----------
    path : str or None
        The scene file.

    Returns
    -------
    Path
        The folder.
    """
    return Path(path).resolve().parent if path else Path.cwd()


def output_base(path: str | None) -> Path:
    """The folder ``output.folder`` is relative to: the scene file's folder, or the current
    folder for a built-in scene or a scene without a file.

    Parameters
    ----------
    path : str or None
        The scene file (None or a built-in scene: none).

    Returns
    -------
    Path
        The folder.
    """
    from bearingsim.scenes.library import FOLDER

    if path is None or Path(path).resolve().parent == FOLDER.resolve():
        return Path.cwd()
    return scene_folder(path)


class SceneFileError(ParameterError):
    """A file named by a scene cannot be used.

    Parameters
    ----------
    key : str
        The scene key that names the file.
    reason : str
        What is wrong.
    allowed : str
        What was expected (empty: not said).

    Attributes
    ----------
    key : str
        The scene key that names the file (``inputs.load.file``, ``bearings``).
    reason : str
        What is wrong.
    allowed : str
        What was expected.
    """

    def __init__(self, key: str, reason: str, allowed: str = ""):
        self.key, self.reason, self.allowed = key, reason, allowed
        super().__init__(f"{key}: {reason}" + (f"; allowed: {allowed}" if allowed else ""))


def column_label(text: str) -> str | None:
    """``text`` quoted if it looks like a column name (letters, digits, ``_ . -`` and spaces, an
    optional ``[unit]``, at most 40 characters), else None: a message may name a column but
    must not quote a file's content.

    Parameters
    ----------
    text : str
        Text read from a file.

    Returns
    -------
    str or None
        The quoted text, or None.
    """
    return repr(text) if _COLUMN_NAME.fullmatch(text) else None


def _columns_hint(header: list[str]) -> str:
    names = [label for h in header if (label := column_label(h)) is not None]
    other = len(header) - len(names)
    return ", ".join(names + ([f"{other} column(s) with other text"] if other else []))


def column_unit(unit: str) -> tuple[float, str | None]:
    """The factor to SI and the SI unit of a table column's unit (``kN`` -> ``(1000.0,
    "N")``, ``ms`` -> ``(0.001, "s")``).

    The one place a table's units are read, with the units library
    (:func:`bearingsim.units.parse_quantity`): any unit of a quantity the models know
    (``kN``, ``ms``, ``rpm``, ``µm``), a dimensionless mark (``-``, ``1``: SI unit None), or a
    coherent SI unit as bearingsim writes it in its own CSV headers (``Pa.s``, ``m^2/s``:
    factor 1, itself). Units with an offset (``degC``) are refused: a column is scaled, never
    shifted.

    Parameters
    ----------
    unit : str
        The column's unit.

    Returns
    -------
    tuple of (float, str or None)
        Factor to SI and SI unit.

    Raises
    ------
    ValueError
        For any other unit (``lbf``, ``degC``, ``Hz``).
    """
    unit = unit.strip()
    if unit in ("", "-", "1"):
        return 1.0, None
    if _COHERENT_SI.fullmatch(unit):
        return 1.0, unit
    one, two = parse_quantity(f"1 {unit}"), parse_quantity(f"2 {unit}")
    if one is None or two is None or not math.isclose(two[0], 2.0 * one[0]):
        raise ValueError(f"unknown unit {unit!r}")
    return one


def _split_header(cell: str) -> tuple[str, str | None]:
    """``"Fr [kN]"`` -> ``("Fr", "kN")``; ``"Fr"`` -> ``("Fr", None)``."""
    m = _HEADER_UNIT.fullmatch(cell.strip())
    return (m.group(1).strip(), m.group(2)) if m else (cell.strip(), None)


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def available_memory() -> int | None:
    """Memory the operating system can give this process now [bytes] (Linux
    ``MemAvailable``; None where unknown).

    Returns
    -------
    int or None
        Available memory [bytes], or None.
    """
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def check_table_memory(rows: int, what: str) -> None:
    """Refuse a table whose rows the run could not hold in memory
    (:data:`BYTES_PER_ROW` each, against :func:`available_memory`).

    Parameters
    ----------
    rows : int
        Rows of the table.
    what : str
        What the table is, for the message.

    Raises
    ------
    ParameterError
        Naming ``what``, the rows, the memory needed and the memory available.
    """
    free = available_memory()
    need = rows * BYTES_PER_ROW
    if free is not None and need > free // 2:
        raise ParameterError(f"{what}: {rows} rows would need about {need / 1e9:.2g} GB to "
                              f"simulate, more than half the {free / 1e9:.2g} GB of memory "
                              f"available; thin the table (a row every time step the run "
                              f"can resolve is enough)")


def read_table_file(key: str, v: dict[str, Any], base: Path, allowed: Sequence[Path] = ()
                    ) -> tuple[list[float], list[float], str, str | None]:
    """The ``(times, values, source, unit)`` of a table input given as ``{ file, column,
    time_column }`` (``key`` is the input's scene key, ``base`` the scene folder, ``allowed``
    further folders the user allowed).

    The file is a CSV file with a header row; a header cell may give its unit (``Fr [kN]``,
    ``time [ms]``), or the first data row may be a unit row (every cell a unit); values are
    converted to SI and ``unit`` is the SI unit of the value column (None: not given or
    dimensionless). Read in one pass, in time and memory linear in its size.

    Parameters
    ----------
    key : str
        The input's scene key.
    v : dict
        The ``{ file, column, time_column }`` table.
    base : Path
        The scene folder.
    allowed : sequence of Path
        Further folders the user allowed.

    Returns
    -------
    tuple of (list of float, list of float, str, str or None)
        Times [s], values (SI units), source and SI unit.

    Raises
    ------
    SceneFileError
        Naming the file, the column or row and what was expected; never quoting the file.
    """
    try:
        path = confined_path(v["file"], base, allowed, "table file")
        free = available_memory()
        fh = open_regular(path, "table file", free // 4 if free else None)
    except FileAccessError as exc:
        raise SceneFileError(f"{key}.file", str(exc),
                             "a CSV file with a header row, relative to the scene file") from None
    name = path.name
    col, tcol = v.get("column"), v.get("time_column", "time")

    def fail(sub: str, reason: str, allowed_text: str = "") -> SceneFileError:
        return SceneFileError(f"{key}.{sub}", f"{name}: {reason}", allowed_text)

    times, vals = array("d"), array("d")
    line = 1
    try:
        with fh:
            reader = csv.reader(fh)
            raw = next(reader, None)
            if not raw:
                raise fail("file", "no header row", "a CSV file whose first row names the "
                           "columns")
            header = [_split_header(c) for c in raw]
            names = [n for n, _ in header]
            for k, n in enumerate(names):
                if n in names[:k]:
                    label = column_label(n) or "(the same text)"
                    raise fail("file", f"columns {names.index(n) + 1} and {k + 1} of the "
                               f"header have the same name {label}", "distinct column names")
            if tcol not in names or col not in names:
                sub = "time_column" if tcol not in names else "column"
                separator = next((f"; the header row is one column with {s!r} in it: the "
                                  "file's cells must be separated by commas"
                                  for s in (";", "\t", "|") if len(raw) == 1 and s in raw[0]),
                                 "")  # (the separator named, never the file's text)
                raise fail(sub, f"column {(tcol if sub == 'time_column' else col)!r} not in "
                           f"the header row{separator}", _columns_hint(names))
            it, iv = names.index(tcol), names.index(col)
            units = [u for _, u in header]
            for row in reader:
                line = reader.line_num
                if not row or (len(row) == 1 and not row[0].strip()):
                    continue  # a blank line
                if len(row) != len(names):
                    raise fail("file", f"line {line} has {len(row)} cells, the header "
                               f"{len(names)}", "a cell for every column")
                if not times and not units[it] and not units[iv] and not any(
                        _is_float(c) for c in row):
                    units = _unit_row(row, line, fail)  # "s, kN" under the header
                    continue
                for index, target in ((it, times), (iv, vals)):
                    try:
                        number = float(row[index])
                    except ValueError:
                        raise fail("file", f"line {line}, column {names[index]!r}: not a "
                                   f"number", "a number in every data row (a unit row only "
                                   "directly under the header, every cell a unit)") from None
                    if not math.isfinite(number):
                        raise fail("file", f"line {line}, column {names[index]!r}: not finite",
                                   "finite numbers")
                    target.append(number)
    except UnicodeDecodeError:
        raise fail("file", "not UTF-8 text", "UTF-8 text (from Excel: save as 'CSV UTF-8')"
                   ) from None
    except csv.Error as exc:
        raise fail("file", f"not a CSV table near line {line} ({type(exc).__name__})") from None
    except OSError as exc:
        raise fail("file", f"cannot read it: {os_reason(exc)}") from None
    try:
        check_table_memory(len(times), f"table file {name}")
    except ParameterError as exc:
        raise SceneFileError(f"{key}.file", str(exc)) from None
    factors = []
    for index, what in ((it, "time_column"), (iv, "column")):
        try:
            factors.append(column_unit(units[index] or ""))
        except ValueError:
            raise fail(what, f"the unit of column {names[index]!r} is not known",
                       "a unit of a model quantity (kN, ms, rpm, mm, µm) "
                       "or coherent SI (Pa.s, m^2/s)") from None
    (t_factor, t_unit), (v_factor, v_unit) = factors
    if t_unit not in (None, "s"):
        raise fail("time_column", f"column {tcol!r} is in {t_unit}, not a time unit",
                   "s, ms or no unit (seconds)")
    if t_factor != 1.0:
        times = array("d", (x * t_factor for x in times))
    if v_factor != 1.0:
        vals = array("d", (x * v_factor for x in vals))
    return times.tolist(), vals.tolist(), f"{name}:{col}", v_unit


def _unit_row(row: list[str], line: int, fail) -> list[str]:
    """The units of a unit row (checked: every cell a unit)."""
    for k, cell in enumerate(row):
        try:
            column_unit(cell)
        except ValueError:
            raise fail("file", f"line {line}, column {k + 1}: neither a number nor a unit",
                       "numbers; a unit row only directly under the header, every cell a "
                       "unit") from None
    return [c.strip() for c in row]


def scene_output_folder(scene) -> Path:
    """The real path of a scene's ``output.folder``: relative to :func:`output_base`, inside
    it or an allowed folder (:func:`~bearingsim.files.confined_path`).

    Parameters
    ----------
    scene : Scene
        The loaded scene.

    Returns
    -------
    Path
        The folder.
    """
    return confined_path(scene.output.folder, output_base(scene.path), scene.allow_paths,
                         "output folder")


def load_bearings_files(files: Any, base: Path, allowed: Sequence[Path] = ()
                        ) -> list[SceneFileError]:
    """Register the bearings of the scene's datasheet file(s) (key ``bearings``, relative to
    the scene folder ``base`` or in an ``allowed`` folder) before the assembly's bearing names
    are checked; the problems found.

    Parameters
    ----------
    files : str or list of str
        The ``bearings`` key: datasheet file name(s).
    base : Path
        The scene folder.
    allowed : sequence of Path
        Further folders the user allowed.

    Returns
    -------
    list of SceneFileError
        The problems found (empty: none).
    """
    if files is None:
        return []
    from bearingsim.catalog import load_datasheet

    problems = []
    for item in files if isinstance(files, list) else [files]:
        if not isinstance(item, str):
            problems.append(SceneFileError("bearings", f"{item!r} is not a file name",
                                           "a datasheet file or a list of them"))
            continue
        try:
            load_datasheet(confined_path(item, base, allowed, "bearing datasheet"),
                           replace=True)
        except BearingsimError as exc:
            problems.append(SceneFileError("bearings", str(exc),
                                           "a CSV or TOML datasheet in catalogue units"))
    return problems
