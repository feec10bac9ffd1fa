"""The assembler: from an instance tree to a compiled :class:`System`.

``assemble`` flattens an assembly and runs the reduction passes (alias elimination, structural
checks, index reduction, matching, pruning, BLT sorting, tearing, code generation) over one
state; the result is a :class:`System` of CasADi functions with names, units and start values,
which :mod:`bearingsim.simulation` integrates, linearizes and solves.
"""

from bearingsim.assembler.pipeline import PASSES, assemble
from bearingsim.assembler.system import Signal, System

__all__ = ["PASSES", "Signal", "System", "assemble"]
