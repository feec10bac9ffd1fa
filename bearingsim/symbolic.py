"""Math that works on floats, numpy arrays and CasADi symbols alike.

Physics functions and component equations are written once with these helpers, so the same code
evaluates numbers in Python and builds symbolic CasADi graphs for the assembler and the FMU.

Dispatch rule: if any argument is a CasADi ``SX``/``MX``/``DM`` object the CasADi function is used,
otherwise numpy's.
"""

from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np

__all__ = [
    "is_symbolic",
    "sqrt",
    "exp",
    "log",
    "sin",
    "cos",
    "tan",
    "tanh",
    "atan",
    "atan2",
    "arccos",
    "arcsin",
    "fabs",
    "fmax",
    "fmin",
    "sign",
    "power",
    "sqrt_power",
    "if_else",
    "smooth_max0",
    "smooth_abs",
    "ellipk",
    "ellipe",
]

_CASADI_TYPES = (ca.SX, ca.MX, ca.DM)


def is_symbolic(*values: Any) -> bool:
    """Return True if any value is a CasADi object (SX, MX or DM).

    Parameters
    ----------
    *values : object
        Anything.

    Returns
    -------
    bool
        Whether one of them is SX, MX or DM.
    """
    return any(isinstance(v, _CASADI_TYPES) for v in values)


def _unary(np_fn, ca_fn):
    def fn(x):
        return ca_fn(x) if is_symbolic(x) else np_fn(x)

    fn.__doc__ = f"Element-wise ``{np_fn.__name__}`` for floats, arrays and CasADi symbols."
    return fn


sqrt = _unary(np.sqrt, ca.sqrt)
exp = _unary(np.exp, ca.exp)
log = _unary(np.log, ca.log)
sin = _unary(np.sin, ca.sin)
cos = _unary(np.cos, ca.cos)
tan = _unary(np.tan, ca.tan)
tanh = _unary(np.tanh, ca.tanh)
atan = _unary(np.arctan, ca.atan)
arccos = _unary(np.arccos, ca.acos)
arcsin = _unary(np.arcsin, ca.asin)
fabs = _unary(np.abs, ca.fabs)
sign = _unary(np.sign, ca.sign)


def atan2(y, x):
    """Four-quadrant arc tangent for floats, arrays and CasADi symbols.

    Parameters
    ----------
    y, x : float, array or CasADi symbol
        Coordinates (same unit).

    Returns
    -------
    float, array or CasADi symbol
        The angle [rad] in (-pi, pi].
    """
    return ca.atan2(y, x) if is_symbolic(y, x) else np.arctan2(y, x)


def fmax(a, b):
    """Element-wise maximum.

    Parameters
    ----------
    a, b : float, array or CasADi symbol
        Operands.

    Returns
    -------
    float, array or CasADi symbol
        The larger of each pair.
    """
    return ca.fmax(a, b) if is_symbolic(a, b) else np.maximum(a, b)


def fmin(a, b):
    """Element-wise minimum.

    Parameters
    ----------
    a, b : float, array or CasADi symbol
        Operands.

    Returns
    -------
    float, array or CasADi symbol
        The smaller of each pair.
    """
    return ca.fmin(a, b) if is_symbolic(a, b) else np.minimum(a, b)


def power(a, b):
    """Element-wise ``a ** b``.

    Parameters
    ----------
    a, b : float, array or CasADi symbol
        Base and exponent.

    Returns
    -------
    float, array or CasADi symbol
        ``a ** b``.
    """
    return ca.power(a, b) if is_symbolic(a, b) else np.power(a, b)


def sqrt_power(x, k: int):
    """``x ** (k + 1/2)`` as ``x**k * sqrt(x)``: a square root and ``k`` products, several
    times cheaper than ``pow`` in generated C (Hertz loads ``delta ** 1.5``). Equal to
    ``power(x, k + 0.5)`` within a few ulp for ``x > 0``; 0 for ``x <= 0``, with the
    derivative 0 there as ``pow``'s (the product form's would be ``0 * inf``: an unloaded
    contact's compression is exactly 0).

    Parameters
    ----------
    x : float, array or CasADi symbol
        Base (any unit ``U``), non-negative in use (compressions, ``1 - eps^2``).
    k : int
        Whole part of the exponent, ``k >= 0``.

    Returns
    -------
    float, array or CasADi symbol
        ``x ** (k + 1/2)`` [``U ** (k + 1/2)``].
    """
    symbolic = is_symbolic(x)
    result = ca.sqrt(x) if symbolic else np.sqrt(np.maximum(x, 0.0))
    for _ in range(k):
        result = x * result
    return ca.if_else(x > 0, result, 0.0) if symbolic else np.where(x > 0, result, 0.0)[()]


