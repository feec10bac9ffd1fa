"""Compiled backend: CasADi functions as native C, loaded back into CasADi.

Functions are generated into one C file (``casadi.CodeGenerator``), compiled with the system C
compiler into a shared library and loaded with ``casadi.external``. Libraries are cached on disk
by the hash of their source, the compiler and its flags, so a library is compiled once per
machine; parameters are function arguments, so a parameter change never recompiles.

:func:`build_library` is the one place that runs the compiler; :func:`compile_system` gives a
copy of a system whose functions run as C (for scipy's integrators, ``steady_state`` and
``linearize``), :mod:`~bearingsim.simulation.kernels` the right-hand sides and exact Jacobians
that CVODES and IDAS evaluate.

A generated function named ``jac_<name>`` with the signature of ``Function.jacobian()``
(inputs: all inputs, then all outputs; outputs: ``jac_<out>_<in>`` for every output and
input) in the same library is what ``casadi.external`` takes as the Jacobian of ``<name>``
(CasADi 3.8: ``External::has_jacobian``), so CasADi differentiates the external by calling it.
"""

from __future__ import annotations

import dataclasses
import hashlib
import os
import shutil
import subprocess
import tempfile
import threading
from collections.abc import Callable, Sequence
from pathlib import Path

import casadi as ca

from bearingsim.assembler.system import System
from bearingsim.errors import BearingsimError

__all__ = ["CompileError", "build_library", "c_compiler", "compilations", "compile_system",
           "default_cache_dir", "DEFAULT_FLAGS"]

DEFAULT_FLAGS: tuple[str, ...] = ("-O1",)
"""Compiler flags of the SUNDIALS kernels: -O1 compiles 2-3x faster than -O2 and runs as fast on
the ball-level models (``bench/sundials_compiled.py``)."""

_COMPILATIONS = [0]
_LOCK = threading.Lock()


class CompileError(BearingsimError):
    """The C compiler is missing or failed."""


def default_cache_dir() -> Path:
    """``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``."""
    root = os.environ.get("BEARINGSIM_CACHE") or Path.home() / ".cache" / "bearingsim"
    return Path(root)


def c_compiler() -> str | None:
    """Path of the C compiler (``$CC``, else ``gcc``, else ``cc``), or None if there is none."""
    return shutil.which(os.environ.get("CC", "gcc")) or shutil.which("cc")


def compilations() -> int:
    """How many times this process has run the C compiler (cache hits do not count)."""
    return _COMPILATIONS[0]


def build_library(functions: Sequence[ca.Function] | Callable[[], Sequence[ca.Function]], *,
                  identity: str | None = None, flags: Sequence[str] = DEFAULT_FLAGS,
                  cache_dir: str | Path | None = None, prefix: str = "bsm") -> Path:
    """Generate C for ``functions`` into one shared library, compiling only on a cache miss.

    Parameters
    ----------
    functions : sequence of casadi.Function, or a callable returning one
        Functions to generate (each under its own name; a ``jac_<name>`` among them becomes
        the Jacobian of ``<name>`` for ``casadi.external``). A callable is called only when
        the library must be built (with ``identity``: a cache hit generates nothing).
    identity : str, optional
        A string that determines the generated source (e.g. the serialized functions and
        how they are derived); the cache key is then its hash instead of the source's.
    flags : sequence of str
        Compiler flags (part of the cache key).
    cache_dir : path, optional
        Where libraries are kept (default :func:`default_cache_dir`).
    prefix : str
        File name prefix of the library.

    Returns
    -------
    pathlib.Path
        The shared library ``<prefix>_<hash>.so``.

    Raises
    ------
    CompileError
        If no C compiler is found or compilation fails.
    """
    cc = c_compiler()
    if cc is None:
        raise CompileError("no C compiler (gcc or cc) on PATH")
    source = None
    if identity is None:
        source = _source(functions, prefix)
        identity = source
    key = "\n".join([identity, ca.__version__, cc, *flags])
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    out_dir = Path(cache_dir) if cache_dir is not None else default_cache_dir()
    out_dir.mkdir(parents=True, exist_ok=True)
    lib = out_dir / f"{prefix}_{digest}.so"
    if lib.exists():
        return lib
    source = source if source is not None else _source(functions, prefix)
    with tempfile.TemporaryDirectory() as tmp:
        source_path = Path(tmp) / f"{prefix}.c"
        source_path.write_text(source)
        tmp_lib = Path(tmp) / lib.name
        cmd = [cc, "-shared", "-fPIC", *flags, str(source_path), "-o", str(tmp_lib), "-lm"]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            raise CompileError(f"{' '.join(cmd)} failed:\n{proc.stderr[-2000:]}")
        with _LOCK:
            _COMPILATIONS[0] += 1
        # a rename within one file system is atomic: a concurrent build of the same library
        # by another process is harmless
        shutil.move(str(tmp_lib), lib)
    return lib


def _source(functions: Sequence[ca.Function] | Callable[[], Sequence[ca.Function]],
            prefix: str) -> str:
    gen = ca.CodeGenerator(f"{prefix}.c", {"with_header": False})
    for fn in functions() if callable(functions) else functions:
        gen.add(fn)
    return gen.dump()


def compile_system(system: System, cache_dir: str | Path | None = None,
                   flags: tuple[str, ...] = ("-O2",)) -> System:
    """Return a copy of ``system`` whose functions run as compiled C.

    Parameters
    ----------
    system : System
        An assembled system.
    cache_dir : path, optional
        Where libraries are kept (default :func:`default_cache_dir`).
    flags : tuple of str
        Extra compiler flags.

    Returns
    -------
    System
        Same names, parameters and metadata; ``functions`` replaced by compiled ones (the
        originals stay in ``symbolic_functions``).

    Raises
    ------
    CompileError
        If no C compiler is found, compilation fails or the system's nonlinear blocks use a
        rootfinder without code generation.
    """
    if system.rootfinder not in (None, "fast_newton"):
        raise CompileError(
            f"compile_system: the nonlinear blocks of {system.name!r} use CasADi's "
            f"{system.rootfinder!r} rootfinder, which generates no C code; assemble with "
            "rootfinder='fast_newton'"
        )
    names = sorted(system.functions)
    try:
        lib = build_library([system.functions[k] for k in names], flags=flags,
                            cache_dir=cache_dir, prefix="bsm_model")
    except CompileError as exc:
        raise CompileError(f"compile_system: {exc}") from None
    functions = {key: ca.external(system.functions[key].name(), str(lib)) for key in names}
    return dataclasses.replace(
        system, functions=functions, symbolic_functions=system.functions,
        report={**system.report, "compiled": str(lib)},
    )
