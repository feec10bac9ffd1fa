"""The flat DAE that the assembler's passes transform.

One :class:`DAE` object travels through the passes. Variables and equations are scalar; each
variable may have a derivative variable (``der(x)``), each equation may be the derivative of
another (index reduction).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca

from bearingsim.errors import StructuralError
from bearingsim.language.symbols import readable

__all__ = ["Var", "Eq", "Param", "Alias", "DAE"]


@dataclass
class Var:
    """A scalar time-varying variable of the flat model."""

    name: str
    sym: ca.SX
    unit: str = "1"
    description: str = ""
    start: float | None = None
    fixed: bool = False
    nominal: float | None = None
    is_input: bool = False
    default: float | None = None
    low: float | None = None
    high: float | None = None
    required: bool = False
    """An input a run must give (:class:`~bearingsim.language.Input` ``required``)."""
    warn_above: float | None = None
    """Input magnitude above which a run warns (e.g. a limiting speed)."""
    limit: str | None = None
    """What ``warn_above`` is: a key of :data:`~bearingsim.input_limits.INPUT_LIMITS`."""
    derivative: Var | None = None
    dummy: bool = False
    """Set when index reduction made this derivative an algebraic (dummy) variable."""
    is_derivative: bool = False

    @property
    def is_state(self) -> bool:
        """Differentiated with a true (non-dummy) derivative.

        Returns
        -------
        bool
            Whether the variable is a state.
        """
        return self.derivative is not None and not self.derivative.dummy

    def __hash__(self) -> int:
        return id(self)

    def __eq__(self, other: object) -> bool:
        return self is other


@dataclass
class Eq:
    """A scalar residual equation ``residual = 0``."""

    residual: ca.SX
    origin: str
    initial: bool = False
    derivative_of: Eq | None = None
    differentiated: Eq | None = None
    text: str = ""
    _symbols: tuple[ca.SX, tuple[str, ...]] | None = field(default=None, init=False,
                                                          repr=False, compare=False)
    """The residual the names below were read from, and the names of its symbols."""

    def symbol_names(self) -> tuple[str, ...]:
        """Names of the symbols in the residual, in ``casadi.symvar`` order; read once per
        residual (a pass that replaces the residual gets the new one's).

        Returns
        -------
        tuple of str
            The symbol names.
        """
        if self._symbols is None or self._symbols[0] is not self.residual:
            self._symbols = (self.residual, tuple(s.name() for s in ca.symvar(self.residual)))
        return self._symbols[1]

    def describe(self) -> str:
        """Origin and readable text, for messages.

        Returns
        -------
        str
            The description.
        """
        body = self.text or readable(self.residual) + " = 0"
        return f"{self.origin or '<root>'}: {body}"

    @property
    def order(self) -> int:
        """How many times this equation was differentiated by index reduction.

        Returns
        -------
        int
            Differentiation order, >= 0.
        """
        n, e = 0, self
        while e.derivative_of is not None:
            n, e = n + 1, e.derivative_of
        return n

    def __hash__(self) -> int:
        return id(self)

    def __eq__(self, other: object) -> bool:
        return self is other


@dataclass
class Param:
    """A free parameter of the flat model."""

    name: str
    sym: ca.SX
    value: float
    unit: str
    description: str
    declaration: object = None


@dataclass(frozen=True)
class Alias:
    """A variable that alias elimination removed: ``value = scale * representative + offset``.

    With ``representative`` None the variable is the constant ``offset`` (and ``scale`` is 0).
    """

    name: str
    """Dotted name of the eliminated variable."""
    scale: float
    representative: Var | None
    offset: float
    unit: str = "1"
    """Unit of the eliminated variable's declaration."""
    description: str = ""
    """Description of the eliminated variable's declaration."""


@dataclass
class DAE:
    """The flat model: flatten builds it, the structural passes transform it in place."""

    vars: list[Var]
    eqs: list[Eq]
    params: list[Param]
    time: ca.SX
    initial_eqs: list[Eq] = field(default_factory=list)
    aliases: dict[str, Alias] = field(default_factory=dict)
    """Eliminated variables by name, each expressed through a remaining variable (or constant)."""
    skipped: list[str] = field(default_factory=list)
    """What pruning dropped, for :attr:`System.skipped`."""

    # ---------------------------------------------------------------- lookups
    def by_name(self) -> dict[str, Var]:
        """Variables by symbol name.

        Returns
        -------
        dict of str to Var
            The variables.
        """
        return {v.sym.name(): v for v in self.vars}

    def incidence(self, eq: Eq, lookup: dict[str, Var] | None = None) -> list[Var]:
        """Variables (not parameters, not time) that appear in an equation.

        Parameters
        ----------
        eq : Eq
            The equation.
        lookup : dict of str to Var, optional
            Variables by symbol name (None: :meth:`by_name`).

        Returns
        -------
        list of Var
            The variables in the equation.
        """
        lookup = lookup if lookup is not None else self.by_name()
        return [lookup[n] for n in eq.symbol_names() if n in lookup]

    @property
    def inputs(self) -> list[Var]:
        """System inputs.

        Returns
        -------
        list of Var
            The inputs.
        """
        return [v for v in self.vars if v.is_input]

    @property
    def states(self) -> list[Var]:
        """Variables integrated by the ODE solver.

        Returns
        -------
        list of Var
            The states.
        """
        return [v for v in self.vars if v.is_state and not v.is_input]

    def unknowns(self) -> list[Var]:
        """Variables the equations must determine: everything but states and inputs.

        Returns
        -------
        list of Var
            The unknowns.
        """
        return [v for v in self.vars if not v.is_state and not v.is_input]

    def check_balance(self, stage: str) -> None:
        """Raise if the number of equations differs from the number of unknowns.

        Parameters
        ----------
        stage : str
            The assembly stage, for the message.
        """
        n_eq, n_unk = len(self.eqs), len(self.unknowns())
        if n_eq != n_unk:
            raise StructuralError(
                f"internal error after pass {stage!r}: {n_eq} equations for {n_unk} unknowns"
            )
