"""Low-overhead numeric calls of CasADi functions from Python.

``casadi.Function.buffer`` evaluates into preallocated numpy arrays without argument
conversion: a call costs a few microseconds instead of a few hundred, which is what scipy's
integrators pay per right-hand-side evaluation.
"""

from __future__ import annotations

import casadi as ca
import numpy as np
import scipy.sparse

__all__ = ["BufferedFunction"]


class BufferedFunction:
    """Call a CasADi function of ``(t, x, p)`` with numpy arrays, reusing buffers.

    Parameters
    ----------
    fn : casadi.Function
        Three inputs (scalar t, vector x, vector p), one output.
    """

    def __init__(self, fn: ca.Function):
        self._buf, self._eval = fn.buffer()
        self._t = np.zeros(1)
        self._x = np.zeros(fn.nnz_in(1))
        self._p = np.zeros(fn.nnz_in(2))
        self._out = np.zeros(fn.nnz_out(0))
        for k, arr in enumerate((self._t, self._x, self._p)):
            self._buf.set_arg(k, memoryview(arr))
        self._buf.set_res(0, memoryview(self._out))
        sp = fn.sparsity_out(0)
        self._shape = (sp.size1(), sp.size2())
        self._indices = np.asarray(sp.row(), dtype=np.int32)
        self._indptr = np.asarray(sp.colind(), dtype=np.int32)
        self._dense = sp.is_dense()

    def _run(self, t: float, x, p) -> np.ndarray:
        self._t[0] = t
        self._x[:] = x
        self._p[:] = p
        self._eval()
        return self._out

    def vector(self, t: float, x, p) -> np.ndarray:
        """Dense column output as a new 1-D array."""
        out = self._run(t, x, p)
        if self._dense:
            return out.copy()
        full = np.zeros(self._shape[0])
        full[self._indices] = out
        return full

    def sparse(self, t: float, x, p) -> scipy.sparse.csc_matrix:
        """Matrix output as a new scipy CSC matrix."""
        data = self._run(t, x, p).copy()
        return scipy.sparse.csc_matrix((data, self._indices, self._indptr), shape=self._shape)
