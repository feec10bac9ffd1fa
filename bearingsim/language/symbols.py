"""Symbols of the modeling language: declared variables become CasADi SX symbols.

Every declared variable, parameter and connector field is one scalar ``casadi.SX`` symbol with a
unique name ``<attr>__<id>``. The registry maps those names back to their declarations so the
assembler can find owners, units and start values, and so that ``der`` can create derivative
symbols. It sees a declaration through the :class:`Declared` protocol only, so this module sits
below :mod:`~bearingsim.language.declarations` and does not import it.
"""

from __future__ import annotations

import itertools
import re
import warnings
import weakref
from typing import Any, Protocol

import casadi as ca

from bearingsim.errors import ModelError, ParameterError

__all__ = ["Declared", "time", "der", "symbol_declaration", "new_symbol", "of_time", "readable"]


class Declared(Protocol):
    """What the symbol registry needs of a declaration
    (:class:`~bearingsim.language.declarations.Declaration`)."""

    is_constant_in_time: bool
    """Whether ``der`` of it is zero (parameters)."""

    @property
    def path(self) -> str:
        """Dotted name relative to the root of the instance tree."""

    def derivative_symbol(self) -> ca.SX:
        """The symbol of its time derivative, created on first use."""


_counter = itertools.count()
_registry: weakref.WeakValueDictionary[str, Declared] = weakref.WeakValueDictionary()
_NAME = re.compile(r"\b([A-Za-z_][A-Za-z0-9_]*?)__(\d+)\b")

time = ca.SX.sym("time")
"""The independent variable t [s], shared by every model."""


_NUMPY_ON_CASADI = r"\s*casadi: a numpy function was called on a casadi value"
"""The start of CasADi's warning when a numpy function meets a CasADi symbol (it still gives
CasADi's function of it)."""


def of_time(function: Any, t: ca.SX, what: str) -> ca.SX:
    """``function(t)`` as an expression of the time symbol ``t``: a function of time written
    with casadi, :mod:`bearingsim.symbolic` or numpy math (numpy's functions of a CasADi
    symbol give CasADi's; CasADi's warning about it, a dozen lines, is not shown).

    Parameters
    ----------
    function : callable
        The function of time [s].
    t : casadi.SX
        The time symbol.
    what : str
        What the function gives, for the message (``"input shaft_speed"``).

    Returns
    -------
    casadi.SX
        The expression.

    Raises
    ------
    ParameterError
        When the function cannot be evaluated on a symbol (a Python ``if`` on the time, a
        function from another library), naming ``what`` and the first line of the failure.
    """
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=_NUMPY_ON_CASADI, category=FutureWarning)
        try:
            return ca.SX(function(t))
        except Exception as exc:  # noqa: BLE001 - report any failure of the user's function
            lines = str(exc).strip().splitlines()
            raise ParameterError(
                f"{what}: the function of time could not be evaluated symbolically "
                f"({(lines[0] if lines else type(exc).__name__)[:200]}); write it with casadi, "
                "numpy or bearingsim.symbolic math (casadi.if_else for a choice on the time)"
            ) from None


def new_symbol(attr: str, declaration: Declared) -> ca.SX:
    """Create the unique SX symbol of a declaration and register it.

    Parameters
    ----------
    attr : str
        Attribute name (the symbol's name before its counter).
    declaration : Declaration
        The declaration the symbol stands for.

    Returns
    -------
    casadi.SX
        The new scalar symbol.
    """
    name = f"{attr}__{next(_counter)}"
    _registry[name] = declaration
    return ca.SX.sym(name)


def symbol_declaration(sym: ca.SX) -> Declared | None:
    """The declaration behind a scalar symbol, or None for foreign symbols.

    Parameters
    ----------
    sym : casadi.SX
        A scalar symbol.

    Returns
    -------
    Declaration or None
        The declaration, or None.
    """
    return _registry.get(sym.name())


def _derivative_of_symbol(sym: ca.SX) -> ca.SX:
    decl = symbol_declaration(sym)
    if decl is None:
        raise ModelError(f"der() of {sym} which is not a declared variable")
    return decl.derivative_symbol()


def der(expr: Any) -> Any:
    """Time derivative of a variable or of an expression of variables.

    ``der(x)`` of a declared variable returns its derivative symbol. For an expression the chain
    rule is applied: ``der(f(x, t)) = df/dx der(x) + df/dt``; parameters count as constants.

    Parameters
    ----------
    expr : casadi.SX or float
        A declared variable or an expression of declared variables.

    Returns
    -------
    casadi.SX
        The derivative expression.
    """
    if not isinstance(expr, ca.SX):
        return 0.0
    if expr.numel() != 1:
        return ca.vertcat(*[der(expr[i]) for i in range(expr.numel())])
    if expr.is_symbolic():
        return _derivative_of_symbol(expr)
    syms = ca.symvar(expr)
    result = ca.SX(0)
    for s in syms:
        if s.name() == time.name():
            result += ca.jacobian(expr, s)
            continue
        decl = symbol_declaration(s)
        if decl is None:
            raise ModelError(f"der() of an expression containing the foreign symbol {s}")
        if decl.is_constant_in_time:
            continue
        result += ca.jacobian(expr, s) * decl.derivative_symbol()
    return result


def readable(expr: Any) -> str:
    """Render an expression with the dotted names of its variables instead of symbol names.

    Parameters
    ----------
    expr : object
        A CasADi expression (or anything with a ``str``).

    Returns
    -------
    str
        The rendered expression.
    """

    def repl(match: re.Match) -> str:
        decl = _registry.get(match.group(0))
        return decl.path if decl is not None else match.group(0)

    return _NAME.sub(repl, str(expr))
