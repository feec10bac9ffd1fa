"""The SI conversions the units library computed, kept on disk for later processes.

A command needs few conversions: the display units of its outputs, the units of its scene's
quantities. Importing pint to compute them costs every process ~0.25 s
(``python -X importtime -c 'import pint'``), more than a warm run's simulation of most
models. So :func:`~bearingsim.units.registry.base_exponents`, which every conversion goes
through, keeps what pint computed (the base units' exponents, factor and offset of a unit, or
why the unit is refused) in ``<cache root>/pint/conversions.json``; a later process reads them
and imports pint only for a unit it has not seen.

The memo is keyed by pint's version and by the source of :mod:`bearingsim.units.registry`
(which translates the model's unit spellings to pint's): a change of either starts a new memo.
It is written whole and renamed into place after each new unit
(:func:`~bearingsim.files.atomic_write_text`); one that cannot be read, parsed, or is of
another key, is ignored and replaced. ``bearingsim cache clear`` removes it with the parsed
definitions.
"""

from __future__ import annotations

import functools
import hashlib
import importlib
import json
import threading
from importlib import metadata
from pathlib import Path
from typing import Any

from bearingsim.cache_paths import cache_root
from bearingsim.files import atomic_write_text

__all__ = ["FILE", "MAX_UNITS", "ConversionMemo", "memo"]

FILE = "conversions.json"
"""File name of the memo in the units library's cache folder."""
MAX_UNITS = 1000
"""Units kept at most: a run's units are few, and text that is not a unit (a refusal is kept
too) must not grow the memo without bound."""


class ConversionMemo:
    """Units -> what pint computed for them, read from and written to ``path``.

    Parameters
    ----------
    path : Path
        The memo file.
    key : str
        What the entries are valid for (pint's version, the translation's source).
    """

    def __init__(self, path: Path, key: str):
        self.path = path
        self.key = key
        self._lock = threading.Lock()
        self._entries: dict[str, Any] = self._read()

    def _read(self) -> dict[str, Any]:
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
        except (OSError, ValueError):  # none yet, unreadable or not JSON: start anew
            return {}
        if not isinstance(data, dict) or data.get("key") != self.key:
            return {}
        entries = data.get("units")
        return entries if isinstance(entries, dict) else {}

    def get(self, unit: str) -> Any:
        """What was kept for ``unit``.

        Parameters
        ----------
        unit : str
            The unit string as asked for.

        Returns
        -------
        object or None
            The kept JSON value, or None.
        """
        return self._entries.get(unit)

    def put(self, unit: str, value: Any) -> None:
        """Keep ``value`` (JSON) for a new ``unit`` and write the memo (nothing once it holds
        :data:`MAX_UNITS`); a memo that cannot be written (a read-only cache) only stays in
        memory.

        Parameters
        ----------
        unit : str
            The unit string.
        value : object
            JSON-serialisable value.
        """
        with self._lock:
            if unit in self._entries or len(self._entries) >= MAX_UNITS:
                return
            self._entries[unit] = value
            text = json.dumps({"key": self.key, "units": self._entries}, ensure_ascii=False)
            try:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                atomic_write_text(self.path, text)
            except OSError:  # a read-only cache: the memo stays in memory
                pass


@functools.lru_cache(maxsize=1)
def memo() -> ConversionMemo:
    """This process's memo, under the cache root's units folder.

    Returns
    -------
    ConversionMemo
        The memo (read on the first call).
    """
    registry = importlib.import_module("bearingsim.units.registry")  # (its function too)
    source = Path(registry.__file__).read_bytes()
    key = f"pint {metadata.version('pint')}; {hashlib.sha256(source).hexdigest()[:16]}"
    return ConversionMemo(cache_root() / registry.PINT_CACHE / FILE, key)
