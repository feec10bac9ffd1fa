"""Assembled systems kept on disk: a model whose structure was assembled before loads instead
of re-assembling (the 270-state nested double-layer bearing: ~11 s to assemble).

An entry is keyed by the model's *structure* and the *code version*
(:mod:`~bearingsim.assembler.fingerprint`):

* the structure is a hash over the instance tree (component classes, names, declarations with
  their units, ranges and start values, connections, and every other attribute, e.g. geometry
  numbers and option strings) **without parameter values**, plus the requested outputs and
  the assembler options; a parameter given another value hits the same entry, and the loaded
  system takes the values (and range checks) of the component it is loaded for;
* the code version is a hash over bearingsim's own source files and the CasADi, NumPy and
  Python versions: any edit of the package starts a new set of entries.

An entry is written atomically (a temporary file renamed into place) as a magic line, the
SHA-256 of the payload and the payload; one whose magic, checksum, format, key or code version
does not match is removed and the model re-assembled, never loaded. The payload holds the
CasADi functions serialized (``Function.serialize``): the right-hand side, observed and output
functions (their Jacobians are rebuilt on first use, as after an assembly), the mapped
per-ball kernels and everything else of the :class:`~bearingsim.assembler.System` as plain
data.

The entries live in ``<root>/systems`` with ``root`` from ``BEARINGSIM_CACHE`` (default
``~/.cache/bearingsim``), the same root as the compiled kernel libraries. The cache keeps to
a size budget with them (:mod:`bearingsim.cache_budget`): an entry loaded is marked used, and
storing one removes the least recently used entries beyond the budget.
"""

from __future__ import annotations

import dataclasses
import hashlib
import pickle
import shutil
import time
import warnings
from collections.abc import Callable, Mapping
from functools import partial
from pathlib import Path
from typing import Any

import casadi as ca

from bearingsim.assembler.dae import Param
from bearingsim.assembler.fingerprint import FORMAT, code_version, structure_key
from bearingsim.assembler.mapped import MappedKernel
from bearingsim.assembler.mapped_forms import MappedForms
from bearingsim.assembler.mapped_parts import NotMappable
from bearingsim.assembler.passes.codegen import GRAPH_KEYS, JACOBIANS
from bearingsim.assembler.system import FunctionTable, System
from bearingsim.cache_budget import budget_bytes, keep_to_budget, mark_used
from bearingsim.cache_paths import (
    KERNEL_NAMES,
    SWEEP_PRELOADS,
    SYSTEM_SUFFIX,
    cache_root,
    library_files,
    system_files,
    systems_dir,
)
from bearingsim.errors import CacheWarning
from bearingsim.files import atomic_path, os_reason
from bearingsim.language.component import Component
from bearingsim.language.declarations import Parameter
from bearingsim.units.registry import PINT_CACHE

__all__ = ["CacheInfo", "assemble_cached", "cache_info", "clear_cache",
           "dumps_system", "loads_system", "read_payload"]

MAGIC = b"bearingsim-system\n"
"""First bytes of an entry file."""


# --------------------------------------------------------------------------- (de)serializing
def _detached(decl: Any) -> Any:
    """A copy of a parameter declaration without its instance tree (range checks and messages
    unchanged: its path becomes its name)."""
    if not isinstance(decl, Parameter):
        return None
    copy = decl.clone()
    copy.attr = decl.path
    copy.binding = None
    return copy


