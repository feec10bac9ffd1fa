"""The figures of a transient run, made without pyplot.

:func:`scene_figures` gives every figure of a run: the assembly's own plots
(:func:`assembly_figures`, :attr:`~bearingsim.assemblies.spec.AssemblySpec.plots`) and the
time traces of the requested outputs (:func:`time_figures`), with the inputs that change
during the run drawn on top. An analysis scene's figures are
:func:`bearingsim.scenes.analysis_figures.analysis_figures`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bearingsim.plotting import LINESTYLES, keep_tight_layout, set_value_scale
from bearingsim.scenes.expressions import compile_expression
from bearingsim.scenes.plots import render_report
from bearingsim.scenes.preparation import Prepared
from bearingsim.scenes.scene import SceneError, line_of
from bearingsim.simulation import Result

__all__ = ["assembly_figures", "scene_figures", "time_figures"]


def _varying_inputs(prep: Prepared, result: Result
                    ) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """The inputs that change during the run, by name, and their units: the model's inputs
    and the assembly's signal arguments given as expressions of t (e.g. a load torque step);
    constant ones are left out."""
    out, units = {}, {}
    for name in prep.system.input_names:
        if name in result:
            out[name] = np.asarray(result[name], dtype=float)
            units[name] = prep.system.inputs[prep.system.input_names.index(name)].unit
    for name, arg in prep.spec.args.items():
        text = prep.args.get(name)
        if arg.kind == "signal" and isinstance(text, str):
            values = compile_expression(text, f"assembly.{name}")(result.t)
            out[name] = np.broadcast_to(np.asarray(values, dtype=float).ravel(), result.t.shape)
            units[name] = arg.unit
    keep = {n: y for n, y in out.items()
            if y.size and np.ptp(y[np.isfinite(y)]) > 0.0}
    return keep, {n: units[n] for n in keep}


def time_figures(stem: str, t: np.ndarray, series: dict[str, np.ndarray],
                 units: dict[str, str], groups: list[list[str]], title: str,
                 inputs: dict[str, np.ndarray] | None = None, prep: Prepared | None = None
                 ) -> list[tuple[str, Any]]:
    """(file name, :class:`matplotlib.figure.Figure`) of the time traces, made without pyplot.

    The inputs that change during the run are drawn on top of every figure (one panel per
    unit), on the same time axis as the outputs they drive; then one panel per group
    (default: per output), at most 6 panels a figure. Axes are labelled with the variables'
    descriptions (``prep``) and display units (r/min, µm, N mm, kN, ...,
    :func:`bearingsim.scenes.plots.display`); loads, torques and powers on linear axes that
    show 0.

    Parameters
    ----------
    stem : str
        File name stem of the run's files.
    t : ndarray
        Times [s].
    series : dict of str to ndarray
        The requested outputs' series by name (SI units).
    units : dict of str to str
        SI unit of each column or series by name.
    groups : list of list of str
        Series drawn together in one panel.
    title : str
        Figure title.
    inputs : dict of str to ndarray, optional
        Input series (SI units) at ``t``.
    prep : Prepared, optional
        The prepared scene (for descriptions).

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        File name and figure of each.
    """
    from matplotlib.figure import Figure

    from bearingsim.scenes.plots import axis_text, describe, display, include_zero

    inputs = inputs or {}
    by_unit: dict[str, list[str]] = {}
    for name in inputs:
        by_unit.setdefault(units.get(name, ""), []).append(name)
    input_groups = list(by_unit.values())
    data = {**inputs, **series}
    groups = groups or [[n] for n in series]
    per_figure = max(6 - len(input_groups), 2)
    figures = []
    for k in range(0, len(groups), per_figure):
        chunk = input_groups + groups[k:k + per_figure]
        fig = Figure(figsize=(7, 1.9 * len(chunk) + 1))
        axes = np.atleast_1d(fig.subplots(len(chunk), 1, sharex=True, squeeze=False)[:, 0])
        for row, (ax, group) in enumerate(zip(axes, chunk, strict=True)):
            unit = units.get(group[0], "")
            shown = []
            for j, n in enumerate(group):
                y, label_unit = display(data[n], unit)
                shown.append(y)
                ax.plot(t, np.where(np.isfinite(y), y, np.nan), label=describe(n, prep),
                        # inputs in grey, told apart by their line style
                        **({"color": "0.35", "linestyle": LINESTYLES[j % len(LINESTYLES)]}
                           if row < len(input_groups) else {}))
            if not include_zero(ax, np.concatenate(shown), label_unit):
                set_value_scale(ax, shown)
            text = (axis_text(group[0], prep, label_unit) if len(group) == 1
                    else f"[{label_unit}]")
            ax.set_ylabel(("input: " if row < len(input_groups) else "") + text, fontsize=8)
            if len(group) > 1:
                ax.legend(fontsize=7)
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time [s]")
        fig.suptitle(title, fontsize=10)
        keep_tight_layout(fig)
        figures.append((f"{stem}.png" if k == 0 else f"{stem}_{k // per_figure + 1}.png", fig))
    return figures


def assembly_figures(prep: Prepared, result: Result, series: dict[str, np.ndarray],
                     stem: str) -> list[tuple[str, Any]]:
    """(file name ``<stem>.<plot>.png``, Figure) of the assembly's own plots
    (:attr:`~bearingsim.assemblies.spec.AssemblySpec.plots`) for this run.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    result : Result
        The run's result.
    series : dict of str to ndarray
        The requested outputs' series by name (SI units).
    stem : str
        File name stem of the run's files.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        File name and figure of each.
    """
    data = {**{n: np.asarray(result[n]) for n in prep.model_outputs + prep.plot_outputs},
            **series}
    figures = []
    for plot in prep.plots:
        spec = plot.make(prep, result, data)
        if spec is not None:
            figures.append((f"{stem}.{plot.name}.png",
                            render_report(spec, f"{prep.scene.title}\n{spec.title}")))
    return figures


def scene_figures(prep: Prepared, result: Result, series: dict[str, np.ndarray], stem: str,
                  units: dict[str, str]) -> list[tuple[str, Any]]:
    """Every figure of a run: the assembly's plots first, then the time traces.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    result : Result
        The run's result.
    series : dict of str to ndarray
        The requested outputs' series by name (SI units).
    stem : str
        File name stem of the run's files.
    units : dict of str to str
        SI unit of each column or series by name.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        File name and figure of each.

    Raises
    ------
    SceneError
        When ``output.plot_groups`` names a series that is not an output.
    """
    groups = [g for g in prep.scene.output.plot_groups]
    missing = sorted({n for g in groups for n in g} - set(series))
    if missing:
        raise SceneError(f"plot group names {', '.join(missing)}, which are not "
                         "outputs", "output.plot_groups",
                         line_of(prep.scene.text, "output.plot_groups"),
                         ", ".join(series), prep.scene.path)
    inputs, input_units = _varying_inputs(prep, result)
    return (assembly_figures(prep, result, series, stem)
            + time_figures(stem, result.t, series, {**input_units, **units}, groups,
                           prep.scene.title, inputs, prep))
