"""Bounded keeps of what is made once and reused: the closed models, input signals and input
bounds a system keeps in its ``__dict__``, the evaluators a thread keeps
(:func:`bearingsim.assembler.numeric.thread_kept`)."""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import TypeVar

__all__ = ["kept"]

T = TypeVar("T")


def kept(store: dict, key: Hashable, make: Callable[[], T], limit: int) -> T:
    """``store[key]``, made by ``make`` on first use; ``store`` holds at most ``limit`` entries
    (the oldest are dropped first).

    Parameters
    ----------
    store : dict
        Where the entries are kept (insertion order is their age).
    key : hashable
        The entry's key.
    make : callable
        Makes the entry (not called when it is kept).
    limit : int
        Most entries ``store`` holds (>= 1).

    Returns
    -------
    object
        The kept entry.
    """
    found = store.get(key)
    if found is None:
        if len(store) >= limit:
            del store[next(iter(store))]
        found = store[key] = make()
    return found
