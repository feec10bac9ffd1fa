"""Equations of the members of a component array, derived once and instantiated by substitution.

A row of Z balls holds Z copies of each ball, contact and pocket (``ball[0]`` ... ``ball[Z-1]``,
one :class:`~bearingsim.language.component.ElementArray`). Building each copy's equations runs
the component's Python code again (every CasADi operation from Python costs tens of
microseconds), which made flattening a 6304 row most of a second. When member ``k`` is the
same as member 0 but for its symbols, its equations are member 0's with member 0's symbols
replaced by member ``k``'s: one ``casadi.substitute`` per member instead of re-running the
component code.

"The same but for its symbols" is checked, not assumed; member ``k`` is built by its own code
when any of these fails:

* both subtrees have the same structure (classes; names of sub-components, connectors,
  declarations) and no added equations;
* every other attribute of corresponding components is equal (numbers, strings, flags,
  arrays, containers, shared objects such as a lubricant; a sub-component or connector
  attribute must be the corresponding one; an expression attribute must be member 0's
  expression with member ``k``'s symbols);
* member 0's equations use only symbols of its own subtree and time (an equation reaching
  outside the member, e.g. through ``parent``, could reach something different from member
  ``k``).

Member ``k``'s derivative declarations are created for the variables whose derivatives member
0's equations created, as its own code would have.
"""

from __future__ import annotations

import functools
from collections.abc import Iterator
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.language.component import Component
from bearingsim.language.connector import Connector
from bearingsim.language.declarations import Declaration, Variable
from bearingsim.language.symbols import time

__all__ = ["MemberEquations"]

_STRUCTURE = {"_declarations", "_children", "_connectors", "_connections", "_extra_equations",
              "parent", "name"}
"""Component attributes that hold the instance structure (compared separately)."""

_DEPTH = 16
"""Depth to which expression attributes are compared node by node (``casadi.is_equal``; its
recursion revisits shared nodes, so the depth bounds the work). Deeper expressions count as
different: the member is then built by its own code, never wrongly substituted."""


def _twin_of(comp: Component) -> Component | None:
    """Member 0 of the array ``comp`` is member ``k >= 1`` of, else None."""
    name, parent = comp.name, comp.parent
    if parent is None or not isinstance(name, str) or not name.endswith("]") or "[" not in name:
        return None
    base, index = name[:-1].split("[", 1)
    if index == "0":
        return None
    return parent._children.get(f"{base}[0]")


def _pairs(a: Component, b: Component) -> Iterator[tuple[Component, Component]]:
    """Corresponding components of two subtrees (depth first), assuming the same structure."""
    yield a, b
    for key, child in a._children.items():
        yield from _pairs(child, b._children[key])


def _same_structure(a: Component, b: Component) -> bool:
    if type(a) is not type(b) or a._extra_equations or b._extra_equations:
        return False
    if (list(a._declarations) != list(b._declarations)
            or list(a._connectors) != list(b._connectors)
            or list(a._children) != list(b._children)):
        return False
    if any(type(c) is not type(b._connectors[k]) or list(c.fields) != list(b._connectors[k].fields)
           for k, c in a._connectors.items()):
        return False
    return all(_same_structure(c, b._children[k]) for k, c in a._children.items())


def _declarations(comp: Component) -> Iterator[Declaration]:
    yield from comp._declarations.values()
    for conn in comp._connectors.values():
        yield from conn.fields.values()


class _Correspondence:
    """Member 0's and member k's objects and symbols, side by side."""

    def __init__(self, twin: Component, member: Component):
        self.objects: dict[int, Any] = {}
        self.decls: list[tuple[Declaration, Declaration]] = []
        for a, b in _pairs(twin, member):
            self.objects[id(a)] = b
            for key, conn in a._connectors.items():
                self.objects[id(conn)] = b._connectors[key]
            self.decls += list(zip(_declarations(a), _declarations(b), strict=True))

    @functools.cached_property
    def twin_syms(self) -> ca.SX:
        """Member 0's declared symbols, stacked."""
        return ca.vertcat(*[a.sym for a, _ in self.decls])

    @functools.cached_property
    def member_syms(self) -> ca.SX:
        """Member k's declared symbols, stacked in the same order."""
        return ca.vertcat(*[b.sym for _, b in self.decls])

    def same(self, a: Any, b: Any) -> bool:
        """Whether attribute values ``a`` (member 0) and ``b`` (member k) correspond."""
        if a is b:
            return not isinstance(a, (Component, Connector)) or self.objects.get(id(a)) is b
        if isinstance(a, (Component, Connector)):
            return self.objects.get(id(a)) is b
        if type(a) is not type(b):
            return False
        if isinstance(a, ca.SX):
            if a.shape != b.shape:
                return False
            mapped = ca.substitute(a, self.twin_syms, self.member_syms)
            return all(ca.is_equal(mapped[i], b[i], _DEPTH) for i in range(b.numel()))
        if isinstance(a, (ca.MX, ca.DM, ca.Function)):
            return False
        if isinstance(a, np.ndarray):
            return a.shape == b.shape and a.dtype == b.dtype and bool(np.array_equal(a, b))
        if isinstance(a, (list, tuple)):
            return len(a) == len(b) and all(self.same(x, y) for x, y in zip(a, b, strict=True))
        if isinstance(a, dict):
            return list(a) == list(b) and all(self.same(a[k], b[k]) for k in a)
        try:
            return bool(a == b) is True
        except Exception:  # noqa: BLE001 - incomparable values are not the same
            return False

    def attributes_match(self, twin: Component, member: Component) -> bool:
        for a, b in _pairs(twin, member):
            own_a = {k: v for k, v in vars(a).items() if k not in _STRUCTURE}
            own_b = {k: v for k, v in vars(b).items() if k not in _STRUCTURE}
            if list(own_a) != list(own_b):
                return False
            declared = {k for k in a._declarations}
            for key, value in own_a.items():
                if key in declared:
                    continue  # the declaration's symbol: corresponds by construction
                if not self.same(value, own_b[key]):
                    return False
        return True


