"""The table of an analysis scene (steady, modes, statics): its columns' SI units and the CSV
file, one row per operating point. Running the points is
:func:`bearingsim.scenes.analyses.run_points`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from bearingsim.files import atomic_path
from bearingsim.scenes.operating_points import point_units
from bearingsim.scenes.preparation import Prepared, point_keys
from bearingsim.scenes.statics_table import statics_of
from bearingsim.series_csv import column_name

__all__ = ["analysis_units", "write_table"]


def analysis_units(prep: Prepared, rows: list[dict[str, Any]]) -> dict[str, str]:
    """SI unit of each column of an analysis table.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    rows : list of dict
        The analysis table's rows, one per operating point.

    Returns
    -------
    dict of str to str
        SI unit by column name.
    """
    scene = prep.scene
    units = point_units(prep, scene, point_keys(scene))
    if scene.analysis == "steady":
        units.update({n: u for n, u in {**prep.system.variable_units,
                                        **{n: q.unit for n, q in prep.post.items()}}.items()
                      if n in prep.outputs})
    elif scene.analysis == "statics":
        units.update({n: unit for n, (unit, _) in statics_of(prep).columns.items()})
    else:
        point = set(units) | {"name", "error"}
        units.update({n: "Hz" for row in rows for n in row if n not in point})
    return units


def write_table(path: Path, rows: list[dict[str, Any]], units: dict[str, str]) -> Path:
    """An analysis table as CSV: one row per operating point, ``name [unit]`` headers (SI),
    written atomically.

    Parameters
    ----------
    path : Path
        The CSV file.
    rows : list of dict
        The analysis table's rows, one per operating point.
    units : dict of str to str
        SI unit of each column or series by name.

    Returns
    -------
    Path
        ``path``.
    """
    import csv

    names = [n for n in (rows[0] if rows else {}) if not n.startswith("_")]
    for row in rows[1:]:
        names += [n for n in row if n not in names and not n.startswith("_")]
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([n if n in ("name", "error") else column_name(n, units.get(n, ""))
                    for n in names])
        w.writerows([[row.get(n, "") for n in names] for row in rows])
    return path
