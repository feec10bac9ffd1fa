"""Declarations: variables, parameters, inputs and connector fields.

A declaration is created in a component's ``__init__`` (or a connector's class body) and bound to
its owner when assigned to an attribute; from then on the attribute reads as the CasADi symbol.
"""

from __future__ import annotations

import math
from typing import Any

import casadi as ca

from bearingsim.errors import ModelError, ParameterError
from bearingsim.input_limits import INPUT_LIMITS
from bearingsim.language.symbols import new_symbol
from bearingsim.units import is_quantity, quantity_to_si
from bearingsim.units.fmi import derivative_unit
from bearingsim.validation import check_range

__all__ = [
    "Declaration",
    "Variable",
    "Parameter",
    "Input",
    "Potential",
    "Flow",
]


class Declaration:
    """Base of everything that becomes a scalar symbol.

    Parameters
    ----------
    unit : str
        SI unit, e.g. ``"rad/s"``.
    description : str
        One line for documentation, errors and FMU model descriptions.
    """

    is_constant_in_time = False

    def __init__(self, unit: str = "1", description: str = ""):
        self.unit = unit
        self.description = description
        self.owner: Any = None
        self.attr: str | None = None
        self.sym: ca.SX | None = None

    def bind(self, owner: Any, attr: str) -> ca.SX:
        """Attach to ``owner`` under ``attr`` and create the symbol.

        Parameters
        ----------
        owner : Component or Connector
            The owner.
        attr : str
            Attribute name of the declaration.

        Returns
        -------
        casadi.SX
            The new symbol.

        Raises
        ------
        ModelError
            When the declaration is already bound.
        """
        if self.owner is not None:
            raise ModelError(
                f"{type(self).__name__} {self.path} is already declared; create a new one for "
                f"{attr!r}"
            )
        self.owner = owner
        self.attr = attr
        self.sym = new_symbol(attr, self)
        return self.sym

    @property
    def path(self) -> str:
        """Dotted name relative to the root of the instance tree.

        Returns
        -------
        str
            The path.
        """
        prefix = self.owner.path if self.owner is not None else ""
        return f"{prefix}.{self.attr}" if prefix else str(self.attr)

    def clone(self) -> Declaration:
        """An unbound copy with the same attributes (used for connector instances).

        Returns
        -------
        Declaration
            The copy.
        """
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        new.owner = None
        new.attr = None
        new.sym = None
        return new


class Variable(Declaration):
    """A continuous time-varying variable.

    A variable becomes a state when its derivative appears in an equation (``der(x)``) and the
    assembler selects it; all others are algebraic.

    Parameters
    ----------
    start : float, optional
        Initial value of a state, or the guess of an algebraic variable.
    unit, description : str
        As for :class:`Declaration`.
    fixed : bool, optional
        Whether ``start`` is an initial condition. Defaults to True when ``start`` is given.
    nominal : float, optional
        Typical magnitude, used for scaling tolerances.
    """

    def __init__(
        self,
        start: float | None = None,
        unit: str = "1",
        description: str = "",
        *,
        fixed: bool | None = None,
        nominal: float | None = None,
    ):
        super().__init__(unit, description)
        if start is not None:
            start = float(check_range(start, "start", unit, where=description or "variable"))
        self.start = start
        self.fixed = (start is not None) if fixed is None else bool(fixed)
        self.nominal = nominal
        self._derivative: Variable | None = None
        self.integral: Variable | None = None

    @classmethod
    def each(cls, unit: str, *descriptions: str) -> tuple[Variable, ...]:
        """One declaration of this kind per description, all in ``unit``: the components of a
        vector declared at once, in order (``x, y = Potential.each("m", "x", "y")``).

        Parameters
        ----------
        unit : str
            Unit of every declaration.
        *descriptions : str
            One description per declaration.

        Returns
        -------
        tuple of Variable
            Instances of the class it is called on, without start values.
        """
        return tuple(cls(unit=unit, description=d) for d in descriptions)

    def derivative_symbol(self) -> ca.SX:
        """The symbol of ``der(self)``, created on first use.

        Returns
        -------
        casadi.SX
            The derivative's symbol [unit/s].

        Raises
        ------
        ModelError
            For a variable that is not declared yet.
        """
        if self.sym is None:
            raise ModelError(f"der() of an undeclared variable {self.attr!r}")
        if self._derivative is None:
            d = Variable(unit=derivative_unit(self.unit),
                         description=f"time derivative of {self.attr}")
            d.integral = self
            d.owner = self.owner
            d.attr = f"der({self.attr})"
            d.sym = new_symbol(f"der_{self.attr.replace('[', '_').replace(']', '_')}", d)
            self._derivative = d
        return self._derivative.sym

    @property
    def derivative(self) -> Variable | None:
        """The derivative declaration, if ``der`` was taken.

        Returns
        -------
        Variable or None
            The derivative, or None.
        """
        return self._derivative

    @property
    def path(self) -> str:
        if self.integral is not None:
            return f"der({self.integral.path})"
        return super().path


