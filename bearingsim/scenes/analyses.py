"""What a scene asks: the analysis kinds and the single operating point they share.

A scene's ``analysis`` (:data:`~bearingsim.scenes.scene.ANALYSES`) says which question it
answers:

* ``transient``: a run in time; its final values are checked for settling
  (:func:`settling_check`, the criterion of :class:`~bearingsim.scenes.scene.Settling`);
* ``steady``: the settled operating point, solved directly (``dx/dt = 0`` by Newton with the
  exact Jacobian, :func:`~bearingsim.simulation.steady_state`), each point of the grid started
  from the solution at the previous one (continuation along the grid's first key);
* ``modes``: natural frequencies and mode names at the equilibrium of each point, from the
  eigenvalues of the model linearized there (:func:`~bearingsim.simulation.linearize`);
* ``statics``: quasi-static ball loads, stiffness, Hertz pressure and ISO/TS 16281 life of each
  load case (:func:`~bearingsim.studies.deep_groove_statics.deep_groove_statics`).

:func:`run_operating_point` runs ONE operating point of any kind and returns its table row; a
scene runs it for each point of its grid or cases (:func:`run_points`), and a sweep runs it
for each of its points. What the points are and which model runs each is
:mod:`bearingsim.scenes.operating_points`.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from bearingsim.errors import BearingsimError, ParameterError, SimulationError
from bearingsim.scenes.analysis_outputs import selected_columns
from bearingsim.scenes.operating_points import (
    filled_point,
    point_label,
    point_model,
    split_point,
)
from bearingsim.scenes.scene import Settling
from bearingsim.scenes.scene_simulation import output_series, run_simulation
from bearingsim.scenes.statics_table import statics_of

__all__ = [
    "NoModesWarning",
    "NotSettledWarning",
    "PointFailedWarning",
    "name_modes",
    "output_resolution",
    "run_operating_point",
    "run_points",
    "settling_check",
    "steady_values",
]

class NotSettledWarning(UserWarning):
    """A transient scene reports final values of outputs that had not settled."""


class NoModesWarning(UserWarning):
    """A modes scene whose linearized model has no oscillating mode at any operating point."""


class PointFailedWarning(UserWarning):
    """Operating points of an analysis scene found no solution: their rows say why (``error``)
    and the other points ran."""


# --------------------------------------------------------------------------- settling
def output_resolution(prep: Any, series: dict[str, np.ndarray]) -> dict[str, float]:
    """The change of each output a run resolves, for :func:`settling_check`: the scene's
    absolute tolerance ``atol`` for an output that is a state (the integrator keeps a
    state's error near ``atol`` where ``rtol`` times the value is smaller, so a smaller
    change is not a result); none for the others.

    Parameters
    ----------
    prep : Prepared
        The prepared scene.
    series : dict of str to numpy.ndarray
        The run's outputs by name.

    Returns
    -------
    dict of str to float
        Absolute resolution [SI unit of the output] by output name.
    """
    states = set(prep.system.state_names)
    return {n: float(prep.scene.simulation.atol) for n in series if n in states}


def settling_check(t: np.ndarray, series: dict[str, np.ndarray], criterion: Settling,
                   resolution: dict[str, float] | None = None) -> dict[str, Any]:
    """Whether each output of a run has settled, and its time constant.

    An output has settled when its range over the last ``criterion.window`` of the run is at
    most ``criterion.tolerance`` times its final magnitude (its largest magnitude in the run
    when it ends near zero, below 1e-3 of that), or at most its ``resolution``, the change
    the run cannot tell from none (:func:`output_resolution`: a displacement that is zero by
    symmetry moves by round-off, 1e-17 m, many times its own magnitude); one that is not
    finite in the window (an
    infinite life at no load) has settled when it keeps one value there. The time constant
    [s] is that of an
    exponential approach through three equally spaced values of the window
    (``y = y_inf + a exp(-t / tau)``: ``tau = -h / ln(d2 / d1)`` for successive differences
    ``d1``, ``d2`` of the same sign and shrinking, the output monotone over the window),
    which also estimates the settled value
    ``y_inf``; NaN when the output does not approach a value that way (constant, oscillating
    or driven by an input that still changes).

    Parameters
    ----------
    t : numpy.ndarray
        Save times [s].
    series : dict of str to numpy.ndarray
        Output values at those times.
    criterion : Settling
        Window and tolerance.
    resolution : dict of str to float, optional
        Absolute change [SI unit of the output] below which an output counts as settled, by
        name (none: the relative criterion alone).

    Returns
    -------
    dict
        ``settled`` (bool, all outputs), ``time_constant`` [s] (the largest of the outputs',
        NaN when none is known), ``unsettled`` (names), ``criterion`` (text) and ``outputs``
        (name -> ``settled``, ``change`` [-], ``time_constant`` [s], ``extrapolated``).
    """
    t = np.asarray(t, dtype=float)
    start = t[-1] - criterion.window * (t[-1] - t[0])
    inside = t >= start
    outputs = {}
    for name, y in series.items():
        y = np.asarray(y, dtype=float)
        tau, estimate = math.nan, math.nan
        window = y[inside]
        if not np.all(np.isfinite(window)):  # e.g. an infinite life at no load
            change = 0.0 if np.all(window == window[-1]) else math.inf
            outputs[name] = {"settled": change == 0.0, "change": change,
                             "time_constant": tau, "extrapolated": estimate}
            continue
        finite = y[np.isfinite(y)]
        peak = float(np.max(np.abs(finite))) if finite.size else 0.0
        scale = max(abs(float(y[-1])), 1e-3 * peak)
        change = float(np.ptp(window)) / scale if scale > 0.0 else 0.0
        h = 0.5 * (t[-1] - start)
        if h > 0.0:
            y1, y2, y3 = np.interp([start, start + h, t[-1]], t, y)
            d1, d2 = y2 - y1, y3 - y2
            monotone = bool(np.all(np.diff(y[inside]) * d1 >= 0.0))
            if d1 != 0.0 and 0.0 < d2 / d1 < 1.0 and monotone:
                r = d2 / d1
                tau = -h / math.log(r)
                estimate = float(y3 + d2 * r / (1.0 - r))
        settled = (change <= criterion.tolerance
                   or float(np.ptp(window)) <= (resolution or {}).get(name, 0.0))
        outputs[name] = {"settled": settled, "change": change, "time_constant": tau,
                         "extrapolated": estimate}
    taus = [o["time_constant"] for o in outputs.values() if math.isfinite(o["time_constant"])]
    return {
        "settled": all(o["settled"] for o in outputs.values()),
        "time_constant": max(taus) if taus else math.nan,
        "unsettled": [n for n, o in outputs.items() if not o["settled"]],
        "criterion": (f"range over the last {criterion.window:.0%} of the run at most "
                      f"{criterion.tolerance:g} of the final magnitude"
                      + (", or a state's at most the run's atol" if resolution else "")),
        "outputs": outputs,
    }


def steady_values(prep: Any, inputs: dict[str, float], parameters: dict[str, float],
                  x_guess: np.ndarray | None = None, t: float = 0.0
                  ) -> dict[str, float] | None:
    """The requested outputs at the steady state under constant ``inputs`` and the assembly's
    own signals at time ``t`` [s] (None when no unique steady state is found from
    ``x_guess``).

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    inputs : dict of str to float
        Input values by name (SI units).
    parameters : dict of str to float
        Parameter values by dotted name (SI units).
    x_guess : ndarray, optional
        Start of the steady-state solve (None: the model's start values).
    t : float
        Time [s] at which the assembly's signals are evaluated.

    Returns
    -------
    dict of str to float or None
        Output values (SI units) by name, or None.
    """
    from bearingsim.simulation import steady_state

    try:
        x = steady_state(prep.system, inputs=inputs, parameters=parameters, x_guess=x_guess,
                         t=t)
    except (SimulationError, BearingsimError):
        return None
    return _observed_outputs(prep, x, inputs, parameters, t)


def _observed_outputs(prep: Any, x: np.ndarray, inputs: dict[str, float],
                      parameters: dict[str, float], t: float = 0.0) -> dict[str, float]:
    system = prep.system
    u = system.u_default()
    for name, value in inputs.items():
        u[system.input_names.index(name)] = value
    obs = {**system.observe(t, x, u, system.p0(parameters)), **inputs}
    out = {}
    for name in prep.outputs:
        if name in prep.post:
            q = prep.post[name]
            out[name] = float(np.asarray(q.compute({n: np.array([obs[n]]) for n in q.needs}),
                                         dtype=float).ravel()[0])
        else:
            out[name] = float(obs[name])
    return out


# --------------------------------------------------------------------------- modes
def _rate_pairs(a: np.ndarray) -> dict[int, int]:
    """Index of each state that has a rate -> index of its rate (``dx_k/dt = x_j`` exactly:
    row k of A is the unit vector e_j)."""
    pairs = {}
    for k in range(a.shape[0]):
        nz = np.flatnonzero(a[k])
        if nz.size == 1 and a[k, nz[0]] == 1.0:
            pairs[k] = int(nz[0])
    return pairs


def name_modes(linear: Any, names: dict[str, str], descriptions: dict[str, str]
               ) -> list[str]:
    """A name for each oscillatory mode of a linear model: that of its dominant degree of
    freedom.

    A degree of freedom is a state with a rate (``dx/dt = v``, found in A); its participation
    in a mode is the larger of its own and its rate's amplitude over the angular frequency,
    relative to the mode's largest. Modes and degrees of freedom are paired one to one for the
    largest total participation (:func:`scipy.optimize.linear_sum_assignment`), so that two
    modes of one repeated frequency (radial x and y of an axisymmetric pair, any combination
    of which is a mode) or of nearly one (the whirl modes of a spinning shaft) get the two
    degrees of freedom they share.

    Parameters
    ----------
    linear : LinearModel
        From :func:`~bearingsim.simulation.linearize`.
    names : dict
        State name -> mode name ("radial x"); other states are named by ``descriptions`` or
        their own name.
    descriptions : dict
        State name -> description.

    Returns
    -------
    list of str
        One per natural frequency (ascending), unique.
    """
    from scipy.optimize import linear_sum_assignment

    a = np.asarray(linear.A, dtype=float)
    pairs = _rate_pairs(a)
    dofs = sorted(pairs) or list(range(a.shape[0]))
    freqs = np.asarray(linear.natural_frequencies)
    shapes = np.asarray(linear.mode_shapes)
    amplitude = np.zeros((freqs.size, len(dofs)))
    for j in range(freqs.size):
        w = max(2.0 * math.pi * freqs[j], 1e-300)
        for i, k in enumerate(dofs):
            rate = abs(shapes[pairs[k], j]) / w if k in pairs else 0.0
            amplitude[j, i] = max(abs(shapes[k, j]), rate)
        amplitude[j] /= max(float(np.max(amplitude[j])), 1e-300)
    modes, chosen = linear_sum_assignment(-amplitude)
    dof_of = dict(zip(modes.tolist(), chosen.tolist(), strict=True))
    labels, seen = [], {}
    for j in range(freqs.size):
        i = dof_of.get(j, int(np.argmax(amplitude[j])))
        state = linear.state_names[dofs[i]]
        label = names.get(state) or descriptions.get(state) or state
        seen[label] = seen.get(label, 0) + 1
        labels.append(label if seen[label] == 1 else f"{label} ({seen[label]})")
    return labels


# --------------------------------------------------------------------------- statics

# --------------------------------------------------------------------------- one point
def run_operating_point(prep: Any, point: dict[str, Any] | None = None,
                        x_guess: np.ndarray | None = None, progress: bool | None = False
                        ) -> dict[str, Any]:
    """Run ONE operating point of a prepared scene's analysis and return its table row.

    Parameters
    ----------
    prep : Prepared
        From :func:`bearingsim.scenes.preparation.prepare` (its scene's ``analysis`` is the kind).
    point : dict, optional
        Keys ``inputs.<name>``, ``parameters.<name>``, ``assembly.<argument>`` (values in SI)
        and an optional ``name``, on top of the scene's own values.
    x_guess : numpy.ndarray, optional
        Start of the steady or equilibrium solve (e.g. the state of the previous point); a
        steady solve that fails from it is made again from the model's own start.
    progress : bool or None
        Progress bar of a transient run.

    Returns
    -------
    dict
        Plain names -> values in SI: the point's keys (``shaft_speed``, ...), ``name`` of a
        case, and by kind: ``transient`` the outputs' final values, ``settled`` (bool),
        ``time_constant`` [s] and ``unsettled`` (names), the last three not for a transient
        on purpose (not checked for settling, as in a single run); ``steady`` the outputs;
        ``modes`` the natural frequency [Hz] by mode name; ``statics`` the columns of
        :class:`Statics`. ``_state`` holds the solved state (for continuation; not a
        table column).

    Raises
    ------
    SceneError
        For assembly arguments that change the model structure, or a statics scene of an
        assembly without a statics solution.
    SimulationError
        When the steady state or equilibrium is not found.
    """
    point = dict(point or {})
    scene = prep.scene
    inputs, parameters, args = split_point(scene, point)
    row = _point_row(prep, point)
    point.pop("name", None)
    if scene.analysis == "statics":
        statics = statics_of(prep)
        values, state = statics.solve(prep, inputs, prep.spec.with_defaults(args), x_guess)
        return {**row, **selected_columns(prep, values), "_state": state}
    prep, overrides = point_model(prep, args)
    parameters.update(overrides)
    if x_guess is not None and np.size(x_guess) != prep.system.n_states:
        x_guess = None  # the previous point's model had other states
    if scene.analysis == "transient":
        result = run_simulation(prep, parameters=parameters, inputs=inputs, progress=progress)
        series = output_series(prep, result)
        row.update({n: float(y[-1]) for n, y in series.items()})
        if not scene.transient_on_purpose:  # as a single run, which does not check those
            check = settling_check(result.t, series, scene.settling,
                                   output_resolution(prep, series))
            row.update(settled=check["settled"], time_constant=check["time_constant"],
                       unsettled=" ".join(check["unsettled"]))
        return {**row, "_state": np.array([result.final(n) for n in prep.system.state_names])}
    from bearingsim.simulation import linearize, steady_state

    system = prep.system
    start = system.x0(scene.initial) if scene.initial else None  # the scene's [initial]
    try:
        x = steady_state(system, inputs=inputs, parameters=parameters,
                         x_guess=start if x_guess is None else x_guess)
    except SimulationError:
        if x_guess is None:
            raise
        # the previous point's state led nowhere (a point of another arrangement: DB's state
        # is no start for DT): from the scene's own start, as the point alone
        x = steady_state(system, inputs=inputs, parameters=parameters, x_guess=start)
    if scene.analysis == "steady":
        return {**row, **_observed_outputs(prep, x, inputs, parameters), "_state": x}
    linear = linearize(system, x, inputs=inputs, parameters=parameters)
    known = prep.spec.mode_names
    names = name_modes(linear, known, {s.name: s.description for s in system.states})
    order = list(known.values())
    modes = sorted(zip(names, linear.natural_frequencies, strict=True),
                   key=lambda m: order.index(m[0]) if m[0] in order else len(order))
    row.update(selected_columns(prep, {n: float(f) for n, f in modes}))
    return {**row, "_state": x}


def _point_row(prep: Any, point: dict[str, Any]) -> dict[str, Any]:
    """The columns a point's row starts with: its keys by plain name (``Fr``), every key of the
    grid or cases filled in, and a case's ``name``."""
    return {point_label(k): v for k, v in filled_point(prep, point).items()}


def run_points(prep: Any, points: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """:func:`run_operating_point` for each point in order, each solve started from the
    solution of the previous point (continuation along the grid; a new curve starts from the
    first point of the previous curve). A point whose solve fails
    (:class:`~bearingsim.errors.SimulationError`: no steady state, not a unique one) or that
    its solver refuses (:class:`~bearingsim.errors.ParameterError`: a nested bearing with
    clearance at zero load, whose balls nothing seats) is a row of its keys and ``error``
    (the message), and the next point starts from the last solution found: one point without
    an answer does not cost the others theirs.

    Parameters
    ----------
    prep : Prepared
        The prepared scene (:class:`~bearingsim.scenes.preparation.Prepared`).
    points : list of dict
        Operating points in run order.

    Returns
    -------
    list of dict
        The rows (``_state`` removed).
    """
    rows: list[dict[str, Any]] = []
    first_key = next(iter(points[0]), None) if points else None
    guess, curve_start = None, None
    for k, point in enumerate(points):
        new_curve = (prep.scene.grid and first_key is not None and k > 0
                     and point[first_key] == points[0][first_key])
        if new_curve:
            guess = curve_start
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", NotSettledWarning)
                row = run_operating_point(prep, point, guess)
        except (SimulationError, ParameterError) as exc:
            rows.append({**_point_row(prep, point), "error": str(exc)})
            continue
        guess = row.pop("_state")
        if k == 0 or new_curve or curve_start is None:
            curve_start = guess
        rows.append(row)
    return rows
