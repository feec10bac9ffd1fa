"""Kernels of the SUNDIALS integrators: a system's right-hand side (or DAE residual) with its
exact Jacobian, evaluated as compiled C or, as the fallback, on CasADi's virtual machine.

A :class:`Kernel` holds one CasADi function ``F`` whose ``F.jacobian()`` is the exact
Jacobian, evaluated by the same backend:

* **compiled C**: ``F`` and ``jac_F = F.jacobian()`` are generated into one library
  (:func:`~bearingsim.simulation.compile.build_library`) and loaded with ``casadi.external``,
  which takes the generated ``jac_F`` as the Jacobian of ``F``;
* **CasADi VM**: the same two SX functions, ``F`` wrapped so that CasADi differentiates it by
  calling ``jac_F`` (option ``custom_jacobian``; forward and reverse mode disabled) instead of
  deriving new derivative functions.

Both backends evaluate the same expression graphs in the same order, so a run gives the same
numbers on either (bit for bit on x86-64 with gcc, which does not contract ``a*b+c`` into
FMAs without ``-march`` flags). The parameters ``p`` are declared non-differentiable (no
integrator asks for derivatives with respect to them), which keeps the generated Jacobian to
the blocks of ``t, x, (z,) u``.

Two forms:

* ``"ode"``: ``ode(t, x, u, p)`` (models with ``newton`` rootfinders cannot be generated; they
  stay on the VM);
* ``"dae"``: ``dae(t, x, z, u, p) -> (ode, alg)``, the semi-explicit form of models with
  nonlinear blocks (``dae_ode``, ``dae_alg``; pure SX, so it compiles whatever the
  rootfinder), with common subexpressions eliminated over both outputs.

Models with ball sets (:attr:`System.mapped`) get the kernel with one function per ball
mapped over each row (:mod:`bearingsim.assembler.mapped`): the same right-hand side, its
Jacobian by the chain rule through the per-ball Jacobians (equal to the inlined one to
round-off), in a library whose size grows with one ball, not with Z. ``mapped=False`` takes
the inlined functions.

Kernels are cached per system (in memory, for the system's lifetime) and form; libraries on
disk by content hash (:func:`_identity`; mapped kernels by their C source). With
``compiled="auto"`` a library that is not on disk yet is compiled in a background thread while
the run goes on the VM; later runs pick it up when it is ready. Since both backends give the
same numbers, a sweep whose first points ran on the VM is not perturbed by the switch.
"""

from __future__ import annotations

import threading
import time
import weakref
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import casadi as ca

from bearingsim.assembler.mapped import MappedKernel
from bearingsim.assembler.mapped_parts import NotMappable
from bearingsim.assembler.system import System
from bearingsim.cache_budget import mark_used
from bearingsim.errors import ParameterError
from bearingsim.simulation.c_compiler import (
    Build,
    CompileError,
    c_compiler,
    default_cache_dir,
    unwritable_cache,
)
from bearingsim.simulation.c_units import generate_units
from bearingsim.simulation.compile import DEFAULT_FLAGS, DEFAULT_SPLIT_FLAGS, library_path
from bearingsim.simulation.kernel_names import remember_library, remembered_library

__all__ = ["COMPILED", "VM", "Kernel", "cache_key", "kernel", "clear_kernel_cache", "pending_build",
           "wait_for_compilations"]

SOURCES = {"ode": ("ode", "observe"), "dae": ("dae_ode", "dae_alg", "dae_observe")}
"""The system functions each kernel form is made of (the last one observes)."""

RECIPE = ("bearingsim kernel v1: F = the sources' outputs (cse, p not differentiable), "
          "jac_F = F.jacobian(), observe (cse)")
"""How a kernel library is derived from its sources (part of its cache key: change it when the
derivation changes)."""

COMPILED = "compiled C"
"""``Kernel.backend`` of generated C."""
VM = "CasADi VM"
"""``Kernel.backend`` of CasADi's SX virtual machine."""