def dumps_system(system: System) -> bytes:
    """A system as bytes (pickle of plain data, CasADi functions serialized).

    Builds what a loaded system cannot rebuild by itself: the right-hand side, observed and
    output functions (one shared common subexpression elimination) and the mapped per-ball
    kernels of both forms. The Jacobians are left to be built on first use.

    Parameters
    ----------
    system : System
        An assembled system.

    Returns
    -------
    bytes
        The serialized system.
    """
    data: dict[str, Any] = {}
    skip = {"functions", "params", "mapped", "init_residual", "symbolic_functions",
            "content_key"}
    for f in dataclasses.fields(System):
        if f.name not in skip:
            data[f.name] = getattr(system, f.name)
    table = system.functions
    ready = {k: table[k] for k in table
             if k in GRAPH_KEYS or not isinstance(table, FunctionTable) or table.built(k)}
    data["functions"] = {k: f.serialize() for k, f in ready.items()}
    data["rebuilt"] = [k for k in JACOBIANS if k in table and k not in ready]
    data["params"] = [(q.name, float(q.value), q.unit, q.description, _detached(q.declaration))
                      for q in system.params]
    data["mapped"] = system.mapped.to_data() if system.mapped is not None else None
    data["init_residual"] = (system.init_residual.serialize()
                             if system.init_residual is not None else None)
    if system.symbolic_functions is not None:
        raise ValueError("dumps_system: a compiled system (symbolic_functions set) is not "
                         "cached; cache the assembled one")
    return pickle.dumps(data, protocol=pickle.HIGHEST_PROTOCOL)


class _LoadedForms(MappedForms):
    """Mapped kernels of a loaded system, deserialized on first request per form."""

    def __init__(self, data: dict):
        super().__init__(None, None, None)
        self.summary = data["summary"]
        self._serialized = data["forms"]

    def get(self, form: str) -> MappedKernel:
        if form not in self._built and form in self._serialized:
            value = self._serialized[form]
            self._built[form] = (NotMappable(value) if isinstance(value, str) else MappedKernel(
                *[ca.Function.deserialize(v) for v in value]))
        return super().get(form)


def _jacobian(function: Callable[[str], ca.Function], name: str, of: str, wrt_index: int,
              out_name: str) -> ca.Function:
    """``d of(t, x, u, p) / d (x or u)`` as a function of (t, x, u, p), built from a loaded
    function (``function(of)``) like the assembler builds it from the shared graph."""
    of = function(of)
    sym = ca.SX if of.is_a("SXFunction") else ca.MX
    args = [sym.sym(n, of.size1_in(k), of.size2_in(k)) for k, n in enumerate("txup")]
    return ca.Function(name, args, [ca.jacobian(of(*args), args[wrt_index])],
                       list("txup"), [out_name])


def loads_system(payload: bytes, parameters: Mapping[str, Parameter] | None = None,
                 content_key: str | None = None) -> System:
    """The :class:`System` of :func:`dumps_system` bytes.

    Parameters
    ----------
    payload : bytes
        From :func:`dumps_system` (trusted: checked by the cache before).
    parameters : mapping, optional
        Parameter declarations by dotted path (of the component the system is loaded for):
        their values and range checks replace the stored ones.
    content_key : str, optional
        The SHA-256 (hex) of ``payload`` when the caller has it already (None: computed).

    Returns
    -------
    System
        The loaded system, its ``content_key`` the SHA-256 of ``payload``.
    """
    data = pickle.loads(payload)  # noqa: S301 - checksummed entries of the user's own cache
    pending = {k: partial(ca.Function.deserialize, v) for k, v in data.pop("functions").items()}
    wrt = {"x": 1, "u": 2}

    def function(name: str) -> ca.Function:
        return table[name]

    for k in data.pop("rebuilt"):
        of, by, out = JACOBIANS[k]
        pending[k] = partial(_jacobian, function, k, of, wrt[by], out)
    table = FunctionTable({}, pending)
    params = []
    live = parameters or {}
    for name, value, unit, description, decl in data.pop("params"):
        own = live.get(name)
        if own is not None and own.value is not None:
            value, decl = float(own.value), own
        params.append(Param(name, ca.SX.sym(name), value, unit, description, decl))
    mapped = data.pop("mapped")
    init_residual = data.pop("init_residual")
    return System(**data, functions=table, params=params,
                  mapped=_LoadedForms(mapped) if mapped is not None else None,
                  init_residual=(ca.Function.deserialize(init_residual)
                                 if init_residual is not None else None),
                  content_key=content_key or hashlib.sha256(payload).hexdigest())


