"""A small, safe expression language for input signals of time, compiled to CasADi.

A scene writes an input as text, for example ``"rpm(10000) * min(t / 0.5, 1)"``. The text is
parsed with :mod:`ast` and only whitelisted nodes are accepted; it is never passed to ``eval``.
The result is a function of the time symbol that returns a CasADi expression, so the signal is
compiled into the right-hand side (no Python runs during the integration).

Grammar (Python syntax, restricted):

* numbers, the time ``t`` [s], the constants ``pi`` and ``e``;
* ``+ - * / **``, unary ``-``/``+``, comparisons (``t < 1``: 1 or 0), ``a if cond else b``;
* functions: ``min max abs sqrt exp log log10 sin cos tan asin acos atan atan2 tanh sinh cosh
  floor ceil sign`` and the helpers ``step(t0)`` (0 before ``t0``, 1 after), ``ramp(t0, t1)``
  (0 before ``t0``, linear to 1 at ``t1``, then 1), ``rpm(n)`` (r/min -> rad/s), ``deg(a)``
  (degrees -> rad).

Everything is in SI units; a number with a unit (``"1000 rpm"``) is a scene value of its own
(:func:`bearingsim.units.parse_quantity`), not part of an expression: inside one write
``rpm(1000)``. Constant parts must be finite: ``1/0``, ``2**1e308`` and a non-finite number with
a unit (``"nan N"``, ``"inf rpm"``, ``"1e999 N"``) are :class:`ExpressionError`.
"""

from __future__ import annotations

import ast
import copy
import functools
import math
import operator
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from bearingsim.errors import ParameterError
from bearingsim.units import parse_quantity, split_quantity

__all__ = ["ExpressionError", "LiftedExpression", "compile_expression", "constant_value",
           "FUNCTIONS", "CONSTANTS"]


class ExpressionError(ParameterError):
    """An input expression uses a construct, name or function outside the whitelist."""


def _step(t, t0):
    return ca.if_else(t >= t0, 1.0, 0.0)


def _ramp(t, t0, t1):
    return ca.fmin(ca.fmax((t - t0) / (t1 - t0), 0.0), 1.0)


def _casadi(nargs: int, names: str) -> dict[str, tuple[int, Callable[..., Any]]]:
    """Table entries for CasADi's functions of the same ``names`` (space separated), each
    taking ``nargs`` arguments (the time argument of a builder is not theirs)."""
    def builder(fn):
        return lambda t, *args: fn(*args)

    return {name: (nargs, builder(getattr(ca, name))) for name in names.split()}


# name -> (number of arguments (None: 2 or more), builder taking (t, *args))
FUNCTIONS: dict[str, tuple[int | None, Callable[..., Any]]] = {
    "min": (None, lambda t, *a: _fold(ca.fmin, a)),
    "max": (None, lambda t, *a: _fold(ca.fmax, a)),
    "abs": (1, lambda t, x: ca.fabs(x)),
    **_casadi(1, "sqrt exp log log10 sin cos tan asin acos atan"),
    **_casadi(2, "atan2"),
    **_casadi(1, "tanh sinh cosh floor ceil sign"),
    "step": (1, lambda t, t0: _step(t, t0)),
    "ramp": (2, lambda t, t0, t1: _ramp(t, t0, t1)),
    "rpm": (1, lambda t, n: n * (2.0 * math.pi / 60.0)),
    "deg": (1, lambda t, a: a * (math.pi / 180.0)),
}
"""Whitelisted functions."""

CONSTANTS = {"pi": math.pi, "e": math.e}
"""Named constants; ``t`` is the time [s]."""

_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow}
_CMPOPS = {ast.Lt: operator.lt, ast.LtE: operator.le, ast.Gt: operator.gt, ast.GtE: operator.ge}
_MAX_LENGTH = 2000
_MAX_NODES = 400


def _fold(fn, args):
    out = args[0]
    for a in args[1:]:
        out = fn(out, a)
    return out


