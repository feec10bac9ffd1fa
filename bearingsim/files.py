"""Output files written whole or not at all.

A run interrupted (Ctrl-C, an error) while it writes a CSV, a plot, a summary or an FMU must not
leave a partial file that looks like a result. :func:`atomic_path` gives the writer a temporary
name in the same folder (with the same suffix, so that tools which infer the format from it
still work) and renames it to the final name only when the writer is done.
"""

from __future__ import annotations

import contextlib
import csv
import os
from collections.abc import Iterator
from pathlib import Path

from bearingsim.units import unit_label

__all__ = ["atomic_path", "column_name", "write_series_csv"]


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """A temporary path to write ``path`` to; renamed to ``path`` when the block completes.

    Parameters
    ----------
    path : str or pathlib.Path
        The final file.

    Yields
    ------
    pathlib.Path
        ``.<stem>.<pid>.part<suffix>`` beside ``path``; removed if the block raises (including
        ``KeyboardInterrupt``).
    """
    path = Path(path)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.part{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()


def column_name(name: str, unit: str) -> str:
    """The CSV header of a series: ``"name [unit]"``, ``[-]`` for a dimensionless one."""
    return f"{name} [{unit_label(unit)}]"


def write_series_csv(path: str | Path, t, columns: dict, units: dict[str, str]) -> Path:
    """Write time series as CSV with one header row ``time [s], name [unit], ...`` (readable by
    ``pandas.read_csv`` without options), atomically (:func:`atomic_path`).

    Parameters
    ----------
    path : str or Path
        The file.
    t : array_like
        Times [s].
    columns : dict
        Name -> values at the times.
    units : dict
        Name -> unit (missing: dimensionless).

    Returns
    -------
    Path
    """
    import numpy as np

    path = Path(path)
    names = list(columns)
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([column_name("time", "s"), *[column_name(n, units.get(n, "")) for n in names]])
        w.writerows(np.vstack([t, *[columns[n] for n in names]]).T.tolist())
    return path
