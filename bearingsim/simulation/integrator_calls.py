"""Calls of a built CVODES or IDAS integrator through ``casadi.Function.buffer``.

``Function.__call__`` with keyword arguments converts the start states and parameters to
``DM``, returns a dictionary of seven ``DM`` outputs, and the states are read back from them:
about 0.1 ms per call on the ball-level models, more than a 1 ms run's own Python. A buffer
evaluates the same function into preallocated arrays (the numbers are the same bit for bit):
the inputs are copied into arrays the buffer holds, the outputs written straight into the
arrays the caller hands in, and the counts of the call are the buffer's ``stats()``.

The buffer's memory object lives from call to call, and the counters and timers of the
integrator's oracle functions in it (``n_call_*``, ``t_wall_*``, ``t_proc_*``) add up over
the calls (the keyword call resets them); :meth:`IntegratorCall.stats` reports them per call,
as their increase since the call before.

A buffer holds one of the integrator's memory objects, so it must not be shared between
threads: :meth:`~bearingsim.simulation.sundials_integrators.Built.call` keeps one per thread
with the integrator (and drops it with the integrator).
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

__all__ = ["IntegratorCall"]


class IntegratorCall:
    """One thread's buffered call of an integrator ``(x0, z0, p) -> (xf, zf)``.

    Parameters
    ----------
    integrator : casadi.Function
        From ``casadi.integrator``.
    """

    def __init__(self, integrator: ca.Function):
        self.integrator = integrator
        self._buf, self._eval = integrator.buffer()
        self._inputs = {}
        for name in ("x0", "z0", "p"):
            k = integrator.index_in(name)
            array = np.zeros(integrator.nnz_in(k))
            self._buf.set_arg(k, memoryview(array))
            self._inputs[name] = array
        self._xf = integrator.index_out("xf")
        self._zf = integrator.index_out("zf")
        self._sizes = (integrator.nnz_out(self._xf), integrator.nnz_out(self._zf))
        self._before: dict[str, float] | None = None
        """The summed oracle counters before the last call (None: to be read before the
        next; the memory may come from CasADi's pool with counts of earlier calls)."""
        self._unread = False

    def __call__(self, x0: np.ndarray, p: np.ndarray, z0: np.ndarray | None,
                 xf: np.ndarray, zf: np.ndarray | None) -> None:
        """Integrate from ``x0`` (and ``z0``) with parameters ``p``, writing the states at
        the output times into ``xf`` (and the algebraic states into ``zf``).

        Parameters
        ----------
        x0 : numpy.ndarray
            Start states (the integrator's order).
        p : numpy.ndarray
            The integrator's parameter vector.
        z0 : numpy.ndarray or None
            Algebraic start values (DAE form), else None.
        xf, zf : numpy.ndarray
            One-dimensional, C-contiguous arrays of the integrator's output sizes (states
            at the output times, column after column); ``zf`` None without algebraic states.

        Raises
        ------
        RuntimeError
            As ``Function.__call__`` raises it for a failed integration.
        """
        inputs = self._inputs
        inputs["x0"][:] = x0
        inputs["p"][:] = p
        if z0 is not None:
            inputs["z0"][:] = z0
        self._set_output(self._xf, xf, 0)
        if zf is not None:
            self._set_output(self._zf, zf, 1)
        if self._before is None or self._unread:
            self._before = self._summed_now()
        self._unread = True
        try:
            self._eval()
        except BaseException:
            self._before = None
            raise

    def _set_output(self, index: int, array: np.ndarray, which: int) -> None:
        if array.size != self._sizes[which] or not array.flags.c_contiguous:
            raise ValueError(f"IntegratorCall: output {index} needs {self._sizes[which]} "
                             f"contiguous numbers, got shape {array.shape}")
        self._buf.set_res(index, memoryview(array))

    def _summed_now(self) -> dict[str, float]:
        """The summed counters in the memory now (none before its first evaluation)."""
        try:
            return _summed(self._buf.stats())
        except RuntimeError:  # "No stats available": a memory not yet evaluated
            return {}

    def stats(self) -> dict[str, Any]:
        """The counts and timers of the last call (``Function.stats`` of the buffer's
        memory, the oracle's counters and timers as their increase over the call).

        Returns
        -------
        dict
            CasADi's statistics of the call.
        """
        stats = self._buf.stats()
        summed = _summed(stats)
        before = self._before or {}
        for name, total in summed.items():
            stats[name] = total - before.get(name, 0)
        self._before, self._unread = summed, False
        return stats


_SUMMED = ("n_call_", "t_wall_", "t_proc_")
"""Prefixes of the statistics that add up over the calls of one memory object."""


def _summed(stats: dict[str, Any]) -> dict[str, float]:
    """The entries of ``stats`` that add up over the calls."""
    return {name: value for name, value in stats.items() if name.startswith(_SUMMED)}

