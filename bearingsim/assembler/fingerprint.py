"""The key of an assembled system in the on-disk cache (:mod:`~bearingsim.assembler.cache`):
the model's *structure* and the *code version*.

* :func:`structure_key` hashes the instance tree (component classes, names, declarations with
  their units, ranges and start values, connections, and every other attribute, e.g. geometry
  numbers and option strings) **without parameter values**, plus the requested outputs, the
  assembler options and the code version; objects are walked by a deterministic fingerprint
  of the object graph (CasADi symbols numbered in order of appearance, objects seen before as
  back references);
* :func:`code_version` hashes bearingsim's own source files and the CasADi, NumPy and Python
  versions and the payload :data:`FORMAT`: any edit of the package starts a new set of entries.
"""

from __future__ import annotations

import enum
import functools
import hashlib
import re
import sys
import types
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.language.component import Component
from bearingsim.language.declarations import Declaration, Parameter

__all__ = ["FORMAT", "code_version", "structure_key"]

FORMAT = 1
"""Version of the payload layout (part of every entry)."""


@functools.cache
def code_version() -> str:
    """Hash of bearingsim's source files (paths and contents) and the CasADi, NumPy and Python
    versions: entries written by other code are never loaded.

    Returns
    -------
    str
        The hash (hex).
    """
    package = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        digest.update(str(path.relative_to(package)).encode())
        digest.update(path.read_bytes())
    digest.update(f"casadi {ca.__version__} numpy {np.__version__} python "
                  f"{sys.version_info[:3]} format {FORMAT}".encode())
    return digest.hexdigest()


_DECLARATION_SKIP = frozenset({"owner", "sym", "_value", "_derivative", "integral", "binding"})
"""Declaration attributes that are not structure: back references, symbols, parameter values
(``binding``, an expression, is added separately)."""


_PLAIN = frozenset({type(None), bool, int, float, str, bytes, complex})
"""Types hashed by their ``repr`` (which tells them apart: ``1``, ``1.0``, ``True``, ``'1'``)."""
_PARENT = frozenset({"parent"})


