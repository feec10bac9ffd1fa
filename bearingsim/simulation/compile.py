"""Compiled backend: a system's CasADi functions as native C, loaded back into CasADi.

All functions are generated into one C file (``casadi.CodeGenerator``), compiled with the system
C compiler into a shared library and loaded with ``casadi.external``. The compiled system has
the same interface as the original, so ``simulate``, ``linearize`` and ``steady_state`` use it
unchanged. Libraries are cached by the hash of their source.
"""

from __future__ import annotations

import dataclasses
import hashlib
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import casadi as ca

from bearingsim.assembler.system import System
from bearingsim.errors import BearingsimError

__all__ = ["compile_system", "CompileError", "default_cache_dir"]


class CompileError(BearingsimError):
    """The C compiler is missing or failed."""


def default_cache_dir() -> Path:
    """``$BEARINGSIM_CACHE`` or ``~/.cache/bearingsim``."""
    root = os.environ.get("BEARINGSIM_CACHE") or Path.home() / ".cache" / "bearingsim"
    return Path(root)


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
        originals stay in ``symbolic_functions`` for CasADi's own integrators, which
        differentiate them).

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
    cc = shutil.which(os.environ.get("CC", "gcc")) or shutil.which("cc")
    if cc is None:
        raise CompileError("compile_system: no C compiler (gcc or cc) on PATH")
    names = sorted(system.functions)
    with tempfile.TemporaryDirectory() as tmp:
        gen = ca.CodeGenerator("bsm_model.c", {"with_header": False})
        for key in names:
            gen.add(system.functions[key])
        source_path = Path(gen.generate(tmp + os.sep))
        source = source_path.read_text()
        digest = hashlib.sha256((source + " ".join(flags)).encode()).hexdigest()[:16]
        out_dir = Path(cache_dir) if cache_dir is not None else default_cache_dir()
        out_dir.mkdir(parents=True, exist_ok=True)
        lib = out_dir / f"bsm_{digest}.so"
        if not lib.exists():
            tmp_lib = Path(tmp) / lib.name
            cmd = [cc, "-shared", "-fPIC", *flags, str(source_path), "-o", str(tmp_lib), "-lm"]
            proc = subprocess.run(cmd, capture_output=True, text=True)
            if proc.returncode != 0:
                raise CompileError(
                    f"compile_system: {' '.join(cmd)} failed:\n{proc.stderr[-2000:]}"
                )
            shutil.move(str(tmp_lib), lib)
    functions = {key: ca.external(system.functions[key].name(), str(lib)) for key in names}
    return dataclasses.replace(
        system, functions=functions, symbolic_functions=system.functions,
        report={**system.report, "compiled": str(lib)},
    )