# --------------------------------------------------------------------------- entries
def _entry(key: str, root: str | Path | None) -> Path:
    return systems_dir(root) / f"{key}{SYSTEM_SUFFIX}"


def _value_dependent(system: System) -> dict[str, float] | None:
    """The parameter values the structure was chosen at, when it depends on them: index
    reduction picks dummy derivatives from the Jacobian at the start point (parameter values
    included); None otherwise."""
    if "index reduction" not in system.report:
        return None
    return {q.name: float(q.value) for q in system.params}


def _write_entry(path: Path, key: str, payload: bytes, values: dict | None) -> None:
    body = pickle.dumps({"format": FORMAT, "key": key, "code": code_version(),
                         "values": values, "payload": payload},
                        protocol=pickle.HIGHEST_PROTOCOL)
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp:
        tmp.write_bytes(MAGIC + hashlib.sha256(body).digest() + body)


def _read_entry(path: Path, key: str, values: dict[str, float]) -> bytes | None:
    """The payload of a valid entry; None (and the file removed) for a missing, stale or
    corrupt one, or one whose structure was chosen at other parameter ``values``."""
    try:
        raw = path.read_bytes()
    except OSError:  # missing, or a cache folder that cannot be read: assembled instead
        return None
    head = len(MAGIC) + 32
    body = raw[head:]
    valid = raw[:len(MAGIC)] == MAGIC and raw[len(MAGIC):head] == hashlib.sha256(body).digest()
    entry = None
    if valid:
        try:
            entry = pickle.loads(body)  # noqa: S301 - checksum verified above
        except Exception:  # noqa: BLE001 - any undecodable entry is rebuilt
            entry = None
    if (not isinstance(entry, dict) or entry.get("format") != FORMAT or entry.get("key") != key
            or entry.get("code") != code_version()
            or (entry.get("values") is not None
                and any(values.get(n, v) != v for n, v in entry["values"].items()))):
        path.unlink(missing_ok=True)
        return None
    mark_used(path)
    return entry["payload"]


def read_payload(path: str | Path, key: str) -> bytes | None:
    """The system bytes (:func:`dumps_system`) of a valid entry, or None (see
    :data:`LAST` for the path and key of the last lookup).

    Parameters
    ----------
    path : str or os.PathLike
        The entry's file.
    key : str
        Expected cache key (:func:`structure_key`).

    Returns
    -------
    bytes or None
        The payload, or None for a missing, stale or damaged entry.
    """
    return _read_entry(Path(path), key, {})


def _parameter_declarations(component: Component) -> dict[str, Parameter]:
    return {decl.path: decl for comp in component.walk()
            for decl in comp.declarations.values() if isinstance(decl, Parameter)}


def _assemble(component: Component, outputs: list[str] | None, **options: Any) -> System:
    """:func:`~bearingsim.assembler.assemble`, imported on use: the passes and networkx take
    ~0.5 s to import, and a model loaded from the cache needs none of them."""
    from bearingsim.assembler.pipeline import assemble

    return assemble(component, outputs, **options)


LAST: dict[str, Any] = {}
"""What the last :func:`assemble_cached` call of this process did: ``hit`` (bool), ``key``,
``path``, ``seconds`` (for reports and tests)."""


