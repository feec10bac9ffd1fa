"""The plots that answer each built-in assembly's question (:data:`BUILTIN_PLOTS`, keyed by
assembly name; the runner draws them beside the time traces, as it does the figures a
registered assembly declares in its spec's ``plots``). They live in the scene layer because
they use the runtime (stiffness and modes of :mod:`bearingsim.studies`), which the models never
import.

* deep-groove ball bearing: ball contact load against azimuth at the end of the run (0 deg is
  the direction of the radial load), with the zero-clearance Stribeck load distribution
  ``Q_max = 4.37 Fr / Z`` for comparison;
* double-layer bearing (alone or in the motor drive): the steady speed ratio Rs against shaft
  speed over the run's speed range (when the shaft speed varies; solved directly at the loads
  of the end of the run, not the run's transient trajectory), with the run's final point and
  the pure-rolling ratio;
* duplex pair: natural frequencies of the shaft on its rows by mode name ("radial x", "axial",
  ...) over the run, from the exact static stiffness at the equilibrium under each time's
  loads.

Each ``*_plots(args, fidelity)`` returns :class:`~bearingsim.assemblies.spec.AssemblyPlot`
objects; their figures are :class:`~bearingsim.plotting.FigureSpec` in SI, shown in engineering
units by :func:`bearingsim.plotting.render`.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from bearingsim.assemblies.spec import AssemblyPlot
from bearingsim.catalog import resolve_bearing
from bearingsim.physics.double_layer_theory import speed_ratio_pure_rolling
from bearingsim.plotting import LINESTYLES, MARKERS, Curve, FigureSpec, Panel
from bearingsim.scenes.statics_table import STATICS, statics_of
from bearingsim.simulation import steady_state
from bearingsim.simulation.statics import static_stiffness
from bearingsim.studies.deep_groove_statics import STATIC_PRESSURE_LIMIT
from bearingsim.studies.duplex import MODE_NAMES, modal_analysis
from bearingsim.units import to_display

__all__ = ["BUILTIN_PLOTS", "STRIBECK", "MODE_SAMPLES", "analysis_figures", "axis_text",
           "ball_loads", "characteristic_figures", "deep_groove_plots", "describe", "display",
           "display_text", "double_layer_plots", "duplex_plots", "include_zero",
           "mode_frequencies", "motor_drive_plots", "render_report", "statics_figures",
           "steady_speed_ratio"]

STRIBECK = 4.37
"""Stribeck's ratio ``Q_max Z / Fr`` of a radially loaded ball row with zero clearance
(Harris & Kotzalas, *Rolling Bearing Analysis*, section 7.2; 5 with the usual clearance)."""
MODE_SAMPLES = 41
"""Save points at which the duplex pair's modes are computed (evenly spread over the run)."""
_ACCEL_TOL = 1e-7  # m/s^2, rad/s^2: equilibrium residual, as in the duplex studies
_SPEED_SPAN = 1.0  # rad/s: a shaft speed varying less than this over the run is not plotted


