"""bearingsim: a Modelica-style, equation-based simulator for rolling-bearing systems.

The modeling language is importable from the top level::

    from bearingsim import Component, Connector, Assembly, connect, der

Its names are imported on first use (:func:`__getattr__`), so that importing a submodule that
needs no model does not wait for CasADi and numpy: ``bearingsim sweep`` starts the process its
workers fork from (:mod:`bearingsim.sweep_server`) before anything else, and that process's
imports are what the sweep's first points wait for.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the language's names for type checkers and editors (at run time: below)
    from bearingsim.language import *  # noqa: F403

__version__ = "0.1.0"


def __getattr__(name: str) -> Any:
    """A name of the modeling language (:mod:`bearingsim.language`), ``language`` itself, or
    ``__all__`` (the language's names), imported on first use.

    Parameters
    ----------
    name : str
        The attribute asked for.

    Returns
    -------
    object
        The language's object of that name.

    Raises
    ------
    AttributeError
        For any other name.
    """
    if name.startswith("__") and name != "__all__":  # probes (__wrapped__, ...), not the language's
        raise AttributeError(f"module 'bearingsim' has no attribute {name!r}")
    language = importlib.import_module("bearingsim.language")
    if name == "__all__":
        return list(language.__all__)
    if name == "language":
        return language
    if name not in language.__all__:
        raise AttributeError(f"module 'bearingsim' has no attribute {name!r}")
    value = getattr(language, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The module's names and the modeling language's.

    Returns
    -------
    list of str
        The names, sorted.
    """
    return sorted({*globals(), *__getattr__("__all__")})
