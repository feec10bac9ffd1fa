"""How a scene's answers are shown: values in the display unit an engineer reads
(:func:`display`), axis labels from descriptions (:func:`axis_text`), and the figures of the
``steady``, ``modes`` and ``statics`` kinds (:func:`analysis_figures`). The figures that answer
each assembly's own question live in its product package (its spec's ``plots``).
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from bearingsim.plotting import LINESTYLES, MARKERS, FigureSpec, keep_tight_layout, wrapped_label
from bearingsim.scenes.operating_points import point_label
from bearingsim.scenes.statics_table import STATICS, statics_of
from bearingsim.units import engineering, to_display

__all__ = ["axis_text", "characteristic_figures", "curve_label", "describe", "display",
           "display_text", "failed_note", "include_zero", "numeric_key", "pressure_limit_line",
           "render_report", "value_axis", "varies"]


# --------------------------------------------------------------------------- display
def display(values, unit: str) -> tuple[np.ndarray, str]:
    """SI ``values`` of ``unit`` in the unit an engineer reads them in (r/min, µm, N mm, kN,
    MPa, °C, h, ``-``; :func:`bearingsim.units.to_display`, the one display-unit table).

    Parameters
    ----------
    values : array_like
        Values in SI units.
    unit : str
        Their SI unit.

    Returns
    -------
    (numpy.ndarray, str)
        The converted values and the display unit.
    """
    return to_display(np.asarray(values, dtype=float), unit)


def display_text(value: float, unit: str) -> str:
    """One SI value as text in its display unit (:func:`display`), e.g. ``"10000 r/min"``.

    Parameters
    ----------
    value : float
        Value in SI units.
    unit : str
        Its SI unit.

    Returns
    -------
    str
        Value and display unit.
    """
    if value is None or not math.isfinite(value):
        return f"{value}"
    return engineering(value, unit, mark_dimensionless=False)


def describe(name: str, prep: Any = None) -> str:
    """The description of a variable, input, state, post-processed quantity or analysis
    column, for axis labels (the name itself when it has none).

    Parameters
    ----------
    name : str
        A dotted name or column.
    prep : Prepared, optional
        The prepared scene whose model describes it (None: the name itself).

    Returns
    -------
    str
        The description.
    """
    if prep is not None and prep.scene.analysis == "statics":
        statics = STATICS.get(prep.spec.name)
        if statics is not None and name in statics.columns:
            return statics.columns[name][1]
    if prep is not None:
        if name in prep.post:
            return prep.post[name].doc.split(" (")[0].split(";")[0]
        label = point_label(name)
        if label != name:  # a swept key ("assembly.preload_force"), or a value from one
            key, space, derived = label.partition(" ")  # ("inputs.shaft_speed at t_end")
            return describe(key, prep) + space + derived
        system = prep.system
        said = system.observed_descriptions.get(name) or next(
            (sig.description for sig in (*system.inputs, *system.states, *system.outputs,
                                         *system.params) if sig.name == name), "")
        if said:  # one of an array's elements says which: "normal contact load, inner[0]"
            return ", ".join([said, *(part for part in name.split(".") if "[" in part)])
        arg = prep.spec.args.get(name)
        if arg is not None and arg.doc:  # up to its unit: "axial preload [N] instead of ..."
            return re.split(r"\s*[\[(]", arg.doc)[0]
    return name


def axis_text(name: str, prep: Any, unit: str) -> str:
    """An axis label: the description and the display unit, ``"middle ring speed [r/min]"``,
    wrapped to about 40 characters.

    Parameters
    ----------
    name : str
        A dotted name or column.
    prep : Prepared or None
        The prepared scene (for the description).
    unit : str
        The display unit.

    Returns
    -------
    str
        The label.
    """
    return wrapped_label(describe(name, prep), unit)


_FROM_ZERO = ("N", "kN", "N m", "N mm", "MPa", "h", "10⁶ rev", "Hz", "W", "N/µm")
"""Display units of quantities whose axis shows 0 (loads, torques, pressures, lives,
frequencies, powers, stiffnesses): a load on a log axis down to 1e-10 N reads as a load."""


def include_zero(ax, values: np.ndarray, unit: str) -> bool:
    """A linear value axis that shows 0 for the display units of :data:`_FROM_ZERO`; returns
    whether the unit is one of them.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes (changed in place).
    values : ndarray
        The plotted values (display units).
    unit : str
        Their display unit.

    Returns
    -------
    bool
        Whether ``unit`` is one of them (the axis then shows 0).
    """
    if unit not in _FROM_ZERO:
        return False
    finite = values[np.isfinite(values)]
    ax.set_yscale("linear")
    if finite.size and np.min(finite) >= 0.0:
        ax.set_ylim(bottom=0.0, top=max(float(np.max(finite)) * 1.05, 1e-300))
    elif finite.size and np.max(finite) <= 0.0:
        ax.set_ylim(top=0.0, bottom=min(float(np.min(finite)) * 1.05, -1e-300))
    return True


def pressure_limit_line(ax, prep: Any, unit: str) -> float:
    """ISO 76's static limit of the scene's assembly
    (:attr:`~bearingsim.scenes.statics_table.Statics.pressure_limit`) drawn across a
    contact pressure panel, labelled; returns it in the display unit.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The pressure panel (changed in place).
    prep : Prepared
        The prepared statics scene.
    unit : str
        The panel's display unit of pressure (MPa).

    Returns
    -------
    float
        The limit in ``unit``.
    """
    limit = float(display([statics_of(prep).pressure_limit], "Pa")[0][0])
    ax.axhline(limit, color="0.2", linestyle="--")
    ax.text(0.99, limit, f"ISO 76 static limit {limit:,.0f} {unit}",
            transform=ax.get_yaxis_transform(), ha="right", va="bottom", fontsize=7)
    return limit


def _same_as(x: np.ndarray, y: np.ndarray) -> bool:
    """Whether a series equals the x axis (a variable plotted against itself)."""
    return x.shape == y.shape and bool(np.allclose(x, y, rtol=1e-9, atol=0.0))


INSIDE_LEGEND_ENTRIES = 4
"""Most entries a legend keeps inside its axes; a longer one (the modes of a duplex pair and
the line style of each speed) goes to the right of them, off the curves it would cover."""


def _legend(ax) -> None:
    """The axes' legend: inside (matplotlib's best place) when short, else to the right."""
    if len(ax.get_legend_handles_labels()[1]) <= INSIDE_LEGEND_ENTRIES:
        ax.legend(fontsize=7)
    else:
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)


MAX_CURVES = 8
"""Most curves a characteristic panel draws; beyond (a sampled sweep: every point its own
combination of the other keys) the points are drawn as markers without lines."""


def _curves(rows: list[dict[str, Any]], keys: list[str]
            ) -> tuple[list[tuple[dict, list[dict]]], bool]:
    """Rows grouped by the values of ``keys[1:]``: one curve over ``keys[0]`` each, its rows
    in increasing ``keys[0]`` (a grid given out of order draws no zig-zag), and False; more
    than :data:`MAX_CURVES` groups: one group of every row and True (draw markers only)."""
    groups: dict[tuple, list[dict]] = {}
    for row in rows:
        groups.setdefault(tuple(row.get(k) for k in keys[1:]), []).append(row)
    sampled = len(groups) > MAX_CURVES
    if sampled:
        groups, keys = {(): list(rows)}, keys[:1]
    return [(dict(zip(keys[1:], g, strict=True)), sorted(members, key=lambda r: r[keys[0]]))
            for g, members in groups.items()], sampled


def value_axis(ax, values: np.ndarray, si_unit: str, unit: str) -> None:
    """A value axis for the kind of quantity: a life (``h``, ``Mrev``), spanning decades
    between operating points, on a logarithmic axis (when all values are positive); other
    quantities linear, from 0 where :func:`include_zero` says so.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes (changed in place).
    values : ndarray
        The plotted values (display units).
    si_unit : str
        Their SI unit (model notation).
    unit : str
        Their display unit.
    """
    finite = values[np.isfinite(values)]
    if si_unit in ("h", "Mrev") and finite.size and (finite > 0).all():
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        return
    include_zero(ax, values, unit)


def curve_label(values: dict[str, Any], units: dict[str, str]) -> str:
    """``Fr = 0.5 kN``: the values of a curve's keys, named as the table names them.

    Parameters
    ----------
    values : dict
        Value by key (SI numbers, or text such as a lubricant's name).
    units : dict of str to str
        SI unit by key.

    Returns
    -------
    str
        The keys' names and values in display units, comma separated.
    """
    return ", ".join(f"{point_label(k)} = {v}" if isinstance(v, str) else
                     f"{point_label(k)} = {display_text(v, units.get(k, ''))}"
                     for k, v in values.items())


def numeric_key(rows: list[dict[str, Any]], key: str) -> bool:
    """Whether every row holds a number (not a bool) under ``key``.

    Parameters
    ----------
    rows : list of dict
        Table rows.
    key : str
        A column.

    Returns
    -------
    bool
        True when each row's value is an int or float.
    """
    return all(isinstance(row.get(key), (int, float)) and not isinstance(row.get(key), bool)
               for row in rows)


def varies(rows: list[dict[str, Any]], key: str) -> bool:
    """Whether ``key`` takes more than one value over ``rows`` (a key every point sets alike
    names no curve and is no axis).

    Parameters
    ----------
    rows : list of dict
        Table rows.
    key : str
        A column.

    Returns
    -------
    bool
        True when two rows differ under ``key``.
    """
    first = rows[0].get(key)
    return any(row.get(key) != first for row in rows[1:])


def characteristic_figures(prep: Any, rows: list[dict[str, Any]], keys: list[str],
                           units: dict[str, str], names: list[str], what: str,
                           failed: int = 0):
    """Steady characteristics: each output against the grid's first key, one curve per value
    of the other keys that vary (the ``steady`` and ``modes`` figures), named by one legend
    on the first panel; a sample (more than :data:`MAX_CURVES` combinations) as markers,
    coloured by the second key's value where it is a number; a series equal to the x axis
    (the variable against itself) is left out.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    rows : list of dict
        The analysis table's rows, one per operating point.
    keys : list of str
        The grid keys (the first is the x axis).
    units : dict of str to str
        SI unit of each column or series by name.
    names : list of str
        The columns to draw.
    what : {"steady", "modes", "statics"}
        The analysis (figure name; a statics scene's grid is drawn as a steady one's).
    failed : int
        Points without an answer, not in ``rows`` (the title says how many).

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
    """
    from matplotlib.figure import Figure

    if not rows or not keys:
        return []
    xkey = keys[0]
    keys = [xkey, *(k for k in keys[1:] if varies(rows, k))]
    x_all = np.array([row[xkey] for row in rows], dtype=float)
    shown = [n for n in names if n != xkey
             and not _same_as(x_all, np.array([row.get(n, math.nan) for row in rows], float))]
    if not shown:
        return []
    per_panel = [shown] if what == "modes" else [[n] for n in shown]
    curves, markers_only = _curves(rows, keys)
    entries = (len(curves) if len(per_panel[0]) == 1
               else len(per_panel[0]) + (len(curves) if len(curves) > 1 else 0))
    beside = entries > INSIDE_LEGEND_ENTRIES  # widen for the legend
    shade = (keys[1] if markers_only and len(per_panel[0]) == 1 and numeric_key(rows, keys[1])
             else None)  # a sample's points coloured by the second key's value
    fig = Figure(figsize=(10 if beside else 7, 2.8 * len(per_panel) + 0.9),
                 layout="constrained" if shade else None)
    axes = np.atleast_1d(fig.subplots(len(per_panel), 1, sharex=True, squeeze=False)[:, 0])
    flagged = False  # a point not settled at t_end drawn hollow
    for ax, panel in zip(axes, per_panel, strict=True):
        all_y = []
        y_unit = ""
        for k, (values, members) in enumerate(curves):
            x, x_unit = display([m[xkey] for m in members], units.get(xkey, ""))
            style = LINESTYLES[k % len(LINESTYLES)]
            for j, n in enumerate(panel):
                y, y_unit = display([m.get(n, math.nan) for m in members], units.get(n, ""))
                if len(panel) > 1:  # several series: a colour each, a line style per curve
                    label = n if k == 0 else None
                    color = f"C{j % 10}"
                else:
                    label, color = curve_label(values, units) or None, f"C{k % 10}"
                if shade is not None:
                    c, c_unit = display([m[shade] for m in members], units.get(shade, ""))
                    mappable = ax.scatter(x, y, c=c, s=16, cmap="viridis")
                else:
                    ax.plot(x, y, label=label, color=color, marker=MARKERS[j % len(MARKERS)],
                            linestyle="none" if markers_only else style, markersize=4)
                loose = [i for i, m in enumerate(members)
                         if n in str(m.get("unsettled") or "").split()]
                if loose:
                    flagged = True
                    ax.scatter(np.asarray(x)[loose], np.asarray(y)[loose], s=64, zorder=3,
                               facecolors="white", edgecolors="0.2" if shade else color)
                all_y.append(y)
            if len(panel) > 1 and len(curves) > 1:
                ax.plot([], [], color="0.3", linestyle=style,
                        label=curve_label(values, units))
        if what == "statics" and units.get(panel[0]) == "Pa":
            all_y.append(np.array([pressure_limit_line(ax, prep, y_unit)]))
        value_axis(ax, np.concatenate(all_y), "Hz" if what == "modes" else
                   units.get(panel[0], ""), "Hz" if what == "modes" else y_unit)
        ax.set_ylabel("natural frequency [Hz]" if what == "modes"
                      else axis_text(panel[0], prep, y_unit), fontsize=8)
        if (len(curves) > 1 or len(panel) > 1) and ax is axes[0]:
            _legend(ax)  # once: every panel has the same curves (a sample: one, its series)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(axis_text(xkey, prep, x_unit), fontsize=8)
    named = [point_label(k) for k in keys]  # "Fr", as an analysis scene's table names it
    per = f", one curve per {', '.join(named[1:])}" if len(keys) > 1 else ""
    if markers_only:
        others = named[2:] if shade else named[1:]
        per = (f" ({len(rows)} points" + (f", coloured by {named[1]}" if shade else "")
               + (f"; {', '.join(others)} {'vary' if len(others) > 1 else 'varies'} too"
                  if others else "") + ")")
        if shade:
            fig.colorbar(mappable, ax=list(axes)).set_label(
                axis_text(shade, prep, c_unit), fontsize=8)
    question = ("natural frequencies by mode" if what == "modes"
                else ", ".join(shown[:3]) + (" ..." if len(shown) > 3 else ""))
    fig.suptitle(f"{prep.scene.title}\n{question} against {describe(xkey, prep)}{per}"
                 + ("\nhollow markers: not settled at t_end (the run's last value)"
                    if flagged else "") + failed_note(failed), fontsize=9)
    if not shade:  # the constrained layout places the colour bar itself
        keep_tight_layout(fig)
    return [(what, fig)]


def failed_note(failed: int) -> str:
    """A figure title's line on the points that found no answer (none: no line).

    Parameters
    ----------
    failed : int
        Points without an answer.

    Returns
    -------
    str
        The line with its leading newline, or empty.
    """
    return (f"\nnot drawn: {failed} point(s) without an answer (the table's error column)"
            if failed else "")


def render_report(spec: FigureSpec, title: str = ""):
    """:func:`bearingsim.plotting.render` of an assembly's figure in the scene display units
    (:func:`display`: kN for every force, N mm for every torque, µm, r/min), loads and
    torques on linear axes that show 0.

    Parameters
    ----------
    spec : FigureSpec
        The assembly's figure (SI units).
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    from dataclasses import replace

    from bearingsim.plotting import render

    panels = []
    for panel in spec.panels:
        curves = []
        for c in panel.curves:
            x, x_unit = display(c.x, panel.x_unit)
            y, y_unit = display(c.y, panel.y_unit)
            curves.append(replace(c, x=x, y=y))
        if not curves:
            x_unit, y_unit = panel.x_unit, panel.y_unit
        scale = "linear" if y_unit in _FROM_ZERO else panel.scale
        panels.append(replace(panel, curves=curves, x_unit=x_unit, y_unit=y_unit, scale=scale))
    fig = render(replace(spec, panels=panels), title)
    for ax, panel in zip(fig.axes, panels, strict=False):
        if panel.curves:
            include_zero(ax, np.concatenate([np.asarray(c.y, float) for c in panel.curves]),
                         panel.y_unit)
    return fig
