"""The sparse LU of the compiled integrators (``c/bsm_lu.c``) called from Python, to check
it against scipy and to measure its cost (``bench/sundials_compiled.py``).

The compiled BDF integrator (:mod:`~bearingsim.simulation.compiled_bdf`) and the FMU's
stepper call the same C directly; this module compiles it alone into a small library
(cached like the kernels) and holds the factors of one matrix pattern.
"""

from __future__ import annotations

import ctypes
import time
from functools import cache
from pathlib import Path

import numpy as np

from bearingsim.simulation.compile import source_library

__all__ = ["SparseLu"]

C_DIR = Path(__file__).with_name("c")
FLAGS = ("-O3", f"-I{C_DIR}")
"""As the compiled BDF integrator's library."""


class _BsmLu(ctypes.Structure):
    """``BsmLu`` of ``c/bsm_lu.h``."""

    _fields_ = [("n", ctypes.c_int), ("keep_order", ctypes.c_int), ("a_start", ctypes.c_void_p),
                ("a_index", ctypes.c_void_p), ("pivoted", ctypes.c_int),
                ("pivotings", ctypes.c_long),
                *[(name, ctypes.c_void_p) for name in (
                    "row_of", "step_of", "l_start", "l_index", "l_val", "u_start", "u_index",
                    "u_pos", "u_val", "ur_start", "ur_index", "ur_val", "inv_diag", "x",
                    "work")]]


@cache
def _library(cache_dir: str | None) -> ctypes.CDLL:
    units = [(C_DIR / name).read_text() for name in ("bsm_lu.c", "bsm_lu_timing.c")]
    lib = source_library(units, headers=[(C_DIR / "bsm_lu.h").read_text()], flags=FLAGS,
                         cache_dir=cache_dir, prefix="bsm_lu")
    dll = ctypes.CDLL(str(lib))
    v, i = ctypes.c_void_p, ctypes.c_int
    dll.bsm_lu_factor.argtypes = [ctypes.POINTER(_BsmLu), v]
    dll.bsm_lu_factor.restype = i
    dll.bsm_lu_solve.argtypes = [ctypes.POINTER(_BsmLu), v, v, v]
    dll.bsm_lu_factor_repeat.argtypes = [ctypes.POINTER(_BsmLu), v, i]
    dll.bsm_lu_solve_repeat.argtypes = [ctypes.POINTER(_BsmLu), v, v, v, v, i, i]
    return dll


