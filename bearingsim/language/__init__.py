"""The modeling language: connectors, components, declarations, ``connect`` and ``der``."""

from bearingsim.language.component import Assembly, Component, connect
from bearingsim.language.connector import Connector
from bearingsim.language.declarations import Flow, Input, Parameter, Potential, Variable
from bearingsim.language.symbols import der, time

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
