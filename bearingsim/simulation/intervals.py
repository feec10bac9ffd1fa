"""Interval arithmetic over a CasADi SX function of one scalar: bounds of an input signal over a
time span, and the places where it is singular, undefined or overflows.

An input signal checked only at the output times can hide a pole or an overflow between them
(``1/(t - 0.1234567)`` on an output grid of 0.01 s). Evaluated on intervals, every operation of
the signal's instruction list returns bounds that contain all its values over a time span, and
flags a division by an interval that contains zero, ``tan`` across its pole, ``log``/``sqrt``
/``asin``/``acos`` outside their domain and magnitudes beyond :data:`OVERFLOW`. Intervals are
widened outwards by a relative :data:`ROUNDING` at every step, so a constant such as ``pi/2``,
which rounds to a float just below the pole of ``tan``, still counts as the pole.

:func:`locate_problem` bisects the time span, depth first from the start, until the earliest
span that still shows the problem is :data:`RESOLUTION` of the whole span wide. Interval
arithmetic over-estimates (``t - t`` on ``[0, 1]`` is ``[-1, 1]``), so a problem that vanishes
on the sub-spans was none; one that survives the bisection is real to that resolution.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import casadi as ca

__all__ = ["Interval", "IntervalProblem", "OVERFLOW", "evaluate", "locate_problem"]

OVERFLOW = 1e100
"""Largest magnitude an input signal may reach [its unit]: no physical input in SI units comes
near it, and such values overflow the model's arithmetic (products, squares)."""
ROUNDING = 1e-12
"""Relative outward widening of every interval bound."""
RESOLUTION = 1e-9
"""Width, relative to the whole span, of the span to which a problem is located."""
_MAX_BOXES = 4000
_EXACT = frozenset((ca.OP_LT, ca.OP_LE, ca.OP_EQ, ca.OP_NE, ca.OP_NOT, ca.OP_AND, ca.OP_OR,
                    ca.OP_FLOOR, ca.OP_CEIL, ca.OP_SIGN, ca.OP_IF_ELSE_ZERO, ca.OP_FMIN,
                    ca.OP_FMAX, ca.OP_NEG, ca.OP_FABS))
"""Operations whose interval result needs no outward rounding (logic, selections, sign)."""


@dataclass(frozen=True)
class Interval:
    """Closed interval ``[lo, hi]``."""

    lo: float
    hi: float

    def widened(self) -> Interval:
        pad = ROUNDING * max(abs(self.lo), abs(self.hi)) + 1e-300
        return Interval(self.lo - pad, self.hi + pad)

    def contains(self, x: float) -> bool:
        return self.lo <= x <= self.hi


@dataclass(frozen=True)
class IntervalProblem:
    """Why an interval evaluation failed, and where (after :func:`locate_problem`)."""

    reason: str
    t_lo: float = math.nan
    t_hi: float = math.nan


class _Unsupported(Exception):
    """An instruction without interval rules: the signal cannot be bounded this way."""


def _span(*values: float) -> Interval:
    finite = [v for v in values if not math.isnan(v)]
    return Interval(min(finite), max(finite))


def _mul(a: Interval, b: Interval) -> Interval:
    products = [x * y if not ((x == 0 and math.isinf(y)) or (y == 0 and math.isinf(x))) else 0.0
                for x in (a.lo, a.hi) for y in (b.lo, b.hi)]
    return _span(*products)


def _monotone(fn, a: Interval, increasing: bool = True) -> Interval:
    lo, hi = fn(a.lo), fn(a.hi)
    return Interval(lo, hi) if increasing else Interval(hi, lo)