AUTO_MIN_INSTRUCTIONS = 1000
"""``compiled="auto"`` generates C for kernels from this many SX instructions (right-hand side
or residual); below it a run is dominated by the integrator's own work and the compiler costs
more than it saves (the 61905/61907 torque level has 122)."""


@dataclass(frozen=True)
class Kernel:
    """A model function with its exact Jacobian on one evaluation backend.

    Attributes
    ----------
    function : casadi.Function
        ``ode(t, x, u, p)`` or ``dae(t, x, z, u, p) -> (ode, alg)``; ``function.jacobian()``
        is its exact Jacobian, evaluated by the same backend.
    observe : casadi.Function
        Every observed variable: ``observe(t, x, u, p)`` or ``dae_observe(t, x, z, u, p)``.
    form : {"ode", "dae"}
    backend : {"compiled C", "CasADi VM"}
    reason : str
        Why the backend was chosen (for ``Result.stats``).
    mapped : str
        The mapped sets (e.g. ``"mapped: root: 7 members"``), or why the functions are inlined.
    library : pathlib.Path or None
        The shared library of a compiled kernel.
    build_time : float
        Wall time of generating and compiling (or loading) the kernel [s].
    """

    function: ca.Function
    observe: ca.Function
    form: str
    backend: str
    reason: str
    library: Path | None
    build_time: float
    mapped: str = ""

    def describe(self) -> dict[str, Any]:
        """The kernel's entries of ``Result.stats``.

        Returns
        -------
        dict
            Backend, the reason for it, the ball mapping, and the library's path if there
            is one.
        """
        out: dict[str, Any] = {"backend": self.backend, "backend_reason": self.reason,
                               "mapped": self.mapped}
        if self.library is not None:
            out["library"] = str(self.library)
        return out


_CACHE: dict[int, dict[tuple, Any]] = {}
"""Per system (id): kernels by request, interim VM kernels and library paths."""
_LOCK = threading.Lock()


def clear_kernel_cache() -> None:
    """Forget every kernel built in this process (libraries on disk stay)."""
    with _LOCK:
        _CACHE.clear()


def _system_cache(system: System) -> dict[tuple, Any]:
    """The kernel cache of one system, dropped when the system is garbage collected."""
    key = id(system)
    with _LOCK:
        cache = _CACHE.get(key)
        if cache is None:
            cache = _CACHE[key] = {}
            weakref.finalize(system, _CACHE.pop, key, None)
    return cache


