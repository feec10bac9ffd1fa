"""Files: output written whole or not at all, and input paths kept inside their folder.

A run interrupted (Ctrl-C, an error, SIGKILL) while it writes a CSV, a plot, a summary or an FMU
must not leave a partial file that looks like a result. :func:`atomic_path` gives the writer a
temporary name in the same folder (with the same suffix, so that tools which infer the format
from it still work) and renames it to the final name only when the writer is done; a failing
write (missing or read-only folder, full disk) raises :class:`FileAccessError`, one line naming
the file.

A scene names files relative to its own folder. :func:`confined_path` resolves such a name and
refuses one that leads outside the folder (absolute, ``..``, ``~``, a symbolic link pointing
out) unless the user allowed the target folder; :func:`open_regular` opens an input file only
if it is a regular file (not a FIFO, a device or a socket, which could block or never end).
Messages name the file, never its content.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from collections.abc import Iterator, Sequence
from pathlib import Path

from bearingsim.errors import BearingsimError

__all__ = [
    "FileAccessError",
    "PathOutsideError",
    "atomic_path",
    "atomic_write_text",
    "confined_path",
    "file_path",
    "open_regular",
    "os_reason",
]

PART = ".part"
"""Marker in the name of a file being written (``.<stem>.<pid>.part<suffix>``)."""


class FileAccessError(BearingsimError, OSError):
    """A file cannot be read or written (missing or read-only folder, full disk, not a regular
    file); the message names the file and the reason, never the file's content."""


class PathOutsideError(FileAccessError):
    """A path given in a scene leads outside the scene's folder and the folders the user
    allowed (``--allow-path DIR``, ``allow_paths=[DIR]``)."""


def os_reason(exc: OSError) -> str:
    """The reason of an operating-system error in words, without the path or content.

    Parameters
    ----------
    exc : OSError
        The error.

    Returns
    -------
    str
        Its reason ("permission denied", ...).
    """
    reasons = {errno.ENOENT: "the folder or file does not exist",
               errno.EACCES: "permission denied", errno.EPERM: "permission denied",
               errno.EROFS: "the file system is read-only",
               errno.ENOSPC: "no space left on the device", errno.EDQUOT: "disk quota exceeded",
               errno.EISDIR: "it is a folder", errno.ENOTDIR: "a part of the path is a file",
               errno.EEXIST: "a file of that name is in the way"}
    return reasons.get(exc.errno, exc.strerror or type(exc).__name__)


def file_path(path: str | Path) -> Path:
    """``path`` as a :class:`~pathlib.Path` to write a file to.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    pathlib.Path
        The same path.

    Raises
    ------
    FileAccessError
        When the path names no file (``"."``, ``".."``, ``""``, a root): a folder.
    """
    path = Path(path)
    if path.name in ("", ".", ".."):  # (Path(".").with_name(...) raises ValueError)
        raise FileAccessError(f"cannot write {str(path)!r}: a folder, not a file path")
    return path


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

    Raises
    ------
    FileAccessError
        When the block or the rename fails with an operating-system error (missing or
        read-only folder, full disk), naming ``path`` and the reason, or ``path`` names a
        folder (:func:`file_path`).
    """
    path = file_path(path)
    tmp = path.with_name(f".{path.stem}.{os.getpid()}{PART}{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    except FileAccessError:
        raise
    except OSError as exc:
        raise FileAccessError(f"cannot write {path}: {os_reason(exc)}") from None
    finally:
        with contextlib.suppress(OSError):
            tmp.unlink()


def atomic_write_text(path: str | Path, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically (:func:`atomic_path`).

    Parameters
    ----------
    path : str or Path
        The file.
    text : str
        Its content.

    Returns
    -------
    Path
        The path written.
    """
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def _inside(path: Path, root: Path) -> bool:
    return path == root or root in path.parents


def confined_path(name: str, base: str | Path, allowed: Sequence[str | Path] = (),
                  what: str = "file") -> Path:
    """The real path of ``name`` (as written in a scene), which must lie inside ``base``.

    Parameters
    ----------
    name : str
        A path relative to ``base``; absolute paths and ``..`` only into ``allowed`` folders;
        ``~`` is not expanded.
    base : str or Path
        The scene's folder.
    allowed : sequence of path
        Further folders the user allowed (``--allow-path``).
    what : str
        What the file is, for messages ("table file", "output folder").

    Returns
    -------
    Path
        With every symbolic link resolved (the file need not exist).

    Raises
    ------
    PathOutsideError
        Naming ``name``, ``base`` and how to allow another folder.
    """
    base = Path(os.path.realpath(base))
    roots = [base, *(Path(os.path.realpath(a)) for a in allowed)]
    how = (f"a path inside the scene folder {base}; to use another folder, allow it with "
           f"--allow-path DIR (API: allow_paths=[DIR])")
    if not isinstance(name, str) or not name.strip() or "\x00" in name:
        raise PathOutsideError(f"{what} {name!r} is not a path; expected {how}")
    if name.startswith("~"):
        raise PathOutsideError(f"{what} {name!r}: '~' is not expanded; expected {how}")
    given = Path(name)
    if not allowed and (given.is_absolute() or ".." in given.parts):
        kind = "an absolute path" if given.is_absolute() else "a path with '..'"
        raise PathOutsideError(f"{what} {name!r} is {kind}; expected {how}")
    real = Path(os.path.realpath(base / given))
    if not any(_inside(real, root) for root in roots):
        raise PathOutsideError(f"{what} {name!r} leads to {real}, outside the scene folder"
                               + (" and the allowed folders" if allowed else "")
                               + f"; expected {how}")
    return real


def open_regular(path: str | Path, what: str = "file", max_bytes: int | None = None):
    """Open ``path`` for reading as text (UTF-8, a byte-order mark skipped; universal
    newlines) if it is a regular file.

    A FIFO, device or socket is refused without blocking (it is opened non-blocking and
    checked before anything is read).

    Parameters
    ----------
    path : str or Path
    what : str
        What the file is, for messages.
    max_bytes : int, optional
        Refuse a larger file (before reading it).

    Returns
    -------
    io.TextIOWrapper

    Raises
    ------
    FileAccessError
        Missing, unreadable, not a regular file, or larger than ``max_bytes``.
    """
    path = Path(path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise FileAccessError(f"{what} {path}: cannot open it: {os_reason(exc)}") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise FileAccessError(f"{what} {path} is not a regular file (a FIFO, device, "
                                  f"socket or folder); expected a text file")
        if max_bytes is not None and info.st_size > max_bytes:
            raise FileAccessError(f"{what} {path} has {info.st_size} bytes, more than the "
                                  f"{max_bytes} bytes it may have")
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        # utf-8-sig: a byte-order mark (Excel's "CSV UTF-8", Notepad) is not text of the file
        return open(fd, encoding="utf-8-sig", newline="")  # noqa: SIM115 - the caller closes it
    except BaseException:
        os.close(fd)
        raise