def _allowed_text() -> str:
    return (
        "numbers, t, " + ", ".join(CONSTANTS) + "; operators + - * / ** < <= > >= and "
        "'a if cond else b'; functions " + ", ".join(f"{k}()" for k in FUNCTIONS)
    )


def _fail(name: str, text: str, why: str) -> ExpressionError:
    return ExpressionError(f"{name}: cannot use the expression {text!r}: {why}. Allowed: "
                           f"{_allowed_text()}")


def _parse(text: str, name: str) -> ast.Expression:
    if not isinstance(text, str):
        raise ExpressionError(f"{name}: an expression must be text, got {type(text).__name__}")
    if len(text) > _MAX_LENGTH:
        raise _fail(name, text[:40] + "...", f"longer than {_MAX_LENGTH} characters")
    quantity = split_quantity(text)
    if quantity is not None and not math.isfinite(quantity[0]):
        raise _fail(name, text, "the number is not finite")
    if quantity is not None:
        si = parse_quantity(text)
        example = (f"rpm({quantity[0]:g})" if si is not None and si[1] == "rad/s"
                   else f"{si[0]:g}" if si is not None else "the SI value")
        raise _fail(name, text, f"a number with a unit is a value of its own, not an expression "
                                f"(a scene input takes it alone); inside an expression values "
                                f"are SI: {example} for {text.strip()}")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SyntaxWarning)
            tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError) as exc:
        hint = ""
        low = text.lower()
        if any(u in low for u in ("rpm", "r/min", "rad/s", "hz", " n", "nm", "mm")):
            hint = (" (inside an expression values are SI: rad/s, N, N m, m, s, and a speed in "
                    "r/min is rpm(1000); a scene value may be a number with a unit alone, "
                    "e.g. '1000 rpm', '2 kN')")
        why = getattr(exc, "msg", str(exc))
        raise _fail(name, text, f"not a valid expression ({why}){hint}") from None
    if sum(1 for _ in ast.walk(tree)) > _MAX_NODES:
        raise _fail(name, text, f"more than {_MAX_NODES} syntax nodes")
    return tree


def compile_expression(text: str, name: str = "input") -> Callable[[Any], Any]:
    """Parse an expression of ``t`` and return ``f(t)`` building the CasADi expression (kept
    per text and name: a sweep's points share few expressions; a failing text raises again).

    Parameters
    ----------
    text : str
        The expression (see the module docstring for the grammar).
    name : str
        The input (or scene key) it belongs to, used in error messages.

    Returns
    -------
    callable
        ``f(t)`` for a CasADi symbol or a number ``t``; returns ``casadi.SX``/``DM``.

    Raises
    ------
    ExpressionError
        For a syntax error or a construct, name or function outside the whitelist.
    """
    if not isinstance(text, str) or not isinstance(name, str):  # refused by the parser
        return _compiled.__wrapped__(text, name)
    return _compiled(text, name)


@functools.lru_cache(maxsize=1024)
def _compiled(text: str, name: str) -> Callable[[Any], Any]:
    """:func:`compile_expression` of text (kept)."""
    tree = _parse(text, name)
    _check(tree.body, name, text)  # fail at compile time, not at the first evaluation

    def f(t):
        return _eval(tree.body, t, name, text)

    f(ca.SX.sym("t"))  # constant parts (tan(pi/2), 1/0) fail now, not at the first run
    f.expression = text  # type: ignore[attr-defined]
    f.lifted = _lifted(tree, name, text)  # type: ignore[attr-defined]
    return f


@dataclass(frozen=True)
class LiftedExpression:
    """An expression with its numbers lifted out: expressions that differ only in their numbers
    (``rpm(1000) * ramp(0, 0.02)`` and ``rpm(2000) * ramp(0, 0.05)``) share ``template`` and
    ``build``, so that a run's inputs keep one structure (one compiled function) for all of
    them; the numbers become values of the run.

    Attributes
    ----------
    template : str
        The expression's text with each lifted number written ``_c<k>``.
    numbers : tuple of float
        The lifted numbers, ``_c0`` first.
    build : callable
        ``build(t, c)`` -> the expression, for a time ``t`` and numbers ``c`` (casadi
        symbols or values; ``c`` indexable, ``len(numbers)`` of them).
    """

    template: str
    numbers: tuple[float, ...]
    build: Callable[[Any, Any], Any]


