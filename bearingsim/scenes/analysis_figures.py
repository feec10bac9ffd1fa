"""The figures that answer an analysis scene (``steady``, ``modes``, ``statics``): curves along
a number that varies (:func:`~bearingsim.scenes.plots.characteristic_figures`), bars per load
case or per point named by text (:mod:`bearingsim.scenes.bar_figures`).
"""

from __future__ import annotations

from typing import Any

from bearingsim.scenes.bar_figures import category_figures, statics_columns, statics_figures
from bearingsim.scenes.plots import characteristic_figures, numeric_key, varies

__all__ = ["analysis_figures", "curves_or_bars"]


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
    if analysis == "statics":
        if not (prep.scene.grid and _axis(solved, keys)):  # load cases, one point: bars
            return statics_figures(prep, solved, units, failed)
        names = statics_columns(prep, solved)  # a grid: along its load, as a steady one
    else:
        point = set(keys) | {"name"}
        names = [n for n in solved[0] if n not in point and not n.startswith("_")] \
            if solved else []
    return curves_or_bars(prep, solved, keys, units, names, analysis, failed)


def _axis(rows: list[dict[str, Any]], keys: list[str]) -> list[str]:
    """The keys that are a number at every point and vary: the axes a curve may run along."""
    return [k for k in keys if numeric_key(rows, k) and varies(rows, k)]


def curves_or_bars(prep: Any, rows: list[dict[str, Any]], keys: list[str],
                   units: dict[str, str], names: list[str], what: str, failed: int = 0):
    """Columns of points that found an answer as curves along the first key that is a number
    and varies (one curve per value of the others,
    :func:`~bearingsim.scenes.plots.characteristic_figures`), or, where none does but the
    points differ (a key of text, a lubricant, varies, or they are named cases), as one bar
    per point (:func:`~bearingsim.scenes.bar_figures.category_figures`): the choice of an
    analysis scene's figure and of a sweep's.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    rows : list of dict
        The rows of the points that found an answer.
    keys : list of str
        The grid, case or sweep keys.
    units : dict of str to str
        SI unit of each column by name.
    names : list of str
        The columns to draw.
    what : {"steady", "modes", "statics"}
        The analysis (figure name).
    failed : int
        Points without an answer, not in ``rows`` (the title says how many).

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        Figure name and figure.
    """
    axis = _axis(rows, keys)
    if rows and not axis and (any(varies(rows, k) for k in keys)
                              or (len(rows) > 1 and all(r.get("name") for r in rows))):
        return category_figures(prep, rows, keys, units, names, what, failed)
    keys = [*axis, *(k for k in keys if k not in axis)]  # along a number that varies
    return characteristic_figures(prep, rows, keys, units, names, what, failed)