def kernel(system: System, form: str = "ode", compiled: bool | str = "auto",
           flags: tuple[str, ...] = DEFAULT_FLAGS, cache_dir: str | Path | None = None,
           mapped: bool = True,
           split_flags: tuple[str, ...] | None = DEFAULT_SPLIT_FLAGS) -> Kernel:
    """The right-hand side (``form="ode"``) or DAE residual (``"dae"``) of ``system`` with its
    exact Jacobian, built once per system, form and backend choice.

    Parameters
    ----------
    system : System
        An assembled system.
    form : {"ode", "dae"}
        ``"dae"`` needs a system with nonlinear blocks (``dae_ode``, ``dae_alg``).
    compiled : bool or "auto"
        ``True``: generated C, compiling it now if it is not cached (raises
        :class:`~bearingsim.simulation.c_compiler.CompileError` if that is impossible);
        ``False``: the CasADi VM; ``"auto"``: C when a compiler exists, the form can be
        generated and the model is not tiny (:data:`AUTO_MIN_INSTRUCTIONS`), else the VM; a
        library not yet on disk is compiled in the background and the VM kernel returned
        until it is ready (the reason is recorded in either case).
    flags : tuple of str
        Compiler flags (of the main translation unit).
    cache_dir : path, optional
        Library cache (default :func:`~bearingsim.simulation.c_compiler.default_cache_dir`).
    mapped : bool
        Use the mapped-ball functions of a model with ball sets (:attr:`System.mapped`);
        ``False``: the inlined ones.
    split_flags : tuple of str or None
        Compiler flags of the translation units split off the main one (the per-ball
        Jacobians, :mod:`~bearingsim.simulation.c_units`); None: ``flags``.

    Returns
    -------
    Kernel
    """
    if compiled not in (True, False, "auto"):
        raise ParameterError(f"compiled must be True, False or 'auto', got {compiled!r}")
    if form not in ("ode", "dae"):
        raise ParameterError(f"form must be 'ode' or 'dae', got {form!r}")
    cache = _system_cache(system)
    key = cache_key(form, compiled, flags, cache_dir, mapped, split_flags)
    found = cache.get(key)
    if found is not None:
        return found
    start = time.perf_counter()
    per_ball = system.mapped.find(form) if mapped and system.mapped is not None else None
    # a mapped kernel never reads the system's inlined functions (built on first access)
    sources = None if per_ball is not None else _sources(system, form)
    use_c, reason = _choose(system, form, compiled, sources)
    if not use_c:
        balls = _ball_sets(system, form, mapped)
        fn, jac, observe = _generated(system, form, per_ball)
        result = _vm_kernel(form, fn, jac, observe, reason, start, balls)
        cache[key] = result
        return result
    prefix = f"bsm_{form}"
    generated = units = None
    lib = cache.get(("library", *key))
    if lib is None:
        identity = None if sources is None else _identity(form, sources)
        if identity is not None:
            lib = library_path(identity, flags=flags, cache_dir=cache_dir, prefix=prefix,
                               split_flags=split_flags)
        else:  # named by its C source: generated once per loaded system's bytes
            recipe = (form, f"mapped={per_ball is not None}", prefix, *flags, "split:",
                      *(flags if split_flags is None else split_flags))
            lib = remembered_library(system, recipe, cache_dir)
            if lib is None:
                generated = _generated(system, form, per_ball)
                units = generate_units(generated, prefix)
                lib = library_path("\n".join(units), flags=flags, cache_dir=cache_dir,
                                   prefix=prefix, split_flags=split_flags)
                remember_library(system, recipe, cache_dir, lib)
        cache[("library", *key)] = lib
    record = lib.with_name(lib.name + ".balls")
    present = mark_used(lib)
    balls = (record.read_text() if present and record.exists()
             else _ball_sets(system, form, mapped))
    if not present:
        with _LOCK:
            pending = _PENDING.get(lib)
        if pending is None:
            generated = generated or _generated(system, form, per_ball)
            try:
                record.parent.mkdir(parents=True, exist_ok=True)
                record.write_text(balls)  # what the library maps, read when it is reused
                pending = _submit(lib, units or generate_units(generated, prefix), flags,
                                  split_flags)
            except (CompileError, OSError) as exc:  # a cache folder that cannot be written
                pending = _FailedBuild(exc if isinstance(exc, CompileError)
                                       else unwritable_cache(record.parent, exc))
        if compiled is True:
            pending.wait()  # raises the CompileError of a failed build
        elif not pending.done():
            interim = cache.get(("interim", *key))
            if interim is None:
                fn, jac, observe = generated or _generated(system, form, per_ball)
                interim = cache[("interim", *key)] = _vm_kernel(
                    form, fn, jac, observe, "C compiling in the background; the VM runs until "
                    "it is ready (same numbers)", start, balls)
            return interim
        else:
            try:
                pending.wait()
            except CompileError as exc:
                fn, jac, observe = generated or _generated(system, form, per_ball)
                result = cache[key] = _vm_kernel(form, fn, jac, observe,
                                                 f"compiling failed: {exc}", start, balls)
                return result
    fn, observe = ((per_ball.function, per_ball.observe) if per_ball is not None
                   else (sources[0], sources[-1]))
    diff = [name != "p" for name in fn.name_in()]
    result = Kernel(ca.external(form, str(lib), {"is_diff_in": diff}),
                    ca.external(observe.name(), str(lib)), form, COMPILED, reason, lib,
                    time.perf_counter() - start, balls)
    cache[key] = result
    return result


