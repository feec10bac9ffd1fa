"""Orders of the unknowns for sparse LU factorizations: minimum degree on the Jacobian's
pattern, so that each ball's unknowns are eliminated before the ring and cage unknowns every
ball couples to and the factors keep the Jacobian's sparsity.

Used by CVODES with the sparse LU (:mod:`~bearingsim.simulation.sundials`); with the pattern
of the Newton matrix in that order (:func:`newton_pattern`) by the sparse LU ``c/bsm_lu.c`` of
the compiled BDF integrator (:mod:`~bearingsim.simulation.compiled_bdf`) and of the FMU's
co-simulation stepper (:mod:`bearingsim.fmu.model_c`).

The order is SuperLU's (scipy.sparse.linalg), and importing scipy.sparse costs a process
0.35-0.5 s, more than a short run of a cached model or a sweep point. So the order of a
compiled kernel's Jacobian is kept beside its library (:func:`kept_order`, the companion file
``<library>.order``, removed with it): a later process, a sweep worker among them, reads it
instead.
"""

from __future__ import annotations

import contextlib
import hashlib
from dataclasses import dataclass
from pathlib import Path

import casadi as ca
import numpy as np

from bearingsim.files import FileAccessError, atomic_path

__all__ = ["ORDER_SUFFIX", "NewtonPattern", "fill_reducing_order", "kept_order",
           "newton_pattern"]

ORDER_SUFFIX = ".order"
"""Suffix of the companion file of a kernel library that keeps its Jacobian's order."""
_DIGEST_BYTES = 16


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


def _digest(pattern: ca.Sparsity) -> bytes:
    """A digest of the pattern (its size and compressed columns)."""
    parts = (np.array([pattern.size1(), pattern.size2()], dtype=np.int64),
             np.asarray(pattern.colind(), dtype=np.int64),
             np.asarray(pattern.row(), dtype=np.int64))
    return hashlib.blake2b(b"".join(a.tobytes() for a in parts),
                           digest_size=_DIGEST_BYTES).digest()


def kept_order(pattern: ca.Sparsity, library: Path | None) -> np.ndarray:
    """:func:`fill_reducing_order` of ``pattern``, kept in the companion file
    ``<library>.order`` of a compiled kernel: read from it when it holds the order of this
    pattern (a digest of the pattern, then the order as int32), else computed and written
    there (atomically; a cache that cannot be written is only not kept). A file of another
    pattern, of the wrong size or not a permutation is never used, but replaced.

    Parameters
    ----------
    pattern : casadi.Sparsity
        Structural non-zeros of ``A`` (``n x n``).
    library : Path or None
        The kernel library the pattern belongs to (None: computed, not kept).

    Returns
    -------
    ndarray of int
        ``order``: the permuted matrix is ``A[order][:, order]``.
    """
    if library is None:
        return fill_reducing_order(pattern)
    path = Path(library).with_name(Path(library).name + ORDER_SUFFIX)
    n, digest = pattern.size1(), _digest(pattern)
    try:
        data = path.read_bytes()
    except OSError:
        data = b""
    if len(data) == _DIGEST_BYTES + 4 * n and data[:_DIGEST_BYTES] == digest:
        order = np.frombuffer(data, dtype=np.int32, offset=_DIGEST_BYTES).astype(np.int64)
        if np.array_equal(np.sort(order), np.arange(n)):
            return order
    order = fill_reducing_order(pattern)
    with contextlib.suppress(FileAccessError):
        with atomic_path(path) as tmp:
            tmp.write_bytes(digest + order.astype(np.int32).tobytes())
    return order


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
