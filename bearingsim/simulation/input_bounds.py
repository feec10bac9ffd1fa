"""The bounds of an input signal's numbers, laid out once per system and signal structure, so
that the numbers of a new run (a sweep's next point) are checked in one vectorised test.

A signal made of constants and tables only is valid when every constant and every table value
is finite, within its input's range and not above its limit (``warn_above``); otherwise the
input-by-input check of :func:`~bearingsim.simulation.input_ranges.check_input_ranges` finds the
value and says what is wrong with it.
"""

from __future__ import annotations

import numpy as np

from bearingsim.assembler.system import System
from bearingsim.keeps import kept

__all__ = ["numbers_valid"]

LAID_OUT_PER_SYSTEM = 64
"""Signal structures whose bounds a system keeps (the oldest dropped first)."""


def numbers_valid(system: System, key: str, q: np.ndarray,
                  lifted: tuple[tuple[int, int], ...]) -> bool:
    """Whether every constant and table value of an input signal is finite, within its
    input's range and not above its limit.

    Parameters
    ----------
    system : System
        The closed system declaring the inputs' ranges and limits.
    key, q, lifted
        The signal's structure key, numbers and their slice per input
        (:class:`~bearingsim.simulation.inputs.InputSignal`; no function of time among them).

    Returns
    -------
    bool
        True when all are; False when one is not (or may not be: the input-by-input check
        decides).
    """
    index, low, high, limit = kept(system.__dict__.setdefault("_number_bounds", {}), key,
                                   lambda: _bounds(system, lifted), LAID_OUT_PER_SYSTEM)
    values = q[index]
    return bool(np.isfinite(values).all() and (values >= low).all() and (values <= high).all()
                and (np.abs(values) <= limit).all())


def _bounds(system: System, lifted: tuple[tuple[int, int], ...]) -> tuple[np.ndarray, ...]:
    """Positions of the checked numbers in a signal's numbers (a constant; a table's values,
    not its times) with the lower and upper bound and the limit of each (infinite where
    none)."""
    index, low, high, limit = [], [], [], []
    for sig, (first, last) in zip(system.inputs, lifted, strict=True):
        values = range(first, last) if last - first == 1 else \
            range(first + (last - first) // 2, last)
        above = getattr(sig, "warn_above", None)
        index.extend(values)
        low.extend([-np.inf if sig.low is None else sig.low] * len(values))
        high.extend([np.inf if sig.high is None else sig.high] * len(values))
        limit.extend([np.inf if above is None else above] * len(values))
    return (np.array(index, dtype=int),
            *(np.array(column, dtype=float) for column in (low, high, limit)))