def _lifted(tree: ast.Expression, name: str, text: str) -> LiftedExpression:
    """The expression of a checked ``tree`` with its numbers lifted, except exponents (``t**2``
    stays a square, whose derivative at ``t = 0`` and for ``t < 0`` a power of a symbol would
    not give) and zeros (``0 * log(t)`` is 0 as CasADi simplifies it, where a lifted zero
    would make 0 * -inf at ``t = 0``, not a number)."""
    numbers: list[float] = []

    class Lift(ast.NodeTransformer):
        def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
            node.left = self.visit(node.left)
            if not isinstance(node.op, ast.Pow):
                node.right = self.visit(node.right)
            return node

        def visit_Constant(self, node: ast.Constant) -> ast.AST:
            if float(node.value) == 0.0:
                return node
            numbers.append(float(node.value))
            return ast.Name(id=f"_c{len(numbers) - 1}", ctx=ast.Load())

    body = Lift().visit(copy.deepcopy(tree.body))

    def build(t, c):
        return _eval(body, t, name, text, c)

    return LiftedExpression(ast.unparse(body), tuple(numbers), build)


def constant_value(value: Any, name: str = "input") -> float | None:
    """The SI value of a scene value that does not change in time: a number, a number with a
    unit (``"500 rpm"``) or a constant expression (``"rpm(500)"``); None for an expression of
    ``t`` or anything else (a table).

    Parameters
    ----------
    value : number or str
    name : str
        For error messages.

    Returns
    -------
    float or None

    Raises
    ------
    ExpressionError
        For text that is neither a number with a unit nor a valid expression.
    """
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    if not isinstance(value, str):
        return None
    quantity = parse_quantity(value)
    if quantity is not None:
        return quantity[0]
    t = ca.SX.sym("t")
    expr = ca.SX(compile_expression(value, name)(t))
    if ca.depends_on(expr, t):
        return None
    return float(ca.evalf(expr))


def _check(node: ast.AST, name: str, text: str) -> None:
    """Walk the tree once to reject anything outside the whitelist."""
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise _fail(name, text, f"the constant {node.value!r} is not a number")
        try:
            finite = math.isfinite(float(node.value))
        except OverflowError:
            finite = False
        if not finite:
            raise _fail(name, text, "numbers must be finite")
        return
    if isinstance(node, ast.Name):
        if node.id != "t" and node.id not in CONSTANTS:
            known = ["t", *CONSTANTS]
            raise _fail(name, text, f"unknown name {node.id!r} (names: {', '.join(known)})")
        return
    if isinstance(node, ast.BinOp):
        if type(node.op) not in _BINOPS:
            raise _fail(name, text, f"operator {type(node.op).__name__} is not allowed")
        _check(node.left, name, text)
        _check(node.right, name, text)
        return
    if isinstance(node, ast.UnaryOp):
        if not isinstance(node.op, (ast.USub, ast.UAdd)):
            raise _fail(name, text, f"operator {type(node.op).__name__} is not allowed")
        _check(node.operand, name, text)
        return
    if isinstance(node, ast.Compare):
        if len(node.ops) != 1 or type(node.ops[0]) not in _CMPOPS:
            raise _fail(name, text, "only single comparisons < <= > >= are allowed")
        _check(node.left, name, text)
        _check(node.comparators[0], name, text)
        return
    if isinstance(node, ast.IfExp):
        for part in (node.test, node.body, node.orelse):
            _check(part, name, text)
        return
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            fn = node.func.id if isinstance(node.func, ast.Name) else ast.unparse(node.func)
            raise _fail(name, text, f"unknown function {fn!r}")
        if node.keywords:
            raise _fail(name, text, "keyword arguments are not allowed")
        nargs, _ = FUNCTIONS[node.func.id]
        if (nargs is None and len(node.args) < 2) or (nargs is not None
                                                      and len(node.args) != nargs):
            want = "2 or more" if nargs is None else str(nargs)
            raise _fail(name, text, f"{node.func.id}() takes {want} argument(s), got "
                                    f"{len(node.args)}")
        for a in node.args:
            if isinstance(a, ast.Starred):
                raise _fail(name, text, "starred arguments are not allowed")
            _check(a, name, text)
        if node.func.id == "ramp":
            _check_ramp(node, name, text)
        return
    raise _fail(name, text, f"{type(node).__name__} is not allowed")


