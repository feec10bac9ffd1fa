"""The modules a scene's sweep workers import at their first point, learned and preloaded.

The fork server of a sweep's LocalCluster (:mod:`bearingsim.sweep_server`) imports
dask.distributed and the sweep worker before it forks the workers; what a point needs beyond
that is imported by each worker at its first point: scipy.linalg and scipy.optimize for a modes
or statics point, scipy.integrate for LSODA, about 0.5-1 s of CPU in every worker (a modes
sweep's first point took 1.2-1.4 s on a worker against 0.06 s for the next). Those modules
depend on the scene (its analysis, integrator and model), which is read only after the server
has started (the server imports while the client reads the scene). So each worker reports the
modules it imported beyond the server's (:func:`imported_since`, with its first chunk),
the client keeps them under the scene file's path when the sweep ends
(:func:`remember_preloads`), and the next sweep of that scene has the server import them once,
before the workers fork (:func:`learned_preloads`): the workers start with them, and their
first point costs what the others do.

A record is one small text file in ``<cache>/sweep_preloads/`` (written atomically): module
names, one a line, the union over the scene's sweeps. A stale name costs the server one import
a sweep (a module that no longer exists is skipped by the server); a record that cannot be read
preloads nothing. ``bearingsim cache clear`` removes the folder.
"""

from __future__ import annotations

import hashlib
import os
import re
import sys
from collections.abc import Iterable
from pathlib import Path

from bearingsim.cache_paths import SWEEP_PRELOADS, cache_root
from bearingsim.files import atomic_path

__all__ = ["BUILTIN_SCENES", "MAX_PRELOADS", "imported_since", "learned_preloads",
           "remember_preloads", "scene_file"]

BUILTIN_SCENES = Path(__file__).resolve().parent / "scenes" / "library"
"""Folder of the built-in scene files (:data:`bearingsim.scenes.library.FOLDER`, named here
without importing the scenes package)."""
MAX_PRELOADS = 200
"""Most module names a record keeps."""

_MODULE = re.compile(r"[A-Za-z][A-Za-z0-9_]*(\.[A-Za-z][A-Za-z0-9_]*)?")
"""A module kept in a record: a package or module and at most one level below it, no private
part (importing ``scipy.optimize`` imports its private modules)."""


def scene_file(scene: str | os.PathLike | None) -> Path | None:
    """The file :func:`~bearingsim.scenes.scene.load_scene` reads for ``scene`` (a path, else
    the name of a built-in scene, with or without ``.toml``), resolved; None if neither exists.

    Parameters
    ----------
    scene : str or os.PathLike or None
        As ``load_scene`` takes it, or a scene's ``path`` (None: a scene made without a file).

    Returns
    -------
    Path or None
        The scene file.
    """
    if scene is None:
        return None
    path = Path(scene)
    if not path.is_file():  # as load_scene: a folder is no scene file
        name = str(scene)
        path = BUILTIN_SCENES / (name if name.endswith(".toml") else f"{name}.toml")
    return path.resolve() if path.is_file() else None


def _record(scene: Path) -> Path:
    """The record of the scene file ``scene``."""
    digest = hashlib.sha256(str(scene).encode()).hexdigest()[:32]
    return cache_root() / SWEEP_PRELOADS / digest


def learned_preloads(scene: Path | None) -> tuple[str, ...]:
    """The modules the workers of the scene file ``scene`` imported in its earlier sweeps.

    Parameters
    ----------
    scene : Path or None
        The resolved scene file (:func:`scene_file`; None: none).

    Returns
    -------
    tuple of str
        Module names (empty: no record, or one that cannot be read).
    """
    if scene is None:
        return ()
    try:
        lines = _record(scene).read_text(encoding="ascii").split()
    except (OSError, UnicodeDecodeError):
        return ()
    return tuple(name for name in lines[:MAX_PRELOADS] if _MODULE.fullmatch(name))


def remember_preloads(scene: Path | None, modules: Iterable[str]) -> None:
    """Add ``modules`` to the record of the scene file ``scene`` (nothing for None, for no new
    module, or when the cache cannot be written).

    Parameters
    ----------
    scene : Path or None
        The resolved scene file (:func:`scene_file`).
    modules : iterable of str
        Module names the workers imported (names that are not kept are left out).
    """
    if scene is None:
        return
    known = learned_preloads(scene)
    new = sorted({m for m in modules if _MODULE.fullmatch(m)} - set(known))
    if not new:
        return
    record = _record(scene)
    try:
        record.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(record) as tmp:
            tmp.write_text("\n".join([*known, *new][:MAX_PRELOADS]) + "\n", encoding="ascii")
    except OSError:
        pass  # a read-only cache: the workers import on first use, as without a record


def imported_since(baseline: frozenset[str]) -> list[str]:
    """The modules of this process that are not in ``baseline``, as a record keeps them (a
    package and at most one level below it, no private part), sorted.

    Parameters
    ----------
    baseline : frozenset of str
        Module names (``sys.modules`` at some earlier time).

    Returns
    -------
    list of str
        Module names.
    """
    return sorted(m for m in set(sys.modules) - baseline if _MODULE.fullmatch(m))
