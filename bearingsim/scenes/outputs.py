"""An output folder that survives faults: one writer at a time, whole files, the summary last.

:class:`OutputFolder` is what a run (or a sweep) writes through:

* a lock (``flock`` on ``.bearingsim.lock``: released by the operating system when the
  process ends, even by SIGKILL) held for the whole run; a second writer stops at once with
  :class:`OutputFolderBusy` naming the holder (process id, host, start time, command);
* every file written atomically (:func:`bearingsim.files.atomic_path`); temporary ``.part``
  files of dead processes removed when the lock is taken;
* the previous summary and the files it names removed before the first file is replaced
  (:meth:`retire`), and the new summary written last (:meth:`write_summary`), listing every
  file of the run with its size and SHA-256: a run killed half-way leaves no summary that
  describes other data;
* figures written one by one, a failing one recorded in :attr:`plot_failures` (a plot failure,
  not a simulation failure).
"""

from __future__ import annotations

import contextlib
import datetime
import hashlib
import json
import os
import re
import socket
import sys
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from bearingsim.errors import ParameterError
from bearingsim.files import PART, FileAccessError, atomic_path, atomic_write_text, os_reason

__all__ = ["LOCK_NAME", "OutputFolder", "OutputFolderBusy", "command_line", "file_record"]

LOCK_NAME = ".bearingsim.lock"
"""The lock file of an output folder: the lock is the ``flock`` on it (a file left by a killed
process locks nothing); removed when the holder ends normally."""
PNG_COMPRESSION = 1
"""zlib level of the figures' PNG files: 1 writes a sweep's four-panel figure in 0.29 s
against 0.50 s at Pillow's default 6, for a file 9 % larger (``savefig`` of the 64-point
sweep figure of ``deep_groove_duty1``, fastest of 3)."""
_STRAY = re.compile(r"\..*\.(\d+)" + re.escape(PART) + r"(\.[^.]*)?")


class OutputFolderBusy(FileAccessError):
    """Another run or sweep is writing into the output folder."""


