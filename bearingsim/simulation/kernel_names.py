"""The names of the kernel libraries of loaded systems, remembered on disk.

A kernel library whose identity is its generated C source (the mapped ball-level kernels, and
kernels of MX functions) is found by generating that source and hashing it
(:func:`~bearingsim.simulation.compile.library_path`), paid by every new process before its
first run even when the library is on disk (for the nested double-layer bearing: section
"Sweep scaling" of ``docs/benchmarks.md``, the warm load's first kernel look-up). A system
loaded from bytes (:func:`~bearingsim.assembler.cache.loads_system`: the system cache, a
sweep's workers) carries
the SHA-256 of those bytes (``System.content_key``), which determines its functions exactly;
together with the code version (bearingsim's sources, which generate the code, and the
CasADi version), the kernel's form, ball mapping, prefix, compiler and flags it determines the
generated source, so the library's name found once is kept under that key and read back
instead of generating the source again.

An entry is one small file in ``<cache>/kernel_names/`` (written atomically) holding the
library's file name; an entry whose name is malformed or whose library is gone is ignored and
rewritten after the library is found (or built) from its source. ``bearingsim cache clear``
removes the folder.
"""

from __future__ import annotations

import hashlib
import re
from collections.abc import Sequence
from pathlib import Path

from bearingsim.assembler.fingerprint import code_version
from bearingsim.assembler.system import System
from bearingsim.cache_budget import mark_used
from bearingsim.cache_paths import KERNEL_NAMES
from bearingsim.files import atomic_path
from bearingsim.simulation.c_compiler import c_compiler, default_cache_dir

__all__ = ["remember_library", "remembered_library"]

_LIBRARY_NAME = re.compile(r"bsm_(ode|dae)_[0-9a-f]{16}\.so")
"""What a remembered kernel library's file name looks like."""


def _entry(system: System, recipe: Sequence[str], cache_dir: str | Path | None) -> Path | None:
    """The entry file of a kernel request (None: the system was not loaded from bytes)."""
    if system.content_key is None:
        return None
    key = "\n".join([system.content_key, code_version(), c_compiler() or "", *recipe])
    folder = Path(cache_dir) if cache_dir is not None else default_cache_dir()
    return folder / KERNEL_NAMES / hashlib.sha256(key.encode()).hexdigest()[:32]


def remembered_library(system: System, recipe: Sequence[str],
                       cache_dir: str | Path | None) -> Path | None:
    """The kernel library remembered for ``system`` and ``recipe``, if it is on disk.

    Parameters
    ----------
    system : System
        The system the kernel is made of.
    recipe : sequence of str
        Everything else that determines the kernel's source and library: form, ball mapping,
        prefix, flags.
    cache_dir : str or os.PathLike, optional
        The library cache (None: :func:`~bearingsim.simulation.c_compiler.default_cache_dir`).

    Returns
    -------
    pathlib.Path or None
        The library, or None: no entry (or a system not loaded from bytes), a malformed
        entry, or a library no longer on disk.
    """
    entry = _entry(system, recipe, cache_dir)
    try:
        name = entry.read_text(encoding="ascii").strip() if entry is not None else ""
    except (OSError, UnicodeDecodeError):
        return None
    if not _LIBRARY_NAME.fullmatch(name):
        return None
    library = entry.parent.parent / name
    return library if mark_used(library) else None


def remember_library(system: System, recipe: Sequence[str], cache_dir: str | Path | None,
                     library: Path) -> None:
    """Keep the name of ``library``, found from the kernel's source, for the next process
    (nothing for a system not loaded from bytes, or when the cache cannot be written).

    Parameters
    ----------
    system : System
        The system the kernel is made of.
    recipe : sequence of str
        As for :func:`remembered_library`.
    cache_dir : str or os.PathLike, optional
        The library cache.
    library : pathlib.Path
        The library's path (in the cache folder).
    """
    entry = _entry(system, recipe, cache_dir)
    if entry is None or not _LIBRARY_NAME.fullmatch(library.name):
        return
    try:
        entry.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(entry) as tmp:
            tmp.write_text(library.name, encoding="ascii")
    except OSError:
        pass  # a read-only cache only costs the next process the source generation
