"""The size budget of the cache: the least recently used entries go when it is exceeded.

Everything in the cache (:mod:`bearingsim.cache_paths`) can be rebuilt, but a cache that only
grows fills the disk: every edit or upgrade of bearingsim starts a new set of assembled
systems (the code version is part of their key) and the old set is never read again, every
bearing size or row count a sweep visits is another structure, and a nested ball-level
model's entry takes ~20 MB. So the cache keeps to a budget, as ccache does:

* using an entry (a system loaded, a compiled library found) marks it used now (its
  modification time, :func:`mark_used`);
* storing one (a system assembled, a library compiled) removes the least recently used
  entries, systems and libraries alike, until the cache holds at most :data:`REFILL` of the
  budget (:func:`keep_to_budget`), so that the next stores do not each scan and remove again.
  The entry just stored is kept, even when it alone exceeds the budget; unfinished builds,
  the remembered library names and the units library's definitions are not counted.

The budget is ``$BEARINGSIM_CACHE_SIZE``, a size with its unit (``"2 GiB"``, ``"500 MB"``;
default :data:`DEFAULT_BUDGET`), read by :func:`budget_bytes` before anything is built, so
that a value that is not a size stops the run before the work it would cost. An entry
removed while another process uses it is harmless: a loaded library stays mapped, a system
read stays in memory, and the next look-up builds it again.
"""

from __future__ import annotations

import contextlib
import math
import os
from dataclasses import dataclass
from pathlib import Path

from bearingsim.cache_paths import entry_name, library_files, system_files
from bearingsim.errors import ParameterError

__all__ = ["BUDGET_VARIABLE", "DEFAULT_BUDGET", "REFILL", "budget_bytes", "keep_to_budget",
           "mark_used"]

BUDGET_VARIABLE = "BEARINGSIM_CACHE_SIZE"
"""The environment variable of the budget."""
DEFAULT_BUDGET = ("2 GiB", 2.0 * 1024**3)
"""The budget when :data:`BUDGET_VARIABLE` is not set: as written, and in bytes."""
REFILL = 0.9
"""After removing, the cache holds at most this fraction of the budget."""


def budget_bytes() -> float:
    """The cache's budget [bytes]: ``$BEARINGSIM_CACHE_SIZE`` or :data:`DEFAULT_BUDGET`.

    Returns
    -------
    float
        The budget [bytes], > 0 and finite.

    Raises
    ------
    ParameterError
        When the variable is not a size with its unit, greater than 0 B and finite.
    """
    text = os.environ.get(BUDGET_VARIABLE, "").strip()
    if not text:
        return DEFAULT_BUDGET[1]
    from bearingsim.units.registry import quantity_to_si

    try:
        size = quantity_to_si(text, "B", BUDGET_VARIABLE)
    except Exception:  # noqa: BLE001 - every unreadable value gets the same advice
        size = math.nan
    if not (math.isfinite(size) and size > 0):
        raise ParameterError(
            f"{BUDGET_VARIABLE}={text[:40]!r} is not a cache size: give a size in bytes with "
            f"its unit, greater than 0 B (e.g. '2 GiB', '500 MB'), or unset it for "
            f"{DEFAULT_BUDGET[0]}")
    return size


def mark_used(path: Path) -> bool:
    """Whether the cache entry ``path`` exists; if it does, mark it used now (its modification
    time), so that it is among the last to go.

    Parameters
    ----------
    path : Path
        A cached system or library.

    Returns
    -------
    bool
        True when ``path`` exists.
    """
    try:
        os.utime(path)
    except FileNotFoundError:
        return False
    except OSError:  # a read-only cache: used, but not marked
        return path.exists()
    return True


@dataclass(frozen=True)
class _Entry:
    files: tuple[Path, ...]
    used: float
    """Last use: the latest modification time of its files [s since the epoch]."""
    size: int
    """Bytes of its files."""


def _owner(path: Path) -> Path:
    """The entry a file belongs to: a library with its companions (``x.so``, ``x.so.balls``,
    ``x.so.order``) is one entry, a system file its own."""
    return path.with_name(entry_name(path.name))


def _entries(root: Path) -> list[_Entry]:
    """The systems and libraries in the cache ``root`` (no unfinished builds)."""
    groups: dict[Path, list[Path]] = {}
    for p in [*system_files(root), *library_files(root)]:
        if not p.name.startswith(".build_"):
            groups.setdefault(_owner(p), []).append(p)
    entries = []
    for files in groups.values():
        stats = []
        for p in files:
            with contextlib.suppress(OSError):  # removed meanwhile by another process
                stats.append(p.stat())
        if stats:
            entries.append(_Entry(tuple(files), max(s.st_mtime for s in stats),
                                  sum(s.st_size for s in stats)))
    return entries


def keep_to_budget(root: Path, stored: Path, budget: float) -> list[Path]:
    """After ``stored`` was written into the cache ``root``: when the cache's systems and
    libraries exceed ``budget``, remove the least recently used until they hold at most
    :data:`REFILL` of it (``stored`` and its companions kept).

    Parameters
    ----------
    root : Path
        The cache folder (libraries in it, systems in its ``systems`` folder).
    stored : Path
        The entry just written.
    budget : float
        The budget [bytes] (:func:`budget_bytes`).

    Returns
    -------
    list of Path
        The files removed, least recently used first.
    """
    entries = _entries(root)
    total = sum(e.size for e in entries)
    if total <= budget:
        return []
    kept = _owner(stored)
    removed = []
    for entry in sorted(entries, key=lambda e: e.used):
        if total <= REFILL * budget:
            break
        if _owner(entry.files[0]) == kept:
            continue
        for p in entry.files:
            with contextlib.suppress(FileNotFoundError):
                p.unlink()
                removed.append(p)
        total -= entry.size
    return removed
