"""Connectors: the ports through which components exchange potentials and flows."""

from __future__ import annotations

from typing import Any

from bearingsim.errors import ModelError
from bearingsim.language.declarations import Declaration, Flow, Potential

__all__ = ["Connector"]


class Connector:
    """Base class of connector types.

    Subclasses declare their fields as class attributes of type :class:`Potential` or
    :class:`Flow`. Each connector instance owns its own symbols; after it is assigned to a component
    attribute its fields read as CasADi symbols (``flange.phi``).

    Parameters
    ----------
    description : str
        What the connector stands for, for the documentation.

    Examples
    --------
    >>> from bearingsim import Connector, Potential, Flow
    >>> class Pin(Connector):
    ...     v = Potential(unit="V", description="electric potential")
    ...     i = Flow(unit="A", description="current into the component")
    """

    _field_decls: dict[str, Declaration] = {}

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        fields = dict(getattr(cls, "_field_decls", {}))
        for key, value in list(vars(cls).items()):
            if isinstance(value, (Potential, Flow)):
                fields[key] = value
        cls._field_decls = fields

    def __init__(self, description: str = ""):
        if not self._field_decls:
            raise ModelError(f"connector type {type(self).__name__} declares no fields")
        self.description = description
        self.owner: Any = None
        self.name: str | None = None
        self.fields: dict[str, Declaration] = {}

    def bind(self, owner: Any, name: str) -> None:
        """Attach to a component under ``name`` and create the field symbols.

        Parameters
        ----------
        owner : Component
            The component.
        name : str
            Attribute name of the connector.

        Raises
        ------
        ModelError
            When the connector already belongs to a component.
        """
        if self.owner is not None:
            raise ModelError(f"connector {self.path} is already part of a component")
        self.owner = owner
        self.name = name
        for key, proto in self._field_decls.items():
            decl = proto.clone()
            setattr(self, key, decl.bind(self, key))
            self.fields[key] = decl

    def guess(self, **values: float) -> None:
        """Start values of potential fields, used as the guesses of the Newton iterations that
        solve them when the assembler finds them algebraic (e.g. a ring displacement in force
        balance).

        Parameters
        ----------
        **values : float
            Field name -> start value [field unit].

        Raises
        ------
        ModelError
            Before the connector belongs to a component, or for a name that is not a potential.
        """
        if self.owner is None:
            raise ModelError(f"{type(self).__name__}.guess: assign the connector to a component "
                             f"first")
        names = [d.attr for d in self.potentials]
        for key, value in values.items():
            if key not in names:
                raise ModelError(f"{self.path}.guess: {key!r} is not a potential of "
                                 f"{type(self).__name__}; potentials: {', '.join(names)}")
            self.fields[key].start = float(value)

    @property
    def path(self) -> str:
        """Dotted name relative to the root.

        Returns
        -------
        str
            The path.
        """
        prefix = self.owner.path if self.owner is not None else ""
        return f"{prefix}.{self.name}" if prefix else str(self.name)

    @property
    def potentials(self) -> list[Declaration]:
        """Potential fields in declaration order.

        Returns
        -------
        list of Declaration
            The potential fields.
        """
        return [d for d in self.fields.values() if isinstance(d, Potential)]

    @property
    def flows(self) -> list[Declaration]:
        """Flow fields in declaration order.

        Returns
        -------
        list of Declaration
            The flow fields.
        """
        return [d for d in self.fields.values() if isinstance(d, Flow)]

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.path}>"
