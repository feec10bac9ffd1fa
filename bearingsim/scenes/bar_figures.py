"""Bar figures of an analysis scene's answers per operating point: the statics columns per load
case (:func:`statics_figures`), and the steady outputs or natural frequencies of points that
differ by a name rather than a number (:func:`category_figures`: a lubricant, a bearing, an
arrangement), which have no axis to draw a curve along.
"""

from __future__ import annotations

import math
import textwrap
from typing import Any

import numpy as np

from bearingsim.plotting import keep_tight_layout
from bearingsim.scenes.operating_points import point_label
from bearingsim.scenes.plots import (
    axis_text,
    curve_label,
    describe,
    display,
    display_text,
    failed_note,
    include_zero,
    pressure_limit_line,
    value_axis,
    varies,
)
from bearingsim.scenes.statics_table import statics_of

__all__ = ["category_figures", "statics_columns", "statics_figures"]


def _value_bars(ax, pos: np.ndarray, y: np.ndarray, width: float = 0.8, color: str = "0.55",
                label: str | None = None, hatched: list[bool] | None = None) -> None:
    """Bars of ``y`` at ``pos``, each with its value written at its end; ``hatched`` bars
    (values not settled at t_end) hatched."""
    drawn = ax.bar(pos, y, width=width, color=color, label=label)
    for patch, hatch in zip(drawn, hatched or [], strict=False):
        if hatch:
            patch.set_hatch("///")
            patch.set_edgecolor("white")
    finite = np.abs(y[np.isfinite(y)])
    zero = 1e-9 * float(finite.max()) if finite.size else 0.0  # round-off of a zero: 0
    for p, v in zip(pos, y, strict=True):
        if math.isfinite(v):
            text = ("0" if abs(v) <= zero else f"{v:,.0f}" if abs(v) >= 100 else f"{v:.3g}")
            ax.annotate(text, (p, v), ha="center", va="bottom" if v >= 0 else "top",
                        fontsize=7)


def statics_columns(prep: Any, rows: list[dict[str, Any]]) -> list[str]:
    """The statics columns a figure draws (the scene's ``outputs``, else
    :attr:`~bearingsim.scenes.statics_table.Statics.figure`): those that are a finite number
    at every point, and the life in revolutions (when in the rows) where one at rest has no
    life in hours.

    Parameters
    ----------
    prep : Prepared
        The prepared scene.
    rows : list of dict
        The rows of the points that found an answer.

    Returns
    -------
    list of str
        The columns.
    """
    figure = prep.outputs if prep.scene.outputs else statics_of(prep).figure
    columns = [n for n in figure
               if all(isinstance(row.get(n), float) and math.isfinite(row[n]) for row in rows)]
    if ("L10h" in figure and "L10h" not in columns and "L10r" not in columns
            and all(isinstance(row.get("L10r"), float) for row in rows)):
        columns.insert(0, "L10r")  # a case at rest (LIFE_AT_REST): the life in revolutions
    return columns


def statics_figures(prep: Any, rows: list[dict[str, Any]], units: dict[str, str],
                    failed: int = 0):
    """The assembly's statics columns (:attr:`~bearingsim.scenes.statics_table.Statics.figure`:
    life, ball load and contact pressure of a deep-groove ball bearing) per load case, as
    bars; lives on a log axis (they span decades between load cases), ISO 76's static limit
    of the assembly (:attr:`~bearingsim.scenes.statics_table.Statics.pressure_limit`: 4200
    MPa for ball bearings, 4000 MPa for roller bearings) drawn on a pressure panel.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    rows : list of dict
        The analysis table's rows, one per operating point.
    units : dict of str to str
        SI unit of each column or series by name.
    failed : int
        Load cases without an answer, not in ``rows`` (the title says how many).

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        File name and figure of each.
    """
    from matplotlib.figure import Figure

    if not rows:
        return []
    names = [str(row.get("name", k + 1)) for k, row in enumerate(rows)]
    columns = statics_columns(prep, rows)
    if not columns:  # outputs that are all text (the life in hours of cases at rest)
        return []
    fig = Figure(figsize=(7, 2.6 * len(columns) + 1.0))
    axes = np.atleast_1d(fig.subplots(len(columns), 1, sharex=True, squeeze=False)[:, 0])
    pos = np.arange(len(rows))
    for ax, n in zip(axes, columns, strict=True):
        y, unit = display([row[n] for row in rows], units.get(n, ""))
        _value_bars(ax, pos, y)
        ax.set_ylabel(axis_text(n, prep, unit), fontsize=8)
        if units.get(n) in ("h", "Mrev"):  # lives span decades between load cases
            ax.set_yscale("log")
            _log_bar_limits(ax, y)
            ax.grid(True, axis="y", which="both", alpha=0.3)
            continue
        shown = y
        if units.get(n) == "Pa":  # the limit in view: the margin to it is the answer
            shown = np.append(y, pressure_limit_line(ax, prep, unit))
        include_zero(ax, shown, unit)
        ax.set_ylim(top=ax.get_ylim()[1] * 1.08)  # room for the values above the bars
        ax.grid(True, axis="y", alpha=0.3)
    axes[-1].set_xticks(pos, names, rotation=15, fontsize=7)
    axes[-1].set_xlabel("load case", fontsize=8)
    what = ", ".join(describe(n, prep) for n in columns) + " per load case"
    fig.suptitle("\n".join([prep.scene.title, *textwrap.wrap(what, 90)]) + failed_note(failed),
                 fontsize=9)
    keep_tight_layout(fig)
    return [("statics", fig)]


