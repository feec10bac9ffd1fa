"""The argument layer of public entry points: a call with unknown or missing arguments raises
:class:`~bearingsim.errors.ParameterError` naming the function, the argument and the accepted
ones (:func:`entry_point`; re-exported by :mod:`bearingsim.validation`)."""

from __future__ import annotations

import difflib
import functools
import inspect
from collections.abc import Callable

from bearingsim.errors import ParameterError

__all__ = ["entry_point"]


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
    required = [k for k, p in enumerate(params) if p.default is inspect.Parameter.empty]
    required_names = [params[k].name for k in required]

    def binds(args: tuple, kwargs: dict) -> bool:
        n = len(args)
        if n > len(positional) or not names.issuperset(kwargs):
            return False
        if any(name in kwargs for name in positional[:n]):
            return False
        return all(k < n or name in kwargs for k, name in zip(required, required_names,
                                                               strict=True))

    return binds
