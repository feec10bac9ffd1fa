"""The figures that answer an analysis scene (``steady``, ``modes``, ``statics``): curves along
a number that varies (:func:`~bearingsim.scenes.plots.characteristic_figures`), bars per load
case or per point named by text (:mod:`bearingsim.scenes.bar_figures`).
"""

from __future__ import annotations

from typing import Any

from bearingsim.scenes.bar_figures import category_figures, statics_columns, statics_figures
from bearingsim.scenes.plots import characteristic_figures, numeric_key, varies

__all__ = ["analysis_figures"]


def analysis_figures(prep: Any, rows: list[dict[str, Any]], keys: list[str],
                     units: dict[str, str]):
    """The figures that answer a ``steady``, ``modes`` or ``statics`` scene: steady outputs
    against the first grid key that is a number and varies (one curve per value of the
    others), natural frequency against it per mode, or life, ball load and pressure per load
    case (a statics grid: against its load, as a steady one); points that differ only by
    text (a lubricant) or by their case's name as bars
    (:func:`~bearingsim.scenes.bar_figures.category_figures`).

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    rows : list of dict
        The analysis table's rows, one per operating point; those of points without an answer
        (an ``error``) are not drawn, and the title counts them.
    keys : list of str
        The grid or case keys.
    units : dict of str to str
        SI unit of each column or series by name.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        Figure name (``steady``, ``modes``, ``statics``) and figure.
    """
    analysis = prep.scene.analysis
    solved = [row for row in rows if "error" not in row]
    failed = len(rows) - len(solved)
    axis = [k for k in keys if numeric_key(solved, k) and varies(solved, k)]
    if analysis == "statics":
        if not (prep.scene.grid and axis):  # load cases, or one point: bars per case
            return statics_figures(prep, solved, units, failed)
        keys = [*axis, *(k for k in keys if k not in axis)]  # a grid: along its load
        return characteristic_figures(prep, solved, keys, units, statics_columns(prep, solved),
                                      analysis, failed)
    point = set(keys) | {"name"}
    names = [n for n in solved[0] if n not in point and not n.startswith("_")] if solved else []
    if solved and not axis and (any(varies(solved, k) for k in keys)
                                or (len(solved) > 1 and all(r.get("name") for r in solved))):
        return category_figures(prep, solved, keys, units, names, analysis, failed)
    keys = [*axis, *(k for k in keys if k not in axis)]  # along a number that varies
    return characteristic_figures(prep, solved, keys, units, names, analysis, failed)
