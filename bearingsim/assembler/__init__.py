"""The assembler: from an instance tree to a compiled :class:`System`.

``assemble`` flattens an assembly and runs the reduction passes (alias elimination, structural
checks, index reduction, matching, pruning, BLT sorting, tearing, code generation) over one
typed :class:`AssemblyState`, as the staged lists :data:`STAGES`; the result is a
:class:`System` of CasADi functions with names, units and start values, which
:mod:`bearingsim.simulation` integrates, linearizes and solves.
"""

from bearingsim.assembler.cache import assemble_cached
from bearingsim.assembler.pipeline import PASS_NAMES, STAGES, Pass, Stage, assemble
from bearingsim.assembler.state import AssemblyState
from bearingsim.assembler.system import Signal, System

__all__ = ["PASS_NAMES", "STAGES", "AssemblyState", "Pass", "Signal", "Stage", "System",
           "assemble", "assemble_cached"]