# --------------------------------------------------------------------------- deep groove
def ball_loads(prep: Any, result: Any, series: dict[str, np.ndarray]
               ) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Ball contact loads at the inner race [N] at the end of the run, their azimuths [rad]
    from the radial load direction (wrapped to (-pi, pi]) and the radial load [N]; None
    without a radial load.

    The azimuths are those of the model: ``row.psi0 + 2 pi j / Z`` at the quasi-static level,
    the balls' orbital angles ``ball[j].theta`` at the dynamic levels.
    """
    z = resolve_bearing(prep.args["bearing"]).ball_count
    fx, fy = (float(result.inputs.get(f"load.{k}", 0.0)) for k in ("Fx", "Fy"))
    fr = math.hypot(fx, fy)
    if fr == 0.0:
        return None
    if prep.fidelity == "quasi-static":
        psi0 = float(result.parameters.get("row.psi0", 0.0))
        psi = psi0 + 2.0 * math.pi * np.arange(z) / z
        q = np.array([series[f"row.Q_i[{j}]"][-1] for j in range(z)])
    else:
        psi = np.array([series[f"ball[{j}].theta"][-1] for j in range(z)])
        q = np.array([series[f"inner[{j}].Q"][-1] for j in range(z)])
    psi = np.angle(np.exp(1j * (psi - math.atan2(fy, fx))))
    order = np.argsort(psi)
    return psi[order], q[order], fr


def _ball_load_figure(prep, result, series) -> FigureSpec | None:
    loads = ball_loads(prep, result, series)
    if loads is None:
        return None
    psi, q, fr = loads
    z = psi.size
    grid = np.linspace(-0.5 * math.pi, 0.5 * math.pi, 91)
    stribeck = STRIBECK * fr / z * np.cos(grid) ** 1.5
    panel = Panel([Curve(psi, q, "model (balls at the end of the run)",
                         {"linestyle": "-", "marker": "o"}),
                   Curve(grid, stribeck, f"zero clearance: {STRIBECK} Fr/Z cos^1.5",
                         {"linestyle": "--", "color": "0.5"})],
                  "azimuth from the load direction", "rad", "ball load at the inner race", "N",
                  scale="linear")
    return FigureSpec("ball_loads", f"ball loads at t = {result.t[-1]:g} s, Fr = "
                      f"{fr:.4g} N, Z = {z}", [panel])


def deep_groove_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Ball contact load against azimuth (every ball's load and, at the dynamic levels, its
    orbital angle)."""
    z = resolve_bearing(args["bearing"]).ball_count
    if fidelity == "quasi-static":
        needs = tuple(f"row.Q_i[{j}]" for j in range(z))
    else:
        needs = (*(f"inner[{j}].Q" for j in range(z)), *(f"ball[{j}].theta" for j in range(z)))
    return [AssemblyPlot("ball_loads", needs, _ball_load_figure)]


# --------------------------------------------------------------------------- double layer
STEADY_SPEEDS = 15
"""Shaft speeds at which the Rs figure of a transient scene solves the steady speed ratio."""


def steady_speed_ratio(prep, result, speed_input: str, rs_name: str, speeds: np.ndarray
                       ) -> np.ndarray:
    """Steady speed ratio [-] at each of ``speeds`` [rad/s] of the input ``speed_input``, the
    other inputs and the assembly's signals at their values at the end of the run, solved
    directly (:func:`~bearingsim.simulation.steady_state`, each speed started from the
    previous solution); NaN where no steady state is found."""
    from bearingsim.errors import BearingsimError

    system = prep.system
    inputs = dict(result.inputs)
    t_end = float(result.t[-1])
    x = np.array([result.final(n) for n in system.state_names])
    rs = np.full(speeds.size, np.nan)
    for k, w in enumerate(speeds):
        inputs[speed_input] = float(w)
        try:
            x = steady_state(system, inputs=inputs, parameters=result.parameters, x_guess=x,
                             t=t_end)
        except BearingsimError:
            continue
        u = system.u_default()
        for name, value in inputs.items():
            u[system.input_names.index(name)] = value
        rs[k] = system.observe(t_end, x, u, system.p0(result.parameters))[rs_name]
    return rs


def _rs_figure(prefix: str, bearing_args: dict[str, Any], speed_input: str):
    def make(prep, result, series) -> FigureSpec | None:
        w, rs = series[prefix + "w_shaft"], series[prefix + "Rs"]
        if np.ptp(w) < _SPEED_SPAN:
            return None
        top = float(np.max(np.abs(w)))
        speeds = np.linspace(top / STEADY_SPEEDS, top, STEADY_SPEEDS)
        steady = steady_speed_ratio(prep, result, speed_input, prefix + "Rs", speeds)
        kin = speed_ratio_pure_rolling(bearing_args["inner"], bearing_args["outer"])
        curves = [Curve(speeds, steady, "steady (loads as at the end of the run)",
                        {"linestyle": "-", "marker": "o", "markersize": 3}),
                  Curve(np.array([abs(w[-1])]), np.array([rs[-1]]),
                        f"the run at t = {result.t[-1]:g} s",
                        {"linestyle": "none", "marker": "x", "markersize": 8,
                         "color": "k"}),
                  Curve(np.array([speeds[0], top]), np.array([kin, kin]), "pure rolling",
                        {"linestyle": "--", "color": "0.5"})]
        panel = Panel(curves, "shaft speed", "rad/s", "speed ratio Rs = n_middle / n_shaft",
                      "1", scale="linear")
        return FigureSpec("rs_speed", "steady speed ratio against shaft speed", [panel])

    return make


