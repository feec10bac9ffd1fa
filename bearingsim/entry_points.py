"""The argument layer of public entry points: a call with unknown or missing arguments raises
:class:`~bearingsim.errors.ParameterError` naming the function, the argument and the accepted
ones (:func:`entry_point`); argument values as
hashable keys, for remembering what was checked or built from them (:func:`value_key`)."""

from __future__ import annotations

import difflib
import functools
import inspect
from collections.abc import Callable
from typing import Any

from bearingsim.errors import ParameterError

__all__ = ["entry_point", "value_key"]


def entry_point(func: Callable) -> Callable:
    """Decorator of public entry points: a call with unknown or missing arguments raises
    :class:`~bearingsim.errors.ParameterError` naming the function, the argument (with a
    did-you-mean hint) and the accepted ones, instead of Python's bare ``TypeError``.

    Parameters
    ----------
    func : callable
        The entry point.

    Returns
    -------
    callable
        ``func`` with its arguments checked on every call.
    """
    signature = inspect.signature(func)
    accepted = [n for n, p in signature.parameters.items()
                if p.kind not in (inspect.Parameter.VAR_POSITIONAL,
                                  inspect.Parameter.VAR_KEYWORD)]
    binds = _binding_rule(signature)

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        if binds is not None and binds(args, kwargs):
            return func(*args, **kwargs)
        try:
            signature.bind(*args, **kwargs)
        except TypeError as exc:
            hint = ""
            unknown = [k for k in kwargs if k not in signature.parameters]
            if unknown:
                close = difflib.get_close_matches(unknown[0], accepted, n=1)
                hint = f"; did you mean {close[0]!r}?" if close else ""
            raise ParameterError(f"{func.__name__}: {exc}{hint}; its arguments are "
                                 f"{', '.join(accepted)}") from None
        return func(*args, **kwargs)

    return wrapper


def _binding_rule(signature: inspect.Signature) -> Callable[[tuple, dict], bool] | None:
    """For a signature of plain parameters (positional-or-keyword, keyword-only; no ``*args``,
    ``**kwargs`` or positional-only), a cheap test that a call binds: no more positional
    arguments than it takes, keywords among its names and not given positionally too, every
    parameter without a default given. ``signature.bind`` is the fallback (and the error)
    where the test says no; None for other signatures."""
    params = list(signature.parameters.values())
    kinds = {inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY}
    if any(p.kind not in kinds for p in params):
        return None
    positional = [p.name for p in params if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD]
    names = frozenset(p.name for p in params)
    required = [(k, p.name) for k, p in enumerate(params) if p.default is inspect.Parameter.empty]
    # per number of positional arguments: the names they fill, the required names left
    filled = [tuple(positional[:n]) for n in range(len(positional) + 1)]
    left = [tuple(name for k, name in required if k >= n) for n in range(len(positional) + 1)]

    def binds(args: tuple, kwargs: dict) -> bool:
        n = len(args)
        if n >= len(filled) or not names.issuperset(kwargs):
            return False
        for name in filled[n]:
            if name in kwargs:
                return False
        for name in left[n]:
            if name not in kwargs:
                return False
        return True

    return binds


def value_key(value: Any) -> tuple | None:
    """A hashable key of an argument value, equal only for values that are the same to every
    check and conversion: a plain number by its bits (``float.hex``: ``-0.0`` is not ``0.0``,
    an ``int`` not the equal ``float``), text by itself; None for anything else (a quantity,
    an array, a function, a ``bool``), whose checks are then made anew on every call.

    Parameters
    ----------
    value : object
        An argument value.

    Returns
    -------
    tuple or None
        ``("float", hex)``, ``("int", value)`` or ``("str", value)``, else None.
    """
    kind = type(value)
    if kind is float:
        return ("float", value.hex())
    if kind is int or kind is str:
        return (kind.__name__, value)
    return None
