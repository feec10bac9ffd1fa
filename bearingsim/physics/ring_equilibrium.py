"""Numeric equilibrium of a ring under external loads, from a seated start.

The unknowns are the ring's displacements (some of x, y, z, tx, ty) and, optionally, further
unknowns of the balls (e.g. their centres at speed). The residual is ``ring load + external
load`` for the ring and the balls' own equations for the rest, given as one CasADi function, so
that the Jacobian is exact.

A bearing with clearance, or with zero clearance at the centred position, has no stiffness
where the rings are centred: Newton started there meets a singular Jacobian. The **seated
start** brings each loaded ring direction alone to balance first, a one-dimensional root of
that direction's load, which exists at any clearance; their sum is the start of a
Levenberg-Marquardt iteration on the exact Jacobian (scipy ``least_squares``), which also leaves
directions without load or stiffness (axial play under a radial load) where symmetry puts them.
Further starts shift the ring by a given axial play either way (a moment with clearance seats
the balls on one shoulder); a load path with step halving is the last resort.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import casadi as ca
import numpy as np

from bearingsim.errors import SimulationError

__all__ = ["RESOLUTION", "EquilibriumProblem"]

RESOLUTION = 1e-12
"""Residual [-, relative to the largest weighted load] within which an unknown that would be
zero counts as zero (:meth:`EquilibriumProblem.solve`): 1000 times tighter than the solve's
convergence test, 1e-9."""


@dataclass
class EquilibriumProblem:  # numpydoc ignore=PR02
    """One equilibrium problem.

    Parameters
    ----------
    residual : casadi.Function
        ``v -> r``: the first ``n_ring`` entries of ``r`` are the loads of the balls on the ring
        (the external load is added to them), the rest the balls' own residuals (zero at
        equilibrium); ``v`` holds the ring displacements first.
    n_ring : int
        Number of ring unknowns.
    scale : sequence of float
        Typical magnitude of every unknown [m or rad].
    weight : sequence of float
        Weight of every residual in the convergence test (e.g. 1 for forces, 1 / radius for
        moments, 1 for ball force balances).
    extra_start : callable, optional
        ``ring -> further unknowns``: a start for the non-ring unknowns at a ring position.
    play : float
        Axial play [m] (0: none); with an axial ring unknown at index ``axial``, the ring
        shifted by it either way is tried as well when the axial load is zero.
    axial : int or None
        Index of the axial ring unknown.
    name : str
        For messages.
    """

    residual: ca.Function
    n_ring: int
    scale: Sequence[float]
    weight: Sequence[float]
    extra_start: Callable[[np.ndarray], np.ndarray] | None = None
    play: float = 0.0
    axial: int | None = None
    name: str = "equilibrium"

    def __post_init__(self) -> None:
        sym = ca.SX if self.residual.is_a("SXFunction") else ca.MX
        v = sym.sym("v", self.residual.size1_in(0))
        self._jac = ca.Function("residual_jacobian", [v], [ca.jacobian(self.residual(v), v)])
        self._scale = np.asarray(self.scale, dtype=float)
        self._weight = np.asarray(self.weight, dtype=float)

    # ------------------------------------------------------------------ pieces
    def _padded(self, f_ext: np.ndarray) -> np.ndarray:
        out = np.zeros(self._scale.size)
        out[:self.n_ring] = f_ext
        return out

    def value(self, v: np.ndarray, f_ext: np.ndarray) -> np.ndarray:
        """The residual ``r(v)`` with the external load added to the ring entries.

        Parameters
        ----------
        v : numpy.ndarray
            The unknowns (ring displacements first) [m, rad].
        f_ext : numpy.ndarray
            External ring load [N, N m].

        Returns
        -------
        numpy.ndarray
            The residual.
        """
        return np.asarray(self.residual(v), dtype=float).ravel() + self._padded(f_ext)

    def jacobian(self, v: np.ndarray) -> np.ndarray:
        """Exact Jacobian ``dr/dv``.

        Parameters
        ----------
        v : numpy.ndarray
            The unknowns [m, rad].

        Returns
        -------
        numpy.ndarray
            dr/dv.
        """
        return np.asarray(self._jac(v), dtype=float)

    def _force_scale(self, f_ext: np.ndarray) -> float:
        return max(float(np.max(np.abs(f_ext * self._weight[:self.n_ring]))), 1.0)

    def converged(self, v: np.ndarray, f_ext: np.ndarray, tol: float = 1e-9) -> bool:
        """Every weighted residual below ``tol`` times the largest weighted load (at least
        1 N).

        Parameters
        ----------
        v : numpy.ndarray
            The unknowns [m, rad].
        f_ext : numpy.ndarray
            External ring load [N, N m].
        tol : float
            Relative tolerance [-].

        Returns
        -------
        bool
            Whether ``v`` is an equilibrium.
        """
        r = self.value(v, f_ext) * self._weight / self._force_scale(f_ext)
        return bool(np.all(np.isfinite(v)) and np.max(np.abs(r)) <= tol)

    def iterate(self, f_ext: np.ndarray, v0: np.ndarray) -> np.ndarray:
        """Levenberg-Marquardt on the scaled unknowns with the exact Jacobian (NaN where the
        residual is not finite at ``v0``).

        Parameters
        ----------
        f_ext : numpy.ndarray
            External ring load [N, N m].
        v0 : numpy.ndarray
            Start [m, rad].

        Returns
        -------
        numpy.ndarray
            The unknowns reached.
        """
        force, weight, scale = self._force_scale(f_ext), self._weight, self._scale

        def fun(u):
            return self.value(u * scale, f_ext) * weight / force

        def jac(u):
            return self.jacobian(u * scale) * scale[None, :] * weight[:, None] / force

        u0 = v0 / scale
        if not np.all(np.isfinite(fun(u0))):  # e.g. a ball flung off its race: no start
            return np.full_like(v0, np.nan)
        from scipy.optimize import least_squares  # on use: importing scipy.optimize takes ~0.6 s

        sol = least_squares(fun, u0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                            max_nfev=400)
        return sol.x * scale

    def _start(self, ring: np.ndarray) -> np.ndarray:
        extra = (self.extra_start(ring) if self.extra_start is not None
                 else np.zeros(self._scale.size - self.n_ring))
        return np.concatenate([ring, extra])

    def seated(self, f_ext: np.ndarray) -> np.ndarray:
        """Each loaded ring direction alone brought to balance (1-D roots), summed.

        Parameters
        ----------
        f_ext : numpy.ndarray
            External ring load [N, N m].

        Returns
        -------
        numpy.ndarray
            A start for the unknowns [m, rad].
        """
        from scipy.optimize import brentq  # on use: importing scipy.optimize takes ~0.6 s

        ring = np.zeros(self.n_ring)
        for k in np.flatnonzero(f_ext):
            unit = np.zeros(self.n_ring)
            unit[k] = np.sign(f_ext[k]) * self._scale[k]

            def residual(t, unit=unit, k=k):
                return self.value(self._start(t * unit), f_ext)[k]

            hi = 1.0
            while np.sign(residual(hi)) == np.sign(residual(0.0)) and hi < 1e7:
                hi *= 2.0
            if np.sign(residual(hi)) != np.sign(residual(0.0)):
                ring += brentq(residual, 0.0, hi, xtol=1e-12) * unit
        return self._start(ring)

    def _starts(self, f_ext: np.ndarray) -> list[np.ndarray]:
        seated = self.seated(f_ext)
        if self.axial is None or self.play == 0.0 or f_ext[self.axial] != 0.0 \
                or not np.any(np.delete(f_ext, self.axial)):
            return [seated]
        shifted = []
        for side in (1.0, -1.0):
            ring = seated[:self.n_ring].copy()
            ring[self.axial] += side * self.play
            shifted.append(self._start(ring))
        return [seated, *shifted]

    def _from_starts(self, f_ext: np.ndarray) -> np.ndarray | None:
        for start in self._starts(f_ext):
            v = self.iterate(f_ext, start)
            if self.converged(v, f_ext):
                return v
        return None

    # ------------------------------------------------------------------ solve
    def solve(self, f_ext: Sequence[float], guess: np.ndarray | None = None) -> np.ndarray:
        """The unknowns at equilibrium under the external ring load ``f_ext``.

        Raises
        ------
        SimulationError
            If no equilibrium is found, naming the load reached on the load path.

        Parameters
        ----------
        f_ext : sequence of float
            External ring load [N, N m].
        guess : numpy.ndarray, optional
            Start for the unknowns [m, rad].

        Returns
        -------
        numpy.ndarray
            The unknowns at equilibrium [m, rad]; exactly 0 where zero balances the load as
            well, to :data:`RESOLUTION` (round-off of the solve is not reported as a value).
        """
        f_ext = np.asarray(f_ext, dtype=float)
        return self._resolved(self._equilibrium(f_ext, guess), f_ext)

    def _equilibrium(self, f_ext: np.ndarray, guess: np.ndarray | None) -> np.ndarray:
        if guess is not None:
            v = self.iterate(f_ext, guess)
            if self.converged(v, f_ext):
                return v
        v = self._from_starts(f_ext)
        if v is not None:
            return v
        v = self._from_starts(0.1 * f_ext)
        if v is None:
            raise SimulationError(f"{self.name}: no equilibrium found for 10 % of the load "
                                  f"{f_ext.tolist()}")
        done, step = 0.1, 0.1
        while done < 1.0:
            trial = min(1.0, done + step)
            v_new = self.iterate(trial * f_ext, v)
            if self.converged(v_new, trial * f_ext):
                v, done, step = v_new, trial, min(2.0 * step, 0.25)
                continue
            step /= 2.0
            if step < 1e-3:
                raise SimulationError(f"{self.name}: no equilibrium found beyond {done:.3g} of "
                                      f"the load {f_ext.tolist()}")
        return v

    def _resolved(self, v: np.ndarray, f_ext: np.ndarray) -> np.ndarray:
        """``v`` with every unknown the equilibrium cannot tell from zero set to zero: one
        whose zero leaves the weighted residual within :data:`RESOLUTION` of the largest
        weighted load (or within the residual ``v`` leaves, if larger). Under a load along x
        alone, the solve's y lands on round-off (the balls' azimuths are rounded), e.g.
        -2e-18 m where 1e-18 m moves the residual by 1e-10 N."""
        def worst(u):
            return float(np.max(np.abs(self.value(u, f_ext) * self._weight)))

        allowed = max(worst(v), RESOLUTION * self._force_scale(f_ext))
        out = v.copy()
        for k in np.flatnonzero(out):
            trial = out.copy()
            trial[k] = 0.0
            if worst(trial) <= allowed:
                out = trial
        return out