def _flock(fh) -> bool:
    """Take the exclusive ``flock`` of an open file without waiting; False if another
    process holds it (True without ``fcntl``, e.g. on Windows: no lock there)."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover
        return True
    try:
        fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        return False
    return True


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def file_record(path: Path) -> dict[str, Any]:
    """``{"name", "bytes", "sha256"}`` of a written file (for the summary).

    Parameters
    ----------
    path : Path
        A written file.

    Returns
    -------
    dict
        Its name, size [bytes] and SHA-256 (hex).
    """
    digest = hashlib.sha256()
    with path.open("rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    return {"name": path.name, "bytes": path.stat().st_size, "sha256": digest.hexdigest()}


class OutputFolder:
    """The output folder of one run or sweep (a context manager holding its lock).

    Parameters
    ----------
    folder : str or Path
        Created (with its parents) if missing.
    command : str
        What writes (shown to a second writer), e.g. ``"bearingsim run scene.toml"``.

    Attributes
    ----------
    files : list of Path
        The files written so far, in order.
    plot_failures : list of dict
        ``{"plot", "error"}`` of each figure that failed.

    Raises
    ------
    OutputFolderBusy
        On entering, when another process holds the folder.
    FileAccessError
        When the folder cannot be created or a file cannot be written (one line: the file and
        the reason).
    """

    def __init__(self, folder: str | Path, command: str):
        self.folder = Path(folder)
        self.command = command
        self.files: list[Path] = []
        self.plot_failures: list[dict[str, str]] = []
        self._fh = None

    # ------------------------------------------------------------------ lock
    def __enter__(self) -> OutputFolder:
        lock = self.folder / LOCK_NAME
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise FileAccessError(f"cannot use the output folder {self.folder}: "
                                  f"{os_reason(exc)}") from None
        while True:
            try:
                fh = open(lock, "a+", encoding="utf-8")  # noqa: SIM115 - held until __exit__
            except OSError as exc:
                raise FileAccessError(f"cannot use the output folder {self.folder}: "
                                      f"{os_reason(exc)}") from None
            if not _flock(fh):
                fh.seek(0)
                holder = fh.read(2000)
                fh.close()
                raise OutputFolderBusy(f"the output folder {self.folder} is in use: "
                                       f"{self._describe(holder)}; wait for it to end or "
                                       f"choose another folder")
            try:  # the holder before may have removed the file between our open and flock
                if os.stat(lock).st_ino == os.fstat(fh.fileno()).st_ino:
                    break
            except FileNotFoundError:
                pass
            fh.close()
        fh.seek(0)
        fh.truncate()
        fh.write(json.dumps({"pid": os.getpid(), "host": socket.gethostname(),
                             "started": datetime.datetime.now(datetime.timezone.utc)
                             .isoformat(timespec="seconds"), "command": self.command}))
        fh.flush()
        self._fh = fh
        self._remove_stray_parts()
        return self

    def __exit__(self, *exc) -> None:
        if self._fh is not None:
            with contextlib.suppress(OSError):  # removed while held: nobody else has it
                (self.folder / LOCK_NAME).unlink()
            self._fh.close()  # releases the flock
            self._fh = None

    @staticmethod
    def _describe(holder: str) -> str:
        try:
            info = json.loads(holder)
            return (f"held by process {int(info['pid'])} on host {str(info['host'])[:64]} "
                    f"since {str(info['started'])[:32]} ({str(info['command'])[:200]})")
        except (ValueError, KeyError, TypeError):
            return "held by another process (it has not recorded itself yet)"

    def _remove_stray_parts(self) -> None:
        """Remove ``.<name>.<pid>.part<suffix>`` files of processes that no longer run."""
        for path in self.folder.iterdir():
            m = _STRAY.fullmatch(path.name)
            if m and int(m.group(1)) != os.getpid() and not _alive(int(m.group(1))):
                with contextlib.suppress(OSError):
                    path.unlink()

    # ------------------------------------------------------------------ writing
    def retire(self, summary_name: str) -> None:
        """Remove an earlier run's summary and the files it names, before anything of that
        run is replaced: a run that then fails half-way leaves none of them behind.

        Parameters
        ----------
        summary_name : str
            File name of the earlier run's summary in the folder.
        """
        path = self.folder / summary_name
        try:
            named = json.loads(path.read_text(encoding="utf-8")).get("files", [])
        except (OSError, ValueError, AttributeError):
            named = []
        names = {Path(f["name"] if isinstance(f, dict) else str(f)).name for f in named
                 if isinstance(f, (dict, str))}
        try:
            path.unlink(missing_ok=True)
            for name in sorted(names - {LOCK_NAME, summary_name, "", ".", ".."}):
                (self.folder / name).unlink(missing_ok=True)
        except (OSError, KeyError, TypeError) as exc:
            reason = os_reason(exc) if isinstance(exc, OSError) else "unreadable file list"
            raise FileAccessError(f"cannot remove the earlier run's files in {self.folder}: "
                                  f"{reason}") from None

    def add(self, path: Path) -> Path:
        """Record a file written (atomically) by another writer.

        Parameters
        ----------
        path : Path
            The written file.

        Returns
        -------
        Path
            ``path``.
        """
        self.files.append(Path(path))
        return Path(path)

    def save_figures(self, make: Callable[[], Iterable[tuple[str, Any]]]) -> None:
        """Make the figures (``make()`` -> (file name, Figure) pairs) and save each as PNG;
        a figure that fails to be made or saved is recorded in :attr:`plot_failures`. File
        errors (folder gone, disk full) still raise :class:`FileAccessError`, and a scene
        error (``output.plot_groups`` naming no output) its ``ParameterError``.

        Parameters
        ----------
        make : callable
            ``make()`` -> iterable of (file name, Figure).
        """
        try:
            figures = list(make())
        except (FileAccessError, ParameterError):  # a file error; a plot the scene misnames
            raise
        except Exception as exc:  # noqa: BLE001 - any failure of a figure is a plot failure
            self.plot_failures.append({"plot": "all figures", "error": _one_line(exc)})
            return
        for name, fig in figures:
            path = self.folder / name
            try:
                with atomic_path(path) as tmp:
                    fig.savefig(tmp, dpi=110, pil_kwargs={"compress_level": PNG_COMPRESSION})
            except FileAccessError:
                raise
            except Exception as exc:  # noqa: BLE001
                self.plot_failures.append({"plot": name, "error": _one_line(exc)})
                continue
            self.files.append(path)

    def write_summary(self, name: str, data: dict[str, Any]) -> Path:
        """Write the JSON summary last: ``data`` with ``files`` (name, bytes, SHA-256 of each
        file of this run) and ``plot_failures``.

        Parameters
        ----------
        name : str
            File name of the summary.
        data : dict
            The summary's content (JSON-serializable).

        Returns
        -------
        Path
            The summary file.
        """
        path = self.folder / name
        data = {**data, "files": [file_record(p) for p in self.files],
                "plot_failures": list(self.plot_failures)}
        atomic_write_text(path, json.dumps(data, indent=2))
        self.files.append(path)
        return path


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0][:300] if text else ''}"


def command_line() -> str:
    """This process's command line, for the lock (``bearingsim run scene.toml``).

    Returns
    -------
    str
        The command line.
    """
    return " ".join(Path(a).name if k == 0 else a for k, a in enumerate(sys.argv))[:300]
