"""Where bearingsim keeps what it can rebuild: ``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``.

One root for every cache: assembled systems (``systems/``, :mod:`bearingsim.assembler.cache`),
compiled kernel libraries (:func:`bearingsim.simulation.compile.default_cache_dir`), the names
of the kernel libraries of loaded systems (``kernel_names/``,
:mod:`bearingsim.simulation.kernel_names`) and the parsed unit definitions of the units library
(``pint/``, :mod:`bearingsim.units.registry`).
``bearingsim cache clear`` empties it; everything in it is rebuilt on demand.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["KERNEL_NAMES", "cache_root"]

KERNEL_NAMES = "kernel_names"
"""The folder of the remembered kernel library names in the cache root."""


def cache_root() -> Path:
    """``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``: the root of every cache of bearingsim.

    Returns
    -------
    Path
        The cache root folder (not created here).
    """
    root = os.environ.get("BEARINGSIM_CACHE") or Path.home() / ".cache" / "bearingsim"
    return Path(root)
