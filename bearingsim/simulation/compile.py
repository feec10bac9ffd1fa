"""Compiled backend: CasADi functions as native C, loaded back into CasADi.

Functions are generated into C (``casadi.CodeGenerator``, in translation units by
:mod:`~bearingsim.simulation.c_units`), compiled by the C compiler driver
(:mod:`~bearingsim.simulation.c_compiler`) into a shared library and loaded with
``casadi.external``. Libraries are cached on disk by the hash of their source, the compiler and
its flags (:func:`library_path`), so a library is compiled once per machine; parameters are
function arguments, so a parameter change never recompiles. :func:`build_library` generates and
compiles only on a cache miss, :func:`compile_source` compiles a given source and waits.
:func:`compile_system` gives a copy of a system whose functions run as C (for scipy's
integrators, ``steady_state`` and ``linearize``), :mod:`~bearingsim.simulation.kernels` the
right-hand sides and exact Jacobians that CVODES and IDAS evaluate.

A generated function named ``jac_<name>`` with the signature of ``Function.jacobian()``
(inputs: all inputs, then all outputs; outputs: ``jac_<out>_<in>`` for every output and
input) in the same library is what ``casadi.external`` takes as the Jacobian of ``<name>``
(CasADi 3.8: ``External::has_jacobian``), so CasADi differentiates the external by calling it.
"""

from __future__ import annotations

import dataclasses
import hashlib
from collections.abc import Callable, Sequence
from functools import partial
from pathlib import Path

import casadi as ca

from bearingsim.assembler.passes.codegen import mapped_ode_functions
from bearingsim.assembler.system import FunctionTable, System
from bearingsim.cache_budget import mark_used
from bearingsim.simulation.c_compiler import (
    Build,
    CompileError,
    default_cache_dir,
    require_compiler,
)
from bearingsim.simulation.c_units import generate_units

__all__ = ["DEFAULT_FLAGS", "DEFAULT_SPLIT_FLAGS", "build_library", "compile_source",
           "compile_system", "library_path", "source_library"]

DEFAULT_FLAGS: tuple[str, ...] = ("-O1",)
"""Compiler flags of the SUNDIALS kernels: -O1 compiles 2-3x faster than -O2 and runs as fast on
the ball-level models (``bench/sundials_compiled.py``)."""

DEFAULT_SPLIT_FLAGS: tuple[str, ...] = ("-Og",)
"""Compiler flags of a kernel's split translation units (the per-ball Jacobians,
:mod:`~bearingsim.simulation.c_units`): -Og compiles them 15-20 % faster than -O1 and the runs
take as long (``bench/sundials_compiled.py``, section "compile")."""


def library_path(identity: str, *, flags: Sequence[str] = DEFAULT_FLAGS,
                 cache_dir: str | Path | None = None, prefix: str = "bsm",
                 split_flags: Sequence[str] | None = None) -> Path:
    """Where the library determined by ``identity`` (its C source, or a string that
    determines the source) is kept: ``<cache>/<prefix>_<hash>.so``, the hash also over the
    casadi version, the compiler, ``flags`` and ``split_flags`` (None: ``flags``).

    Parameters
    ----------
    identity : str
        The C source, or a string that determines it.
    flags : sequence of str, default DEFAULT_FLAGS
        Compiler flags (of the first translation unit).
    cache_dir : str or Path, optional
        Cache folder (default :func:`default_cache_dir`).
    prefix : str, default "bsm"
        Start of the library's file name.
    split_flags : sequence of str, optional
        Flags of the translation units after the first (default ``flags``).

    Returns
    -------
    Path
        ``<cache>/<prefix>_<hash>.so`` (not necessarily built yet).

    Raises
    ------
    CompileError
        If no C compiler is found.
    """
    cc = require_compiler()
    split = flags if split_flags is None else split_flags
    key = "\n".join([identity, ca.__version__, cc, *flags, "split:", *split])
    digest = hashlib.sha256(key.encode()).hexdigest()[:16]
    out_dir = Path(cache_dir) if cache_dir is not None else default_cache_dir()
    return out_dir / f"{prefix}_{digest}.so"


