"""Low-overhead numeric calls of CasADi functions from Python.

``casadi.Function.buffer`` evaluates into preallocated numpy arrays without argument
conversion: a call costs a few microseconds instead of a few hundred, which is what scipy's
integrators pay per right-hand-side evaluation. :func:`mapped_function` keeps the
``Function.map(n)`` of the functions evaluated at every output time (a new map costs about
0.1 ms, more than the mapped call of a short run); :class:`ColumnsCall` calls one with its
inputs copied column-major into the buffer and a parameter vector repeated there, without the
generic argument handling of :func:`evaluate`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import casadi as ca
import numpy as np

from bearingsim.assembler.numeric import buffered, thread_kept

if TYPE_CHECKING:
    import scipy.sparse

__all__ = ["BufferedFunction", "ColumnsCall", "buffered_function", "columns_call", "evaluate",
           "mapped_function"]

_MAPPED: dict[tuple[int, int], tuple[ca.Function, ca.Function]] = {}
"""``fn.map(n)`` by ``(id(fn), n)``, with ``fn`` kept so that its id stays unique."""
MAPPED_LIMIT = 256
"""Most mapped functions kept (the oldest are forgotten first)."""


def mapped_function(fn: ca.Function, n: int) -> ca.Function:
    """``fn.map(n)`` (``n`` evaluations in one call), built once per function and ``n``.

    Parameters
    ----------
    fn : casadi.Function
        The function to map.
    n : int
        Evaluations per call (>= 1).

    Returns
    -------
    casadi.Function
        ``fn.map(n)``: its inputs and outputs have ``n`` columns.
    """
    key = (id(fn), n)
    found = _MAPPED.get(key)
    if found is not None and found[0] is fn:
        return found[1]
    if len(_MAPPED) >= MAPPED_LIMIT:
        del _MAPPED[next(iter(_MAPPED))]
    mapped = fn.map(n)
    _MAPPED[key] = (fn, mapped)
    return mapped


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
        """Dense column output as a new 1-D array.

        Parameters
        ----------
        t : float
            Time [s].
        x : array_like
            State vector.
        p : array_like
            Parameter vector.

        Returns
        -------
        numpy.ndarray
            The output, zeros filled in where it is structurally zero.
        """
        out = self._run(t, x, p)
        if self._dense:
            return out.copy()
        full = np.zeros(self._shape[0])
        full[self._indices] = out
        return full

    def sparse(self, t: float, x, p) -> scipy.sparse.csc_matrix:
        """Matrix output as a new scipy CSC matrix.

        Parameters
        ----------
        t : float
            Time [s].
        x : array_like
            State vector.
        p : array_like
            Parameter vector.

        Returns
        -------
        scipy.sparse.csc_matrix
            The output in its sparsity pattern.
        """
        import scipy.sparse  # on use: a command that needs no sparse matrix imports none

        data = self._run(t, x, p).copy()
        return scipy.sparse.csc_matrix((data, self._indices, self._indptr), shape=self._shape)


BUFFERED_PER_THREAD = 64
"""Most :class:`BufferedFunction` a thread keeps (the oldest are forgotten first)."""


def buffered_function(fn: ca.Function) -> BufferedFunction:
    """This thread's :class:`BufferedFunction` of ``fn``, made on first use (making one costs
    more than a short run's right-hand sides: repeated runs on one closed model reuse it).

    Parameters
    ----------
    fn : casadi.Function
        The function to evaluate.

    Returns
    -------
    BufferedFunction
        The thread's evaluator of ``fn``.
    """
    return thread_kept("buffered_function", id(fn), fn, lambda: BufferedFunction(fn),
                       BUFFERED_PER_THREAD)


def evaluate(fn: ca.Function, *args: np.ndarray | float) -> list[np.ndarray]:
    """``fn(*args)`` through this thread's buffer of ``fn``
    (:func:`~bearingsim.assembler.numeric.buffered`): every output as a dense numpy array of
    its shape.

    Parameters
    ----------
    fn : casadi.Function
        The function to evaluate.
    *args : numpy.ndarray or float
        Its inputs, in order.

    Returns
    -------
    list of numpy.ndarray
        Its outputs, in order.
    """
    return buffered(fn)(*args)


class ColumnsCall:
    """``fn.map(n)`` through one buffer: inputs of ``n`` columns (a vector given once for every
    column where :meth:`__call__` says so), the output as a new dense array.

    Not thread-safe: :func:`columns_call` keeps one per thread.

    Parameters
    ----------
    fn : casadi.Function
        The function evaluated per column (dense inputs).
    n : int
        Columns.
    """

    def __init__(self, fn: ca.Function, n: int):
        self.fn, self.n = fn, n
        mapped = mapped_function(fn, n)
        self._buf, self._eval = mapped.buffer()
        self._inputs = []
        for k in range(mapped.n_in()):
            array = np.zeros(mapped.nnz_in(k))
            self._buf.set_arg(k, memoryview(array))
            self._inputs.append(array.reshape((fn.nnz_in(k), n), order="F"))
        sp = mapped.sparsity_out(0)
        self._out = np.zeros(sp.nnz())
        self._buf.set_res(0, memoryview(self._out))
        self._shape = (fn.size1_out(0), n)
        self._rows = None if sp.is_dense() else np.asarray(sp.find(), dtype=np.int64)

    def __call__(self, *columns: np.ndarray, repeated: int | None = None) -> np.ndarray:
        """The first output for inputs ``columns`` (arrays of ``n`` columns, or for input
        ``repeated`` one vector, the same in every column).

        Parameters
        ----------
        *columns : numpy.ndarray
            The inputs, in order.
        repeated : int, optional
            The position of the input given as one vector for all columns.

        Returns
        -------
        numpy.ndarray
            The output, shape ``(rows, n)`` (C order; structural zeros as 0.0).

        Raises
        ------
        RuntimeError
            When the evaluation fails.
        """
        for k, (array, value) in enumerate(zip(self._inputs, columns, strict=True)):
            array[:] = value[:, None] if k == repeated else value
        self._eval()
        if self._buf.ret() != 0:
            raise RuntimeError(f"evaluation of {self.fn.name()} failed (return code "
                               f"{self._buf.ret()})")
        if self._rows is None:
            return self._out.reshape(self._shape, order="F").copy()
        full = np.zeros(self._shape[0] * self._shape[1])
        full[self._rows] = self._out
        return full.reshape(self._shape, order="F")


def columns_call(fn: ca.Function, n: int) -> ColumnsCall:
    """This thread's :class:`ColumnsCall` of ``fn`` over ``n`` columns, made on first use.

    Parameters
    ----------
    fn : casadi.Function
        The function evaluated per column.
    n : int
        Columns (>= 1).

    Returns
    -------
    ColumnsCall
        The thread's call.
    """
    return thread_kept("columns", (id(fn), n), fn, lambda: ColumnsCall(fn, n),
                       BUFFERED_PER_THREAD)
