"""Quasi-static deep-groove ball bearing under any combination of Fx, Fy, Fz, Mx, My.

The inner ring moves against the fixed outer ring in five degrees of freedom (three
translations, two tilts, z along the axis) until the ball loads balance the external load.
Two forms of the same problem:

* ``method="exact"``: bearingsim's ball row (:func:`~bearingsim.components.ball_row.row_loads`,
  rings centred with the diametral clearance): exact rigid-ring kinematics of the groove
  curvature centres, the exact lever of every contact, the Hertz constants of
  :mod:`bearingsim.physics.hertz` at the free contact angle.
* ``method="iso_ts_16281"``: the form ISO/TS 16281 writes (:mod:`bearingsim.physics.iso_ts_16281`):
  small-rotation kinematics with the inner groove-centre radius, moments with the pitch radius,
  the standard's spring constant and ratings. Use it to compare with tools that implement the
  standard.

The equilibrium is found by :class:`~bearingsim.physics.ring_equilibrium.EquilibriumProblem`:
Levenberg-Marquardt on the exact Jacobian (CasADi) from a seated start (each loaded direction
alone solved first, a one-dimensional root that exists for any clearance including zero, where
the Jacobian at the centred position is singular), with the axial play as further starts and a
load path as the last resort. The result carries the ball loads,
contact angles, the 5x5 stiffness (exact Jacobian) and the ISO/TS 16281 basic reference rating
life.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import casadi as ca
import numpy as np

from bearingsim.catalog import BearingGeometry, resolve_bearing
from bearingsim.components.ball_row import row_loads, row_parameters
from bearingsim.components.dynamic.ring import load_value
from bearingsim.errors import ParameterError
from bearingsim.physical_checks import check_static_pressure
from bearingsim.physics import iso_ts_16281 as iso
from bearingsim.physics.contact_curvature import raceway_radii
from bearingsim.physics.hertz import max_pressure
from bearingsim.physics.life import (
    bearing_life,
    contact_life,
    dynamic_load_rating,
    raceway_dynamic_ratings,
    raceway_equivalent_load,
)
from bearingsim.physics.materials import STEEL, Material, effective_modulus
from bearingsim.physics.ring_equilibrium import EquilibriumProblem
from bearingsim.validation import check_choice, check_mapping, check_quantity, check_range

__all__ = ["DeepGrooveStatics", "LOAD_NAMES", "METHODS",
           "STATIC_PRESSURE_LIMIT", "deep_groove_statics"]

LOAD_NAMES = ("Fx", "Fy", "Fz", "Mx", "My")
"""External loads on the inner ring: forces [N], moments [N m]; z is the bearing axis."""
METHODS = ("exact", "iso_ts_16281")
STATIC_PRESSURE_LIMIT = 4.2e9
"""Hertz pressure [Pa] at which ISO 76 sets the static load rating of ball bearings (the onset of
a permanent deformation of 1e-4 Dw); above it a warning is given."""

_SCALE = np.array([1e-5, 1e-5, 1e-5, 1e-4, 1e-4])
"""Typical magnitudes of the unknowns [m, m, m, rad, rad], for the iteration."""


@dataclass(frozen=True)
class DeepGrooveStatics:
    """Equilibrium of a deep-groove ball bearing (:func:`deep_groove_statics`)."""

    method: str
    """``"exact"`` or ``"iso_ts_16281"``."""
    geometry: BearingGeometry
    """The bearing, with the clearance used."""
    loads: dict[str, float]
    """The external loads on the inner ring [N, N m]."""
    displacement: np.ndarray
    """Inner ring against outer ring (x, y, z) [m]."""
    tilt: np.ndarray
    """Tilts (tx about x, ty about y) [rad]."""
    azimuths: np.ndarray
    """Azimuth of every ball [rad]."""
    ball_loads: np.ndarray
    """Contact load of every ball [N] (the same at both raceways, no speed effects)."""
    contact_angles: np.ndarray
    """Operating contact angle of every ball [rad]."""
    stiffness: np.ndarray
    """``-d(load of the balls on the inner ring) / d(x, y, z, tx, ty)``, 5x5 [N/m, N/rad,
    N m/m, N m/rad]; a direction without stiffness (play) shows as a zero row."""
    max_pressure: float
    """Largest Hertz pressure of the ball-raceway contacts [Pa]."""
    reference_life: float
    """ISO/TS 16281 basic reference rating life L10r [10^6 revolutions] (inf without load)."""
    state: np.ndarray
    """``(x, y, z, tx, ty)``: a start for a nearby load case (``guess``)."""


def deep_groove_statics(bearing: str | BearingGeometry = "6304",
                        loads: Mapping[str, float] | None = None, *,
                        clearance: float | str | None = None,
                        ball_material: Material = STEEL, ring_material: Material = STEEL,
                        method: str = "exact", guess=None,
                        ball_position_angle: float | str = 0.0,
                        inner_rotating: bool = True,
                        dynamic_load_rating_n: float | None = None) -> DeepGrooveStatics:
    """Solve the quasi-static equilibrium of a deep-groove ball bearing.

    Parameters
    ----------
    bearing : str or BearingGeometry
        Catalogue designation or geometry.
    loads : dict, optional
        External loads on the inner ring, keys among ``Fx, Fy, Fz`` [N] and ``Mx, My`` [N m]
        (z is the axis); missing keys are 0. Finite numbers.
    clearance : float or str, optional
        Diametral clearance Pd [m], >= 0 (0 allowed), or a number with a unit (``"20 um"``);
        default: the geometry's.
    ball_material, ring_material : Material
        Materials of the balls and rings (Hertz constants; e.g.
        :data:`~bearingsim.physics.materials.SILICON_NITRIDE` balls).
    method : {"exact", "iso_ts_16281"}
        bearingsim's exact kinematics or the form ISO/TS 16281 writes (module docstring).
    guess : array of 5, optional
        Start ``(x, y, z, tx, ty)`` [m, rad], e.g. the ``state`` of a nearby case.
    ball_position_angle : float or str
        Azimuth of ball 0 [rad], finite, or a number with a unit (``"10 deg"``).
    inner_rotating : bool
        Whether the inner ring rotates against the load (life: cubic mean of its ball loads).
    dynamic_load_rating_n : float, optional
        Basic dynamic load rating C [N] for the life; default the catalogue value, else
        ISO 281's C of the geometry.

    Returns
    -------
    DeepGrooveStatics

    Raises
    ------
    ParameterError
        For an unknown load name, a non-finite load, loads beyond the strength of bearing steel
        (see below), a clearance outside ``[0, Pd(45 deg)]``, a ball position angle that is
        not finite,
        a method other than the two above or a ``guess`` that is not 5 finite numbers.
    SimulationError
        If no equilibrium is found (the message names the load reached on the load path).

    Warns
    -----
    PlasticDeformationWarning
        When the largest Hertz pressure exceeds 4 200 MPa (ISO 76's static limit); above the
        pressure of :data:`~bearingsim.checks.MAX_STATIC_LOAD_FACTOR` times C0 (about
        9 000 MPa) a :class:`~bearingsim.errors.ParameterError` instead.
    """
    where = "deep_groove_statics"
    check_choice(method, "method", METHODS, where)
    g = resolve_bearing(bearing)
    if clearance is not None:
        clearance = check_quantity(clearance, "clearance", "m", 0.0, where=where)
        g = dataclasses.replace(g, diametral_clearance=float(clearance))
    ball_position_angle = float(check_quantity(ball_position_angle, "ball_position_angle",
                                               "rad", where=where))
    f_ext = _load_vector(loads, where)
    x0 = None if guess is None else _guess_vector(guess, where)
    problem = _Problem(g, method, ball_material, ring_material, ball_position_angle)
    state = problem.equilibrium.solve(f_ext, x0)
    q, alpha = problem.balls(state)
    stiffness = -np.asarray(problem.jacobian(state), dtype=float)
    p_max = problem.max_pressure(q, alpha)
    check_static_pressure(p_max, STATIC_PRESSURE_LIMIT, "1/3", f"{where}({g.designation})",
                          f"{dict(loads or {})} [N, N.m]")
    c = dynamic_load_rating_n or g.dynamic_load_rating or float(dynamic_load_rating(
        g.ball_diameter, g.pitch_diameter, g.ball_count, g.contact_angle))
    life = problem.life(q, c, inner_rotating) if np.any(f_ext) else math.inf
    return DeepGrooveStatics(
        method=method, geometry=g, loads=dict(zip(LOAD_NAMES, f_ext.tolist(), strict=True)),
        displacement=state[:3].copy(), tilt=state[3:].copy(), azimuths=problem.azimuths,
        ball_loads=q, contact_angles=alpha, stiffness=stiffness, max_pressure=p_max,
        reference_life=life, state=state)


def _load_vector(loads, where: str) -> np.ndarray:
    loads = check_mapping(loads, "loads", where, f"load names ({', '.join(LOAD_NAMES)})")
    unknown = sorted(set(loads) - set(LOAD_NAMES))
    if unknown:
        raise ParameterError(f"{where}: unknown load(s) {', '.join(map(repr, unknown))}; the "
                             f"loads are {', '.join(LOAD_NAMES)} (forces [N], moments [N.m], z "
                             f"is the bearing axis)")
    out = np.zeros(5)
    for k, name in enumerate(LOAD_NAMES):
        out[k] = load_value(loads.get(name, 0.0), name, where)
    return out


def _guess_vector(guess, where: str) -> np.ndarray:
    try:
        x = np.asarray(guess, dtype=float).ravel()
    except (TypeError, ValueError):
        raise ParameterError(f"{where}: guess must be 5 numbers (x, y, z, tx, ty) [m, rad], "
                             f"got {guess!r}") from None
    if x.size != 5:
        raise ParameterError(f"{where}: guess must be 5 numbers (x, y, z, tx, ty) [m, rad], got "
                             f"{x.size}")
    check_range(x, "guess", "m, rad", where=where)
    return x


class _Problem:
    """Residual, Jacobian and post-processing of one bearing in one form."""

    def __init__(self, g: BearingGeometry, method: str, ball: Material, ring: Material,
                 ball_position_angle: float):
        self.g, self.method = g, method
        self.ball, self.ring = ball, ring
        z = g.ball_count
        self.azimuths = ball_position_angle + 2.0 * np.pi * np.arange(z) / z
        qs = ca.SX.sym("q", 5)
        q_list = [qs[k] for k in range(5)]
        if method == "exact":
            p = row_parameters(g, None, ball_position_angle, 1e-9, ball, ring)
            c = row_loads(p, q_list, [0.0] * 5, z, 1, reference="centred")
            ring_load, balls, angles = c.inner_load, c.Q_i, c.alpha_i
        else:
            cp = iso.contact_spring_constant(g, ball, ring)
            delta, angles = iso.deflections(g, q_list, ball_position_angle)
            balls = [cp * ca.power(ca.fmax(d, 0.0), 1.5) for d in delta]
            ring_load = iso.ring_loads(g, balls, angles, ball_position_angle)
        ring_load = ca.vertcat(*ring_load)
        self.equilibrium = EquilibriumProblem(
            ca.Function("ring_load", [qs], [ring_load]), 5, _SCALE,
            [1.0, 1.0, 1.0] + [2.0 / g.pitch_diameter] * 2,
            play=g.groove_centre_distance * math.sin(g.free_contact_angle), axial=2,
            name=f"deep_groove_statics({g.designation})")
        self._balls = ca.Function("balls", [qs], [ca.vertcat(*balls), ca.vertcat(*angles)])

    def jacobian(self, x: np.ndarray) -> np.ndarray:
        return self.equilibrium.jacobian(x)

    def balls(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        q, a = self._balls(x)
        return np.asarray(q, dtype=float).ravel(), np.asarray(a, dtype=float).ravel()

    # ------------------------------------------------------------------ results
    def max_pressure(self, q: np.ndarray, alpha: np.ndarray) -> float:
        if not np.any(q > 0.0):
            return 0.0
        j = int(np.argmax(q))
        e_eff = effective_modulus(self.ball, self.ring)
        g = self.g
        return max(float(max_pressure(q[j], *raceway_radii(
            g.ball_diameter, g.pitch_diameter, f, abs(alpha[j]), race), e_eff))
            for race, f in (("inner", g.fi), ("outer", g.fo)))

    def life(self, q: np.ndarray, c: float, inner_rotating: bool) -> float:
        g = self.g
        if self.method == "exact":
            qci, qce = (float(v) for v in raceway_dynamic_ratings(
                c, g.fi, g.fo, g.gamma, g.ball_count, g.contact_angle))
        else:
            qci, qce = iso.raceway_ratings(c, g)
        qei = float(raceway_equivalent_load(q, rotating=inner_rotating))
        qee = float(raceway_equivalent_load(q, rotating=not inner_rotating))
        return float(bearing_life(contact_life(qci, qei), contact_life(qce, qee)))
