"""CSV files of named series with the unit of each in its header (``name [unit]``), written
whole or not at all (:func:`~bearingsim.files.atomic_path`): a scene's or a result's time
series, and the header cells of the analysis and sweep tables.
"""

from __future__ import annotations

import csv
from pathlib import Path

from bearingsim.files import atomic_path
from bearingsim.units import unit_label

__all__ = ["column_name", "write_series_csv"]


def column_name(name: str, unit: str) -> str:
    """The CSV header of a series: ``"name [unit]"``, ``[-]`` for a dimensionless one.

    Parameters
    ----------
    name : str
        Series name.
    unit : str
        Its SI unit (``"1"`` or ``""`` for dimensionless).

    Returns
    -------
    str
        The header.
    """
    return f"{name} [{unit_label(unit)}]"


def write_series_csv(path: str | Path, t, columns: dict, units: dict[str, str]) -> Path:
    """Write time series as CSV with one header row ``time [s], name [unit], ...`` (readable by
    ``pandas.read_csv`` without options), atomically (:func:`~bearingsim.files.atomic_path`).

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