class SparseLu:
    """LU factors ``P A = L U`` of matrices on one compressed-column pattern.

    Parameters
    ----------
    start, index : array_like of int
        The pattern of ``A`` (``n x n``): column starts (``n + 1``) and the rows of each
        column's nonzeros (distinct, the diagonal included).
    keep_order : bool
        Keep the pivot order while every pivot is at least ``BSM_LU_TOL`` times the largest
        candidate of its column (the compiled BDF integrator's choice); otherwise only while
        the pivoting rule would choose it, so that the factors depend on the matrix only
        (the FMU stepper's).
    cache_dir : path, optional
        Library cache (default: the kernels').

    Raises
    ------
    CompileError
        If no C compiler is found.
    """

    def __init__(self, start, index, keep_order: bool = False,
                 cache_dir: str | Path | None = None):
        self.start = np.ascontiguousarray(start, dtype=np.int32)
        self.index = np.ascontiguousarray(index, dtype=np.int32)
        n = self.n = self.start.size - 1
        if self.start[-1] != self.index.size:
            raise ValueError(f"SparseLu: start[-1] = {self.start[-1]} is not the number of "
                             f"row indices {self.index.size}")
        self._dll = _library(None if cache_dir is None else str(cache_dir))
        half = max(n * (n - 1) // 2, 1)
        ints = lambda size: np.zeros(size, dtype=np.int32)  # noqa: E731
        self._arrays = {"row_of": ints(n), "step_of": ints(n), "l_start": ints(n + 1),
                        "l_index": ints(half), "l_val": np.zeros(half),
                        "u_start": ints(n + 1), "u_index": ints(half), "u_pos": ints(half),
                        "u_val": np.zeros(half), "ur_start": ints(n + 1),
                        "ur_index": ints(half), "ur_val": np.zeros(half),
                        "inv_diag": np.zeros(n), "x": np.zeros(n), "work": ints(3 * n)}
        self._c = _BsmLu(n, int(keep_order), self.start.ctypes.data, self.index.ctypes.data, 0, 0,
                         *[a.ctypes.data for a in self._arrays.values()])
        self._work = np.zeros(n)
        self._identity = np.arange(n, dtype=np.int32)

    def factor(self, values: np.ndarray, fresh: bool = False) -> int:
        """Factorise the matrix with nonzeros ``values`` (in the pattern's order); with
        ``fresh``, with a new pivot order and pattern whatever the last ones.

        Parameters
        ----------
        values : numpy.ndarray
            Nonzeros of the matrix, in the pattern's order.
        fresh : bool
            Find a new pivot order and fill pattern.

        Returns
        -------
        int
            0, or ``1 +`` the elimination step at which the matrix is singular.
        """
        values = np.ascontiguousarray(values, dtype=float)
        if values.size != self.index.size:
            raise ValueError(f"SparseLu.factor: {values.size} values for a pattern of "
                             f"{self.index.size} nonzeros")
        if fresh:
            self._c.pivoted = 0
        return self._dll.bsm_lu_factor(ctypes.byref(self._c), values.ctypes.data)

    def solve(self, b: np.ndarray) -> np.ndarray:
        """``A^-1 b`` with the last factors.

        Parameters
        ----------
        b : numpy.ndarray
            Right-hand side (n,).

        Returns
        -------
        numpy.ndarray
            The solution ``x`` of ``A x = b``.
        """
        x = np.array(b, dtype=float)
        self._dll.bsm_lu_solve(ctypes.byref(self._c), self._identity.ctypes.data,
                               self._work.ctypes.data, x.ctypes.data)
        return x

    def time_calls(self, values: np.ndarray, b: np.ndarray, repeats: int = 2000,
                   loops: int = 7) -> tuple[float, float]:
        """CPU time of one factorisation in the kept pivot order and of one solve [s], each
        repeated inside C (``c/bsm_lu_timing.c``: without the caller's share; the solve's
        copy of ``b`` before each solve measured alone and taken out), the least of ``loops``
        loops of ``repeats`` calls.

        Parameters
        ----------
        values : numpy.ndarray
            Nonzeros of the matrix, in the pattern's order (factorised once first).
        b : numpy.ndarray
            Right-hand side (n,).
        repeats, loops : int
            Calls per loop and loops.

        Returns
        -------
        tuple of float
            ``(factor, solve)`` [s].
        """
        values = np.ascontiguousarray(values, dtype=float)
        b = np.ascontiguousarray(b, dtype=float)
        x = np.empty_like(b)
        self.factor(values)
        dll, c = self._dll, ctypes.byref(self._c)
        pointers = [a.ctypes.data for a in (self._identity, self._work, b, x)]

        def least(call) -> float:
            times = []
            for _ in range(loops):
                start = time.thread_time()
                call()
                times.append((time.thread_time() - start) / repeats)
            return min(times)

        factor = least(lambda: dll.bsm_lu_factor_repeat(c, values.ctypes.data, repeats))
        solve = least(lambda: dll.bsm_lu_solve_repeat(c, *pointers, repeats, 1))
        copy = least(lambda: dll.bsm_lu_solve_repeat(c, *pointers, repeats, 0))
        return factor, max(solve - copy, 0.0)

    @property
    def pivotings(self) -> int:
        """Factorisations with a new pivot order and pattern so far.

        Returns
        -------
        int
            The count.
        """
        return int(self._c.pivotings)

    @property
    def row_of(self) -> np.ndarray:
        """The row of ``A`` pivoted at each elimination step.

        Returns
        -------
        numpy.ndarray
            Row index per step.
        """
        return self._arrays["row_of"].copy()

    @property
    def nnz(self) -> tuple[int, int]:
        """Nonzeros of ``L`` and ``U`` off their diagonals.

        Returns
        -------
        tuple of int
            Nonzeros of L and of U.
        """
        return int(self._arrays["l_start"][-1]), int(self._arrays["u_start"][-1])
