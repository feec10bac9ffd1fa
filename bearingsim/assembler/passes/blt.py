"""BLT sorting: the matched equations in block lower triangular order (networkx)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import networkx as nx

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.graph import incidence_map

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "Block", "run", "blt_blocks"]

NAME = "BLT sorting"
"""The pass name in timings, logs and ``extra_passes``."""

Block = list[tuple[Eq, Var]]
"""One block of the BLT form: (equation, the unknown it determines) pairs solved together."""


def blt_blocks(dae: DAE, matching: dict[Eq, Var]) -> list[Block]:
    """Block lower triangular order: strongly connected components in topological order."""
    var_eq = {v: e for e, v in matching.items()}
    unknowns = list(var_eq)
    inc = incidence_map(dae, list(matching), unknowns)
    g = nx.DiGraph()
    g.add_nodes_from(id(e) for e in matching)
    for e, vs in inc.items():
        for v in vs:
            src = var_eq[v]
            if src is not e:
                g.add_edge(id(src), id(e))
    cond = nx.condensation(g)
    eq_by_id = {id(e): e for e in matching}
    position = {id(e): k for k, e in enumerate(dae.eqs)}
    blocks = []
    for node in nx.topological_sort(cond):
        members = sorted(cond.nodes[node]["members"], key=position.__getitem__)
        blocks.append([(eq_by_id[i], matching[eq_by_id[i]]) for i in members])
    return blocks


def run(state: AssemblyState) -> None:
    """Set ``state.blocks`` from ``state.dae`` and ``state.matching``."""
    state.require(NAME, "dae", "matching")
    state.blocks = blt_blocks(state.dae, state.matching)
