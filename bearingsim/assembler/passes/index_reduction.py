"""Index reduction: Pantelides' algorithm and the dummy derivative method.

Pantelides (1988) finds the equations that must be differentiated so that every equation can be
matched to a highest-derivative variable; the equations are differentiated symbolically with
CasADi. Mattsson and Söderlind (1993) then turn selected derivatives into algebraic "dummy
derivatives" so the augmented system is index 1 with exactly the true number of states. The
selection uses the Jacobian at the start values with column pivoting (static state selection).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import casadi as ca
import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.csgraph

from bearingsim.assembler.dae import DAE, Eq, Var
from bearingsim.assembler.graph import incidence_map, maximum_matching
from bearingsim.errors import ModelError, SingularBlockError
from bearingsim.units.fmi import derivative_unit

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "pantelides", "dummy_derivatives", "reduce_index"]

NAME = "index reduction"
"""The pass name in timings, logs and ``extra_passes``."""


def _derivative_var(dae: DAE, v: Var, lookup: dict[str, Var]) -> Var:
    if v.derivative is None:
        if v.is_input:
            raise ModelError(
                f"index reduction needs the time derivative of input {v.name}; "
                "drive it through a state (e.g. a filter) or give it as a time function"
            )
        d = Var(f"der({v.name})", ca.SX.sym(f"der_{v.sym.name()}"), derivative_unit(v.unit))
        d.is_derivative = True
        v.derivative = d
        dae.vars.append(d)
        lookup[d.sym.name()] = d
    return v.derivative


def _differentiate(dae: DAE, eq: Eq, lookup: dict[str, Var]) -> Eq:
    if eq.differentiated is not None:
        return eq.differentiated
    r = eq.residual
    vs = dae.incidence(eq, lookup)
    dr = ca.jacobian(r, dae.time)
    if vs:
        syms = ca.vertcat(*[v.sym for v in vs])
        ders = ca.vertcat(*[_derivative_var(dae, v, lookup).sym for v in vs])
        dr = dr + ca.jtimes(r, syms, ders)
    new = Eq(ca.simplify(dr), eq.origin, derivative_of=eq)
    new.text = f"d/dt({eq.text or 'eq'})"
    eq.differentiated = new
    dae.eqs.append(new)
    return new


def _augment(e: Eq, inc, eligible, assign: dict, colored_e: set, colored_v: set) -> bool:
    """Pantelides' augmenting path search from equation ``e`` (colours what it visits).

    A depth-first search with an explicit stack (the path through the assigned variables can
    be as long as the model has equations, deeper than Python's recursion allows), visiting in
    the order of the recursive formulation: an equation first takes a free eligible variable of
    its own, else follows its eligible uncoloured variables to the equations they are assigned
    to; a path that ends at a free variable is flipped along its length.
    """
    if _take_free(e, inc, eligible, assign, colored_e):
        return True
    stack = [(e, iter(inc(e)))]
    via: list = []  # via[k]: the variable that led from stack[k] to stack[k + 1]
    while stack:
        here, candidates = stack[-1]
        for v in candidates:
            if eligible(v) and v not in colored_v:
                colored_v.add(v)
                nxt = assign[v]
                if _take_free(nxt, inc, eligible, assign, colored_e):
                    assign[v] = here
                    for (frame, _), step in zip(stack[:-1], via, strict=True):
                        assign[step] = frame
                    return True
                via.append(v)
                stack.append((nxt, iter(inc(nxt))))
                break
        else:
            stack.pop()
            if via:
                via.pop()
    return False


def _take_free(e: Eq, inc, eligible, assign: dict, colored_e: set) -> bool:
    """Colour ``e`` and assign it a free eligible variable of its own, if it has one."""
    colored_e.add(e)
    for v in inc(e):
        if eligible(v) and assign.get(v) is None:
            assign[v] = e
            return True
    return False


def pantelides(dae: DAE, max_passes: int = 20) -> int:
    """Differentiate equations until each can be matched to a highest derivative.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    max_passes : int
        Most differentiation passes.

    Returns
    -------
    int
        The number of differentiated equations added.
    """
    lookup = dae.by_name()

    def eligible(v: Var) -> bool:
        return v.derivative is None and not v.is_input

    inc_cache: dict[Eq, list[Var]] = {}

    def inc(e: Eq) -> list[Var]:
        if e not in inc_cache:
            inc_cache[e] = dae.incidence(e, lookup)
        return inc_cache[e]

    candidates = [v for v in dae.vars if eligible(v)]
    start = maximum_matching(incidence_map(dae, dae.eqs, candidates), candidates)
    assign: dict[Var, Eq] = {v: e for e, v in start.items()}
    added = 0
    for k in list(dae.eqs):
        if k in start:
            continue
        i = k
        for _ in range(max_passes):
            colored_e: set[Eq] = set()
            colored_v: set[Var] = set()

            if _augment(i, inc, eligible, assign, colored_e, colored_v):
                break
            for v in colored_v:
                _derivative_var(dae, v, lookup)
            for e in colored_e:
                if e.differentiated is None:
                    added += 1
                _differentiate(dae, e, lookup)
            for v in colored_v:
                assign[v.derivative] = assign[v].differentiated
            i = i.differentiated
        else:
            raise SingularBlockError(
                f"index reduction did not converge after {max_passes} differentiations: "
                "the equations are structurally singular",
                equations=[e.describe() for e in colored_e],
                unknowns=[v.name for v in colored_v],
            )
    return added


def _start_point(dae: DAE) -> tuple[ca.SX, np.ndarray]:
    syms, vals = [], []
    for v in dae.vars:
        syms.append(v.sym)
        vals.append(v.start if v.start is not None else (v.default or 0.0))
    for p in dae.params:
        syms.append(p.sym)
        vals.append(p.value)
    syms.append(dae.time)
    vals.append(0.0)
    return ca.vertcat(*syms), np.array(vals, dtype=float)


def _select_columns(h: np.ndarray, m: int) -> list[int]:
    """``m`` independent columns of the dense ``m x n`` block ``h`` (n >= m), by QR with column
    pivoting; all of them when ``h`` is square."""
    if h.shape[1] == m:
        return list(range(m))
    _, r, piv = scipy.linalg.qr(h, pivoting=True, mode="economic")
    diag = np.abs(np.diag(r))[:m] if r.size else np.zeros(0)
    if diag.size == m and diag.min() > 1e-10 * max(diag.max(), 1.0):
        return list(piv[:m])
    raise np.linalg.LinAlgError


def _blocks(pattern: ca.Sparsity) -> list[tuple[np.ndarray, np.ndarray]]:
    """The independent blocks of an ``m x n`` sparsity pattern: the rows and columns of each
    connected component of its bipartite graph that has rows."""
    m, n = pattern.shape
    rows, cols = (np.asarray(a, dtype=int) for a in pattern.get_triplet())
    graph = scipy.sparse.coo_matrix((np.ones(rows.size), (rows, m + cols)), shape=(m + n, m + n))
    count, label = scipy.sparse.csgraph.connected_components(graph, directed=False)
    order = np.argsort(label, kind="stable")
    bounds = np.searchsorted(label[order], np.arange(count + 1))
    out = []
    for k in range(count):
        members = order[bounds[k]:bounds[k + 1]]
        block_rows = members[members < m]
        if block_rows.size:
            out.append((block_rows, members[members >= m] - m))
    return out


def _select_sparse(jac_f: ca.Function, vals: np.ndarray, rng: np.random.Generator,
                   ) -> list[int] | None:
    """Independent columns of the sparse ``m x n`` Jacobian ``jac_f``, one per row.

    Each independent block of the Jacobian (:func:`_blocks`) is selected on its own with
    :func:`_select_columns`, which picks what pivoted QR of the whole matrix picks, in the memory
    of the largest block instead of the whole ``m x n`` matrix. A block that is singular at the
    start values ``vals`` is retried at up to three random points near them.

    Returns
    -------
    list of int or None
        The selected columns in ascending order; None if a block stayed singular.
    """
    blocks = _blocks(jac_f.sparsity_out(0))
    chosen: dict[int, list[int]] = {}
    for attempt in range(4):
        noise = rng.normal(0.0, 0.1, vals.size) * (1 + abs(vals))
        point = vals if attempt == 0 else vals + noise
        h = jac_f(point).sparse().tocsr()
        for k, (rows, cols) in enumerate(blocks):
            if k not in chosen:
                try:
                    sel = _select_columns(h[rows][:, cols].toarray(), rows.size)
                except np.linalg.LinAlgError:
                    continue
                chosen[k] = [int(cols[j]) for j in sel]
        if len(chosen) == len(blocks):
            return sorted(c for sel in chosen.values() for c in sel)
    return None


def dummy_derivatives(dae: DAE) -> list[str]:
    """Select dummy derivatives (Mattsson-Söderlind) after :func:`pantelides`.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.

    Returns
    -------
    list of str
        Names of the derivatives made algebraic.
    """
    g = [e for e in dae.eqs if e.derivative_of is not None and e.differentiated is None]
    if not g:
        return []
    integral_of = {v.derivative: v for v in dae.vars if v.derivative is not None}
    z = [v for v in dae.vars if v.derivative is None and not v.is_input]
    syms, vals = _start_point(dae)
    rng = np.random.default_rng(0)
    chosen_names: list[str] = []
    while g:
        lookup = {v.sym.name(): v for v in z}
        present: dict[Var, None] = {}  # insertion-ordered set
        for e in g:
            present.update(dict.fromkeys(dae.incidence(e, lookup)))
        candidates = list(present)
        if len(candidates) < len(g):
            raise SingularBlockError(
                "dummy derivative selection failed: too few candidate derivatives",
                equations=[e.describe() for e in g],
                unknowns=[v.name for v in candidates],
            )
        if len(candidates) == len(g):
            chosen = candidates
        else:
            jac = ca.jacobian(ca.vertcat(*[e.residual for e in g]),
                              ca.vertcat(*[v.sym for v in candidates]))
            sel = _select_sparse(ca.Function("h", [syms], [jac]), vals, rng)
            if sel is None:
                raise SingularBlockError(
                    "dummy derivative selection failed: the differentiated constraints are "
                    "singular",
                    equations=[e.describe() for e in g],
                    unknowns=[v.name for v in candidates],
                )
            chosen = [candidates[k] for k in sel]
        for v in chosen:
            if v in integral_of:
                v.dummy = True
                chosen_names.append(v.name)
        g = [e.derivative_of for e in g if e.derivative_of.derivative_of is not None]
        z = [integral_of[v] for v in chosen if v in integral_of]
    return chosen_names


def reduce_index(dae: DAE) -> dict:
    """Run Pantelides and dummy derivatives; return a summary for the pass log.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.

    Returns
    -------
    dict
        ``differentiated_equations`` and ``dummy_derivatives``.
    """
    added = pantelides(dae)
    dummies = dummy_derivatives(dae) if added else []
    return {"differentiated_equations": added, "dummy_derivatives": dummies}


def run(state: AssemblyState) -> None:
    """Reduce ``state.dae`` to index 1 in place; report what was differentiated.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae")
    info = reduce_index(state.dae)
    if info["differentiated_equations"]:
        state.report["index reduction"] = (
            f"{info['differentiated_equations']} equation(s) differentiated; dummy derivatives: "
            + (", ".join(info["dummy_derivatives"]) or "none")
        )
