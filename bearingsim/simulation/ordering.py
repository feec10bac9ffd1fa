"""Orders of the unknowns for sparse LU factorizations: minimum degree on the Jacobian's
pattern, so that each ball's unknowns are eliminated before the ring and cage unknowns every
ball couples to and the factors keep the Jacobian's sparsity.

Used by CVODES with the sparse LU (:mod:`~bearingsim.simulation.sundials`) and by the FMU's
co-simulation stepper (:mod:`bearingsim.fmu.model_c`, ``bsm_lu_order``).
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import scipy.sparse as sparse
from scipy.sparse.linalg import splu

__all__ = ["fill_reducing_order"]


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
    n = pattern.size1()
    rows, cols = pattern.get_triplet()
    # ones off the diagonal, n on it: diagonally dominant, so SuperLU keeps the diagonal
    # pivots and its column order is the minimum-degree order itself
    a = (sparse.csc_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
         + n * sparse.identity(n, format="csc"))
    lu = splu(a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    return np.argsort(lu.perm_c)
