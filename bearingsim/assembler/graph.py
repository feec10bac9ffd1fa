"""Bipartite graph helpers shared by the structural passes (networkx): which unknowns occur in
which equations, and a maximum matching of equations to unknowns."""

from __future__ import annotations

import networkx as nx

from bearingsim.assembler.dae import DAE, Eq, Var

__all__ = ["incidence_map", "maximum_matching"]


def incidence_map(dae: DAE, eqs: list[Eq], unknowns: list[Var]) -> dict[Eq, list[Var]]:
    """For each equation, the unknowns (from ``unknowns``) that occur in it.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    eqs : list of Eq
        The equations.
    unknowns : list of Var
        The unknowns to look for.

    Returns
    -------
    dict of Eq to list of Var
        The unknowns of each equation.
    """
    lookup = {v.sym.name(): v for v in unknowns}
    return {e: dae.incidence(e, lookup) for e in eqs}


def maximum_matching(inc: dict[Eq, list[Var]], unknowns: list[Var]) -> dict[Eq, Var]:
    """Maximum bipartite matching of equations to unknowns (Hopcroft-Karp).

    Parameters
    ----------
    inc : dict of Eq to list of Var
        Incidence (:func:`incidence_map`).
    unknowns : list of Var
        The unknowns.

    Returns
    -------
    dict of Eq to Var
        The matched pairs.
    """
    g = nx.Graph()
    eq_nodes = [("e", id(e)) for e in inc]
    g.add_nodes_from(eq_nodes, bipartite=0)
    g.add_nodes_from((("v", id(v)) for v in unknowns), bipartite=1)
    for e, vs in inc.items():
        for v in vs:
            g.add_edge(("e", id(e)), ("v", id(v)))
    m = nx.bipartite.hopcroft_karp_matching(g, top_nodes=eq_nodes)
    eq_by_id = {id(e): e for e in inc}
    var_by_id = {id(v): v for v in unknowns}
    return {eq_by_id[k[1]]: var_by_id[m[k][1]] for k in eq_nodes if k in m}
