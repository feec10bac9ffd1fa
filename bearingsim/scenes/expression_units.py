"""The unit an input expression's value has where its text fixes one.

Inside an expression values are SI numbers (:mod:`bearingsim.scenes.expressions`): a bare
number or the time ``t`` may stand for any quantity (``"200 + 800 * step(1.5)"`` is a force in N
as much as ``"1000 * t"`` is a speed ramp in rad/s), so they fix no unit. Only ``rpm(n)``
(r/min -> rad/s) and ``deg(a)`` (degrees -> rad) do: ``"rpm(100)"`` is a speed, and given to a
force it would be read as 10.47 N. :func:`expression_unit` follows those units through the
expression and gives the unit of its value when the text fixes it, so that a scene's check can
refuse ``"rpm(100)"`` for a load. Products with a bare number or ``t`` leave the unit open
(``"10 * rpm(100)"``: the 10 may carry any unit), as do values without a unit (``sin(t)``,
``rpm(n) / rpm(1000)``); such expressions are never refused.
"""

from __future__ import annotations

import ast

from bearingsim.scenes.expressions import ExpressionError, compile_expression

__all__ = ["expression_unit"]

Exponents = tuple[tuple[str, float], ...]
"""Powers of ``rad`` and ``s``, sorted by name; ``()`` a pure number."""

_OPEN = None
"""A value whose unit the text leaves open (a bare number, ``t``)."""

_FIXED = {"rpm": (("rad", 1.0), ("s", -1.0)), "deg": (("rad", 1.0),)}
"""The functions that fix a unit, and the unit of their value."""

_SAME_AS_ARGUMENTS = ("min", "max", "abs", "floor", "ceil")
"""Functions whose value has the unit of their arguments."""


def _combine(a: Exponents, b: Exponents, sign: float) -> Exponents:
    powers = dict(a)
    for name, power in b:
        powers[name] = powers.get(name, 0.0) + sign * power
    return tuple(sorted((n, p) for n, p in powers.items() if p != 0.0))


def _scaled(a: Exponents, factor: float) -> Exponents:
    return tuple((n, p * factor) for n, p in a)


def _label(exps: Exponents) -> str:
    def part(name: str, power: float) -> str:
        power = abs(power)
        return name if power == 1.0 else f"{name}{power:g}"

    top = [part(n, p) for n, p in exps if p > 0]
    bottom = [part(n, p) for n, p in exps if p < 0]
    return ".".join(top or ["1"]) + ("/" + ".".join(bottom) if bottom else "")


class _Mismatch(Exception):
    def __init__(self, node: ast.AST, units: list[Exponents]):
        self.node, self.units = node, units


def _alike(node: ast.AST, parts: list[Exponents | None]) -> Exponents | None:
    """The unit of a sum, a choice or a min/max: its parts' common fixed unit, ``()`` parts
    (pure numbers) and open ones taking any."""
    fixed = list(dict.fromkeys(p for p in parts if p))
    if len(fixed) > 1:
        raise _Mismatch(node, fixed)
    if fixed:
        return fixed[0]
    return () if parts and all(p == () for p in parts) else _OPEN


def _unit(node: ast.AST) -> Exponents | None:
    if isinstance(node, (ast.Constant, ast.Name)):
        return _OPEN
    if isinstance(node, ast.UnaryOp):
        return _unit(node.operand)
    if isinstance(node, ast.Compare):
        return ()
    if isinstance(node, ast.IfExp):
        return _alike(node, [_unit(node.body), _unit(node.orelse)])
    if isinstance(node, ast.BinOp):
        left, right = _unit(node.left), _unit(node.right)
        if isinstance(node.op, (ast.Add, ast.Sub)):
            return _alike(node, [left, right])
        if isinstance(node.op, ast.Pow):
            if left is _OPEN or left == ():
                return left
            if isinstance(node.right, ast.Constant):
                return _scaled(left, float(node.right.value))
            return _OPEN
        if left is _OPEN or right is _OPEN:
            return _OPEN
        return _combine(left, right, 1.0 if isinstance(node.op, ast.Mult) else -1.0)
    if isinstance(node, ast.Call):
        name = node.func.id  # type: ignore[attr-defined]  (checked by the compiler)
        args = [_unit(a) for a in node.args]
        if name in _FIXED:
            return _combine(_FIXED[name], args[0] or (), 1.0)
        if name in _SAME_AS_ARGUMENTS:
            return _alike(node, args)
        if name == "sqrt":
            return _scaled(args[0], 0.5) if args[0] else args[0]
        return ()  # step, ramp, sign and the transcendental functions: pure numbers
    return _OPEN  # pragma: no cover  (the compiler refuses every other node)


def expression_unit(text: str, name: str = "input") -> str | None:
    """The SI unit of an expression's value where ``rpm()`` or ``deg()`` fix it.

    Parameters
    ----------
    text : str
        A valid expression (:func:`~bearingsim.scenes.expressions.compile_expression`).
    name : str
        The input it belongs to, for error messages.

    Returns
    -------
    str or None
        ``"rad/s"``, ``"rad"``, ``"rad/s2"`` ... (model notation); None when the text leaves
        the unit open (a bare number or ``t`` in a product) or the value has no unit.

    Raises
    ------
    ExpressionError
        For an expression that is not valid, or that adds (or chooses between, or takes the
        least of) values of different units, such as ``"rpm(100) + deg(5)"``.

    Examples
    --------
    >>> expression_unit("rpm(6000) * ramp(0, 0.5)")
    'rad/s'
    >>> expression_unit("200 + 800 * step(1.5)") is None
    True
    """
    compile_expression(text, name)
    try:
        exps = _unit(ast.parse(text.strip(), mode="eval").body)
    except _Mismatch as exc:
        shown = " and ".join(_label(u) for u in exc.units)
        raise ExpressionError(
            f"{name}: cannot use the expression {text!r}: {ast.unparse(exc.node)} mixes values "
            f"in {shown} (rpm() gives rad/s, deg() rad). Allowed: parts of one unit") from None
    return _label(exps) if exps else None
