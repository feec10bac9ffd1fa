"""Components and assemblies: declarations, sub-components, connections and equations."""

from __future__ import annotations

import functools
from collections.abc import Iterable
from typing import Any

import casadi as ca

from bearingsim.checks import check_identifier
from bearingsim.errors import ConnectionError_, ModelError
from bearingsim.language.connector import Connector
from bearingsim.language.declarations import Declaration, Parameter
from bearingsim.language.symbols import time

__all__ = ["Component", "Assembly", "connect", "ElementArray"]

_building: list[Component] = []


class ElementArray(tuple):
    """An array of sub-components or connectors (``self.ball[3]``), named ``name[i]``."""


class Component:
    """Base class of all models.

    A subclass declares, in ``__init__`` after ``super().__init__()``, its parameters
    (:class:`~bearingsim.Parameter`), variables (:class:`~bearingsim.Variable`), inputs, connectors
    and sub-components by assigning them to attributes, and returns its equations from
    :meth:`equations`. Equations are CasADi expressions ``lhs == rhs`` or residuals ``expr`` (= 0).

    Assigning a number to an attribute that holds a parameter changes its value (a modifier);
    the value is checked against the parameter's range.

    Parameters
    ----------
    name : str, optional
        Name of a root component (sub-components take their attribute name).
    """

    needs_line_search: bool = False
    """Whether the component's nonlinear equations need a Newton method with a line search
    (the assembler then picks CasADi's ``newton`` rootfinder over ``fast_newton``)."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        init = cls.__dict__.get("__init__")
        if init is None:
            return

        @functools.wraps(init)
        def wrapped(self, *args, **kw):
            _building.append(self)
            try:
                init(self, *args, **kw)
            finally:
                _building.pop()

        cls.__init__ = wrapped

    def __init__(self, name: str | None = None):
        object.__setattr__(self, "_declarations", {})
        object.__setattr__(self, "_children", {})
        object.__setattr__(self, "_connectors", {})
        object.__setattr__(self, "_connections", [])
        object.__setattr__(self, "_extra_equations", [])
        object.__setattr__(self, "parent", None)
        if name is not None:
            check_identifier(name, "name", type(self).__name__)
        object.__setattr__(self, "name", name)

    # ------------------------------------------------------------------ declarations
    def __setattr__(self, key: str, value: Any) -> None:
        if "_declarations" not in self.__dict__:
            raise ModelError(
                f"{type(self).__name__}.__init__ must call super().__init__() before declaring "
                f"{key!r}"
            )
        existing = self._declarations.get(key)
        if isinstance(value, Declaration):
            if existing is not None or key in self._children or key in self._connectors:
                raise ModelError(f"{self._where(key)} is declared twice")
            self._declarations[key] = value
            object.__setattr__(self, key, value.bind(self, key))
        elif isinstance(value, Component):
            self._add_child(key, value)
            object.__setattr__(self, key, value)
        elif isinstance(value, Connector):
            value.bind(self, key)
            self._connectors[key] = value
            object.__setattr__(self, key, value)
        elif _is_element_list(value):
            items = ElementArray(value)
            for i, item in enumerate(items):
                sub = f"{key}[{i}]"
                if isinstance(item, Component):
                    self._add_child(sub, item)
                else:
                    item.bind(self, sub)
                    self._connectors[sub] = item
            object.__setattr__(self, key, items)
        elif isinstance(existing, Parameter):
            if isinstance(value, ca.SX):
                existing.binding = value
            else:
                existing.value = value
        elif existing is not None:
            raise ModelError(
                f"{self._where(key)} is a {type(existing).__name__}; only parameters take new "
                "values after declaration"
            )
        else:
            object.__setattr__(self, key, value)

    def _add_child(self, key: str, child: Component) -> None:
        if child.parent is not None:
            raise ModelError(f"component {child.path} cannot also be {self._where(key)}")
        if child is self:
            raise ModelError(f"{self._where(key)}: a component cannot contain itself")
        object.__setattr__(child, "parent", self)
        object.__setattr__(child, "name", key)
        self._children[key] = child

    def add(self, name: str, element: Any) -> Any:
        """Add a declaration, sub-component or connector under a computed name; return it.

        Parameters
        ----------
        name : str
            Attribute name (an identifier), e.g. ``f"ball_{j}"``.
        element : Declaration or Component or Connector
            The element to add.

        Returns
        -------
        object
            The element as the attribute reads (a declaration reads as its CasADi symbol).
        """
        setattr(self, name, element)
        return getattr(self, name)

    def _where(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    # ------------------------------------------------------------------ structure
    @property
    def path(self) -> str:
        """Dotted name relative to the root ('' for the root).

        Returns
        -------
        str
            The path.
        """
        if self.parent is None:
            return ""
        prefix = self.parent.path
        return f"{prefix}.{self.name}" if prefix else str(self.name)

    @property
    def display_name(self) -> str:
        """Path, or the class name for the root.

        Returns
        -------
        str
            The display name.
        """
        return self.path or (self.name or type(self).__name__)

    @property
    def children(self) -> dict[str, Component]:
        """Direct sub-components by name.

        Returns
        -------
        dict of str to Component
            A copy of the sub-components.
        """
        return dict(self._children)

    @property
    def connectors(self) -> dict[str, Connector]:
        """Own connectors by name.

        Returns
        -------
        dict of str to Connector
            A copy of the connectors.
        """
        return dict(self._connectors)

    @property
    def declarations(self) -> dict[str, Declaration]:
        """Own parameters, variables and inputs by name.

        Returns
        -------
        dict of str to Declaration
            A copy of the declarations.
        """
        return dict(self._declarations)

    def parameter(self, name: str) -> Parameter:
        """The parameter declaration ``name`` of this component.

        Parameters
        ----------
        name : str
            Attribute name of the parameter.

        Returns
        -------
        Parameter
            The declaration.

        Raises
        ------
        KeyError
            When the component has no parameter ``name``.
        """
        decl = self._declarations.get(name)
        if not isinstance(decl, Parameter):
            raise KeyError(f"{self.display_name} has no parameter {name!r}")
        return decl

    def walk(self) -> Iterable[Component]:
        """This component and all its descendants, depth first."""
        yield self
        for child in self._children.values():
            yield from child.walk()

    @property
    def time(self) -> ca.SX:
        """The time symbol t [s].

        Returns
        -------
        casadi.SX
            The shared time symbol.
        """
        return time

    # ------------------------------------------------------------------ equations
    def equations(self) -> Iterable[Any]:
        """Equations of this component (override). ``lhs == rhs`` or residual expressions."""
        return ()

    def initial_equations(self) -> Iterable[Any]:
        """Equations that hold at the start time only (override).

        Returns
        -------
        iterable
            Initial equations (none by default).
        """
        return ()

    def add_equation(self, *equations: Any) -> None:
        """Append equations to an ad-hoc component or assembly.

        Parameters
        ----------
        *equations
            Equations (``lhs == rhs`` expressions or connect statements).
        """
        self._extra_equations.extend(equations)

    def all_equations(self) -> list[Any]:
        """Declared plus added equations.

        Returns
        -------
        list
            The equations of :meth:`equations` then those added.
        """
        return list(self.equations()) + list(self._extra_equations)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.display_name}>"


class Assembly(Component):
    """A component made of connected sub-components; assemblies nest like any component."""


def _is_element_list(value: Any) -> bool:
    if not isinstance(value, (list, tuple)) or not value:
        return False
    return all(isinstance(v, Component) for v in value) or all(
        isinstance(v, Connector) for v in value
    )


def _ancestors(component: Component) -> list[Component]:
    chain = []
    node = component
    while node is not None:
        chain.append(node)
        node = node.parent
    return chain


def _connection_scope(connectors: tuple[Connector, ...]) -> Component:
    if _building and all(_is_within(c.owner, _building[-1]) for c in connectors):
        return _building[-1]
    owners = [c.owner for c in connectors]
    if all(o is owners[0] for o in owners):
        if owners[0].parent is None:
            raise ConnectionError_(
                f"connectors {', '.join(c.path for c in connectors)} of the root component "
                "can only be connected to sub-components"
            )
        return owners[0].parent
    common = None
    for anc in _ancestors(owners[0]):
        if all(_is_within(o, anc) for o in owners):
            common = anc
            break
    if common is None:
        raise ConnectionError_(
            "connected components are not in one instance tree: "
            + ", ".join(c.path for c in connectors)
        )
    return common


def _is_within(component: Component, scope: Component) -> bool:
    return any(a is scope for a in _ancestors(component))


def connect(*connectors: Connector) -> None:
    """Connect connectors of the same type (Modelica semantics).

    Potentials of all connectors become equal and their flows sum to zero (flows of the enclosing
    component's own connectors count with the opposite sign). A flow of a sub-component
    connector that is connected nowhere is zero.

    Parameters
    ----------
    *connectors : Connector
        Two or more connectors of one type, owned by the component being built or by its
        descendants.

    Raises
    ------
    ConnectionError_
        If the connectors differ in type or are not part of one instance tree.
    """
    if len(connectors) < 2:
        raise ConnectionError_("connect() needs at least two connectors")
    for c in connectors:
        if not isinstance(c, Connector):
            raise ConnectionError_(f"connect() takes connectors, got {c!r}")
        if c.owner is None:
            raise ConnectionError_(
                f"connect(): a {type(c).__name__} must be assigned to a component before it is "
                "connected"
            )
    kind = type(connectors[0])
    for c in connectors[1:]:
        if type(c) is not kind:
            raise ConnectionError_(
                f"cannot connect {connectors[0].path} ({kind.__name__}) with {c.path} "
                f"({type(c).__name__}): connector types differ"
            )
        for a, b in zip(connectors[0].fields.values(), c.fields.values(), strict=True):
            if a.unit != b.unit:
                raise ConnectionError_(
                    f"unit mismatch connecting {a.path} [{a.unit}] with {b.path} [{b.unit}]"
                )
    scope = _connection_scope(connectors)
    scope._connections.append(tuple(connectors))


def flow_sign(connector: Connector, scope: Component) -> float:
    """+1 for a connector of a sub-component (inside), -1 for the scope's own (outside).

    Parameters
    ----------
    connector : Connector
        A connector in a connect statement.
    scope : Component
        The component whose equations hold the statement.

    Returns
    -------
    float
        +1.0 or -1.0.
    """
    return -1.0 if connector.owner is scope else 1.0