def _periodic(fn, a: Interval, peaks: float, troughs: float, period: float) -> Interval:
    """Range of sin/cos on ``a``: endpoints, and the extrema inside."""
    if a.hi - a.lo >= period:
        return Interval(-1.0, 1.0)
    lo, hi = sorted((fn(a.lo), fn(a.hi)))
    k = math.ceil((a.lo - peaks) / period)
    if peaks + k * period <= a.hi:
        hi = 1.0
    k = math.ceil((a.lo - troughs) / period)
    if troughs + k * period <= a.hi:
        lo = -1.0
    return Interval(lo, hi)


def _power(a: Interval, b: Interval) -> Interval:
    if b.lo == b.hi and float(b.lo).is_integer():
        n = int(b.lo)
        if n < 0 and a.contains(0.0):
            raise ArithmeticError("division by zero (negative power of an interval with 0)")
        values = [a.lo**n, a.hi**n]
        if a.contains(0.0) and n > 0:
            values.append(0.0)
        return _span(*values)
    if a.lo < 0.0:
        raise ArithmeticError("power of a negative number to a non-integer exponent")
    if a.lo == 0.0 and b.lo < 0.0:
        raise ArithmeticError("division by zero (zero to a negative power)")
    return _span(*[x**y for x in (a.lo, a.hi) for y in (b.lo, b.hi)])


def _compare(a: Interval, b: Interval, op: int) -> Interval:
    if op == ca.OP_LT:
        sure, never = a.hi < b.lo, a.lo >= b.hi
    elif op == ca.OP_LE:
        sure, never = a.hi <= b.lo, a.lo > b.hi
    elif op == ca.OP_EQ:
        sure, never = a.lo == a.hi == b.lo == b.hi, a.hi < b.lo or b.hi < a.lo
    else:  # OP_NE
        never, sure = a.lo == a.hi == b.lo == b.hi, a.hi < b.lo or b.hi < a.lo
    return Interval(1.0, 1.0) if sure else Interval(0.0, 0.0) if never else Interval(0.0, 1.0)


