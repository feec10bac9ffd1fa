"""Speed-ratio studies of double-layer bearings (docs/studies.md, section A)."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assembler.system import System, as_system
from bearingsim.assemblies.double_layer import DynamicDoubleLayerBearing, double_layer_bearing
from bearingsim.checks import checked
from bearingsim.errors import MultipleSteadyStatesWarning, ParameterError, SimulationError
from bearingsim.simulation import simulate, steady_state
from bearingsim.validation import check_quantity, check_range, check_vector

__all__ = ["SpeedRatioEstimate", "SpeedRatioSweep", "SteadyBranch", "speed_ratio",
           "speed_ratio_sweep", "steady_branches", "steady_ratio"]

BRANCH_SCAN_POINTS = 200
"""Middle-ring speeds sampled in [-|w|, 2|w|] when looking for every steady state."""


@dataclass(frozen=True)
class SteadyBranch:
    """One steady state of a one-state (torque-level) double-layer bearing."""

    w_middle: float
    """Middle-ring speed [rad/s]."""
    stable: bool
    """Whether small deviations decay (d(dw/dt)/dw < 0)."""


def steady_branches(system: System, inputs: dict[str, float], p: np.ndarray
                    ) -> list[SteadyBranch]:
    """Every steady state of a system with one state (the middle-ring speed of the torque
    level) at constant inputs, with its stability, in increasing speed.

    The derivative is sampled at :data:`BRANCH_SCAN_POINTS` middle-ring speeds in
    ``[-|w|, 2|w|]`` (``w`` the shaft speed; friction alone cannot drive the middle ring
    outside ``[0, w]``, the margin catches sign slips) and every sign change refined with
    Brent's method.

    Parameters
    ----------
    system : System
        The assembled torque-level bearing (one state).
    inputs : dict of str to float
        Its inputs (SI).
    p : numpy.ndarray
        Its parameter vector.

    Returns
    -------
    list of SteadyBranch
        The steady states, in increasing middle-ring speed.
    """
    u = system.u_default()
    for name, value in inputs.items():
        u[system.input_names.index(name)] = value
    rhs = system.functions["ode"]
    w = abs(inputs["shaft_speed"])

    def f(wm: float) -> float:
        return float(np.asarray(rhs(0.0, [wm], u, p)).ravel()[0])

    grid = np.linspace(-w, 2.0 * w, BRANCH_SCAN_POINTS)
    n = grid.size
    values = np.asarray(rhs.map(n)(np.zeros((1, n)), grid[None, :], np.repeat(
        u[:, None], n, axis=1), np.repeat(p[:, None], n, axis=1)), dtype=float).ravel()
    from scipy.optimize import brentq  # on use: importing scipy.optimize takes ~0.6 s

    branches = []
    for k in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) <= 0.0):
        if values[k] == 0.0 and k > 0 and values[k - 1] == 0.0:
            continue  # a flat zero counted once
        root = grid[k] if values[k] == 0.0 else brentq(
            f, grid[k], grid[k + 1], xtol=1e-12 * max(w, 1.0))
        stable = values[k] >= 0.0 >= values[k + 1] and values[k] != values[k + 1]
        branches.append(SteadyBranch(float(root), bool(stable)))
    return branches


def _settles_on(branches: list[SteadyBranch], start: float, moving_up: bool
                ) -> SteadyBranch | None:
    """The stable branch a one-state run from ``start`` settles on (it moves monotonically to
    the next steady state in the direction of its derivative)."""
    ahead = [b for b in branches if (b.w_middle >= start if moving_up else b.w_middle <= start)]
    if not ahead:
        return None
    nearest = min(ahead, key=lambda b: abs(b.w_middle - start))
    return nearest if nearest.stable else None


@dataclass
class SpeedRatioSweep:
    """Steady speed ratio against shaft speed."""

    speeds: np.ndarray
    """Shaft speeds [rad/s]."""
    rs: np.ndarray
    """Speed distribution ratio at each speed [1]."""
    friction_torque: np.ndarray
    """Friction torque on the shaft at each speed [N m]."""


@checked(skip=("system",))
def steady_ratio(system: System, speed: float | str, loads=(0.0, 0.0), parameters=None,
                 x_guess=None) -> tuple[float, float, np.ndarray]:
    """Steady ``Rs`` and shaft friction torque of an assembled double-layer bearing.

    Parameters
    ----------
    system : System
        An assembled double-layer bearing with the input ``shaft_speed`` and the variables
        ``Rs`` and ``M_shaft`` (:func:`double_layer_bearing` with ``drive="speed"``,
        ``speed=None``).
    speed : float or str
        Shaft speed [rad/s] or a number with a unit (``"3000 rpm"``), finite and not 0
        (either sign): at rest ``Rs = w_middle / w_shaft`` is 0/0 (the model's regularized
        ``Rs`` is 0 there, which is no answer).
    loads : (float, float)
        Radial and axial load [N] (or numbers with a unit, ``"2 kN"``), finite, set when the
        system has the inputs ``Fr`` and ``Fa`` (a kinematic level's Rs does not depend on
        them).
    parameters : dict, optional
        Parameter overrides.
    x_guess : array, optional
        Starting guess of the steady state.

    Returns
    -------
    (Rs [1], M_shaft [N m], steady state vector)
        Evaluated with the inputs above and every other input at its start value
        (``system.u_default()``), the values the steady state was solved with.

    Warns
    -----
    MultipleSteadyStatesWarning
        When a one-state (torque-level) model has more than one stable steady state (the SKF
        model at low speed and moderate load: Rs near 0 and near 1, an unstable one between).
        The branches are found by :func:`steady_branches`; the one returned is the stable
        steady state a run from the start value (``x_guess``, else the model's start value of
        the middle-ring speed) settles on, exactly so for one state: the speed moves
        monotonically to the next steady state in the direction of its derivative. The
        warning lists every branch with its stability and says which was returned.

    Raises
    ------
    ParameterError
        For a speed of 0 or not finite, or ``loads`` that are not two finite numbers.
    SimulationError
        If the steady state is not found or not unique (e.g. the SKF model at zero load: no
        friction in either layer, so nothing sets the middle ring's speed).
    """
    where = "steady_ratio"
    system = as_system(system, where)
    speed = check_quantity(speed, "speed", "rad/s", where=where)
    if speed == 0.0:
        raise ParameterError(
            f"{where}: speed = 0 rad/s: the speed ratio Rs = w_middle / w_shaft is 0/0 at rest, "
            f"so it has no value there; valid range: a finite shaft speed other than 0 [rad/s] "
            f"(either sign; 1000 r/min = 104.7 rad/s)")
    if isinstance(loads, (tuple, list)):  # numbers with a unit: "2 kN"
        loads = [check_quantity(v, f"loads[{k}]", "N", where=where) for k, v in enumerate(loads)]
    loads = tuple(float(v) for v in check_vector(loads, 2, "loads (Fr, Fa)", "N", where))
    inputs = {"shaft_speed": float(speed)}
    if "Fr" in system.input_names:
        inputs.update({"Fr": loads[0], "Fa": loads[1]})
    if system.n_states == 1:
        x_guess = _choose_branch(system, inputs, parameters, x_guess, loads)
    try:
        x = steady_state(system, inputs=inputs, parameters=parameters, x_guess=x_guess)
    except SimulationError as exc:
        raise SimulationError(
            f"{where} at {speed:g} rad/s, loads Fr, Fa = {loads} N: {exc}. Without "
            "load, a friction model with no load-independent torque (SKF without seals or "
            "drag) turns neither layer, so the middle ring's speed and Rs are undetermined: "
            "give a load, seals or an oil level") from None
    u = system.u_default()
    for name, value in inputs.items():
        u[system.input_names.index(name)] = value
    obs = system.observe(0.0, x, u, system.p0(parameters))
    return obs["Rs"], obs["M_shaft"], x


def _choose_branch(system: System, inputs: dict[str, float], parameters, x_guess,
                   loads) -> np.ndarray | None:
    """The start guess of the branch :func:`steady_ratio` returns, warning when the model has
    another stable steady state (see :func:`steady_ratio`)."""
    p = system.p0(parameters)
    branches = steady_branches(system, inputs, p)
    stable = [b for b in branches if b.stable]
    if not stable:
        return x_guess
    start = float(system.x0()[0] if x_guess is None else np.ravel(x_guess)[0])
    u = system.u_default()
    for name, value in inputs.items():
        u[system.input_names.index(name)] = value
    moving_up = float(np.asarray(system.functions["ode"](0.0, [start], u, p)).ravel()[0]) >= 0
    chosen = _settles_on(branches, start, moving_up) or min(
        stable, key=lambda b: abs(b.w_middle - start))
    if len(stable) == 1:
        return np.array([chosen.w_middle])  # one branch: its speed starts the Newton solve
    w = inputs["shaft_speed"]
    listed = ", ".join(f"Rs = {b.w_middle / w:.4g} ({'stable' if b.stable else 'unstable'})"
                       for b in branches)
    warnings.warn(
        f"steady_ratio at {w:g} rad/s, loads Fr, Fa = {tuple(loads)} N: the model has "
        f"{len(branches)} steady states, {listed}; returned Rs = {chosen.w_middle / w:.4g}, the "
        f"stable one a run from the start value middle-ring speed {start:g} rad/s settles on "
        f"(give x_guess near another to get it)", MultipleSteadyStatesWarning, stacklevel=4)
    return np.array([chosen.w_middle])


def speed_ratio_sweep(speeds, inner=None, outer=None, loads=(0.0, 0.0), parameters=None,
                      system: System | None = None, **bearing) -> SpeedRatioSweep:
    """Steady speed ratio over shaft speeds with ONE assembled system (no re-assembly).

    Parameters
    ----------
    speeds : array_like
        Shaft speeds [rad/s], > 0, or numbers with a unit (``["1000 rpm", "5000 rpm"]``, a
        :class:`pint.Quantity` array).
    inner, outer : str or BearingGeometry, optional
        Bearings (default "61905" in "61907"); only without ``system``.
    loads : (float, float)
        Radial and axial load [N] (torque fidelity).
    parameters : dict, optional
        Parameter overrides (e.g. another viscosity).
    system : System, optional
        A system assembled from :func:`double_layer_bearing` (built if not given).
    **bearing
        Passed to :func:`double_layer_bearing` (structure, fidelity, lubrication, ...); only
        without ``system``.

    Returns
    -------
    SpeedRatioSweep

    Raises
    ------
    ParameterError
        For speeds that are not positive finite numbers (checked before anything is
        assembled), or ``system`` given together with ``inner``, ``outer`` or bearing
        keywords (they would be ignored: the system is already assembled).
    """
    where = "speed_ratio_sweep"
    if isinstance(speeds, (list, tuple)):  # each a number or a number with a unit
        speeds = [check_quantity(v, "speeds", "rad/s", where=where) for v in speeds]
    else:
        speeds = check_quantity(speeds, "speeds", "rad/s", where=where)
    try:
        speeds = np.asarray(speeds, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{where}: speeds must be numbers [rad/s] or numbers with a unit "
                             f"('3000 rpm'), got {speeds!r:.60}") from None
    if speeds.ndim != 1 or speeds.size == 0:
        raise ParameterError(f"{where}: speeds must be a non-empty list of shaft speeds "
                             f"[rad/s], got shape {speeds.shape}")
    check_range(speeds, "speeds", "rad/s", 0.0, None, low_inclusive=False, where=where)
    if system is None:
        inner = "61905" if inner is None else inner
        outer = "61907" if outer is None else outer
        system = assemble(double_layer_bearing(inner, outer, **bearing),
                          outputs=["Rs", "M_shaft"])
    else:
        ignored = ([k for k, v in (("inner", inner), ("outer", outer)) if v is not None]
                   + sorted(bearing))
        if ignored:
            raise ParameterError(
                f"{where}: {', '.join(ignored)} cannot be combined with system= "
                "(the system is already assembled); give either the bearing or the system"
            )
    rs, torque = np.empty_like(speeds), np.empty_like(speeds)
    x = None
    for k, w in enumerate(speeds):
        rs[k], torque[k], x = steady_ratio(system, w, loads, parameters, x_guess=x)
    return SpeedRatioSweep(speeds, rs, torque)


@dataclass(frozen=True)
class SpeedRatioEstimate:
    """Result of :func:`speed_ratio`.

    Attributes
    ----------
    rs : float
        Speed ratio where the net middle-ring torque vanishes [-].
    bracket : (float, float)
        The last two speed ratios on either side of ``rs`` [-].
    torques : (float, float)
        Mean net torque on the middle ring at each [N m]: positive (the ring speeds up) at
        the lower, negative at the upper.
    evaluations : tuple of (float, float)
        Every (speed ratio [-], mean net torque [N m]) run, in order.
    """

    rs: float
    bracket: tuple[float, float]
    torques: tuple[float, float]
    evaluations: tuple[tuple[float, float], ...] = ()

    @property
    def bracketed(self) -> bool:
        """Whether the middle ring speeds up below and slows down above the bracket.

        Returns
        -------
        bool
            Whether the bracket holds the steady ratio.
        """
        return self.torques[0] > 0.0 > self.torques[1]


def speed_ratio(bearing: DynamicDoubleLayerBearing, system: System, w_shaft: float | str,
                bracket: tuple[float, float] | None = None, parameters: dict | None = None,
                t_run: float | str = 0.02, tol: float = 1e-4,
                max_runs: int = 16) -> SpeedRatioEstimate:
    """Steady speed ratio from the net middle-ring torque of short runs.

    Each run starts in pure rolling (``bearing.rolling_start``) with the middle ring at
    ``Rs * w_shaft`` and lasts ``t_run`` (the balls and cages settle within some milliseconds,
    the middle ring's own time constant is a large fraction of a second); the net torque
    ``M_middle`` averaged over the second half says whether the ring would speed up (> 0) or
    slow down. From a start (``bracket``, or the torque level's ratio for the layers'
    lubricants and 5 % beside it) the search widens until the torque changes sign and then
    narrows the bracket by regula falsi (Illinois variant) until two successive ratios differ
    by less than ``tol``: the answer no longer depends on where the search started.

    Parameters
    ----------
    bearing : DynamicDoubleLayerBearing
        The assembly (for its pure-rolling start values).
    system : System
        ``bearing`` assembled as the root, with the input ``shaft_speed``
        (``drive="speed"``, ``speed=None``) and ``M_middle`` among its outputs.
    w_shaft : float or str
        Shaft speed [rad/s], > 0, or a number with a unit (``"5000 rpm"``).
    bracket : (float, float), optional
        Two speed ratios to start from [-], in (0, 1); default: the torque level's.
    parameters : dict, optional
        Parameter overrides (e.g. ``{"inner_layer.ring_drag.f0": 1.62}``).
    t_run : float or str
        Length of each run [s], > 0, or a number with a unit (``"20 ms"``).
    tol : float
        Convergence of the ratio [-], > 0.
    max_runs : int
        Most runs before giving up.

    Returns
    -------
    SpeedRatioEstimate

    Raises
    ------
    SimulationError
        If the net torque does not change sign within ``(0, 1)`` or the search does not
        converge within ``max_runs`` runs.
    """
    where = "speed_ratio"
    system = as_system(system, where)
    w_shaft = float(check_quantity(w_shaft, "w_shaft", "rad/s", 0.0, None, low_inclusive=False,
                                   where=where))
    t_run = float(check_quantity(t_run, "t_run", "s", 0.0, None, low_inclusive=False,
                                 where=where))
    check_range(tol, "tol", "-", 0.0, None, low_inclusive=False, where=where)
    if "shaft_speed" not in system.input_names or "M_middle" not in system.output_names:
        raise ParameterError("speed_ratio: assemble the bearing as the root with "
                             "drive='speed', speed=None and outputs=['M_middle', ...]")
    runs: list[tuple[float, float]] = []

    def torque(rs: float) -> float:
        if len(runs) >= max_runs:
            raise SimulationError(f"{where}: no convergence to {tol:g} within {max_runs} runs; "
                                  f"runs (Rs, M_middle [N m]): {runs}")
        x0 = bearing.rolling_start(w_shaft, rs * w_shaft, system.state_names)
        res = simulate(system, t_run, x0=x0, inputs={"shaft_speed": w_shaft},
                       parameters=parameters, method="cvodes", rtol=1e-5, atol=1e-8,
                       n_points=21, progress=False)
        m = float(np.mean(res["M_middle"][res.t >= 0.5 * t_run]))
        runs.append((rs, m))
        return m

    if bracket is None:
        seed = _torque_level_ratio(bearing, w_shaft)
        bracket = (seed, 1.05 * seed)
    for rs in bracket:
        check_range(rs, "bracket", "-", 0.0, 1.0, low_inclusive=False, high_inclusive=False,
                    where=where)
    (r_a, r_b) = sorted(float(r) for r in bracket)
    m_a, m_b = torque(r_a), torque(r_b)
    # widen until the net torque changes sign: speeding up below, slowing down above
    while m_a <= 0.0 or m_b >= 0.0:
        width = r_b - r_a
        if m_a <= 0.0:
            r_b, m_b, r_a = r_a, m_a, max(0.5 * r_a, r_a - 2.0 * width)
            m_a = torque(r_a)
        else:
            r_a, m_a, r_b = r_b, m_b, min(0.5 * (1.0 + r_b), r_b + 2.0 * width)
            m_b = torque(r_b)
        if r_a < 1e-6 or r_b > 1.0 - 1e-6:
            raise SimulationError(f"{where}: the net middle-ring torque does not change sign "
                                  f"in (0, 1); runs (Rs, M_middle [N m]): {runs}")
    # regula falsi, Illinois variant: halve the kept end's torque when an end repeats
    rs, side = r_a, 0
    while True:
        new = r_b - m_b * (r_b - r_a) / (m_b - m_a)
        if abs(new - rs) < tol:
            rs = new
            break
        rs = new
        m = torque(rs)
        if m > 0.0:
            r_a, m_a = rs, m
            if side == -1:
                m_b *= 0.5
            side = -1
        else:
            r_b, m_b = rs, m
            if side == 1:
                m_a *= 0.5
            side = 1
    final_a = max((r for r, m in runs if m > 0.0 and r <= rs), default=r_a)
    final_b = min((r for r, m in runs if m <= 0.0 and r >= rs), default=r_b)
    torques = dict(runs)
    return SpeedRatioEstimate(rs, (final_a, final_b), (torques[final_a], torques[final_b]),
                              tuple(runs))


def _torque_level_ratio(bearing: DynamicDoubleLayerBearing, w_shaft: float) -> float:
    """Rs of the Palmgren torque level with the layers' lubricants (a start for the search)."""
    twin = double_layer_bearing(*bearing.geometries, structure=bearing.structure,
                                fidelity="torque",
                                lubrication=(bearing.inner_layer.lubricant,
                                             bearing.outer_layer.lubricant))
    rs, _, _ = steady_ratio(assemble(twin), w_shaft)
    return float(rs)
