"""The table of a sweep on disk: one CSV row per finished point, appended as it arrives.

Each row is written by one ``write`` on a file opened for appending and flushed, so the table
is readable (``pandas.read_csv``) while the sweep runs and a sweep killed at any moment leaves
every finished row whole (at worst a last line cut mid-way, which :func:`open_table` drops).
When the sweep completes, the table is rewritten in point order (atomically) and copied to
Parquet when pyarrow is installed. ``resume`` keeps the rows of an earlier run of the same
sweep (same columns, same values at each point number) and reports their points as done.
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path
from typing import Any

from bearingsim.files import atomic_path
from bearingsim.scenes.sampling import SweepError
from bearingsim.series_csv import column_name

__all__ = ["SweepTable", "open_table", "cell", "from_cell"]


def cell(value: Any) -> str:
    """A value as the table writes it (floats round-trip exactly).

    Parameters
    ----------
    value : object
        A table value.

    Returns
    -------
    str
        Its text.
    """
    if isinstance(value, float):  # numpy's float64 too, whose repr names its type
        return repr(float(value))
    return str(value)


class SweepTable:
    """An append-only CSV table with a fixed header.

    Parameters
    ----------
    path : Path
        The CSV file.
    columns : list of str
        Column keys in order; ``units`` gives the ``[unit]`` of the numeric ones.
    units : dict
        Key -> SI unit.
    """

    def __init__(self, path: Path, columns: list[str], units: dict[str, str]):
        self.path = Path(path)
        self.columns = list(columns)
        self.header = [column_name(k, units[k]) if k in units else k for k in columns]

    def _line(self, values: list[str]) -> bytes:
        buf = io.StringIO()
        csv.writer(buf, lineterminator="\n").writerow(values)
        return buf.getvalue().encode()

    def start(self) -> None:
        """Create the file with its header (replacing an earlier table)."""
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(self.path) as tmp:
            tmp.write_bytes(self._line(self.header))

    def append(self, row: dict[str, Any]) -> None:
        """Append one row, whole (one write, flushed to the operating system).

        Parameters
        ----------
        row : dict
            Values by column.
        """
        line = self._line([cell(row.get(k, "")) for k in self.columns])
        fd = os.open(self.path, os.O_WRONLY | os.O_APPEND)
        try:
            os.write(fd, line)
        finally:
            os.close(fd)

    @staticmethod
    def ready() -> None:
        """Import what :meth:`finish` takes to write the Parquet copy (pyarrow, if installed),
        ahead of the sweep's end."""
        try:
            import pyarrow.csv  # noqa: F401
            import pyarrow.parquet  # noqa: F401
        except ImportError:
            pass

    def finish(self, rows: list[dict[str, Any]]) -> list[Path]:
        """Rewrite the table with ``rows`` (in the given order) atomically; add the Parquet copy
        when pyarrow is installed. Returns the files.

        Parameters
        ----------
        rows : list of dict
            Every row of the sweep.

        Returns
        -------
        list of Path
            The table and, with pyarrow, the Parquet copy.
        """
        with atomic_path(self.path) as tmp:
            tmp.write_bytes(self._line(self.header) + b"".join(
                self._line([cell(r.get(k, "")) for k in self.columns]) for r in rows))
        files = [self.path]
        try:
            import pyarrow.csv as pacsv
            import pyarrow.parquet as pq
        except ImportError:
            return files
        parquet = self.path.with_suffix(".parquet")
        with atomic_path(parquet) as tmp:
            pq.write_table(pacsv.read_csv(self.path), tmp)
        return files + [parquet]


def open_table(table: SweepTable, resume: bool, expected: dict[int, dict[str, str]]
               ) -> dict[int, dict[str, str]]:
    """Start ``table`` or, with ``resume``, read the rows an earlier run left.

    Parameters
    ----------
    table : SweepTable
    resume : bool
        Keep an existing table with the same header; otherwise start a new one.
    expected : dict
        Point number -> {column key: cell text} of the swept values, to check that a row of
        the earlier run belongs to the same point.

    Returns
    -------
    dict
        Point number -> row (column key -> cell text) of the rows kept.

    Raises
    ------
    SweepError
        When the existing table has other columns, or a row's swept values differ from the
        point of the same number (another sweep wrote it).
    """
    if not resume or not table.path.is_file():
        table.start()
        return {}
    raw = table.path.read_bytes()
    if raw and not raw.endswith(b"\n"):  # a row cut by a kill: drop it
        raw = raw[: raw.rfind(b"\n") + 1]
        with open(table.path, "r+b") as fh:
            fh.truncate(len(raw))
    lines = list(csv.reader(io.StringIO(raw.decode())))
    if not lines or lines[0] != table.header:
        raise SweepError(f"--resume: {table.path} has other columns than this sweep "
                         f"({', '.join(lines[0]) if lines else 'empty'}); resume the same "
                         "sweep, or give another --out")
    done: dict[int, dict[str, str]] = {}
    for values in lines[1:]:
        row = dict(zip(table.columns, values, strict=True))
        index = int(row["point"])
        want = expected.get(index)
        if want is None or any(row[k] != v for k, v in want.items()):
            raise SweepError(f"--resume: row of point {index} in {table.path} has other values "
                             f"than this sweep's point {index} ({want}); resume the same "
                             "sweep, or give another --out")
        done[index] = row
    return done


def from_cell(text: str) -> Any:
    """A table cell read back: int, float, bool or text.

    Parameters
    ----------
    text : str
        The cell as :func:`cell` wrote it.

    Returns
    -------
    int or float or bool or str
        The value.
    """
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return {"True": True, "False": False}.get(text, text)