def _log_bar_limits(ax, values: np.ndarray) -> None:
    """A log axis of bars from a decade below the least value (a bar's height then compares
    with the others': from just below the least, 221 861 h and 229 328 h looked like nothing
    and a bar) to room for the values written above them."""
    finite = values[np.isfinite(values) & (values > 0)]
    if finite.size:
        ax.set_ylim(bottom=10.0 ** (math.floor(math.log10(np.min(finite))) - 1),
                    top=float(np.max(finite)) * 3.0)


def _point_names(rows: list[dict[str, Any]], keys: list[str], units: dict[str, str]
                 ) -> list[str]:
    """A bar's label: the case's name, else the values of the keys that vary (the value
    alone when one key varies: the axis names it)."""
    if all(row.get("name") for row in rows):
        return [str(row["name"]) for row in rows]
    if len(keys) == 1:
        return [v if isinstance(v, str) else display_text(v, units.get(keys[0], ""))
                for v in (row.get(keys[0]) for row in rows)]
    return [curve_label({k: row.get(k) for k in keys}, units) for row in rows]


def category_figures(prep: Any, rows: list[dict[str, Any]], keys: list[str],
                     units: dict[str, str], names: list[str], what: str, failed: int = 0):
    """Steady outputs (one panel each) or natural frequencies (one panel, a bar per mode) as
    bars, one per operating point, named by its case or by the values of the keys that vary:
    the figure of points that differ by text (``assembly.lubrication``), which give no axis
    to draw a characteristic along.

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
        The columns to draw (those that are a number at every point are).
    what : {"steady", "modes"}
        The analysis (figure name).
    failed : int
        Points without an answer, not in ``rows`` (the title says how many).

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        Figure name and figure (none without a column to draw).
    """
    from matplotlib.figure import Figure

    names = [n for n in names if rows and all(
        isinstance(row.get(n), (int, float)) and not isinstance(row.get(n), bool)
        for row in rows)]
    if not names:
        return []
    shown = [k for k in keys if varies(rows, k)] or keys
    labels = _point_names(rows, shown, units)
    per_panel = [names] if what == "modes" else [[n] for n in names]
    bars = len(rows) * len(per_panel[0])
    fig = Figure(figsize=(min(12.0, max(7.0, 0.35 * bars + 3.0)),
                          (3.4 if len(per_panel[0]) > 1 else 2.6) * len(per_panel) + 1.1))
    axes = np.atleast_1d(fig.subplots(len(per_panel), 1, sharex=True, squeeze=False)[:, 0])
    pos = np.arange(len(rows), dtype=float)
    flagged = False  # a value not settled at t_end (a transient sweep's) hatched
    for ax, panel in zip(axes, per_panel, strict=True):
        width = 0.8 / len(panel)
        drawn = []
        for j, n in enumerate(panel):
            y, unit = display([row[n] for row in rows], units.get(n, ""))
            several = len(panel) > 1
            loose = [n in str(row.get("unsettled") or "").split() for row in rows]
            flagged = flagged or any(loose)
            _value_bars(ax, pos + (j - (len(panel) - 1) / 2) * width, y, width,
                        f"C{j % 10}" if several else "0.55", n if several else None, loose)
            drawn.append(y)
        modes = what == "modes"
        values = np.concatenate(drawn)
        value_axis(ax, values, "Hz" if modes else units.get(panel[0], ""),
                   "Hz" if modes else unit)
        if ax.get_yscale() == "log":
            _log_bar_limits(ax, values)
        ax.set_ylabel("natural frequency [Hz]" if modes else axis_text(panel[0], prep, unit),
                      fontsize=8)
        if len(panel) > 1:  # beside the bars, off their values
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                      borderaxespad=0.0)
        ax.grid(True, axis="y", alpha=0.3)
    long = max(len(label) for label in labels) > 12
    axes[-1].set_xticks(pos, labels, rotation=15 if long else 0, fontsize=7)
    named = ", ".join(point_label(k) for k in shown)
    by_case = all(row.get("name") for row in rows)
    axes[-1].set_xlabel("case" if by_case else named, fontsize=8)
    question = ("natural frequencies by mode" if what == "modes"
                else ", ".join(describe(n, prep) for n in names[:3])
                + (" ..." if len(names) > 3 else ""))
    per = "case" if by_case else named
    fig.suptitle("\n".join([prep.scene.title, *textwrap.wrap(f"{question} per {per}", 90)])
                 + ("\nhatched: not settled at t_end (the run's last value)" if flagged else "")
                 + failed_note(failed), fontsize=9)
    keep_tight_layout(fig)
    return [(what, fig)]
