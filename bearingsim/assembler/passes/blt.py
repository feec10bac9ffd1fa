"""BLT sorting: the matched equations in block lower triangular order (networkx)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import networkx as nx

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.graph import incidence_map
from bearingsim.assembler.ir import Block
from bearingsim.assembler.passes.ball_sets import find_ball_sets, owners

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "blt_blocks"]

NAME = "BLT sorting"
"""The pass name in timings, logs and ``extra_passes``."""

def blt_blocks(dae: DAE, matching: dict[Eq, Var]) -> list[Block]:
    """Block lower triangular order: strongly connected components in topological order; among
    the valid orders, members' blocks of ball sets first and shared blocks that read members'
    unknowns last, each by the position of the block's first equation in ``dae.eqs``.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    matching : dict of Eq to Var
        Each equation -> the unknown it determines.

    Returns
    -------
    list of Block
        The blocks in solution order.
    """
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
    # Among the valid orders: the blocks of ball sets' members as early as they can come, then
    # the shared blocks that read no member's unknowns, then those that do, each group in the
    # model's equation order. Ball 0's blocks are then solved before a shared block reads
    # another ball's unknowns, and tearing copies each ball from ball 0 at once.
    in_sets = set(owners(find_ball_sets(dae)))

    def rank(eqs: list[Eq]) -> int:
        if any(id(matching[e]) in in_sets for e in eqs):
            return 0
        return 2 if any(id(v) in in_sets for e in eqs for v in inc[e]) else 1

    key = {}
    for node in cond:
        eqs = [eq_by_id[i] for i in cond.nodes[node]["members"]]
        key[node] = (rank(eqs), min(position[id(e)] for e in eqs))
    blocks = []
    for node in nx.lexicographical_topological_sort(cond, key=key.__getitem__):
        members = sorted(cond.nodes[node]["members"], key=position.__getitem__)
        blocks.append([(eq_by_id[i], matching[eq_by_id[i]]) for i in members])
    return blocks


def run(state: AssemblyState) -> None:
    """Set ``state.blocks`` from ``state.dae`` and ``state.matching``.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae", "matching")
    state.blocks = blt_blocks(state.dae, state.matching)