def _check_ramp(node: ast.Call, name: str, text: str) -> None:
    """``ramp(t0, t1)`` needs ``t1 > t0`` [s] (checked here for constant arguments; others are
    checked over the simulated span by interval arithmetic)."""
    try:
        t0, t1 = (float(ast.literal_eval(a)) for a in node.args)
    except (ValueError, TypeError, SyntaxError):
        return
    if not t1 > t0:
        raise _fail(name, text, f"ramp(t0, t1) rises from 0 at t0 to 1 at t1 and needs t1 > t0 "
                                f"[s], got ramp({t0:g}, {t1:g}); use step(t0) for a jump")


def _eval(node: ast.AST, t, name: str, text: str, lifted=None):
    """The expression of ``node`` at time ``t``; ``lifted``: the values of the names ``_c<k>``
    of a :class:`LiftedExpression`'s tree."""
    if isinstance(node, ast.Constant):
        return float(node.value)
    if isinstance(node, ast.Name):
        if node.id.startswith("_c"):  # (a user's text cannot name one: _check refuses it)
            return lifted[int(node.id[2:])]
        return t if node.id == "t" else CONSTANTS[node.id]
    if isinstance(node, ast.BinOp):
        a, b = (_eval(node.left, t, name, text, lifted),
                _eval(node.right, t, name, text, lifted))
        if isinstance(a, float) and isinstance(b, float):
            a = ca.DM(a)  # keep float arithmetic symbolic-friendly (no ZeroDivisionError)
        return _finite(_BINOPS[type(node.op)](a, b), node, name, text)
    if isinstance(node, ast.UnaryOp):
        v = _eval(node.operand, t, name, text, lifted)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.Compare):
        a = _eval(node.left, t, name, text, lifted)
        b = _eval(node.comparators[0], t, name, text, lifted)
        return ca.if_else(_CMPOPS[type(node.ops[0])](ca.SX(a) if isinstance(a, float) else a, b),
                          1.0, 0.0)
    if isinstance(node, ast.IfExp):
        cond = _eval(node.test, t, name, text, lifted)
        return ca.if_else(cond, _eval(node.body, t, name, text, lifted),
                          _eval(node.orelse, t, name, text, lifted))
    if isinstance(node, ast.Call):
        _, fn = FUNCTIONS[node.func.id]
        args = [_eval(a, t, name, text, lifted) for a in node.args]
        args = [ca.DM(a) if isinstance(a, float) else a for a in args]
        if node.func.id == "tan" and isinstance(args[0], ca.DM):
            x = float(args[0])
            if abs(math.cos(x)) < 1e-12 * max(1.0, abs(x)):
                raise _fail(name, text, f"tan({x:g}) is at the pole pi/2 + k pi of tan")
        return _finite(fn(t, *args), node, name, text)
    raise _fail(name, text, f"{type(node).__name__} is not allowed")  # pragma: no cover


def _finite(value, node: ast.AST, name: str, text: str):
    """``value`` unless it is a constant that is not finite (``1/0``, ``2**1e308``)."""
    if isinstance(value, (ca.DM, float)) and not np.all(np.isfinite(np.asarray(value, float))):
        raise _fail(name, text, f"{ast.unparse(node)} is not a finite number")
    return value
