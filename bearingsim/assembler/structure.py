"""Structural analysis: bipartite matching, balance diagnostics, BLT sorting (networkx)."""

from __future__ import annotations

import networkx as nx

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.errors import OverdeterminedError, SingularBlockError, UnderdeterminedError

__all__ = ["incidence_map", "maximum_matching", "check_structure", "match", "blt_blocks"]


def incidence_map(dae: DAE, eqs: list[Eq], unknowns: list[Var]) -> dict[Eq, list[Var]]:
    """For each equation, the unknowns (from ``unknowns``) that occur in it."""
    lookup = {v.sym.name(): v for v in unknowns}
    return {e: dae.incidence(e, lookup) for e in eqs}


def maximum_matching(inc: dict[Eq, list[Var]], unknowns: list[Var]) -> dict[Eq, Var]:
    """Maximum bipartite matching of equations to unknowns (Hopcroft-Karp)."""
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


def check_structure(dae: DAE) -> None:
    """Raise a named error if equations and unknowns do not balance.

    Under-determined: the unknowns left unmatched by a maximum matching and the equations that
    contain them. Over-determined: the equations left unmatched.
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


def match(dae: DAE) -> dict[Eq, Var]:
    """Perfect matching of the (index-1) equations to the unknowns, or a named error."""
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