def _apply(op: int, args: list[Interval]) -> Interval:  # noqa: C901 - one case per operation
    a = args[0] if args else None
    b = args[1] if len(args) > 1 else None
    if op == ca.OP_ADD:
        return Interval(a.lo + b.lo, a.hi + b.hi)
    if op == ca.OP_SUB:
        return Interval(a.lo - b.hi, a.hi - b.lo)
    if op == ca.OP_NEG:
        return Interval(-a.hi, -a.lo)
    if op == ca.OP_MUL:
        return _mul(a, b)
    if op == ca.OP_TWICE:
        return Interval(2 * a.lo, 2 * a.hi)
    if op in (ca.OP_DIV, ca.OP_INV):
        den = b if op == ca.OP_DIV else a
        if den.contains(0.0):
            raise ArithmeticError("division by zero")
        inv = Interval(1.0 / den.hi, 1.0 / den.lo)
        return _mul(a, inv) if op == ca.OP_DIV else inv
    if op == ca.OP_SQ:
        return _power(a, Interval(2.0, 2.0))
    if op in (ca.OP_POW, ca.OP_CONSTPOW):
        return _power(a, b)
    if op == ca.OP_SQRT:
        if a.lo < 0.0:
            raise ArithmeticError("square root of a negative number")
        return _monotone(math.sqrt, a)
    if op in (ca.OP_LOG, ca.OP_LOG1P):
        shift = 1.0 if op == ca.OP_LOG1P else 0.0
        if a.lo + shift <= 0.0:
            raise ArithmeticError("logarithm of a non-positive number")
        return _monotone(lambda x: math.log(x + shift), a)
    if op in (ca.OP_EXP, ca.OP_EXPM1):
        if a.hi > 709.0:
            raise ArithmeticError(f"exp overflows (argument up to {a.hi:.3g})")
        return _monotone(math.exp if op == ca.OP_EXP else math.expm1, a)
    if op == ca.OP_SIN:
        return _periodic(math.sin, a, math.pi / 2, -math.pi / 2, 2 * math.pi)
    if op == ca.OP_COS:
        return _periodic(math.cos, a, 0.0, math.pi, 2 * math.pi)
    if op == ca.OP_TAN:
        k = math.ceil((a.lo - math.pi / 2) / math.pi)
        if a.hi - a.lo >= math.pi or math.pi / 2 + k * math.pi <= a.hi:
            raise ArithmeticError("tan at its pole (pi/2 + k pi)")
        return _monotone(math.tan, a)
    if op in (ca.OP_ASIN, ca.OP_ACOS):
        if a.lo < -1.0 or a.hi > 1.0:
            raise ArithmeticError(f"{'asin' if op == ca.OP_ASIN else 'acos'} of a number "
                                  f"outside [-1, 1]")
        return _monotone(math.asin, a) if op == ca.OP_ASIN else _monotone(math.acos, a, False)
    if op == ca.OP_ATAN:
        return _monotone(math.atan, a)
    if op == ca.OP_ATAN2:
        return Interval(-math.pi, math.pi)
    if op in (ca.OP_SINH, ca.OP_TANH, ca.OP_ASINH, ca.OP_ERF, ca.OP_FLOOR, ca.OP_CEIL,
              ca.OP_SIGN):
        fn = {ca.OP_SINH: math.sinh, ca.OP_TANH: math.tanh, ca.OP_ASINH: math.asinh,
              ca.OP_ERF: math.erf, ca.OP_FLOOR: math.floor, ca.OP_CEIL: math.ceil,
              ca.OP_SIGN: lambda x: math.copysign(1.0, x) if x else 0.0}[op]
        if op == ca.OP_SINH and max(abs(a.lo), abs(a.hi)) > 709.0:
            raise ArithmeticError("sinh overflows")
        return _monotone(fn, a)
    if op == ca.OP_COSH:
        if max(abs(a.lo), abs(a.hi)) > 709.0:
            raise ArithmeticError("cosh overflows")
        return _span(math.cosh(a.lo), math.cosh(a.hi), *([1.0] if a.contains(0.0) else []))
    if op == ca.OP_FABS:
        if a.contains(0.0):
            return Interval(0.0, max(-a.lo, a.hi))
        return Interval(min(abs(a.lo), abs(a.hi)), max(abs(a.lo), abs(a.hi)))
    if op == ca.OP_FMIN:
        return Interval(min(a.lo, b.lo), min(a.hi, b.hi))
    if op == ca.OP_FMAX:
        return Interval(max(a.lo, b.lo), max(a.hi, b.hi))
    if op in (ca.OP_LT, ca.OP_LE, ca.OP_EQ, ca.OP_NE):
        return _compare(a, b, op)
    if op == ca.OP_NOT:
        return Interval(1.0 - a.hi, 1.0 - a.lo) if a.lo >= 0 and a.hi <= 1 else Interval(0, 1)
    if op in (ca.OP_AND, ca.OP_OR):
        truth = [(x.lo > 0 or x.hi < 0, x.lo == x.hi == 0) for x in (a, b)]
        if op == ca.OP_AND:
            sure, never = truth[0][0] and truth[1][0], truth[0][1] or truth[1][1]
        else:
            sure, never = truth[0][0] or truth[1][0], truth[0][1] and truth[1][1]
        return Interval(1.0, 1.0) if sure else Interval(0.0, 0.0) if never else Interval(0, 1)
    if op == ca.OP_IF_ELSE_ZERO:
        if a.lo == a.hi == 0.0:
            return Interval(0.0, 0.0)
        if a.lo > 0.0 or a.hi < 0.0:
            return b
        return _span(b.lo, b.hi, 0.0)
    if op == ca.OP_HYPOT:
        return _power(_apply(ca.OP_ADD, [_power(a, Interval(2, 2)), _power(b, Interval(2, 2))]),
                      Interval(0.5, 0.5))
    raise _Unsupported(op)


