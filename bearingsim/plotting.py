"""Plot helpers shared by :meth:`bearingsim.simulation.Result.plot` and the scene runner, and
the figure specs (:class:`FigureSpec`) an assembly declares for the plots that answer its
scenes' question (ball load against azimuth, modes by name, speed ratio against speed)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from bearingsim.units import display_label, to_display, unit_label

__all__ = ["WIDE_RANGE", "Curve", "FigureSpec", "Panel", "axis_label", "is_wide_positive",
           "keep_tight_layout", "render", "set_value_scale"]

WIDE_RANGE = 1e3
"""Ratio of the largest to the smallest value above which a positive series is drawn on a
logarithmic axis (e.g. a rating life that falls from millions of hours at rest to a few
thousand at speed)."""


def keep_tight_layout(fig) -> None:
    """Lay ``fig`` out tightly (``Figure.tight_layout``) and keep the positions it found.

    ``tight_layout`` leaves a placeholder layout engine on the figure, and ``savefig`` then
    draws a figure with an engine twice: once with rendering off (every text laid out, the
    ticks placed) and once more to render it. Without an engine a save draws once; the pixels
    are the same.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure, its artists in place.
    """
    fig.tight_layout()
    fig.set_layout_engine(None)


def is_wide_positive(values: Sequence[np.ndarray]) -> bool:
    """Whether the finite values of all series are positive and span at least
    :data:`WIDE_RANGE`.

    Parameters
    ----------
    values : sequence of numpy.ndarray
        The series drawn on one axis.

    Returns
    -------
    bool
    """
    finite = np.concatenate([np.asarray(v, dtype=float).ravel() for v in values])
    finite = finite[np.isfinite(finite)]
    if finite.size == 0 or np.min(finite) <= 0.0:
        return False
    return bool(np.max(finite) / np.min(finite) >= WIDE_RANGE)


def set_value_scale(ax, values: Sequence[np.ndarray]) -> None:
    """Use a logarithmic value axis for positive series spanning :data:`WIDE_RANGE` or more,
    a linear one otherwise.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axis the series are drawn on.
    values : sequence of numpy.ndarray
        Those series.
    """
    if is_wide_positive(values):
        ax.set_yscale("log")


# --------------------------------------------------------------------------- figure specs
MARKERS = ("o", "s", "^", "v", "D", "x", "+", "*")
"""Markers of the curves of one panel, in turn (with :data:`LINESTYLES`): curves that coincide,
e.g. the radial x and y modes of an axisymmetric pair, stay both visible."""
LINESTYLES = ("-", "--", ":", "-.")


@dataclass
class Curve:
    """One curve of a :class:`Panel`: ``x`` and ``y`` in the panel's SI units."""

    x: np.ndarray
    y: np.ndarray
    label: str = ""
    style: dict = field(default_factory=dict)
    """Keyword arguments of :meth:`matplotlib.axes.Axes.plot` (default: a line style and
    marker of :data:`LINESTYLES`, :data:`MARKERS` by the curve's position)."""


@dataclass
class Panel:
    """One axes: curves over a common x quantity, values in SI (shown in engineering units,
    :func:`bearingsim.units.to_display`)."""

    curves: list[Curve]
    x_name: str
    x_unit: str
    y_name: str
    y_unit: str
    scale: str = "auto"
    """Value axis: "auto" (:func:`set_value_scale`) or "linear"."""


@dataclass
class FigureSpec:
    """A figure an assembly declares for its scenes (see
    :attr:`bearingsim.assemblies.spec.AssemblySpec.plots`), written as ``<scene>.<name>.png``."""

    name: str
    title: str
    panels: list[Panel]


def axis_label(name: str, unit: str) -> str:
    """``"name [unit]"`` with the unit as shown to users (``-`` for dimensionless).

    Parameters
    ----------
    name : str
        Quantity name or description.
    unit : str
        Its unit.

    Returns
    -------
    str
        The axis label.
    """
    return f"{name} [{unit_label(unit)}]"


def wrapped_label(text: str, unit: str) -> str:
    """An axis label ``"text [unit]"`` wrapped to about 36 characters a line, the unit never
    split (a long description otherwise runs off a small panel).

    Parameters
    ----------
    text : str
        The quantity's description.
    unit : str
        Its display unit.

    Returns
    -------
    str
        The label, lines joined by newlines.
    """
    import textwrap

    lines = textwrap.wrap(text, 32) or [""]
    if len(lines[-1]) + len(unit) + 3 <= 36:
        lines[-1] = f"{lines[-1]} [{unit}]".lstrip()
    else:
        lines.append(f"[{unit}]")
    return "\n".join(lines)


def render(spec: FigureSpec, title: str = ""):
    """The :class:`matplotlib.figure.Figure` of a :class:`FigureSpec` (made without pyplot),
    every axis in the display unit of its quantity (r/min, µm, deg, kN, N mm, ``-``:
    :mod:`bearingsim.units.display`).

    Parameters
    ----------
    spec : FigureSpec
    title : str
        Figure title (default: the spec's).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    n = len(spec.panels)
    fig = Figure(figsize=(7, 2.6 * n + 0.8))
    axes = np.atleast_1d(fig.subplots(n, 1, squeeze=False)[:, 0])
    for ax, panel in zip(axes, spec.panels, strict=True):
        ux, uy = display_label(panel.x_unit), display_label(panel.y_unit)
        shown = []
        for k, c in enumerate(panel.curves):
            # hollow markers shrinking from curve to curve: coinciding curves stay visible
            style = c.style or {"linestyle": LINESTYLES[k % len(LINESTYLES)],
                                "marker": MARKERS[k % len(MARKERS)],
                                "markersize": max(9.0 - 1.5 * k, 3.0), "fillstyle": "none"}
            y = to_display(c.y, panel.y_unit)[0]
            shown.append(y)
            ax.plot(to_display(c.x, panel.x_unit)[0], np.where(np.isfinite(y), y, np.nan),
                    label=c.label, **style)
        if panel.scale == "auto":
            set_value_scale(ax, shown)
        ax.set_xlabel(axis_label(panel.x_name, ux), fontsize=8)
        ax.set_ylabel(axis_label(panel.y_name, uy), fontsize=8)
        if any(c.label for c in panel.curves):
            ax.legend(fontsize=7)
        ax.grid(True, alpha=0.3)
    fig.suptitle(title or spec.title, fontsize=10)
    keep_tight_layout(fig)
    return fig
