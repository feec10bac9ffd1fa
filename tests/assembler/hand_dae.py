"""Hand-made flat DAEs for the per-pass tests: variables, equations and the state a pass sees."""

from __future__ import annotations

import casadi as ca

from bearingsim.assembler import AssemblyState
from bearingsim.assembler.dae import DAE, Eq, Param, Var
from bearingsim.language.component import Component
from bearingsim.language.symbols import time


def var(name: str, start: float | None = None, **fields) -> Var:
    """An algebraic variable whose symbol has the same name."""
    return Var(name, ca.SX.sym(name), start=start, **fields)


def state_var(name: str, start: float, fixed: bool = True) -> tuple[Var, Var]:
    """A variable and its derivative ``der(name)``."""
    x = Var(name, ca.SX.sym(name), start=start, fixed=fixed)
    dx = Var(f"der({name})", ca.SX.sym(f"der_{name}"), is_derivative=True)
    x.derivative = dx
    return x, dx


def param(name: str, value: float) -> Param:
    """A free parameter."""
    return Param(name, ca.SX.sym(name), value, "1", "")


def eq(residual: ca.SX, text: str) -> Eq:
    """An equation ``residual = 0`` of the hand-made model."""
    return Eq(residual, "hand", text=text)


def dae(variables: list[Var], equations: list[Eq], params: list[Param] = ()) -> DAE:
    """A flat DAE over the language's time symbol."""
    return DAE(vars=list(variables), eqs=list(equations), params=list(params), time=time)


def state_of(model: DAE, outputs: list[str] | None = None, **fields) -> AssemblyState:
    """The assembly state a pass after flattening sees, with ``model`` as its DAE."""
    return AssemblyState(Component("hand"), outputs, dae=model, **fields)


def evaluate(expr: ca.SX, values: dict[Var, float]) -> float:
    """The value of an expression at values of its variables."""
    syms = [v.sym for v in values]
    return float(ca.Function("f", syms, [expr])(*values.values()))