def compile_source(source: str | Sequence[str], lib: Path, *,
                   flags: Sequence[str] = DEFAULT_FLAGS,
                   split_flags: Sequence[str] | None = None) -> Path:
    """Compile ``source`` (or its translation units) into the shared library ``lib`` and wait
    for it (:class:`Build`; ``split_flags`` for the units after the first, default ``flags``).

    Parameters
    ----------
    source : str or sequence of str
        The C source, or its translation units.
    lib : Path
        Path of the shared library to write.
    flags : sequence of str, default DEFAULT_FLAGS
        Compiler flags.
    split_flags : sequence of str, optional
        Flags of the units after the first (default ``flags``).

    Returns
    -------
    Path
        ``lib``, built.

    Raises
    ------
    CompileError
        If no C compiler is found or compilation fails.
    """
    return Build(source, lib, flags, split_flags).wait()


def source_library(units: Sequence[str], *, headers: Sequence[str] = (),
                   flags: Sequence[str] = DEFAULT_FLAGS, cache_dir: str | Path | None = None,
                   prefix: str = "bsm") -> Path:
    """The shared library of the hand-written C translation units ``units``, named by their
    source and the ``headers`` they include, compiled only on a cache miss.

    Parameters
    ----------
    units : sequence of str
        The translation units' source.
    headers : sequence of str
        The source of the headers they include (part of the name, not compiled).
    flags : sequence of str
        Compiler flags (part of the name).
    cache_dir : path, optional
        Where libraries are kept (default :func:`default_cache_dir`).
    prefix : str
        File name prefix of the library.

    Returns
    -------
    pathlib.Path
        The shared library ``<prefix>_<hash>.so``, built.

    Raises
    ------
    CompileError
        If no C compiler is found or compilation fails.
    """
    lib = library_path("\n".join([*units, *headers]), flags=flags, cache_dir=cache_dir,
                       prefix=prefix)
    return lib if mark_used(lib) else compile_source(list(units), lib, flags=flags)


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
    units = None
    if identity is None:
        units = generate_units(functions() if callable(functions) else functions, prefix)
    lib = library_path(identity if identity is not None else "\n".join(units), flags=flags,
                       cache_dir=cache_dir, prefix=prefix)
    if mark_used(lib):
        return lib
    if units is None:
        units = generate_units(functions() if callable(functions) else functions, prefix)
    return compile_source(units, lib, flags=flags)


def compile_system(system: System, cache_dir: str | Path | None = None,
                   flags: tuple[str, ...] = ("-O2",), mapped: bool = True) -> System:
    """Return a copy of ``system`` whose functions run as compiled C.

    A system with ball sets gets the functions a run evaluates (right-hand side, its
    Jacobians, observed and output variables) with one function per ball mapped over each row
    (:func:`~bearingsim.assembler.passes.codegen.mapped_ode_functions`): C that grows with one
    ball, not with Z, and the inlined functions are not built. Its other functions stay
    symbolic, built on first access: the outputs' Jacobians (once per linearization) and the
    DAE form (IDAS compiles the mapped DAE kernel itself,
    :mod:`~bearingsim.simulation.kernels`; ``dae_z`` runs once per integration).

    Parameters
    ----------
    system : System
        An assembled system.
    cache_dir : path, optional
        Where libraries are kept (default :func:`default_cache_dir`).
    flags : tuple of str
        Extra compiler flags.
    mapped : bool
        Map the balls of a system with ball sets; ``False``: generate the inlined functions.

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
    per_ball = mapped_ode_functions(system) if mapped else None
    chosen = per_ball if per_ball is not None else system.functions
    names = sorted(chosen)
    try:
        lib = build_library([chosen[k] for k in names], flags=flags, cache_dir=cache_dir,
                            prefix="bsm_model")
    except CompileError as exc:
        raise CompileError(f"compile_system: {exc}") from None
    compiled = {key: ca.external(chosen[key].name(), str(lib)) for key in names}
    symbolic = {key: partial(system.functions.__getitem__, key)
                for key in system.functions if key not in compiled}
    return dataclasses.replace(
        system, functions=FunctionTable(compiled, symbolic),
        symbolic_functions=system.functions,
        report={**system.report, "compiled": str(lib),
                "compiled_balls": "mapped" if per_ball is not None else "inlined"},
    )
