"""BLT sorting: the matched equations in block lower triangular order (networkx)."""

from __future__ import annotations

import networkx as nx

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.graph import incidence_map

__all__ = ["blt_blocks"]


def blt_blocks(dae: DAE, matching: dict[Eq, Var]) -> list[list[tuple[Eq, Var]]]:
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
