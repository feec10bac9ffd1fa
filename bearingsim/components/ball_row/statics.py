"""A ball row's statics outside a model: the stiffness of the row at a displacement
(:func:`row_stiffness`) and the inner ring's equilibrium under loads (:func:`row_equilibrium`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.components.ball_row.loads import _groove_centres, row_loads
from bearingsim.components.ball_row.parameters import STEEL_DENSITY, RowParameters
from bearingsim.physics.hertz import (
    combined_load_deflection_constant,
)
from bearingsim.physics.ring_equilibrium import EquilibriumProblem


def row_stiffness(p: RowParameters, n_balls: int, inner=(0.0,) * 5, direction: int = 1, *,
                  reference: str = "touching", exact: bool = True) -> np.ndarray:
    """5x5 stiffness matrix of a ball row (classic form) from the exact CasADi Jacobian.

    ``K = -d(load on the inner ring) / d(inner ring displacement)`` with the outer ring fixed;
    rows and columns ordered (x, y, z, tx, ty) [N/m, N/rad, N m/m, N m/rad].

    Parameters
    ----------
    p : RowParameters
    n_balls : int
    inner : sequence of 5
        Inner ring displacement of the operating point [m, rad].
    direction, reference, exact
        As for :func:`row_loads`.

    Returns
    -------
    numpy.ndarray of shape (5, 5)
    """
    q = ca.SX.sym("q", 5)
    loads = row_loads(p, [q[k] for k in range(5)], [0.0] * 5, n_balls, direction,
                      reference=reference, exact=exact)
    jac = ca.Function("row_jac", [q], [ca.jacobian(ca.vertcat(*loads.inner_load), q)])
    return -np.asarray(jac(ca.DM(list(inner))).full(), dtype=float)


@dataclass(frozen=True)
class RowEquilibrium:
    """Result of :func:`row_equilibrium`."""

    inner: np.ndarray
    """Inner ring translation (x, y, z) against the outer ring [m] (tilts held at 0)."""
    centres: np.ndarray | None
    """Ball centres ``(b_r, b_z)`` per ball [m] (Jones-Harris form), else None."""


def _classic_centres(p: Any, inner: np.ndarray, n_balls: int, reference: str,
                     density: float, speeds: tuple[float, float]) -> np.ndarray:
    """Ball centres of the two-force (classic) ball, pressed out by the centrifugal force of the
    cage speed where it carries no load: a start for the Jones-Harris unknowns [m]."""
    k_ball = combined_load_deflection_constant(p.K_i, p.K_o)
    g = p.Dw / p.dm
    w_cage = speeds[0] * 0.5 * (1.0 - g) + speeds[1] * 0.5 * (1.0 + g)
    f_c = 0.5 * density * math.pi * p.Dw**3 / 6.0 * p.dm * w_cage**2
    out = np.zeros((n_balls, 2))
    for j in range(n_balls):
        psi = p.psi0 + 2.0 * math.pi * j / n_balls
        c_i0, c_o0 = _groove_centres(p, psi, 1, reference)
        c_i = (c_i0[0] + inner[0], c_i0[1] + inner[1], c_i0[2] + inner[2])
        ci = (math.cos(psi) * c_i[0] + math.sin(psi) * c_i[1], c_i[2])
        co = (math.cos(psi) * c_o0[0] + math.sin(psi) * c_o0[1], c_o0[2])
        d = (ci[0] - co[0], ci[1] - co[1])
        length = math.hypot(*d)
        q = k_ball * max(length - (p.fi + p.fo - 1.0) * p.Dw, 0.0) ** 1.5
        reach = (p.fo - 0.5) * p.Dw + ((q + f_c) / p.K_o) ** (2.0 / 3.0)
        out[j] = (co[0] + reach * d[0] / length - 0.5 * p.dm, co[1] + reach * d[1] / length)
    return out


def row_equilibrium(p: RowParameters, n_balls: int, loads=(0.0, 0.0, 0.0), *,
                    speeds=(0.0, 0.0), speed_effects: bool = False,
                    reference: str = "centred",
                    ball_density: float = STEEL_DENSITY) -> RowEquilibrium:
    """Numeric equilibrium of a row with the inner ring held straight, e.g. for start values.

    Solved by :class:`~bearingsim.physics.ring_equilibrium.EquilibriumProblem` (seated start,
    Levenberg-Marquardt on the exact Jacobian): first the classic form, then, with
    ``speed_effects``, the Jones-Harris form from it (ball centres pressed out by the centrifugal
    force as the start).

    Parameters
    ----------
    p : RowParameters
    n_balls : int
        Number of balls Z.
    loads : (Fx, Fy, Fz)
        External load on the inner ring [N].
    speeds : (float, float)
        Inner and outer ring speeds [rad/s].
    speed_effects : bool
        Jones-Harris form (centrifugal force, gyroscopic moment).
    reference : {"touching", "centred"}
    ball_density : float
        [kg/m^3].

    Returns
    -------
    RowEquilibrium

    Raises
    ------
    SimulationError
        If no equilibrium is found (named by the speed with ``speed_effects``).
    """
    a_play = (p.fi + p.fo - 1.0) * p.Dw * math.sin(p.alpha0) if reference == "centred" else 0.0
    x = ca.SX.sym("x", 3)
    ring = [x[0], x[1], x[2], 0.0, 0.0]
    classic = row_loads(p, ring, [0.0] * 5, n_balls, 1, reference=reference)
    problem = EquilibriumProblem(ca.Function("row", [x], [ca.vertcat(*classic.inner_load[:3])]),
                                 3, [1e-5] * 3, [1.0] * 3, play=a_play, axial=2,
                                 name=f"row_equilibrium({n_balls} balls)")
    inner = problem.solve(np.asarray(loads, dtype=float))
    if not speed_effects:
        return RowEquilibrium(inner, None)
    b = ca.SX.sym("b", 2 * n_balls)
    centres = [(b[2 * j], b[2 * j + 1]) for j in range(n_balls)]
    jh = row_loads(p, ring, [0.0] * 5, n_balls, 1, reference=reference, ball_centres=centres,
                   speeds=speeds, ball_density=ball_density)
    v = ca.vertcat(x, b)
    problem = EquilibriumProblem(
        ca.Function("row_jh", [v], [ca.vertcat(*jh.inner_load[:3], *jh.residual)]),
        3, [1e-5] * 3 + [1e-6] * (2 * n_balls), [1.0] * (3 + 2 * n_balls),
        extra_start=lambda r: _classic_centres(p, r, n_balls, reference, ball_density,
                                                speeds).ravel(),
        play=a_play, axial=2,
        name=f"row_equilibrium at inner-ring speed {speeds[0]:g} rad/s "
             f"({speeds[0] * 30 / math.pi:.0f} r/min)")
    guess = np.concatenate([inner, _classic_centres(p, inner, n_balls, reference, ball_density,
                                                    speeds).ravel()])
    sol = problem.solve(np.asarray(loads, dtype=float), guess)
    return RowEquilibrium(sol[:3], sol[3:].reshape(n_balls, 2))
