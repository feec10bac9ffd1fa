"""Output files written whole or not at all.

A run interrupted (Ctrl-C, an error) while it writes a CSV, a plot, a summary or an FMU must not
leave a partial file that looks like a result. :func:`atomic_path` gives the writer a temporary
name in the same folder (with the same suffix, so that tools which infer the format from it
still work) and renames it to the final name only when the writer is done.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path

__all__ = ["atomic_path"]


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """A temporary path to write ``path`` to; renamed to ``path`` when the block completes.

    Parameters
    ----------
    path : str or pathlib.Path
        The final file.

    Yields
    ------
    pathlib.Path
        ``.<stem>.<pid>.part<suffix>`` beside ``path``; removed if the block raises (including
        ``KeyboardInterrupt``).
    """
    path = Path(path)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}.part{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