def cache_key(form: str, compiled: bool | str, flags: tuple[str, ...] = DEFAULT_FLAGS,
              cache_dir: str | Path | None = None, mapped: bool = True,
              split_flags: tuple[str, ...] | None = DEFAULT_SPLIT_FLAGS) -> tuple:
    """The key of a :func:`kernel` request in a system's kernel cache (same arguments).

    Parameters
    ----------
    form : {"ode", "dae"}
        As :func:`kernel` takes it.
    compiled : bool or "auto"
        As :func:`kernel` takes it.
    flags : tuple of str
        Compiler flags (of the main translation unit).
    cache_dir : path, optional
        Library cache (default :func:`~bearingsim.simulation.c_compiler.default_cache_dir`).
    mapped : bool
        Whether the mapped-ball functions are used.
    split_flags : tuple of str or None
        Compiler flags of the split-off translation units; None: ``flags``.

    Returns
    -------
    tuple
        Hashable key; equal keys mean the same kernel.
    """
    return (form, compiled, tuple(flags), str(cache_dir or default_cache_dir()), bool(mapped),
            None if split_flags is None else tuple(split_flags))


def _vm_kernel(form: str, fn: ca.Function, jac: ca.Function, observe: ca.Function,
               reason: str, start: float, balls: str) -> Kernel:
    return Kernel(_with_jacobian(fn, jac), observe, form, VM, reason, None,
                  time.perf_counter() - start, balls)


def _ball_sets(system: System, form: str, mapped: bool) -> str:
    """``"mapped: <sets>"`` when the kernel maps its balls, else why it inlines them."""
    if not mapped:
        return "inlined: mapped=False"
    if system.mapped is None:
        return "inlined: no ball sets"
    try:
        system.mapped.get(form)
    except NotMappable as exc:
        return f"inlined: {exc}"
    return f"mapped: {system.mapped.summary}"


_PENDING: dict[Path, Build] = {}


class _FailedBuild:
    """A build that could not start (its cache folder cannot be written): done, and waiting
    for it raises its error, as a failed compilation's :class:`Build` does."""

    def __init__(self, error: CompileError):
        self.error = error

    def done(self) -> bool:
        return True

    def wait(self) -> Path:
        raise self.error


def _submit(lib: Path, units: list[str], flags: tuple[str, ...],
            split_flags: tuple[str, ...] | None) -> Build:
    """Start compiling the translation units ``units`` into ``lib`` (once per library and
    process)."""
    with _LOCK:
        if lib not in _PENDING:
            _PENDING[lib] = Build(units, lib, flags, split_flags)
        return _PENDING[lib]


def wait_for_compilations() -> None:
    """Block until every compilation this process started has finished (failures are
    reported by the next :func:`kernel` call that needs the library)."""
    with _LOCK:
        pending = list(_PENDING.values())
    for build in pending:
        try:
            build.wait()
        except CompileError:
            pass


def _choose(system: System, form: str, compiled: bool | str,
            sources: list[ca.Function] | None) -> tuple[bool, str]:
    """(generate C?, why) for a kernel request (``sources`` None: a mapped kernel, whose ball
    sets make it large enough)."""
    if compiled is False:
        return False, "compiled=False"
    blocker = None
    if c_compiler() is None:
        blocker = "no C compiler on PATH"
    elif form == "ode" and system.rootfinder not in (None, "fast_newton"):
        blocker = (f"the {system.rootfinder!r} rootfinder of the nonlinear blocks has no C code "
                   "generation (IDAS on the DAE form compiles)")
    if blocker is not None:
        if compiled is True:
            raise CompileError(f"cannot compile the {form} kernel of {system.name!r}: {blocker}")
        return False, blocker
    if compiled is True:
        return True, "compiled=True"
    rhs = [] if sources is None else sources[:-1]
    if rhs and all(f.is_a("SXFunction") for f in rhs):
        size = sum(f.n_instructions() for f in rhs)
        if size < AUTO_MIN_INSTRUCTIONS:
            return False, f"tiny model ({size} instructions): the VM costs less than compiling"
    return True, "C compiler found"