def double_layer_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Rs against shaft speed (none at the quasi-static level: load sharing, no speeds)."""
    if fidelity == "quasi-static":
        return []
    return [AssemblyPlot("rs_speed", ("w_shaft", "Rs"), _rs_figure("", args, "shaft_speed"))]


def motor_drive_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Rs of the bearing against shaft speed."""
    return [AssemblyPlot("rs_speed", ("bearing.w_shaft", "bearing.Rs"),
                         _rs_figure("bearing.", args["bearing"], "motor.w_ref"))]


# --------------------------------------------------------------------------- duplex
_POSITIONS = tuple(f"shaft.{k}" for k in ("x", "y", "z", "tx", "ty"))
_LOADS = tuple(f"shaft.{k}" for k in ("Fx", "Fy", "Fz", "Mx", "My"))


def mode_frequencies(prep, result, samples: int = MODE_SAMPLES
                     ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Sample times [s] and the natural frequencies [Hz] by mode name there: the modes of
    ``K phi = w^2 M phi`` at the quasi-static equilibrium under the scene's loads at that time
    (Newton from the saved state), K the exact static stiffness of the model there
    (:func:`bearingsim.studies.duplex.modal_analysis`). The equilibrium, not the saved state:
    after a load step the undamped shaft oscillates about it, and the stiffness at the
    swinging states would show the oscillation rather than the pair."""
    system = prep.system
    m = result.parameters["shaft.mass"]
    jt = result.parameters["shaft.transverse_inertia"]
    mass = np.diag([m, m, m, jt, jt])
    index = np.unique(np.linspace(0, result.t.size - 1, samples).round().astype(int))
    freqs = {n: np.empty(index.size) for n in MODE_NAMES}
    solved: dict[tuple[float, ...], dict[str, float]] = {}
    for k, i in enumerate(index):
        inputs = {n: float(result[n][i]) for n in system.input_names}
        key = tuple(inputs.values())
        if key not in solved:
            guess = np.array([result[n][i] for n in system.state_names])
            x = steady_state(system, inputs=inputs, parameters=result.parameters,
                             x_guess=guess, residual_tol=_ACCEL_TOL)
            stiffness = static_stiffness(system, x, _POSITIONS, _LOADS, inputs,
                                         result.parameters)
            solved[key] = modal_analysis(stiffness, mass).by_name()
        for name, f in solved[key].items():
            freqs[name][k] = f
    return result.t[index], freqs


def _modes_figure(prep, result, series) -> FigureSpec:
    t, freqs = mode_frequencies(prep, result)
    panel = Panel([Curve(t, f, name) for name, f in freqs.items()], "time", "s",
                  "natural frequency", "Hz")
    return FigureSpec("modes", "natural frequencies of the shaft by mode at the equilibrium "
                      "under the loads of each time", [panel])


def duplex_plots(args: dict[str, Any], fidelity: str) -> list[AssemblyPlot]:
    """Natural frequencies by mode name over the run; none for the axisymmetric reduction (one
    ball per row has no radial or tilt stiffness)."""
    if args.get("axisymmetric"):
        return []
    return [AssemblyPlot("modes", _POSITIONS, _modes_figure)]


BUILTIN_PLOTS = {
    "deep_groove_ball_bearing": deep_groove_plots,
    "double_layer_bearing": double_layer_plots,
    "motor_drive": motor_drive_plots,
    "duplex_pair": duplex_plots,
}
"""Assembly name -> ``plots(args, fidelity)`` of the built-in assemblies."""


# --------------------------------------------------------------------------- display
def display(values, unit: str) -> tuple[np.ndarray, str]:
    """SI ``values`` of ``unit`` in the unit an engineer reads them in (r/min, µm, N mm, kN,
    MPa, °C, h, ``-``; :func:`bearingsim.units.to_display`, the one display-unit table).

    Returns
    -------
    (numpy.ndarray, str)
        The converted values and the display unit.
    """
    values = np.asarray(values, dtype=float)
    if unit == "Mrev":  # a life in millions of revolutions, as ISO 281 states it
        return values, "10⁶ rev"
    return to_display(values, unit)


def display_text(value: float, unit: str) -> str:
    """One SI value as text in its display unit (:func:`display`), e.g. ``"10000 r/min"``."""
    if value is None or not math.isfinite(value):
        return f"{value}"
    shown, label = display(np.array([value]), unit)
    return f"{shown[0]:.5g}" + ("" if label == "-" else f" {label}")


def describe(name: str, prep: Any = None) -> str:
    """The description of a variable, input, state, post-processed quantity or analysis
    column, for axis labels (the name itself when it has none)."""
    if prep is not None and prep.scene.analysis == "statics":
        statics = STATICS.get(prep.spec.name)
        if statics is not None and name in statics.columns:
            return statics.columns[name][1]
    if prep is not None:
        if name in prep.post:
            return prep.post[name].doc.split(" (")[0].split(";")[0]
        system = prep.system
        for sig in (*system.inputs, *system.states, *system.outputs):
            if sig.name == name and sig.description:
                return sig.description
        if system.observed_descriptions.get(name):
            return system.observed_descriptions[name]
        arg = prep.spec.args.get(name)
        if arg is not None and arg.doc:  # up to its unit: "axial preload [N] instead of ..."
            return re.split(r"\s*[\[(]", arg.doc)[0]
    return name


def axis_text(name: str, prep: Any, unit: str) -> str:
    """An axis label: the description and the display unit, ``"middle ring speed [r/min]"``,
    wrapped to about 40 characters."""
    import textwrap

    lines = textwrap.wrap(describe(name, prep), 32) or [""]
    if len(lines[-1]) + len(unit) + 3 <= 36:  # the unit never split: "[N mm]"
        lines[-1] = f"{lines[-1]} [{unit}]".lstrip()
    else:
        lines.append(f"[{unit}]")
    return "\n".join(lines)


_FROM_ZERO = ("N", "kN", "N m", "N mm", "MPa", "h", "10⁶ rev", "Hz", "W", "N/µm")
"""Display units of quantities whose axis shows 0 (loads, torques, pressures, lives,
frequencies, powers, stiffnesses): a load on a log axis down to 1e-10 N reads as a load."""


def include_zero(ax, values: np.ndarray, unit: str) -> bool:
    """A linear value axis that shows 0 for the display units of :data:`_FROM_ZERO`; returns
    whether the unit is one of them."""
    if unit not in _FROM_ZERO:
        return False
    finite = values[np.isfinite(values)]
    ax.set_yscale("linear")
    if finite.size and np.min(finite) >= 0.0:
        ax.set_ylim(bottom=0.0, top=max(float(np.max(finite)) * 1.05, 1e-300))
    elif finite.size and np.max(finite) <= 0.0:
        ax.set_ylim(top=0.0, bottom=min(float(np.min(finite)) * 1.05, -1e-300))
    return True


def _same_as(x: np.ndarray, y: np.ndarray) -> bool:
    """Whether a series equals the x axis (a variable plotted against itself)."""
    return x.shape == y.shape and bool(np.allclose(x, y, rtol=1e-9, atol=0.0))


def _curves(rows: list[dict[str, Any]], keys: list[str]) -> list[tuple[dict, list[dict]]]:
    """Rows grouped by the values of ``keys[1:]``: one curve over ``keys[0]`` each."""
    groups: dict[tuple, list[dict]] = {}
    for row in rows:
        groups.setdefault(tuple(row.get(k) for k in keys[1:]), []).append(row)
    return [(dict(zip(keys[1:], g, strict=True)), members) for g, members in groups.items()]


def _curve_label(values: dict[str, Any], units: dict[str, str]) -> str:
    return ", ".join(f"{k} = {v}" if isinstance(v, str) else
                     f"{k} = {display_text(v, units.get(k, ''))}" for k, v in values.items())


def characteristic_figures(prep: Any, rows: list[dict[str, Any]], keys: list[str],
                           units: dict[str, str], names: list[str], what: str):
    """Steady characteristics: each output against the grid's first key, one curve per value
    of the other keys (the ``steady`` and ``modes`` figures); a series equal to the x axis
    (the variable against itself) is left out.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
    """
    from matplotlib.figure import Figure

    if not rows or not keys:
        return []
    xkey = keys[0]
    x_all = np.array([row[xkey] for row in rows], dtype=float)
    shown = [n for n in names if n != xkey
             and not _same_as(x_all, np.array([row.get(n, math.nan) for row in rows], float))]
    if not shown:
        return []
    per_panel = [shown] if what == "modes" else [[n] for n in shown]
    fig = Figure(figsize=(7, 2.8 * len(per_panel) + 0.9))
    axes = np.atleast_1d(fig.subplots(len(per_panel), 1, sharex=True, squeeze=False)[:, 0])
    curves = _curves(rows, keys)
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
                    label, color = _curve_label(values, units) or None, f"C{k % 10}"
                ax.plot(x, y, label=label, color=color, marker=MARKERS[j % len(MARKERS)],
                        linestyle=style, markersize=4)
                all_y.append(y)
            if len(panel) > 1 and len(curves) > 1:
                ax.plot([], [], color="0.3", linestyle=style,
                        label=_curve_label(values, units))
        include_zero(ax, np.concatenate(all_y), "Hz" if what == "modes" else y_unit)
        ax.set_ylabel("natural frequency [Hz]" if what == "modes"
                      else axis_text(panel[0], prep, y_unit), fontsize=8)
        if len(curves) > 1 or len(panel) > 1:
            ax.legend(fontsize=7)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(axis_text(xkey, prep, x_unit), fontsize=8)
    per = f", one curve per {', '.join(keys[1:])}" if len(keys) > 1 else ""
    question = ("natural frequencies by mode" if what == "modes"
                else ", ".join(shown[:3]) + (" ..." if len(shown) > 3 else ""))
    fig.suptitle(f"{prep.scene.title}\n{question} against {describe(xkey, prep)}{per}",
                 fontsize=9)
    fig.tight_layout()
    return [("modes" if what == "modes" else "steady", fig)]




def statics_figures(prep: Any, rows: list[dict[str, Any]], units: dict[str, str]):
    """The assembly's statics columns (:attr:`~bearingsim.scenes.statics_table.Statics.figure`:
    life, ball load and contact pressure of a deep-groove ball bearing) per load case, as
    bars; lives on a log axis (they span decades between load cases), the 4200 MPa of ISO 76
    drawn on a pressure panel."""
    from matplotlib.figure import Figure

    if not rows:
        return []
    names = [str(row.get("name", k + 1)) for k, row in enumerate(rows)]
    columns = [n for n in statics_of(prep).figure
               if all(math.isfinite(row.get(n, math.nan)) for row in rows)]
    if "L10h" in statics_of(prep).figure and "L10h" not in columns:
        columns.insert(0, "L10r")  # no speed given: the life in revolutions
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
            ax.grid(True, axis="y", which="both", alpha=0.3)
            continue
        if units.get(n) == "Pa":
            limit, _ = display([STATIC_PRESSURE_LIMIT], "Pa")
            ax.axhline(limit[0], color="0.2", linestyle="--", label="ISO 76 static limit")
            ax.legend(fontsize=7)
        include_zero(ax, y, unit)
        ax.grid(True, axis="y", alpha=0.3)
    axes[-1].set_xticks(pos, names, rotation=15, fontsize=7)
    axes[-1].set_xlabel("load case", fontsize=8)
    import textwrap

    what = ", ".join(describe(n, prep) for n in columns) + " per load case"
    fig.suptitle("\n".join([prep.scene.title, *textwrap.wrap(what, 90)]), fontsize=9)
    fig.tight_layout()
    return [("statics", fig)]


def analysis_figures(prep: Any, rows: list[dict[str, Any]], keys: list[str],
                     units: dict[str, str]):
    """The figures that answer a ``steady``, ``modes`` or ``statics`` scene: steady outputs
    against the first grid key (one curve per value of the second), natural frequency against
    the first key per mode, or life, ball load and pressure per load case.

    Returns
    -------
    list of (str, matplotlib.figure.Figure)
        Figure name (``steady``, ``modes``, ``statics``) and figure.
    """
    analysis = prep.scene.analysis
    if analysis == "statics":
        return statics_figures(prep, rows, units)
    point = set(keys) | {"name"}
    names = [n for n in rows[0] if n not in point and not n.startswith("_")] if rows else []
    return characteristic_figures(prep, rows, keys, units, names, analysis)


def render_report(spec: FigureSpec, title: str = ""):
    """:func:`bearingsim.plotting.render` of an assembly's figure in the scene display units
    (:func:`display`: kN for every force, N mm for every torque, µm, r/min), loads and
    torques on linear axes that show 0."""
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
