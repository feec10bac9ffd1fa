"""Matching: pair every (index-1) equation with the unknown it determines."""

from __future__ import annotations

from typing import TYPE_CHECKING

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.graph import incidence_map, maximum_matching
from bearingsim.errors import SingularBlockError

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "match"]

NAME = "matching"
"""The pass name in timings, logs and ``extra_passes``."""


def match(dae: DAE) -> dict[Eq, Var]:
    """Perfect matching of the (index-1) equations to the unknowns, or a named error.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.

    Returns
    -------
    dict of Eq to Var
        Each equation -> the unknown it determines.
    """
    unknowns = dae.unknowns()
    inc = incidence_map(dae, dae.eqs, unknowns)
    matching = maximum_matching(inc, unknowns)
    if len(matching) < len(dae.eqs):
        matched = set(matching.values())
        bad_eqs = [e for e in dae.eqs if e not in matching]
        bad_vars = [v for v in unknowns if v not in matched]
        raise SingularBlockError(
            "the equations are structurally singular: these equations and unknowns cannot be "
            "paired",
            equations=[e.describe() for e in bad_eqs],
            unknowns=[v.name for v in bad_vars],
        )
    return matching


def run(state: AssemblyState) -> None:
    """Set ``state.matching``: each equation of ``state.dae`` -> the unknown it determines.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae")
    state.matching = match(state.dae)