def if_else(cond, a, b):
    """``a`` where ``cond`` holds, else ``b`` (both branches are evaluated).

    Parameters
    ----------
    cond : bool, array or CasADi symbol
        The condition.
    a, b : float, array or CasADi symbol
        Values where it holds and where not.

    Returns
    -------
    float, array or CasADi symbol
        The selected values.
    """
    if is_symbolic(cond, a, b):
        return ca.if_else(cond, a, b)
    return np.where(cond, a, b)


def smooth_max0(x, eps):
    """Smooth approximation of ``max(x, 0)``: ``(x + sqrt(x^2 + eps^2)) / 2``.

    Differentiable everywhere (no events in the integrator); the error is at most ``eps / 2``.

    Parameters
    ----------
    x : float, array or CasADi symbol
        The argument (any unit).
    eps : float
        Smoothing width (same unit), > 0.

    Returns
    -------
    float, array or CasADi symbol
        ``(x + sqrt(x^2 + eps^2)) / 2``.
    """
    return 0.5 * (x + sqrt(x * x + eps * eps))


def smooth_abs(x, eps):
    """Smooth approximation of ``|x|``: ``sqrt(x^2 + eps^2)``.

    Parameters
    ----------
    x : float, array or CasADi symbol
        The argument (any unit).
    eps : float
        Smoothing width (same unit), > 0.

    Returns
    -------
    float, array or CasADi symbol
        ``sqrt(x^2 + eps^2)``.
    """
    return sqrt(x * x + eps * eps)


AGM_STEPS = 8
"""Steps of the arithmetic-geometric mean of :func:`ellipk` and :func:`ellipe`: converged to
machine precision for ``m <= 1 - 1e-15`` (within 6e-15 of :mod:`scipy.special`'s, tested)."""


def _agm(m):
    """The arithmetic-geometric mean of ``1`` and ``sqrt(1 - m)`` after :data:`AGM_STEPS`
    steps, and Gauss-Legendre's sum ``m/2 + sum 2^(n-1) c_n^2`` of the half-differences
    ``c_n``; refuses a number ``m >= 1`` (K is infinite at 1, undefined above)."""
    if not is_symbolic(m) and np.any(np.asarray(m) >= 1.0):
        raise ValueError(f"elliptic integrals: the parameter m must be below 1 [1], got "
                         f"{float(np.max(m))!r}")
    a, b = 1.0, sqrt(1.0 - m)
    c2_sum = 0.5 * m  # sum of 2^(n-1) c_n^2 starting with c_0^2 = m
    scale = 0.5
    for _ in range(AGM_STEPS):
        c = 0.5 * (a - b)
        a, b = 0.5 * (a + b), sqrt(a * b)
        scale *= 2.0
        c2_sum = c2_sum + scale * c * c
    return a, c2_sum


def ellipk(m):
    """Complete elliptic integral of the first kind K(m), parameter ``m = k^2``, by the
    arithmetic-geometric mean: ``K = pi / (2 AGM(1, sqrt(1 - m)))``.

    One expression for numbers and CasADi symbols, so that the values computed in Python (a
    bearing's design, the client of a sweep) are those of the generated model; it also keeps
    :mod:`scipy.special` (0.45 s to import) out of every process that builds a ball bearing.

    Parameters
    ----------
    m : float, array or CasADi symbol
        Parameter ``m = k^2`` [1], ``m <= 1 - 1e-15`` (Hertz's ellipticity equation keeps it
        in ``[1e-12, 1 - 1e-15]``).

    Returns
    -------
    float, array or CasADi symbol
        K(m) [1].

    Raises
    ------
    ValueError
        For a number ``m >= 1``.
    """
    a, _ = _agm(m)
    return np.pi / (2.0 * a)


def ellipe(m):
    """Complete elliptic integral of the second kind E(m), parameter ``m = k^2``, by the
    arithmetic-geometric mean with Gauss-Legendre's sum:
    ``E = K (1 - m/2 - sum 2^(n-1) c_n^2)`` (one expression for numbers and symbols, as
    :func:`ellipk`).

    Parameters
    ----------
    m : float, array or CasADi symbol
        Parameter ``m = k^2`` [1], ``m <= 1 - 1e-15``.

    Returns
    -------
    float, array or CasADi symbol
        E(m) [1].

    Raises
    ------
    ValueError
        For a number ``m >= 1``.
    """
    a, c2_sum = _agm(m)
    return np.pi / (2.0 * a) * (1.0 - c2_sum)