def evaluate(fn: ca.Function, span: Interval) -> Interval:
    """Bounds of the scalar SX function ``fn(t)`` for ``t`` in ``span``.

    Parameters
    ----------
    fn : casadi.Function
        Scalar SX function of one scalar, time [s].
    span : Interval
        The times [s].

    Returns
    -------
    Interval
        Enclosure of ``fn(t)`` over ``span``.

    Raises
    ------
    ArithmeticError
        Naming the problem (division by zero, a domain error, overflow beyond
        :data:`OVERFLOW`).
    """
    work: dict[int, Interval] = {}
    result = None
    for k in range(fn.n_instructions()):
        op = fn.instruction_id(k)
        out = fn.instruction_output(k)
        ins = fn.instruction_input(k)
        if op == ca.OP_CONST:
            c = float(fn.instruction_constant(k))
            work[out[0]] = Interval(c, c).widened()
        elif op == ca.OP_INPUT:
            work[out[0]] = span
        elif op == ca.OP_OUTPUT:
            result = work[ins[0]]
        else:
            value = _apply(op, [work[i] for i in ins])
            if op not in _EXACT:
                value = value.widened()
            if math.isnan(value.lo) or math.isnan(value.hi):
                raise ArithmeticError("not a number")
            if max(abs(value.lo), abs(value.hi)) > OVERFLOW:
                raise ArithmeticError(f"magnitude beyond {OVERFLOW:.0e} (overflow)")
            work[out[0]] = value
    return result if result is not None else Interval(0.0, 0.0)


def _slack(limit: float) -> float:
    """Tolerance of a range limit: the outward rounding of values at the limit."""
    return 1e3 * ROUNDING * abs(limit) + 1e-200


def _confirmed(fn: ca.Function, a: float, b: float, reason: str, low: float | None,
               high: float | None) -> bool:
    """A range violation located to a tiny span is confirmed by the values there (a span that
    straddles a kink of a piecewise signal bounds both pieces' formulas beyond the kink);
    singularities and overflow stand as found."""
    if not reason.startswith(("below its valid", "above its valid")):
        return True
    values = [float(fn(t)) for t in (a, 0.5 * (a + b), b)]
    if low is not None and min(values) < low - _slack(low):
        return True
    return high is not None and max(values) > high + _slack(high)


def locate_problem(fn: ca.Function, t0: float, t1: float, low: float | None = None,
                   high: float | None = None) -> IntervalProblem | None:
    """The earliest time span in ``[t0, t1]`` where ``fn(t)`` is singular, undefined, overflows
    or leaves ``[low, high]``, or None when there is none (or when the function has operations
    without interval rules, which the sampled checks then cover).

    The span is located to :data:`RESOLUTION` of ``t1 - t0`` by depth-first bisection.

    Parameters
    ----------
    fn : casadi.Function
        Scalar SX function of time [s].
    t0, t1 : float
        The time span [s], ``t0 <= t1``.
    low, high : float, optional
        The valid range of ``fn`` (None: unbounded on that side).

    Returns
    -------
    IntervalProblem or None
        The reason and the span, or None.
    """
    width = RESOLUTION * (t1 - t0)
    boxes = [(t0, t1)]
    seen = 0
    while boxes:
        a, b = boxes.pop()
        seen += 1
        if seen > _MAX_BOXES:
            return None
        try:
            bounds = evaluate(fn, Interval(a, b))
            reason = None
            if low is not None and bounds.lo < low - _slack(low):
                reason = f"below its valid minimum {low:g}"
            elif high is not None and bounds.hi > high + _slack(high):
                reason = f"above its valid maximum {high:g}"
        except _Unsupported:
            return None
        except ArithmeticError as exc:
            reason = str(exc)
        if reason is None:
            continue
        if b - a <= width:
            if _confirmed(fn, a, b, reason, low, high):
                return IntervalProblem(reason, a, b)
            continue
        mid = 0.5 * (a + b)
        boxes += [(mid, b), (a, mid)]  # depth first, earliest half first
    return None