class Input(Variable):
    """A causal input signal.

    Inputs of the root component become inputs of the assembled system. Inputs of sub-components
    must be bound by an equation or connection of an enclosing component, unless they have a
    ``default`` value, in which case they become system inputs with that default.

    Parameters
    ----------
    default : float, optional
        Value used when the input is left free; ``None`` makes a sub-component input required.
    unit, description : str
        As for :class:`Declaration`.
    low, high : float, optional
        Valid range, checked on the input signal before a simulation.
    required : bool, optional
        Whether a run must give the input (``simulate``, ``steady_state`` and scenes refuse to
        hold it at its default, e.g. a shaft speed at 0). Default: ``default is None``.
    warn_above : float, optional
        Magnitude [unit] above which a run warns (``limit`` says what this limit is);
        ``low``/``high`` stay the hard bounds.
    limit : str, optional
        The kind of ``warn_above``, a key of :data:`~bearingsim.input_limits.INPUT_LIMITS`
        (``"speed"``: :class:`~bearingsim.errors.SpeedLimitWarning` above a bearing's limiting
        speed; ``"static load"``: :class:`~bearingsim.errors.PlasticDeformationWarning`
        above the load that alone reaches the static load rating); needed with ``warn_above``.
    """

    def __init__(self, default: float | None = None, unit: str = "1", description: str = "",
                 *, low: float | None = None, high: float | None = None,
                 required: bool | None = None, warn_above: float | None = None,
                 limit: str | None = None):
        super().__init__(start=None, unit=unit, description=description, fixed=False)
        self.default = None if default is None else float(
            check_range(default, "default", unit, low, high, where=description or "input"))
        self.low = low
        self.high = high
        self.required = default is None if required is None else bool(required)
        if (warn_above is None) != (limit is None) or (limit is not None
                                                       and limit not in INPUT_LIMITS):
            raise ParameterError(f"{description or 'input'}: warn_above needs a limit, one of "
                                 f"{', '.join(INPUT_LIMITS)} (and a limit needs warn_above); "
                                 f"got warn_above={warn_above!r}, limit={limit!r}")
        self.warn_above = warn_above
        self.limit = limit


class Parameter(Declaration):
    """A constant of the model whose value can change between runs without recompiling.

    Parameters
    ----------
    value : float or casadi.SX
        The value in SI units, or an expression of other parameters (a binding, e.g. a parent
        assembly passing its own parameter down).
    unit, description : str
        As for :class:`Declaration`.
    low, high : float, optional
        Valid range; ``None`` is unbounded.
    low_inclusive, high_inclusive : bool
        Whether the bounds are allowed values.
    """

    is_constant_in_time = True

    def __init__(
        self,
        value: float,
        unit: str = "1",
        description: str = "",
        *,
        low: float | None = None,
        high: float | None = None,
        low_inclusive: bool = True,
        high_inclusive: bool = True,
    ):
        super().__init__(unit, description)
        self.low = low
        self.high = high
        self.low_inclusive = low_inclusive
        self.high_inclusive = high_inclusive
        self.binding: ca.SX | None = None
        if isinstance(value, ca.SX):
            self.binding = value
            self._value = None
        else:
            self._value = self.validate(value, where=description or "parameter")

    @property
    def value(self) -> float:
        """Current value [unit].

        Returns
        -------
        float or None
            The value [unit], None when bound to a symbol.
        """
        return self._value

    @value.setter
    def value(self, new: float) -> None:
        self._value = self.validate(new)
        self.binding = None

    def validate(self, value: Any, where: str | None = None) -> float:
        """Check type and range of a candidate value; return it as float.

        Parameters
        ----------
        value : Any
            The candidate value.
        where : str, optional
            Shown in parentheses after the parameter's name in messages; the constructor passes
            the description, since an unbound parameter has no path yet.

        Returns
        -------
        float
            The value as a float.

        Raises
        ------
        ParameterError
            Naming the parameter path (or, before it is bound, ``value`` and its description),
            unit and valid range.
        """
        name = self.path if self.owner is not None else (self.attr or "value")
        label = f"{name} ({where})" if where else name
        if isinstance(value, str) or is_quantity(value):  # "5 kg", "0.002 kg m^2"
            value = quantity_to_si(value, self.unit, label)
        if isinstance(value, bool) or not isinstance(value, (int, float)) and not hasattr(
            value, "__float__"
        ):
            raise ParameterError(
                f"{label} must be a real number in "
                f"[{self.unit}], got {value!r} of type {type(value).__name__}"
            )
        value = float(value)
        if math.isnan(value):
            raise ParameterError(f"{label} is NaN; expected a number in [{self.unit}]")
        check_range(
            value,
            label,
            self.unit,
            self.low,
            self.high,
            low_inclusive=self.low_inclusive,
            high_inclusive=self.high_inclusive,
        )
        return value


class Potential(Variable):
    """A potential (across) field of a connector: equal for all connected connectors."""


class Flow(Variable):
    """A flow (through) field of a connector: sums to zero over a connection set.

    Positive flow goes into the component that owns the connector.
    """
