"""Deep-groove ball bearing studies (docs/studies.md, section C): validation case and
motor duty cycle.

The runs use :func:`~bearingsim.assemblies.deep_groove.deep_groove_ball_bearing`; quantities
needed only at save points (film thickness, fatigue life) are computed after the integration
from the result (:func:`post_process`), never in the right-hand side.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from bearingsim.assembler import assemble
from bearingsim.assemblies.deep_groove import deep_groove_ball_bearing
from bearingsim.physics.bearing_design import BearingDesign
from bearingsim.physics.film import hamrock_dowson
from bearingsim.physics.geometry import ball_revolutions_per_revolution
from bearingsim.physics.life import (
    ball_contact_capacity,
    combined_contact_life,
    contact_life,
    dynamic_load_rating,
    life_hours,
    raceway_contact_capacity,
    rating_life,
    reference_rating_life,
)
from bearingsim.physics.lubricant import Dry, Lubricant, as_lubricant
from bearingsim.simulation import Result, simulate
from bearingsim.units import rpm_to_rad_s

__all__ = ["DUTY_CYCLE", "VALIDATION", "RunSummary", "outputs_for", "run_bearing",
           "validation_case", "duty_condition", "post_process", "settling_time",
           "largest_pocket_force", "StartUp", "start_up"]

DUTY_CYCLE = ((1730.0, 938.0), (3703.0, 903.0), (1785.0, 266.0), (3998.0, 206.0))
"""The four motor working conditions of docs/studies.md, section C: (speed [r/min],
radial load [N])."""

VALIDATION = {"load": 500.0, "acceleration": 500.0, "mu": 0.02}
"""Validation case of docs/studies.md, section C: radial load [N], inner-ring acceleration
[rad/s^2], dry mu."""


@dataclass
class RunSummary:
    """Post-processed quantities of one run (averages over the evaluation window).

    Attributes
    ----------
    slip : float
        Mean cage slip ratio [-].
    q_inner_max, q_outer_max : float
        Largest inner / outer contact load [N].
    pocket_force_max : float
        Largest ball-pocket force [N] (a single sample: one impact decides it).
    collision_force : float
        Ball-cage collision force [N]: the 99th percentile over the window of the largest
        pocket force among the balls (the peak level of the repeated impacts, insensitive to
        one outlier).
    collision_rms : float
        RMS of the pocket forces of all balls over the window [N].
    h_min : float
        Smallest minimum film thickness of the loaded contacts [m] (0 when dry).
    life_lp, life_iso281, life_ts16281 : float
        L10 [10^6 rev]: Lundberg-Palmgren per contact (docs/studies.md, section C), ISO 281 (C/P)^3,
        ISO/TS 16281 from the internal load distribution.
    life_hours_iso281 : float
        ISO 281 life at the run's speed [h].
    """

    slip: float
    q_inner_max: float
    q_outer_max: float
    pocket_force_max: float
    collision_force: float
    collision_rms: float
    h_min: float
    life_lp: float
    life_iso281: float
    life_ts16281: float
    life_hours_iso281: float


def outputs_for(n_balls: int) -> list[str]:
    """Outputs a study needs: slip, speeds, contact loads, entrainment speeds, pocket forces,
    cage centre and ball speeds (states, so they cost nothing).

    Parameters
    ----------
    n_balls : int
        Number of balls Z.

    Returns
    -------
    list of str
        The output names.
    """
    names = ["slip", "w_cage", "w_inner", "w_epicyclic", "cage.x", "cage.y"]
    for j in range(n_balls):
        names += [f"inner[{j}].Q", f"outer[{j}].Q", f"inner[{j}].u_entrain",
                  f"outer[{j}].u_entrain", f"pocket[{j}].F", f"ball[{j}].w_orbit",
                  f"ball[{j}].wr", f"ball[{j}].wt", f"ball[{j}].wz"]
    return names


def run_bearing(speed, load: float, t_end: float, *, designation: str = "6304",
                lubricant: Lubricant | str = "ISO VG 32",
                fidelity: str = "dynamic_massive_balls", method: str = "cvodes",
                rtol: float = 1e-5, atol: float = 1e-6, n_points: int = 201,
                **options) -> tuple[Result, BearingDesign]:
    """Assemble and simulate one run with a radial load ``Fx = load`` on the inner ring.

    Parameters
    ----------
    speed : callable or float
        Inner-ring speed [rad/s] (symbolic function of time allowed).
    load : float
        Radial load [N].
    t_end : float
        Simulated time [s].
    designation, lubricant, fidelity
        As in :func:`~bearingsim.assemblies.deep_groove.deep_groove_ball_bearing`.
    method, rtol, atol, n_points
        As in :func:`~bearingsim.simulation.simulate`.
    **options
        Further bearing options (``n_slices``, ``damping``, ...).

    Returns
    -------
    (Result, BearingDesign)
    """
    bearing = deep_groove_ball_bearing(designation, fidelity, lubricant=lubricant, speed=speed,
                                       loads={"Fx": float(load)}, **options)
    system = assemble(bearing, outputs=outputs_for(bearing.design.geometry.ball_count))
    res = simulate(system, t_end, method=method, rtol=rtol, atol=atol, n_points=n_points,
                   progress=False)
    return res, bearing.design


def validation_case(t_end: float = 0.1, **kwargs) -> tuple[Result, BearingDesign]:
    """Validation case of docs/studies.md, section C: 6304 geometry, 500 N, spin-up at 500 rad/s^2,
    dry mu = 0.02.

    Parameters
    ----------
    t_end : float
        Run length [s].
    **kwargs
        Keywords of :func:`run_bearing`.

    Returns
    -------
    tuple
        The :class:`~bearingsim.simulation.Result` and the bearing's design.
    """
    acc = VALIDATION["acceleration"]
    kwargs.setdefault("lubricant", Dry(VALIDATION["mu"]))
    return run_bearing(lambda t: acc * t, VALIDATION["load"], t_end, **kwargs)


def duty_condition(k: int, t_end: float = 0.1, ramp: float = 0.02,
                   **kwargs) -> tuple[Result, BearingDesign]:
    """Duty-cycle condition ``k`` (1..4): speed ramped from rest over ``ramp`` seconds.

    Parameters
    ----------
    k : int
        Duty condition, 1..4.
    t_end : float
        Run length [s].
    ramp : float
        Duration of the speed ramp [s].
    **kwargs
        Keywords of :func:`run_bearing`.

    Returns
    -------
    tuple
        The :class:`~bearingsim.simulation.Result` and the bearing's design.
    """
    n_rpm, load = DUTY_CYCLE[k - 1]
    w = rpm_to_rad_s(n_rpm)
    return run_bearing(lambda t: w * ca.fmin(t / ramp, 1.0), load, t_end, **kwargs)


def settling_time(t: np.ndarray, signal: np.ndarray, band: float, t_min: float = 0.0) -> float:
    """Earliest time after which ``signal`` stays within ``band`` of its final mean [s].

    The final mean is taken over the last fifth of the run; ``t_min`` excludes the start.

    Parameters
    ----------
    t : numpy.ndarray
        Times [s].
    signal : numpy.ndarray
        Values at those times.
    band : float
        Half-width of the band (the signal's unit).
    t_min : float
        Earliest time considered [s].

    Returns
    -------
    float
        The settling time [s].
    """
    tail = signal[int(0.8 * len(signal)):]
    outside = np.nonzero((np.abs(signal - tail.mean()) > band) & (t >= t_min))[0]
    return float(t[outside[-1]]) if outside.size else float(t_min)


def largest_pocket_force(res: Result, n_balls: int) -> np.ndarray:
    """Largest ball-pocket (collision) force among the balls at every save point [N].

    Parameters
    ----------
    res : Result
        A run with the outputs of :func:`outputs_for`.
    n_balls : int
        Number of balls Z.

    Returns
    -------
    numpy.ndarray
        The largest pocket force at each save point [N].
    """
    return np.max(np.abs([res[f"pocket[{j}].F"] for j in range(n_balls)]), axis=0)


@dataclass
class StartUp:
    """Start-up transient of a run from rest (the findings on slip and collisions, docs/studies.md,
    section C).

    Attributes
    ----------
    slip_settling : float
        Time after which the cage slip stays within the slip band of its final mean [s].
    collision_peak : float
        Largest ball-pocket force of the run [N] (a single sample: one impact decides it).
    collision_level : float
        Largest trailing average of the largest pocket force [N]: the force level the balls
        sustain on the cage while they accelerate it (less sensitive to where the save points
        fall on the short Hertz impacts than the peak).
    collision_settling : float
        Time after which that average stays within the force band of its final mean [s].
    impacts : int
        Number of times the largest pocket force rises through half of ``collision_level``
        before ``collision_settling`` [-] (repeated collisions: the start-up oscillation).
    """

    slip_settling: float
    collision_peak: float
    collision_level: float
    collision_settling: float
    impacts: int


def start_up(res: Result, design: BearingDesign, *, slip_band: float = 0.05,
             force_band: float = 2.0, averaging: float = 5e-4) -> StartUp:
    """Settling of the cage slip and of the ball-cage collision forces after a start from rest.

    Parameters
    ----------
    res : Result
        A run from rest with the outputs of :func:`outputs_for`, saved densely enough to
        resolve the collisions (10 us in the tests).
    design : BearingDesign
        The bearing's design.
    slip_band : float
        Band of :func:`settling_time` for the slip [-].
    force_band : float
        Band of :func:`settling_time` for the averaged collision force [N].
    averaging : float
        Length of the trailing average of the largest pocket force [s].

    Returns
    -------
    StartUp
    """
    force = largest_pocket_force(res, design.geometry.ball_count)
    n = max(1, int(round(averaging / (res.t[1] - res.t[0]))))
    level = np.convolve(force, np.ones(n) / n)[:force.size]  # trailing; at rest before t = 0
    t_force = settling_time(res.t, level, force_band)
    half = 0.5 * level.max()
    rises = (force[1:] > half) & (force[:-1] <= half) & (res.t[1:] <= t_force)
    return StartUp(
        slip_settling=settling_time(res.t, res["slip"], slip_band),
        collision_peak=float(force.max()),
        collision_level=float(level.max()),
        collision_settling=t_force,
        impacts=int(np.count_nonzero(rises)),
    )


def post_process(res: Result, design: BearingDesign, lubricant: Lubricant | str, load: float,
                 window: float = 0.5) -> RunSummary:
    """Film thickness and lives from a run, over its last ``window`` fraction.

    Film: Hamrock-Dowson minimum film thickness of every contact at every save point
    (:func:`~bearingsim.physics.film.hamrock_dowson`, E' of Hamrock = ``design.e_eff``).
    Lives: per ball the cubic-mean load of each contact over the window; Lundberg-Palmgren
    contact lives combined by :func:`~bearingsim.physics.life.combined_contact_life`; ISO 281
    ``(C/P)^3`` with C from the geometry and ``P = Fr``; ISO/TS 16281
    (:func:`~bearingsim.physics.life.reference_rating_life`).

    Parameters
    ----------
    res : Result
        A run with the outputs of :func:`outputs_for`.
    design : BearingDesign
        The bearing's design.
    lubricant : Lubricant or str
        The lubricant of the run.
    load : float
        Radial load [N].
    window : float
        Fraction of the run at its end that is evaluated, in (0, 1].

    Returns
    -------
    RunSummary
        Film thickness and lives.
    """
    lub = as_lubricant(lubricant, "deep_groove")
    g = design.geometry
    nz, dw, dm, a0 = g.ball_count, g.ball_diameter, g.pitch_diameter, design.free_contact_angle
    sel = res.t >= res.t[0] + (1.0 - window) * (res.t[-1] - res.t[0])
    q_i = np.array([res[f"inner[{j}].Q"][sel] for j in range(nz)])
    q_o = np.array([res[f"outer[{j}].Q"][sel] for j in range(nz)])
    eta, alpha = float(lub.dynamic_viscosity()), float(lub.pressure_viscosity())
    h_min = 0.0
    if eta > 0.0:
        films = []
        for race, q, rx, ry in (("inner", q_i, design.rx_inner, design.ry_inner),
                                ("outer", q_o, design.rx_outer, design.ry_outer)):
            u = np.array([res[f"{race}[{j}].u_entrain"][sel] for j in range(nz)])
            loaded = q > 0.05 * load
            if np.any(loaded):
                films.append(hamrock_dowson(q[loaded], u[loaded], rx, ry, design.e_eff, eta,
                                            alpha).h_min.min())
        h_min = float(min(films)) if films else 0.0
    qe_i = np.cbrt(np.mean(q_i**3, axis=1)) + 1e-9
    qe_o = np.cbrt(np.mean(q_o**3, axis=1)) + 1e-9
    cap = {race: (raceway_contact_capacity(dw, dm, f, nz, a0, race),
                  ball_contact_capacity(dw, dm, f, nz, a0, race))
           for race, f in (("inner", g.fi), ("outer", g.fo))}
    n_ball = ball_revolutions_per_revolution(dw, dm, a0)
    life_lp = combined_contact_life(contact_life(cap["outer"][0], qe_o),
                                    contact_life(cap["inner"][0], qe_i),
                                    contact_life(cap["outer"][1], qe_o),
                                    contact_life(cap["inner"][1], qe_i), n_ball)
    c = dynamic_load_rating(dw, dm, nz, 0.0)
    life_iso = rating_life(c, load)
    life_ts = reference_rating_life(qe_i, qe_o, c, g.fi, g.fo, design.gamma)
    speed = float(np.mean(res["w_inner"][sel]))
    pocket = np.abs(np.array([res[f"pocket[{j}].F"][sel] for j in range(nz)]))
    return RunSummary(
        slip=float(np.mean(res["slip"][sel])),
        q_inner_max=float(q_i.max()),
        q_outer_max=float(q_o.max()),
        pocket_force_max=float(pocket.max()),
        collision_force=float(np.percentile(pocket.max(axis=0), 99.0)),
        collision_rms=float(np.sqrt(np.mean(pocket**2))),
        h_min=h_min,
        life_lp=float(life_lp),
        life_iso281=float(life_iso),
        life_ts16281=float(life_ts),
        life_hours_iso281=float(life_hours(life_iso, speed)) if speed > 0 else float("inf"),
    )
