"""Orders of the unknowns for sparse LU factorizations: minimum degree on the Jacobian's
pattern, so that each ball's unknowns are eliminated before the ring and cage unknowns every
ball couples to and the factors keep the Jacobian's sparsity.

Used by CVODES with the sparse LU (:mod:`~bearingsim.simulation.sundials`); with the pattern
of the Newton matrix in that order (:func:`newton_pattern`) by the sparse LU ``c/bsm_lu.c`` of
the compiled BDF integrator (:mod:`~bearingsim.simulation.compiled_bdf`) and of the FMU's
co-simulation stepper (:mod:`bearingsim.fmu.model_c`).
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

__all__ = ["NewtonPattern", "fill_reducing_order", "newton_pattern"]


def fill_reducing_order(pattern: ca.Sparsity) -> np.ndarray:
    """A minimum-degree order of the unknowns of a square sparse matrix: SuperLU's multiple
    minimum degree on the pattern of ``A^T + A`` (scipy), for a sparse LU without fill-in
    beyond what the coupling forces.

    Parameters
    ----------
    pattern : casadi.Sparsity
        Structural non-zeros of ``A`` (``n x n``).

    Returns
    -------
    ndarray of int
        ``order``: the permuted matrix is ``A[order][:, order]``.
    """
    import scipy.sparse as sparse  # on use: scipy.sparse.linalg imports scipy.linalg
    from scipy.sparse.linalg import splu

    n = pattern.size1()
    rows, cols = pattern.get_triplet()
    # ones off the diagonal, n on it: diagonally dominant, so SuperLU keeps the diagonal
    # pivots and its column order is the minimum-degree order itself
    a = (sparse.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
         + n * sparse.identity(n, format="csc"))
    lu = splu(a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    return np.argsort(lu.perm_c)


@dataclass(frozen=True)
class NewtonPattern:
    """The pattern of a Newton matrix ``I - c J`` in a fill-reducing order, as the sparse LU
    of ``c/bsm_lu.c`` takes it: row and column ``i`` are unknown ``order[i]``.

    Attributes
    ----------
    order : ndarray of int32
        The unknowns in the LU's order (:func:`fill_reducing_order`).
    start, index : ndarray of int32
        Compressed columns of the ordered matrix (``n + 1`` column starts, row per nonzero);
        the pattern of ``J`` and the diagonal.
    jac_slot : ndarray of int32
        For each nonzero of ``J`` (in ``J``'s compressed-column order), its nonzero in the
        ordered matrix.
    diag_slot : ndarray of int32
        For each ``i``, the nonzero of the ordered matrix's diagonal entry ``(i, i)``.
    """

    order: np.ndarray
    start: np.ndarray
    index: np.ndarray
    jac_slot: np.ndarray
    diag_slot: np.ndarray

    def values(self, jacobian_nonzeros: np.ndarray, c: float) -> np.ndarray:
        """The nonzeros of the ordered ``I - c J`` from ``J``'s nonzeros (the same
        arithmetic as the C callers: ``1`` on the diagonal, then ``- c J``).

        Parameters
        ----------
        jacobian_nonzeros : numpy.ndarray
            Nonzeros of the Jacobian J, in its own sparsity's order.
        c : float
            The factor of J [s].

        Returns
        -------
        numpy.ndarray
            Nonzeros of ``I - c J`` in the pattern's order.
        """
        out = np.zeros(self.index.size)
        out[self.diag_slot] = 1.0
        out[self.jac_slot] -= c * np.asarray(jacobian_nonzeros, dtype=float)
        return out


def newton_pattern(pattern: ca.Sparsity, order: np.ndarray | None = None) -> NewtonPattern:
    """The compressed-column pattern of ``I - c J`` with the unknowns in ``order``.

    Parameters
    ----------
    pattern : casadi.Sparsity
        Structural non-zeros of ``J`` (``n x n``).
    order : ndarray of int, optional
        The unknowns' order; default :func:`fill_reducing_order` of ``pattern``.

    Returns
    -------
    NewtonPattern
    """
    n = pattern.size1()
    order = fill_reducing_order(pattern) if order is None else np.asarray(order)
    position = np.empty(n, dtype=np.int64)
    position[order] = np.arange(n)
    rows, cols = (np.asarray(v, dtype=np.int64) for v in pattern.get_triplet())
    jac_keys = position[cols] * n + position[rows]
    diag_keys = np.arange(n, dtype=np.int64) * (n + 1)
    keys = np.unique(np.concatenate([jac_keys, diag_keys]))
    start = np.searchsorted(keys // n, np.arange(n + 1))
    as_int = lambda a: np.ascontiguousarray(a, dtype=np.int32)  # noqa: E731
    return NewtonPattern(as_int(order), as_int(start), as_int(keys % n),
                         as_int(np.searchsorted(keys, jac_keys)),
                         as_int(np.searchsorted(keys, diag_keys)))
