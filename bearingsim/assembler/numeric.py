"""Numeric calls of CasADi functions with numpy arrays through reusable buffers.

``casadi.Function.__call__`` converts every numpy argument to ``DM`` and every result back,
which costs 0.1-0.5 ms per call on the assembled systems' functions (more than the function
itself for a small model); a call through ``Function.buffer`` copies numbers into
preallocated arrays and costs about a microsecond plus the function.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Hashable
from typing import TypeVar

import casadi as ca
import numpy as np

from bearingsim.keeps import kept

__all__ = ["Buffered", "buffered"]


class Buffered:
    """A CasADi function called with numpy arrays through one reusable buffer: the inputs are
    copied into preallocated arrays, the outputs come back as dense numpy arrays (structural
    zeros filled in). A call costs about a microsecond plus the function itself, where
    ``fn(*args)`` with conversion to and from ``DM`` costs 0.1-0.5 ms.

    Not thread-safe: make one per thread.

    Parameters
    ----------
    fn : casadi.Function
        A function with dense inputs.
    """

    def __init__(self, fn: ca.Function):
        self.fn = fn
        self._buf, self._eval = fn.buffer()
        self._args = []
        for k in range(fn.n_in()):
            if not fn.sparsity_in(k).is_dense():
                raise ValueError(f"Buffered: input {fn.name_in(k)} of {fn.name()} is sparse")
            arg = np.zeros(fn.nnz_in(k))
            self._buf.set_arg(k, memoryview(arg))
            self._args.append(arg)
        self._outs, self._layout = [], []
        for k in range(fn.n_out()):
            out = np.zeros(fn.nnz_out(k))
            self._buf.set_res(k, memoryview(out))
            self._outs.append(out)
            sp = fn.sparsity_out(k)
            self._layout.append(((sp.size1(), sp.size2()), None if sp.is_dense()
                                 else np.asarray(sp.find(), dtype=np.int64)))

    def __call__(self, *args: np.ndarray | float) -> list[np.ndarray]:
        """Every output of ``fn(*args)`` as a new dense array of the output's shape (inputs
        of the inputs' shapes, column-major as CasADi stores them)."""
        for k, (arg, value) in enumerate(zip(self._args, args, strict=True)):
            if isinstance(value, np.ndarray) and value.ndim > 1:
                value = np.asarray(value, dtype=float).ravel(order="F")
            try:
                arg[:] = value
            except ValueError:
                raise ValueError(f"Buffered: input {self.fn.name_in(k)} of {self.fn.name()} "
                                 f"has shape {np.shape(value)}, expected {arg.size} "
                                 f"numbers") from None
        self._eval()
        if self._buf.ret() != 0:
            raise RuntimeError(f"evaluation of {self.fn.name()} failed (return code "
                               f"{self._buf.ret()})")
        results = []
        for out, (shape, nonzeros) in zip(self._outs, self._layout, strict=True):
            if nonzeros is None:
                results.append(out.reshape(shape, order="F").copy())
            else:
                full = np.zeros(shape[0] * shape[1])
                full[nonzeros] = out
                results.append(full.reshape(shape, order="F"))
        return results


_LOCAL = threading.local()
BUFFERS_PER_THREAD = 256
"""Most buffers a thread keeps (the oldest are dropped first)."""

T = TypeVar("T")


def thread_kept(kind: str, key: Hashable, fn: ca.Function, make: Callable[[], T],
                limit: int) -> T:
    """This thread's evaluator of ``kind`` for ``fn`` under ``key``, made by ``make`` on first
    use; a thread keeps at most ``limit`` of a kind (the oldest are dropped first).

    An entry is only returned for the very ``fn`` it was made for (a key holding ``id(fn)``
    may come back for another function once ``fn`` is gone).

    Parameters
    ----------
    kind : str
        Which evaluators (each kind is kept apart).
    key : hashable
        The evaluator's key within its kind (``id(fn)`` and what else shapes it).
    fn : casadi.Function
        The function it evaluates.
    make : callable
        Makes the evaluator.
    limit : int
        Most evaluators of the kind a thread keeps.

    Returns
    -------
    object
        The thread's evaluator.
    """
    store = _LOCAL.__dict__.setdefault(kind, {})
    found = store.get(key)
    if found is not None and found[0] is not fn:  # the key of a function that is gone
        del store[key]
    return kept(store, key, lambda: (fn, make()), limit)[1]


def buffered(fn: ca.Function) -> Buffered:
    """This thread's :class:`Buffered` of ``fn``, made on first use.

    Parameters
    ----------
    fn : casadi.Function
        The function.

    Returns
    -------
    Buffered
        This thread's buffered evaluator of ``fn``.
    """
    return thread_kept("buffered", id(fn), fn, lambda: Buffered(fn), BUFFERS_PER_THREAD)
