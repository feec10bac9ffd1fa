"""bearingsim: a Modelica-style, equation-based simulator for rolling-bearing systems.

The modeling language is importable from the top level::

    from bearingsim import Component, Connector, Assembly, connect, der
"""

from bearingsim.language import (
    Assembly,
    Component,
    Connector,
    Flow,
    Input,
    Parameter,
    Potential,
    Variable,
    connect,
    der,
    time,
)

__version__ = "0.1.0"

__all__ = [
    "Assembly",
    "Component",
    "Connector",
    "Flow",
    "Input",
    "Parameter",
    "Potential",
    "Variable",
    "connect",
    "der",
    "time",
]
