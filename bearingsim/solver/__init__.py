"""The assembler and the simulation core.

``assemble`` flattens an assembly and runs the reduction passes; ``simulate``, ``linearize`` and
``steady_state`` work on the resulting :class:`System`.
"""

from bearingsim.solver.linearize import LinearModel, linearize
from bearingsim.solver.pipeline import PASSES, assemble
from bearingsim.solver.result import Result
from bearingsim.solver.simulate import simulate
from bearingsim.solver.steady import steady_state
from bearingsim.solver.system import System

__all__ = [
    "PASSES",
    "LinearModel",
    "Result",
    "System",
    "assemble",
    "linearize",
    "simulate",
    "steady_state",
]
