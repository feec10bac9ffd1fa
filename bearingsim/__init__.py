"""bearingsim: a Modelica-style, equation-based simulator for rolling-bearing systems.

The modeling language is importable from the top level::

    from bearingsim import Component, Connector, Assembly, connect, der
"""

from bearingsim import language
from bearingsim.language import *  # noqa: F403 - the language is the top-level API

__version__ = "0.1.0"

__all__ = list(language.__all__)
