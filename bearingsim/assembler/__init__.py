"""The assembler: from an instance tree to a compiled :class:`System`.

``assemble`` flattens an assembly and runs the reduction passes (alias elimination, structural
checks, index reduction, matching, pruning, BLT sorting, tearing, code generation) over one
typed :class:`AssemblyState`, as the staged lists :data:`STAGES`; the result is a
:class:`System` of CasADi functions with names, units and start values, which
:mod:`bearingsim.simulation` integrates, linearizes and solves.
"""

from typing import Any

from bearingsim.assembler.cache import assemble_cached
from bearingsim.assembler.state import AssemblyState
from bearingsim.assembler.system import Signal, System

__all__ = ["PASS_NAMES", "STAGES", "AssemblyState", "Pass", "Signal", "Stage", "System",
           "assemble", "assemble_cached"]

_PIPELINE = ("PASS_NAMES", "STAGES", "Pass", "Stage", "assemble")
"""Names of :mod:`bearingsim.assembler.pipeline`, imported on first use: the passes and networkx
take ~0.5 s to import, and a model loaded from the cache needs none of them."""


def __getattr__(name: str) -> Any:
    """A name of the pipeline (:data:`_PIPELINE`), importing it on first use.

    Parameters
    ----------
    name : str
        The attribute asked for.

    Returns
    -------
    object
        The pipeline's object of that name.

    Raises
    ------
    AttributeError
        For any other name.
    """
    if name in _PIPELINE:
        from bearingsim.assembler import pipeline

        return getattr(pipeline, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
