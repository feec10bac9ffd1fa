"""Natural frequencies and mode shapes of a rigid shaft on its bearings (5 degrees of freedom:
x, y, z and the tilts tx, ty): ``K phi = w^2 M phi`` solved by :func:`scipy.linalg.eigh` on the
symmetric part of K, the modes named after their dominant degree of freedom, repeated
frequencies' modes rotated onto the axes, and modal damping from a loss factor ``eta``: hysteretic
damping ``C = (eta / w) K`` at each mode's frequency, i.e. the modal damping ratio
``zeta = eta / 2`` (Harris & Piersol, *Shock and Vibration Handbook*, chapter "Material
damping").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from bearingsim.errors import BearingsimError, ParameterError
from bearingsim.validation import check_range, check_vector

__all__ = ["DOFS", "LOSS_FACTOR", "MODE_NAMES", "Modes", "modal_analysis"]

DOFS = ("x", "y", "z", "tx", "ty")
MODE_NAMES = ("radial x", "radial y", "axial", "tilt about x", "tilt about y")
"""Mode names, one per dominant degree of freedom (x, y, z, tx, ty)."""
LOSS_FACTOR = 0.005
"""Loss factor eta of the duplex-pair study (docs/studies.md, section B) [-]."""
_DEGENERATE = 1e-6  # relative gap of eigenvalues treated as one (repeated) frequency


@dataclass
class Modes:
    """Natural frequencies and mode shapes of the shaft on its bearings.

    Attributes
    ----------
    frequencies : ndarray (5,)
        Undamped natural frequencies [Hz], ascending.
    names : list of str
        Name of each mode (:data:`MODE_NAMES`).
    shapes : ndarray (5, 5)
        Columns: mass-normalised mode shapes in (x, y, z, tx, ty).
    damping_ratios : ndarray (5,)
        Modal damping ratios [-].
    damped_frequencies : ndarray (5,)
        ``f sqrt(1 - zeta^2)`` [Hz].
    stiffness, mass : ndarray (5, 5)
        K [N/m, N/rad, N m/rad] and M [kg, kg m^2].
    """

    frequencies: np.ndarray
    names: list[str]
    shapes: np.ndarray
    damping_ratios: np.ndarray
    damped_frequencies: np.ndarray
    stiffness: np.ndarray
    mass: np.ndarray

    def frequency(self, name: str) -> float:
        """Natural frequency of the mode called ``name`` [Hz].

        Parameters
        ----------
        name : str
            A mode name of :data:`MODE_NAMES`.

        Returns
        -------
        float
            Its frequency [Hz].
        """
        if name not in self.names:
            raise ParameterError(f"no mode named {name!r}; modes: {', '.join(self.names)}")
        return float(self.frequencies[self.names.index(name)])

    def by_name(self) -> dict[str, float]:
        """Frequencies [Hz] keyed by mode name, in :data:`MODE_NAMES` order.

        Returns
        -------
        dict of str to float
            Frequency [Hz] by mode name.
        """
        return {n: self.frequency(n) for n in MODE_NAMES}

    def __repr__(self) -> str:
        modes = ", ".join(f"{n} {f:.5g} Hz" for n, f in zip(self.names, self.frequencies,
                                                            strict=True))
        zeta = np.unique(np.round(self.damping_ratios, 12))
        damping = (f"{zeta[0]:.3g} [-]" if zeta.size == 1
                   else ", ".join(f"{z:.3g}" for z in self.damping_ratios) + " [-]")
        return f"<Modes: {modes}; damping ratio {damping}>"

    def damping_matrix(self) -> np.ndarray:
        """Viscous damping matrix of the modal damping ratios, ``M Phi diag(2 zeta w) Phi^T M``.

        Returns
        -------
        numpy.ndarray
            C (5, 5) [N s/m, N m s/rad].
        """
        w = 2.0 * np.pi * self.frequencies
        mp = self.mass @ self.shapes
        return mp @ np.diag(2.0 * self.damping_ratios * w) @ mp.T


def _name_modes(shapes: np.ndarray, mass: np.ndarray) -> list[str]:
    """Assign each mode the degree of freedom that holds most of its kinetic energy."""
    energy = shapes * (mass @ shapes)  # energy[i, k]: share of DOF i in mode k (M diagonal)
    from scipy.optimize import (
        linear_sum_assignment,  # on use: importing scipy.optimize takes ~0.6 s
    )

    rows, cols = linear_sum_assignment(-np.abs(energy.T))
    names = [""] * shapes.shape[1]
    for k, i in zip(rows, cols, strict=True):
        names[k] = MODE_NAMES[i]
    return names


def _align_repeated(w2: np.ndarray, shapes: np.ndarray, mass: np.ndarray) -> np.ndarray:
    """Within each group of repeated eigenvalues, rotate the modes onto the DOF axes."""
    shapes = shapes.copy()
    k = 0
    while k < w2.size:
        end = k + 1
        while end < w2.size and w2[end] - w2[k] <= _DEGENERATE * abs(w2[k]):
            end += 1
        if end - k > 1:
            v = shapes[:, k:end]
            share = np.sum(np.abs(v * (mass @ v)), axis=1)
            axes = np.eye(w2.size)[:, np.sort(np.argsort(share)[-(end - k):])]
            proj = v @ (v.T @ mass @ axes)
            for j in range(end - k):  # mass-orthonormalise (Gram-Schmidt)
                for i in range(j):
                    proj[:, j] -= (proj[:, i] @ mass @ proj[:, j]) * proj[:, i]
                proj[:, j] /= np.sqrt(proj[:, j] @ mass @ proj[:, j])
            shapes[:, k:end] = proj
        k = end
    return shapes


def modal_analysis(stiffness: np.ndarray, mass: np.ndarray,
                   loss_factor: float = LOSS_FACTOR) -> Modes:
    """Natural frequencies, named mode shapes and modal damping from K and M.

    Parameters
    ----------
    stiffness : array (5, 5)
        Stiffness matrix; its symmetric part is used.
    mass : array (5, 5)
        Mass matrix, symmetric positive definite.
    loss_factor : float
        Loss factor eta [-], >= 0; the modal damping ratio is eta / 2.

    Returns
    -------
    Modes

    Raises
    ------
    ParameterError
        For matrices that are not 5 x 5 finite numbers, a mass matrix that is not positive
        definite or a negative loss factor.
    BearingsimError
        If K is not positive definite (a direction without stiffness, e.g. unloaded rows).
    """
    where = "modal_analysis"
    size = len(DOFS)
    stiffness = check_vector(stiffness, size * size, "stiffness", "N/m, N/rad, N m/rad",
                             where).reshape(size, size)
    mass = check_vector(mass, size * size, "mass", "kg, kg m^2", where).reshape(size, size)
    check_range(loss_factor, "loss_factor", "1", 0.0, where=where)
    k_sym = 0.5 * (stiffness + stiffness.T)
    try:
        import scipy.linalg  # on use: with scipy's common base, ~0.25 s of every command

        w2, shapes = scipy.linalg.eigh(k_sym, 0.5 * (mass + mass.T))
    except np.linalg.LinAlgError:
        raise ParameterError(f"{where}: the mass matrix must be symmetric positive definite "
                             f"(masses [kg] and inertias [kg m^2] > 0)") from None
    if w2[0] <= 0.0:
        raise BearingsimError(
            "the stiffness matrix is not positive definite (smallest eigenvalue "
            f"{w2[0]:.3g}): the shaft has a direction without stiffness; are the rows preloaded?"
        )
    shapes = _align_repeated(w2, shapes, mass)
    freqs = np.sqrt(w2) / (2.0 * np.pi)
    zeta = np.full(freqs.size, 0.5 * loss_factor)
    return Modes(freqs, _name_modes(shapes, mass), shapes, zeta, freqs * np.sqrt(1 - zeta**2),
                 np.asarray(stiffness, dtype=float), np.asarray(mass, dtype=float))