def assemble_cached(component: Component, outputs: list[str] | None = None, *,
                    cache: bool = True, cache_dir: str | Path | None = None,
                    **options: Any) -> System:
    """:func:`~bearingsim.assembler.assemble` through the on-disk cache.

    Parameters
    ----------
    component : Component
        The model.
    outputs : list of str, optional
        As for ``assemble``.
    cache : bool
        Look up and store the entry; False: assemble only.
    cache_dir : path, optional
        Root of the cache (default :func:`~bearingsim.cache_paths.cache_root`).
    **options
        Keywords of ``assemble`` (``newton_tol``, ``rootfinder``); with ``extra_passes`` the
        model is assembled and not cached (user passes are not part of the key).

    Returns
    -------
    System
        Loaded (a hit: ``system.report["cache"]`` says so, ``system.timings`` holds the load
        time) or assembled and stored.
    """
    if not cache or options.get("extra_passes"):
        return _assemble(component, outputs, **options)
    t0 = time.perf_counter()
    key = structure_key(component, outputs, **options)
    path = _entry(key, cache_dir)
    declarations = _parameter_declarations(component)
    payload = _read_entry(path, key, {n: d.value for n, d in declarations.items()})
    if payload is not None:
        try:
            system = loads_system(payload, declarations)
        except Exception:  # noqa: BLE001 - an entry that does not load is rebuilt
            path.unlink(missing_ok=True)
        else:
            seconds = time.perf_counter() - t0
            system.report = {**system.report, "cache": f"loaded {path.name} in {seconds:.2f} s"}
            system.timings = [("cache load", seconds)]
            LAST.update(hit=True, key=key, path=path, seconds=seconds)
            return system
    budget = budget_bytes()  # a budget that is not a size stops before the assembly
    system = _assemble(component, outputs, **options)
    try:
        _write_entry(path, key, dumps_system(system), _value_dependent(system))
        keep_to_budget(path.parent.parent, path, budget)
    except OSError as exc:  # a read-only or full cache costs the next run an assembly
        _warn_unwritable(path.parent.parent, exc)
    LAST.update(hit=False, key=key, path=path, seconds=time.perf_counter() - t0)
    return system


_UNWRITABLE: set[Path] = set()
"""The cache roots this process has warned about (:func:`_warn_unwritable`)."""


def _warn_unwritable(root: Path, exc: OSError) -> None:
    """Say once per process and cache root that nothing can be kept there, and why."""
    if root in _UNWRITABLE:
        return
    _UNWRITABLE.add(root)
    warnings.warn(f"the cache {root} cannot be written ({os_reason(exc)}): assembled systems "
                  "are not kept, so every run assembles anew; set $BEARINGSIM_CACHE to a "
                  "writable folder", CacheWarning, stacklevel=3)


# --------------------------------------------------------------------------- housekeeping
@dataclasses.dataclass
class CacheInfo:
    """What the cache holds: its root, the assembled systems, the compiled libraries and the
    units library's parsed definitions."""

    root: Path
    systems: int
    systems_bytes: int
    libraries: int
    libraries_bytes: int
    units_bytes: int


def _size(path: Path) -> int:
    if path.is_dir():
        return sum(f.stat().st_size for f in path.rglob("*") if f.is_file())
    return path.stat().st_size


def cache_info(root: str | Path | None = None) -> CacheInfo:
    """Count and size [bytes] of the cached systems and libraries, and the size of the parsed
    unit definitions, under ``root``.

    Parameters
    ----------
    root : str or os.PathLike, optional
        Cache root (None: :func:`~bearingsim.cache_paths.cache_root`).

    Returns
    -------
    CacheInfo
        Counts and sizes [bytes].
    """
    root = Path(root) if root is not None else cache_root()
    systems = system_files(root)
    libs = library_files(root)
    units = root / PINT_CACHE
    return CacheInfo(root, len(systems), sum(_size(p) for p in systems), len(libs),
                     sum(_size(p) for p in libs), _size(units) if units.is_dir() else 0)


def clear_cache(root: str | Path | None = None) -> CacheInfo:
    """Remove every cached system, compiled library (and the remembered library names) and the
    parsed unit definitions under ``root``; returns what was there. Other files in the folder
    are left alone.

    Parameters
    ----------
    root : str or os.PathLike, optional
        Cache root (None: :func:`~bearingsim.cache_paths.cache_root`).

    Returns
    -------
    CacheInfo
        What was there before.
    """
    root = Path(root) if root is not None else cache_root()
    before = cache_info(root)
    if systems_dir(root).is_dir():
        shutil.rmtree(systems_dir(root))
    for p in [*library_files(root), root / KERNEL_NAMES, root / SWEEP_PRELOADS,
              root / PINT_CACHE]:
        if p.is_dir():
            shutil.rmtree(p, ignore_errors=True)
        else:
            p.unlink(missing_ok=True)
    return before
