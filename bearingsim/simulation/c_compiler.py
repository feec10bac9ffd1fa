"""bearingsim's one C compiler driver: it finds the compiler (:func:`c_compiler`), builds the
compile and link commands, runs them and reports failures as :class:`CompileError`.

:class:`Build` compiles a library in the background, in a private folder inside the library
cache (:func:`default_cache_dir`), renamed into place when complete; no compiler outlives the
program (:func:`stop_builds`), and a finished build records its speed for
:func:`compile_estimate`. :func:`compile_units` compiles files on disk, each with its own flags,
and waits (the FMU export, which passes its own compiler, e.g. zig's for a cross target, and
flags, e.g. the glibc 2.17 pin). :func:`compilations` counts the compiler runs of this process.
What is compiled, and the cache of libraries, is :mod:`~bearingsim.simulation.compile`'s.
"""

from __future__ import annotations

import atexit
import contextlib
import functools
import os
import shlex
import shutil
import signal
import subprocess
import tempfile
import threading
import time
from collections.abc import Sequence
from pathlib import Path

from bearingsim.cache_budget import budget_bytes, keep_to_budget
from bearingsim.cache_paths import cache_root
from bearingsim.errors import BearingsimError
from bearingsim.files import os_reason

__all__ = ["Build", "CompileError", "c_compiler", "compilations", "compile_estimate",
           "compile_units", "default_cache_dir", "require_compiler", "stop_builds",
           "unwritable_cache"]

_COMPILATIONS = [0]
_LOCK = threading.Lock()
_RUNNING: set[Build] = set()

EXIT_GRACE = 10.0
"""Seconds [s] a build still running at interpreter exit may take to finish before it is
stopped (a finished library serves the next program)."""

DEFAULT_COMPILE_RATE = 1.7e5
"""C source bytes compiled per wall second [bytes/s] before this machine has recorded its own
(:func:`compile_estimate`): the 6304 massive-ball kernel, 0.35 MB of C in 3 units, builds in
about 2 s on the benchmark machine (the units in parallel)."""

_RATE_FILE = "compile_rate.txt"


def _record_rate(cache: Path, rate: float) -> None:
    """Remember the speed of a finished build in the cache folder (atomic write)."""
    with contextlib.suppress(OSError):
        tmp = cache / f".{_RATE_FILE}.{os.getpid()}"
        tmp.write_text(f"{rate:.6g}\n")
        os.replace(tmp, cache / _RATE_FILE)


def compile_estimate(source_bytes: int, cache_dir: str | Path | None = None) -> float:
    """Expected wall time [s] of building a library from ``source_bytes`` of C: at the speed
    of the last build recorded in the cache folder, else :data:`DEFAULT_COMPILE_RATE`.

    Parameters
    ----------
    source_bytes : int
        Size of the C source [bytes] (>= 0).
    cache_dir : str or Path, optional
        Cache folder holding the recorded build speed (default
        :func:`default_cache_dir`).

    Returns
    -------
    float
        Expected build time [s].
    """
    rate = DEFAULT_COMPILE_RATE
    path = Path(cache_dir or default_cache_dir()) / _RATE_FILE
    with contextlib.suppress(OSError, ValueError):
        rate = float(path.read_text().strip())
    return 0.2 + source_bytes / max(rate, 1.0)


def stop_builds(grace: float = EXIT_GRACE) -> None:
    """Give running builds ``grace`` seconds [s] to finish, then stop the rest (run at
    interpreter exit: no compiler outlives the program).

    Parameters
    ----------
    grace : float, default EXIT_GRACE
        Time the running builds get to finish [s] (>= 0).
    """
    deadline = time.perf_counter() + grace
    with _LOCK:
        running = list(_RUNNING)
    for build in running:
        with contextlib.suppress(subprocess.TimeoutExpired):
            build._proc.wait(timeout=max(deadline - time.perf_counter(), 0.0))
        if build.done():
            continue
        build.stop()


atexit.register(stop_builds)


class CompileError(BearingsimError):
    """The C compiler is missing or failed, or what it built is unusable (e.g. an FMU binary
    that needs a newer glibc than its baseline)."""


def default_cache_dir() -> Path:
    """``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``: the root shared with the assembled
    systems (:func:`bearingsim.cache_paths.cache_root`; found once per value of the
    variables it depends on: every run's kernel look-up asks for it).

    Returns
    -------
    Path
        The cache folder.
    """
    return _cache_dir(os.environ.get("BEARINGSIM_CACHE"), os.environ.get("HOME"))


@functools.lru_cache(maxsize=8)
def _cache_dir(setting: str | None, home: str | None) -> Path:
    """:func:`cache_root` for these values of ``$BEARINGSIM_CACHE`` and ``$HOME``."""
    return cache_root()


def c_compiler() -> str | None:
    """Path of the C compiler (``$CC``, else ``gcc``, else ``cc``), or None if there is none
    (looked up once per ``$CC`` and ``$PATH``).

    Returns
    -------
    str or None
        The compiler's path, None without one.
    """
    return _find_compiler(os.environ.get("CC", "gcc"), os.environ.get("PATH"))


