"""Messages about a failed integration: which states diverged."""

from __future__ import annotations

import numpy as np

from bearingsim.assembler.system import System

__all__ = ["diverged"]


def diverged(system: System, x: np.ndarray, x0: np.ndarray) -> str:
    """The non-finite states of ``x``, or the five that grew most from ``x0``, for messages.

    Parameters
    ----------
    system : System
        The system whose state vector ``x`` is.
    x, x0 : numpy.ndarray
        The state where the integration failed and the start state.

    Returns
    -------
    str
        ``"non-finite: a, b"`` or ``"largest growth: a=1e3, ..."``.
    """
    bad = [n for n, v in zip(system.state_names, x, strict=True) if not np.isfinite(v)]
    if bad:
        return "non-finite: " + ", ".join(bad[:10])
    growth = np.abs(x) / (np.abs(x0) + 1.0)
    order = np.argsort(growth)[::-1][:5]
    return "largest growth: " + ", ".join(
        f"{system.state_names[k]}={x[k]:.3g}" for k in order
    )
