"""Where bearingsim keeps what it can rebuild: ``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``.

One root for every cache: assembled systems (``systems/``, :mod:`bearingsim.assembler.cache`),
compiled kernel libraries (:func:`bearingsim.simulation.compile.default_cache_dir`), the names
of the kernel libraries of loaded systems (``kernel_names/``,
:mod:`bearingsim.simulation.kernel_names`), the modules sweep workers import
(``sweep_preloads/``, :mod:`bearingsim.sweep_preloads`) and the parsed unit definitions of
the units library (``pint/``, :mod:`bearingsim.units.registry`).
``bearingsim cache clear`` empties it; everything in it is rebuilt on demand. The systems and
libraries keep to a size budget, the least recently used going first
(:mod:`bearingsim.cache_budget`).
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["KERNEL_NAMES", "SWEEP_PRELOADS", "SYSTEM_SUFFIX", "cache_root", "entry_name",
           "library_files", "system_files", "systems_dir"]

KERNEL_NAMES = "kernel_names"
"""The folder of the remembered kernel library names in the cache root."""
SWEEP_PRELOADS = "sweep_preloads"
"""The folder of the modules learned for sweep workers (:mod:`bearingsim.sweep_preloads`) in
the cache root."""
SYSTEM_SUFFIX = ".bsys"
"""File suffix of an assembled system's entry (:mod:`bearingsim.assembler.cache`)."""


def cache_root() -> Path:
    """``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``: the root of every cache of bearingsim.

    Returns
    -------
    Path
        The cache root folder (not created here).
    """
    root = os.environ.get("BEARINGSIM_CACHE") or Path.home() / ".cache" / "bearingsim"
    return Path(root)


def systems_dir(root: str | Path | None = None) -> Path:
    """The folder of the assembled systems: ``<root>/systems``.

    Parameters
    ----------
    root : str or os.PathLike, optional
        Cache root (None: :func:`~bearingsim.cache_paths.cache_root`).

    Returns
    -------
    Path
        The systems folder.
    """
    return Path(root if root is not None else cache_root()) / "systems"


def system_files(root: str | Path | None = None) -> list[Path]:
    """The entries of the assembled systems in the cache ``root``, sorted by name.

    Parameters
    ----------
    root : str or os.PathLike, optional
        Cache root (None: :func:`~bearingsim.cache_paths.cache_root`).

    Returns
    -------
    list of Path
        The ``<root>/systems/*.bsys`` files.
    """
    folder = systems_dir(root)
    return sorted(folder.glob(f"*{SYSTEM_SUFFIX}")) if folder.is_dir() else []


def entry_name(file_name: str) -> str:
    """The name of the cache entry a file belongs to: a library's companions
    (``x.so.balls``, ``x.so.order``) and the library (``x.so``) share ``x``; a file without
    ``.so`` in its name is its own entry.

    Parameters
    ----------
    file_name : str
        A file's name in the cache.

    Returns
    -------
    str
        The name before ``.so`` (the whole name without it).
    """
    return file_name.split(".so", 1)[0]


def library_files(root: Path) -> list[Path]:
    """The compiled kernel libraries (``<prefix>_<16 hex>.so`` and their companions) and
    unfinished build folders in ``root``.

    Parameters
    ----------
    root : Path
        The cache folder of the libraries.

    Returns
    -------
    list of Path
        The libraries, their companion files and the build folders.
    """
    if not root.is_dir():
        return []
    out = []
    for p in root.iterdir():
        stem = entry_name(p.name)
        if p.name.startswith(".build_") or (".so" in p.name and len(stem) > 17
                                            and stem[-17] == "_"
                                            and all(c in "0123456789abcdef"
                                                    for c in stem[-16:])):
            out.append(p)
    return out