def _identity(form: str, sources: list[ca.Function]) -> str | None:
    """What determines an inlined kernel library, without generating it: the recipe and the
    source functions serialized with fresh input symbols (the assembler's symbol names carry
    global counters, so the same model assembled after other models serializes differently).
    None for MX sources (their rootfinders hold SX functions with those names): the library is
    then named by its generated C source, as mapped kernels always are."""
    if not all(f.is_a("SXFunction") for f in sources):
        return None
    parts = [RECIPE, form]
    for f in sources:
        fresh = [ca.SX.sym(f.name_in(i), f.sparsity_in(i)) for i in range(f.n_in())]
        parts.append(ca.Function(f.name(), fresh, f.call(fresh), f.name_in(),
                                 f.name_out()).serialize())
    return "\n".join(parts)


def _sources(system: System, form: str) -> list[ca.Function]:
    """The system's functions a kernel is made of: the right-hand side (``ode``) or the
    residual (``dae_ode``, ``dae_alg``), then the observe function."""
    funcs = system.symbolic_functions or system.functions
    if form == "dae" and "dae_ode" not in funcs:
        raise ParameterError(f"{system.name!r} has no nonlinear blocks, so no DAE form")
    return [funcs[k] for k in SOURCES[form]]


def _symbolic(system: System, form: str) -> tuple[ca.Function, ca.Function]:
    """The kernel function (``p`` not differentiable) and its observe function, symbolic; SX
    functions with common subexpressions eliminated over all their outputs."""
    *parts, obs = _sources(system, form)
    names_in = parts[0].name_in()
    diff = [name != "p" for name in names_in]
    out_names = ["ode"] if form == "ode" else ["ode", "alg"]
    return (_rebuilt(form, parts, names_in, out_names, {"is_diff_in": diff}),
            _rebuilt(obs.name(), [obs], names_in, obs.name_out(), {}))


def _generated(system: System, form: str, per_ball: MappedKernel | None
               ) -> list[ca.Function]:
    """The kernel, its Jacobian (``jac_<form>``, which ``casadi.external`` takes as the
    kernel's Jacobian) and the observe function: what a library holds, and what the VM
    evaluates. The mapped-ball functions ``per_ball``, else the inlined ones."""
    if per_ball is not None:
        return [per_ball.function, per_ball.jacobian, per_ball.observe]
    fn, observe = _symbolic(system, form)
    return [fn, fn.jacobian(), observe]


def _rebuilt(name: str, parts: list[ca.Function], names_in: list[str], names_out: list[str],
             opts: dict[str, Any]) -> ca.Function:
    """One function of the outputs of ``parts`` (same inputs), SX ones with ``cse``."""
    sx = all(f.is_a("SXFunction") for f in parts)
    sym = parts[0].sx_in() if sx else parts[0].mx_in()
    outs = [out for f in parts for out in f.call(sym)]
    return ca.Function(name, sym, outs, names_in, names_out, {**opts, "cse": True} if sx else opts)


def _with_jacobian(fn: ca.Function, jac: ca.Function) -> ca.Function:
    """``fn`` as a function that CasADi differentiates by calling ``jac`` (VM backend)."""
    sym = fn.mx_in()
    return ca.Function(fn.name(), sym, fn.call(sym), fn.name_in(), fn.name_out(),
                       {"custom_jacobian": jac, "enable_forward": False,
                        "enable_reverse": False, "never_inline": True,
                        "is_diff_in": fn.is_diff_in()})


def pending_build(system: System, form: str = "ode",
                  cache_dir: str | Path | None = None) -> Build | None:
    """The background build of ``system``'s ``compiled="auto"`` kernel library still running
    in this process, if any (started by :func:`kernel`).

    Parameters
    ----------
    system : System
        An assembled system.
    form : {"ode", "dae"}
        The kernel's form.
    cache_dir : path, optional
        Library cache (default :func:`~bearingsim.simulation.c_compiler.default_cache_dir`).

    Returns
    -------
    Build or None
        The running build, or None when there is none or it has finished.
    """
    lib = _system_cache(system).get(("library", *cache_key(form, "auto", cache_dir=cache_dir)))
    if lib is None:
        return None
    with _LOCK:
        build = _PENDING.get(lib)
    return None if build is None or build.done() else build