class _Fingerprint:
    """A deterministic hash of an object graph; objects seen before hash as a back reference."""

    def __init__(self) -> None:
        self.parts: list[str] = []
        self.seen: dict[int, int] = {}
        self.symbols: dict[str, str] = {}
        self.keep: list[Any] = []  # ids stay unique while the walk runs

    def text(self, *parts: Any) -> None:
        self.parts.extend(map(str, parts))

    def casadi(self, expr: ca.SX | ca.MX) -> None:
        """A symbol or expression with its symbols numbered in order of appearance (their
        names carry a process-wide counter: ``J__2`` in one build is ``J__28`` in the next)."""
        if expr.is_symbolic() and expr.numel() == 1:
            self.parts.append(self._symbol(expr.name()))
            return
        names = {s.name(): self._symbol(s.name()) for s in ca.symvar(expr)}
        text = str(expr)
        if names:
            pattern = re.compile(r"\b(" + "|".join(map(re.escape, sorted(names, key=len,
                                                                           reverse=True)))
                                 + r")\b")
            text = pattern.sub(lambda m: names[m.group(0)], text)
        self.text("expr", expr.shape, text)

    def _symbol(self, name: str) -> str:
        return self.symbols.setdefault(name, f"sym{len(self.symbols)}")

    def hexdigest(self) -> str:
        return hashlib.sha256("\x00".join(self.parts).encode()).hexdigest()

    def fields(self, state: dict[str, Any], skip: frozenset[str] | set[str] = frozenset()
               ) -> None:
        """Attributes by name (plain values inline: this is the hot loop of a large tree)."""
        parts = self.parts
        for name in sorted(state):
            if name in skip:
                continue
            value = state[name]
            parts.append(name)
            if type(value) in _PLAIN:
                parts.append(repr(value))
            else:
                self.feed(value)

    def feed(self, obj: Any) -> None:
        if type(obj) in _PLAIN:
            self.parts.append(repr(obj))
            return
        if isinstance(obj, (ca.SX, ca.MX)):
            self.casadi(obj)
            return
        if isinstance(obj, ca.DM):
            self.text("DM", obj.shape, str(obj))
            return
        if isinstance(obj, np.generic):
            self.text("np", obj.dtype, repr(obj.item()))
            return
        key = id(obj)
        if key in self.seen:
            self.text("ref", self.seen[key])
            return
        self.seen[key] = len(self.seen)
        self.keep.append(obj)
        if isinstance(obj, np.ndarray):
            self.text("array", obj.dtype, obj.shape,
                      hashlib.sha256(np.ascontiguousarray(obj).tobytes()).hexdigest())
        elif isinstance(obj, Declaration):
            self.text("decl", type(obj).__qualname__)
            self.fields(vars(obj), _DECLARATION_SKIP)
            if isinstance(obj, Parameter):
                self.text("bound" if obj.binding is not None else "free")
                if obj.binding is not None:
                    self.feed(obj.binding)
        elif isinstance(obj, type):
            self.text("class", obj.__module__, obj.__qualname__)
        elif isinstance(obj, types.ModuleType):  # its code is in the code version
            self.text("module", obj.__name__)
        elif isinstance(obj, types.CodeType):
            self.text("code", obj.co_name, obj.co_names, obj.co_code.hex())
            self.feed(obj.co_consts)
        elif isinstance(obj, enum.Enum):
            self.text("enum", type(obj).__qualname__, obj.name)
        elif isinstance(obj, Mapping):
            self.text("map", type(obj).__qualname__, len(obj))
            for k in sorted(obj, key=repr):
                self.feed(k)
                self.feed(obj[k])
        elif isinstance(obj, (list, tuple)):
            self.text("seq", type(obj).__qualname__, len(obj))
            for item in obj:
                self.feed(item)
        elif isinstance(obj, (set, frozenset)):
            self.text("set", sorted(repr(item) for item in obj))
        elif isinstance(obj, (functools.partial,)):
            self.text("partial")
            self.feed(obj.func)
            self.feed(obj.args)
            self.feed(obj.keywords)
        elif callable(obj) and hasattr(obj, "__qualname__") and not hasattr(obj, "__dict__"):
            self.text("callable", getattr(obj, "__module__", ""), obj.__qualname__)
        elif hasattr(obj, "__code__"):  # a Python function: its code and the values it closes
            self.text("function", obj.__module__, obj.__qualname__)
            self.feed(obj.__code__)
            for cell in obj.__closure__ or ():
                try:
                    self.feed(cell.cell_contents)
                except ValueError:  # an empty cell
                    self.text("empty cell")
            self.feed(obj.__defaults__)
        elif hasattr(obj, "__dict__") or hasattr(type(obj), "__slots__"):
            cls = type(obj)
            self.text("object", cls.__module__, cls.__qualname__)
            state = dict(getattr(obj, "__dict__", {}))
            for slot in getattr(cls, "__slots__", ()):
                if hasattr(obj, slot):
                    state[slot] = getattr(obj, slot)
            # the tree is walked from its root
            self.fields(state, _PARENT if isinstance(obj, Component) else frozenset())
        else:  # no state to read: its text (an address in it only costs a cache miss)
            self.text("repr", type(obj).__qualname__, repr(obj))


def structure_key(component: Component, outputs: list[str] | None = None,
                  **options: Any) -> str:
    """The cache key of assembling ``component``: its structure without parameter values,
    the outputs, the assembler options and :func:`code_version` (SHA-256, hex).

    Parameters
    ----------
    component : Component
        The root component to assemble.
    outputs : list of str, optional
        Requested outputs (None: every variable).
    **options
        The assembler options.

    Returns
    -------
    str
        SHA-256 hex digest.
    """
    fp = _Fingerprint()
    fp.text("outputs", None if outputs is None else list(outputs))
    fp.text("options", sorted(options.items()))
    fp.text("code", code_version())
    fp.feed(component)
    return fp.hexdigest()
