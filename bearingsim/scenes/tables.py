"""Files a scene reads: input tables (CSV) and bearing datasheets (key ``bearings``).

Each reader raises :class:`SceneFileError` naming the scene key it serves (``inputs.load.file``,
``bearings``), so that the scene validator can report it with the line of that key.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path
from typing import Any

from bearingsim.errors import BearingsimError, ParameterError

__all__ = ["SceneFileError", "read_table_file", "load_bearings_files"]


class SceneFileError(ParameterError):
    """A file named by a scene cannot be used.

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


def read_table_file(key: str, v: dict[str, Any], base: Path
                    ) -> tuple[list[float], list[float], str]:
    """The ``(times, values, source)`` of a table input given as ``{ file, column,
    time_column }`` (``key`` is the input's scene key, ``base`` the scene folder).

    Raises
    ------
    SceneFileError
    """
    path = Path(v["file"])
    path = path if path.is_absolute() else base / path
    col = v.get("column")
    tcol = v.get("time_column", "time")
    if not path.is_file():
        raise SceneFileError(f"{key}.file", f"table file {str(path)!r} not found",
                             "a CSV file with a header row, relative to the scene file")
    try:
        with path.open(newline="") as fh:
            rows = list(csv.reader(fh))
    except OSError as exc:
        raise SceneFileError(f"{key}.file", f"cannot read {str(path)!r}: {exc}") from None
    # "name [unit]" headers (bearingsim's own CSVs) match the name alone
    header = [re.sub(r"\s*\[[^\]]*\]$", "", h.strip()) for h in rows[0]] if rows else []
    if tcol not in header or col not in header:
        missing = "time_column" if tcol not in header else "column"
        raise SceneFileError(f"{key}.{missing}", f"column "
                             f"{(tcol if missing == 'time_column' else col)!r} not in "
                             f"{path.name}", ", ".join(header))
    it, iv = header.index(tcol), header.index(col)
    times, vals = [], []
    for k, row in enumerate(rows[1:], start=2):
        try:
            times.append(float(row[it]))
            vals.append(float(row[iv]))
        except (ValueError, IndexError):
            if k == 2:  # a unit row
                continue
            raise SceneFileError(f"{key}.file", f"{path.name} line {k}: not a number in "
                                 f"{tcol!r} or {col!r}", "numbers in SI units") from None
    return times, vals, f"{path.name}:{col}"


def load_bearings_files(files: Any, path: str | None) -> list[SceneFileError]:
    """Register the bearings of the scene's datasheet file(s) (key ``bearings``, relative to
    the scene file) before the assembly's bearing names are checked; the problems found."""
    if files is None:
        return []
    from bearingsim.catalog import load_datasheet

    problems = []
    base = Path(path).resolve().parent if path else Path.cwd()
    for item in files if isinstance(files, list) else [files]:
        if not isinstance(item, str):
            problems.append(SceneFileError("bearings", f"{item!r} is not a file name",
                                           "a datasheet file or a list of them"))
            continue
        file = Path(item) if Path(item).is_absolute() else base / item
        try:
            load_datasheet(file, replace=True)
        except BearingsimError as exc:
            problems.append(SceneFileError("bearings", str(exc),
                                           "a CSV or TOML datasheet in catalogue units"))
    return problems
