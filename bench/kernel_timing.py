"""Per-call CPU cost of a compiled kernel's functions, the calls repeated in a loop inside C.

A loop of calls from Python (``Function.buffer``, less a trivial function's loop) measures a
5-20 us kernel call to within 30 % on the shared machine: the Python loop costs as much as
the call and its own cost moves between the two loops. Here one ctypes call runs ``repeats``
calls of the kernel's C function through its pointer, as the compiled integrators call it
(``c/bdf.c``: the same arguments, and of the Jacobian only the block d ode / d x it asks
for), so the caller's share is one call in ``repeats``. Many short loops (200 of 50 calls,
1-8 ms each), the least kept: on this shared machine the other jobs slow a call by up to
1.5x for stretches of a second or more, which long loops average in and short ones miss
(five such measurements of the nested bearing's right-hand side: 18.3-18.5 us with 200
loops of 50, 19-27 us with 70 of 200 or 7 of 2000).
"""

from __future__ import annotations

import ctypes
import time
from functools import cache

import numpy as np

from bearingsim.simulation.compile import source_library
from bearingsim.simulation.kernels import Kernel

__all__ = ["kernel_call_us"]

SOURCE = r"""
typedef long long bsm_int;
typedef int (*bsm_fn)(const double **arg, double **res, bsm_int *iw, double *w, int mem);

/* fn(arg, res, iw, w, 0) repeated; the number of calls that failed */
int bsm_kernel_repeat(bsm_fn fn, const double **arg, double **res, bsm_int *iw, double *w,
                      int repeats) {
    int failed = 0;
    for (int k = 0; k < repeats; ++k) failed += fn(arg, res, iw, w, 0) != 0;
    return failed;
}
"""

FLAGS = ("-O2",)


@cache
def _library() -> ctypes.CDLL:
    dll = ctypes.CDLL(str(source_library([SOURCE], flags=FLAGS, prefix="bsm_kernel_timing")))
    p = ctypes.c_void_p
    dll.bsm_kernel_repeat.argtypes = [p, p, p, p, p, ctypes.c_int]
    return dll


def kernel_call_us(kern: Kernel, which: str, args: list, repeats: int = 50,
                   loops: int = 200) -> float:
    """CPU time of one call [us] of the kernel's ``ode`` (``which="rhs"``) or of its
    Jacobian's d ode / d x block (``which="jac"``) at ``args`` = (t, x, u, p), the least of
    ``loops`` loops of ``repeats`` calls inside C (thread CPU time).

    Parameters
    ----------
    kern : Kernel
        A compiled ODE kernel (its library is loaded).
    which : {"rhs", "jac"}
        The function.
    args : list
        ``t, x, u, p`` (numbers or arrays).
    repeats, loops : int
        Calls per loop and loops.

    Returns
    -------
    float
        Microseconds per call.

    Raises
    ------
    ValueError
        If ``which`` is neither, or the kernel reports a failure at ``args``.
    """
    function = kern.function
    fn = {"rhs": function, "jac": function.jacobian()}.get(which)
    if fn is None:
        raise ValueError(f"kernel_call_us: which must be 'rhs' or 'jac', not {which!r}")
    kernel_dll = ctypes.CDLL(str(kern.library))
    address = ctypes.cast(getattr(kernel_dll, fn.name()), ctypes.c_void_p).value
    inputs = [np.ascontiguousarray(np.atleast_1d(np.asarray(a, dtype=float)).ravel())
              for a in args]
    arg = (ctypes.c_void_p * max(int(fn.sz_arg()), 5))()
    res = (ctypes.c_void_p * max(int(fn.sz_res()), 4))()
    for i, a in enumerate(inputs):
        arg[i] = a.ctypes.data
    # the integrator's outputs: ode's xdot; of the Jacobian only d ode / d x (output 1)
    kept = [np.zeros(fn.nnz_out(0 if which == "rhs" else 1) + 1)]
    res[0 if which == "rhs" else 1] = kept[0].ctypes.data
    iw = np.zeros(int(fn.sz_iw()) + 1, dtype=np.int64)
    w = np.zeros(int(fn.sz_w()) + 1)
    dll = _library()
    pointers = (address, ctypes.addressof(arg), ctypes.addressof(res), iw.ctypes.data,
                w.ctypes.data)
    if dll.bsm_kernel_repeat(*pointers, 1):
        raise ValueError(f"kernel_call_us: the kernel's {which} failed at the given arguments")
    times = []
    for _ in range(loops):
        t0 = time.thread_time()
        dll.bsm_kernel_repeat(*pointers, repeats)
        times.append((time.thread_time() - t0) / repeats * 1e6)
    return min(times)