@functools.lru_cache(maxsize=8)
def _find_compiler(cc: str, path: str | None) -> str | None:
    """The compiler ``cc`` (else ``cc``) found on ``path``."""
    return shutil.which(cc, path=path) or shutil.which("cc", path=path)


def require_compiler() -> str:
    """:func:`c_compiler`, or :class:`CompileError` if there is none.

    Returns
    -------
    str
        The compiler's path.

    Raises
    ------
    CompileError
        If no C compiler is found.
    """
    cc = c_compiler()
    if cc is None:
        raise CompileError("no C compiler (gcc or cc) on PATH; install gcc or set CC")
    return cc


def _compile_command(cc: Sequence[str], source: Path, obj: Path, flags: Sequence[str],
                     pic: bool = True) -> list[str]:
    """The command compiling ``source`` into the object file ``obj``."""
    return [*cc, "-c", *(["-fPIC"] if pic else []), *flags, str(source), "-o", str(obj)]


def _link_command(cc: Sequence[str], objects: Sequence[str], output: Path,
                  flags: Sequence[str] = ()) -> list[str]:
    """The command linking ``objects`` (and libm) into the shared library ``output``."""
    return [*cc, "-shared", *flags, *objects, "-o", str(output), "-lm"]


def compile_units(units: Sequence[tuple[Path, Sequence[str]]], output: Path, *,
                  compiler: Sequence[str] | None = None, flags: Sequence[str] = (),
                  link_flags: Sequence[str] = (), pic: bool = True,
                  what: str = "the library") -> Path:
    """Compile C files, each with its own flags and all in parallel, link them into a shared
    library and wait (no cache: the caller owns ``output``).

    Parameters
    ----------
    units : sequence of (pathlib.Path, sequence of str)
        The ``.c`` files and the flags of each (e.g. its optimisation).
        Their object files go next to ``output``.
    output : pathlib.Path
        The shared library to write.
    compiler : sequence of str, optional
        The compiler command (e.g. ``[python, "-m", "ziglang", "cc", "-target", ...]`` for a
        cross target); default :func:`c_compiler`.
    flags : sequence of str
        Flags of every file (include folders, definitions, forced includes).
    link_flags : sequence of str
        Flags of the link.
    pic : bool
        Compile position-independent code (``-fPIC``; not for Windows targets).
    what : str
        What is built, for the error message.

    Returns
    -------
    pathlib.Path
        ``output``.

    Raises
    ------
    CompileError
        If no C compiler is found, or with the compiler's or linker's messages.
    """
    cc = list(compiler) if compiler is not None else [require_compiler()]
    jobs = []
    for source, unit_flags in units:
        obj = output.parent / f"{output.stem}_{source.stem}.o"
        cmd = _compile_command(cc, source, obj, [*flags, *unit_flags], pic)
        jobs.append((cmd, str(obj), subprocess.Popen(cmd, stdout=subprocess.DEVNULL,
                                                     stderr=subprocess.PIPE, text=True)))
    with _LOCK:
        _COMPILATIONS[0] += 1
    results = [(cmd, proc.communicate()[1], proc.returncode) for cmd, _, proc in jobs]
    failed = [(cmd, err) for cmd, err, code in results if code != 0]
    if failed:
        cmd, err = failed[0]
        raise CompileError(f"compiling {what} failed ({shlex.join(cmd)}):\n{err[-4000:]}")
    link = _link_command(cc, [obj for _, obj, _ in jobs], output, link_flags)
    proc = subprocess.run(link, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise CompileError(f"linking {what} failed ({shlex.join(link)}):\n"
                           f"{proc.stderr[-4000:]}")
    return output


def compilations() -> int:
    """How many times this process has run the C compiler (cache hits do not count).

    Returns
    -------
    int
        Compiler runs so far.
    """
    return _COMPILATIONS[0]


def _build_folder(lib: Path, units: list[str]) -> Path:
    """A private build folder beside ``lib`` holding the units' sources
    (``<lib stem>_<k>.c``).

    Raises
    ------
    CompileError
        When the cache folder cannot be created or written (a file in its place, no
        permission, a full disk), naming the folder and ``BEARINGSIM_CACHE``.
    """
    folder = None
    try:
        lib.parent.mkdir(parents=True, exist_ok=True)
        folder = Path(tempfile.mkdtemp(dir=lib.parent, prefix=".build_"))
        for k, unit in enumerate(units):
            (folder / f"{lib.stem}_{k}.c").write_text(unit)
    except OSError as exc:
        if folder is not None:
            shutil.rmtree(folder, ignore_errors=True)
        raise unwritable_cache(lib.parent, exc) from None
    return folder


def unwritable_cache(folder: Path, exc: OSError) -> CompileError:
    """The error of a kernel cache folder that cannot be created or written.

    Parameters
    ----------
    folder : Path
        The cache folder.
    exc : OSError
        What creating or writing in it raised.

    Returns
    -------
    CompileError
        Naming the folder, the reason and ``BEARINGSIM_CACHE``.
    """
    return CompileError(f"the kernel cache folder {folder} cannot be written ({os_reason(exc)}): "
                        "point BEARINGSIM_CACHE at a folder this user can write")


class Build:
    """A compilation of one library by the C compiler in a child process.

    The library's translation units (:func:`~bearingsim.simulation.c_units.generate_units`)
    are compiled in parallel and linked. The child works in a private build directory inside
    the cache and renames the library into place only when complete, so the library appears
    whole or not at all and a concurrent build of the same library by another process is
    harmless. No compiler outlives the program: at interpreter exit a build still running is
    given :data:`EXIT_GRACE` seconds to finish, then stopped and its build directory removed
    (:func:`stop_builds`). A finished build records its speed (source bytes per second of
    wall time) for :func:`compile_estimate`.

    Parameters
    ----------
    sources : str or sequence of str
        The C source, or its translation units (the first is the main unit).
    lib : pathlib.Path
        The library to build.
    flags : sequence of str
        Compiler flags of the main unit.
    split_flags : sequence of str, optional
        Compiler flags of the other units (default ``flags``).
    """

    def __init__(self, sources: str | Sequence[str], lib: Path, flags: Sequence[str],
                 split_flags: Sequence[str] | None = None):
        cc = require_compiler()
        units = [sources] if isinstance(sources, str) else list(sources)
        self.lib = lib
        self.budget = budget_bytes()
        """The cache's budget [bytes], kept to when the library is in place."""
        self.source_bytes = sum(len(unit) for unit in units)
        """Size of the C source [bytes]."""
        self.started = time.perf_counter()
        self._dir = _build_folder(lib, units)
        self._log = self._dir / "cc.log"
        tmp_lib = self._dir / lib.name
        objects, compile_lines = [], []
        for k in range(len(units)):
            source_path = self._dir / f"{lib.stem}_{k}.c"
            obj = self._dir / f"{lib.stem}_{k}.o"
            objects.append(str(obj))
            unit_flags = flags if k == 0 or split_flags is None else split_flags
            command = _compile_command([cc], source_path, obj, unit_flags)
            log = shlex.quote(str(self._dir / f"cc_{k}.log"))
            compile_lines.append(f"{shlex.join(command)} 2> {log} & p{k}=$!")
        link = _link_command([cc], objects, tmp_lib)
        split = "" if split_flags is None else f" (split units: {' '.join(split_flags)})"
        self.command = (f"{cc} -c -fPIC {' '.join(flags)}{split} on {len(units)} unit(s) in "
                        f"{self._dir}, then {shlex.join(link)}")
        q = shlex.quote
        script = "\n".join([
            *compile_lines,
            f"ok=0; {' ; '.join(f'wait $p{k} || ok=1' for k in range(len(units)))}",
            f"cat {q(str(self._dir))}/cc_*.log > {q(str(self._log))}",
            f"[ $ok = 0 ] && {shlex.join(link)} 2>> {q(str(self._log))} && "
            f"mv -f {q(str(tmp_lib))} {q(str(lib))} && rm -rf {q(str(self._dir))}",
        ])
        self._proc = subprocess.Popen(["sh", "-c", script], stdin=subprocess.DEVNULL,
                                      stdout=subprocess.DEVNULL, start_new_session=True)
        with _LOCK:
            _COMPILATIONS[0] += 1
            _RUNNING.add(self)

    def done(self) -> bool:
        """Whether the compiler has finished (successfully or not).

        Returns
        -------
        bool
            True once the compiler process has exited.
        """
        finished = self._proc.poll() is not None
        if finished:
            self._finished()
        return finished

    def _finished(self) -> None:
        """Record a successful build's speed (once) and forget it as running."""
        with _LOCK:
            if self not in _RUNNING:
                return
            _RUNNING.discard(self)
        if self._proc.returncode == 0 and self.lib.exists():
            _record_rate(self.lib.parent, self.source_bytes / max(
                time.perf_counter() - self.started, 1e-3))
            with contextlib.suppress(OSError):  # a read-only cache keeps what it has
                keep_to_budget(self.lib.parent, self.lib, self.budget)

    def stop(self) -> None:
        """Stop the compiler (its whole process group) and remove the build directory."""
        if self._proc.poll() is None:
            with contextlib.suppress(ProcessLookupError, PermissionError):
                os.killpg(self._proc.pid, signal.SIGKILL)
            self._proc.wait()
        with _LOCK:
            _RUNNING.discard(self)
        shutil.rmtree(self._dir, ignore_errors=True)

    def wait(self) -> Path:
        """Wait for the library.

        Returns
        -------
        Path
            The built shared library.

        Raises
        ------
        CompileError
            With the compiler's messages, if it failed.
        """
        returncode = self._proc.wait()
        self._finished()
        if returncode != 0 or not self.lib.exists():
            log = self._log.read_text()[-2000:] if self._log.exists() else ""
            shutil.rmtree(self._dir, ignore_errors=True)
            raise CompileError(f"{self.command} failed:\n{log}")
        return self.lib
