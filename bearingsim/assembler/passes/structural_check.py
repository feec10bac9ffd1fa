"""Structural check: equations and unknowns must balance, else a named error."""

from __future__ import annotations

from typing import TYPE_CHECKING

from bearingsim.assembler.dae import DAE
from bearingsim.assembler.graph import incidence_map, maximum_matching
from bearingsim.errors import OverdeterminedError, UnderdeterminedError

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "check_structure"]

NAME = "structural check"
"""The pass name in timings, logs and ``extra_passes``."""


def check_structure(dae: DAE) -> None:
    """Raise a named error if equations and unknowns do not balance.

    Under-determined: the unknowns left unmatched by a maximum matching and the equations that
    contain them. Over-determined: the equations left unmatched.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    """
    unknowns = dae.unknowns()
    inc = incidence_map(dae, dae.eqs, unknowns)
    n_eq, n_unk = len(dae.eqs), len(unknowns)
    if n_eq == n_unk:
        return
    matching = maximum_matching(inc, unknowns)
    matched_vars = set(matching.values())
    if n_eq < n_unk:
        free = [v for v in unknowns if v not in matched_vars]
        related = [e for e, vs in inc.items() if any(v in free for v in vs)]
        raise UnderdeterminedError(
            f"the model is under-determined: {n_eq} equations for {n_unk} unknowns; "
            f"no equation is left to determine {len(free)} of them",
            equations=[e.describe() for e in related],
            unknowns=[v.name for v in free],
        )
    extra = [e for e in dae.eqs if e not in matching]
    vs = sorted({v.name for e in extra for v in inc[e]})
    raise OverdeterminedError(
        f"the model is over-determined: {n_eq} equations for {n_unk} unknowns; "
        f"{len(extra)} equation(s) have no unknown left to determine",
        equations=[e.describe() for e in extra],
        unknowns=vs,
    )


def run(state: AssemblyState) -> None:
    """Check that the equations and unknowns of ``state.dae`` balance.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae")
    check_structure(state.dae)
