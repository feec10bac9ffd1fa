"""Bar figures of an analysis scene's answers per operating point: the statics columns per load
case (:func:`statics_figures`).
"""

from __future__ import annotations

import math
import textwrap
from typing import Any

import numpy as np

from bearingsim.plotting import keep_tight_layout
from bearingsim.scenes.plots import axis_text, describe, display, failed_note, include_zero
from bearingsim.scenes.statics_table import statics_of

__all__ = ["statics_figures"]


def statics_figures(prep: Any, rows: list[dict[str, Any]], units: dict[str, str],
                    failed: int = 0):
    """The assembly's statics columns (:attr:`~bearingsim.scenes.statics_table.Statics.figure`:
    life, ball load and contact pressure of a deep-groove ball bearing) per load case, as
    bars; lives on a log axis (they span decades between load cases), the 4200 MPa of ISO 76
    drawn on a pressure panel.

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
    columns = [n for n in statics_of(prep).figure
               if all(isinstance(row.get(n), float) and math.isfinite(row[n]) for row in rows)]
    if "L10h" in statics_of(prep).figure and "L10h" not in columns:
        columns.insert(0, "L10r")  # a case at rest (LIFE_AT_REST): the life in revolutions
    fig = Figure(figsize=(7, 2.6 * len(columns) + 1.0))
    axes = np.atleast_1d(fig.subplots(len(columns), 1, sharex=True, squeeze=False)[:, 0])
    pos = np.arange(len(rows))
    for ax, n in zip(axes, columns, strict=True):
        y, unit = display([row[n] for row in rows], units.get(n, ""))
        ax.bar(pos, y, color="0.55")
        for p, v in zip(pos, y, strict=True):
            ax.annotate(f"{v:,.0f}" if abs(v) >= 100 else f"{v:.3g}", (p, v), ha="center",
                        va="bottom", fontsize=7)
        ax.set_ylabel(axis_text(n, prep, unit), fontsize=8)
        if units.get(n) in ("h", "Mrev"):  # lives span decades between load cases
            ax.set_yscale("log")
            ax.set_ylim(top=float(np.max(y)) * 1.6)  # room for the values above the bars
            ax.grid(True, axis="y", which="both", alpha=0.3)
            continue
        shown = y
        if units.get(n) == "Pa":
            limit, _ = display([statics_of(prep).pressure_limit], "Pa")
            ax.axhline(limit[0], color="0.2", linestyle="--")
            ax.text(0.99, limit[0], f"ISO 76 static limit {limit[0]:,.0f} {unit}",
                    transform=ax.get_yaxis_transform(), ha="right", va="bottom", fontsize=7)
            shown = np.append(y, limit)  # the limit in view: the margin to it is the answer
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