class MemberEquations:
    """Residuals of the components of a flattening, member k's from member 0's when they
    correspond (module docstring); one instance per flattening.

    Parameters
    ----------
    enabled : bool
        ``False``: every component is built by its own code (for comparisons).
    """

    def __init__(self, enabled: bool = True) -> None:
        self.enabled = enabled
        self._residuals: dict[int, list[ca.SX]] = {}
        self._derivatives: dict[int, set[int]] = {}
        self._instantiated: dict[int, dict[int, list[ca.SX]]] = {}
        self._stacked: dict[int, ca.SX | None] = {}
        self._old: dict[tuple[int, tuple[int, ...]], ca.SX] = {}
        self.instantiated = 0
        """How many components got their equations by substitution."""

    def begin(self, comp: Component) -> None:
        """Note which derivatives exist before ``comp``'s (an array member 0's) equations.

        Parameters
        ----------
        comp : Component
            An array's member 0.
        """
        if comp.name is not None and str(comp.name).endswith("[0]"):
            self._derivatives[id(comp)] = {
                id(d) for c, _ in _pairs(comp, comp) for d in _declarations(c)
                if isinstance(d, Variable) and d.derivative is not None}

    def record(self, comp: Component, residuals: list[ca.SX]) -> None:
        """Keep the residuals of a component built by its own code.

        Parameters
        ----------
        comp : Component
            The component.
        residuals : list of casadi.SX
            Its residuals.
        """
        self._residuals[id(comp)] = residuals

    def instantiate(self, comp: Component) -> list[ca.SX] | None:
        """``comp``'s residuals by substitution from its array's member 0, or None when it must
        be built by its own code.

        Parameters
        ----------
        comp : Component
            An array member.

        Returns
        -------
        list of casadi.SX or None
            The residuals, or None.
        """
        if not self.enabled:
            return None
        found = self._instantiated.get(id(comp))
        if found is not None:
            return found.pop(id(comp), None)
        twin = _twin_of(comp)
        if twin is None or id(twin) not in self._derivatives:
            return None
        per_comp = self._substituted(twin, comp)
        if per_comp is None:
            return None
        for _, b in _pairs(twin, comp):
            self._instantiated[id(b)] = per_comp
        self.instantiated += len(per_comp)
        return per_comp.pop(id(comp))

    def _substituted(self, twin: Component, member: Component) -> dict[int, list[ca.SX]] | None:
        if not _same_structure(twin, member):
            return None
        pairs = list(_pairs(twin, member))
        if any(id(a) not in self._residuals for a, _ in pairs):
            return None
        corr = _Correspondence(twin, member)
        if not corr.attributes_match(twin, member):
            return None
        before = self._derivatives[id(twin)]
        created = [b for a, b in corr.decls
                   if isinstance(a, Variable) and a.derivative is not None
                   and id(a) not in before]
        stacked = self._stacked_residuals(twin, corr)
        if stacked is None:
            return None
        for b in created:
            b.derivative_symbol()
        derivs = tuple(i for i, (a, b) in enumerate(corr.decls)
                       if isinstance(a, Variable) and a.derivative is not None
                       and b.derivative is not None)
        if (id(twin), derivs) not in self._old:  # member 0's side, the same for most members
            self._old[(id(twin), derivs)] = ca.vertcat(
                *[a.sym for a, _ in corr.decls], *[corr.decls[i][0].derivative.sym for i in derivs])
        old = self._old[(id(twin), derivs)]
        new = ca.vertcat(*[b.sym for _, b in corr.decls],
                         *[corr.decls[i][1].derivative.sym for i in derivs])
        values = ca.vertsplit(ca.substitute(stacked, old, new))
        out, pos = {}, 0
        for a, b in pairs:
            n = len(self._residuals[id(a)])
            out[id(b)] = values[pos:pos + n]
            pos += n
        return out

    def _stacked_residuals(self, twin: Component, corr: _Correspondence) -> ca.SX | None:
        """Member 0's residuals stacked, or None when there are none or they use a symbol from
        outside member 0's subtree (and time); worked out once per array."""
        if id(twin) not in self._stacked:
            own = {a.sym.name() for a, _ in corr.decls}
            own |= {a.derivative.sym.name() for a, _ in corr.decls
                    if isinstance(a, Variable) and a.derivative is not None}
            own.add(time.name())
            residuals = [r for a, _ in _pairs(twin, twin) for r in self._residuals[id(a)]]
            stacked = ca.vertcat(*residuals) if residuals else None
            if stacked is not None and any(s.name() not in own for s in ca.symvar(stacked)):
                stacked = None
            self._stacked[id(twin)] = stacked
        return self._stacked[id(twin)]
