"""Alias elimination: ``a = ±b`` and ``a = constant`` equations are removed by substitution.

The eliminated variables are kept in ``dae.aliases`` so results can still report them (MTK's
"observed" equations). Derivative links are carried over to the representative.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import casadi as ca
import numpy as np

from bearingsim.assembler.dae import DAE, Alias, Eq, Var
from bearingsim.units.fmi import derivative_unit

if TYPE_CHECKING:
    from bearingsim.assembler.state import AssemblyState

__all__ = ["NAME", "run", "eliminate_aliases"]

NAME = "alias elimination"
"""The pass name in timings, logs and ``extra_passes``."""


def _classify_all(dae: DAE) -> list[tuple]:
    """Alias candidates of all equations, found with whole-vector CasADi operations.

    Returns a list of ('alias', eq, a, b, s) for ``a = s*b`` and ('const', eq, a, c) for
    ``a = c``; equations with parameters, time or more than two variables are never aliases.
    """
    if not dae.eqs or not dae.vars:
        return []
    r = ca.vertcat(*[e.residual for e in dae.eqs])
    v = ca.vertcat(*[x.sym for x in dae.vars])
    rows, _ = ca.jacobian_sparsity(r, v).get_triplet()
    count = np.bincount(np.asarray(rows, dtype=int), minlength=len(dae.eqs))
    others = [q.sym for q in dae.params] + [dae.time]
    has_other = np.zeros(len(dae.eqs), dtype=bool)
    if others:
        prow, _ = ca.jacobian_sparsity(r, ca.vertcat(*others)).get_triplet()
        has_other[np.asarray(prow, dtype=int)] = True
    cand = [i for i in range(len(dae.eqs)) if 1 <= count[i] <= 2 and not has_other[i]]
    if not cand:
        return []
    rc = ca.vertcat(*[dae.eqs[i].residual for i in cand])
    jac = ca.jacobian(rc, v)
    rest = ca.substitute(rc, v, ca.DM.zeros(v.numel()))
    jrows, jcols = jac.sparsity().get_triplet()
    jnz = jac.nonzeros()
    entries: dict[int, list[tuple[int, ca.SX]]] = {}
    for k, (i, j) in enumerate(zip(jrows, jcols, strict=True)):
        entries.setdefault(i, []).append((j, jnz[k]))
    rest_nz = ca.vertsplit(rest)
    out = []
    for i, row in entries.items():
        eq = dae.eqs[cand[i]]
        const = rest_nz[i]
        if not const.is_constant() or not all(c.is_constant() for _, c in row):
            continue
        coef = [float(c) for _, c in row]
        if any(c == 0.0 for c in coef):
            continue
        xs = [dae.vars[j] for j, _ in row]
        if len(xs) == 1:
            out.append(("const", eq, xs[0], -float(const) / coef[0]))
        elif float(const) == 0.0 and abs(coef[0]) == abs(coef[1]):
            out.append(("alias", eq, xs[0], xs[1], -coef[1] / coef[0]))
    return out


def _priority(v: Var) -> tuple:
    # lower is better as representative
    return (not v.is_input, v.is_derivative, v.derivative is None, not v.fixed, len(v.name), v.name)


def eliminate_aliases(dae: DAE, max_rounds: int = 8) -> None:
    """Remove alias and constant equations from ``dae`` in place.

    Parameters
    ----------
    dae : DAE
        The flattened equation system.
    max_rounds : int
        Most rounds of elimination.
    """
    for _ in range(max_rounds):
        if not _one_round(dae):
            break


def _one_round(dae: DAE) -> bool:
    lookup = dae.by_name()
    parent: dict[Var, Var] = {}
    sign: dict[Var, float] = {}

    def find(v: Var) -> tuple[Var, float]:
        s = 1.0
        while parent.get(v, v) is not v:
            s *= sign[v]
            v = parent[v]
        return v, s

    integral_of: dict[Var, Var] = {}
    for v in dae.vars:
        if v.derivative is not None:
            integral_of[v.derivative] = v

    used: list[Eq] = []
    consts: list[tuple[Var, float, Eq]] = []
    for kind in _classify_all(dae):
        if kind[0] == "const":
            _, eq, a, c = kind
            consts.append((a, c, eq))
            continue
        _, eq, a, b, s = kind
        if a.is_input and b.is_input:
            continue
        if s < 0 and (a in integral_of or b in integral_of):
            continue
        ra, sa = find(a)
        rb, sb = find(b)
        if ra is rb or _in_derivative_chain(ra, rb) or _in_derivative_chain(rb, ra):
            continue  # redundant, conflicting or an ODE x' = x: not an alias
        # a = s b  ->  sa*ra = s*sb*rb  ->  ra = (s*sb/sa) rb
        rel = s * sb / sa
        if _priority(rb) <= _priority(ra):
            parent[ra], sign[ra] = rb, rel
        else:
            parent[rb], sign[rb] = ra, 1.0 / rel
        used.append(eq)

    # constants on representatives
    const_val: dict[Var, float] = {}
    for v, c, eq in consts:
        r, s = find(v)
        if r in const_val or r.is_input or r in integral_of:
            continue
        const_val[r] = c / s
        used.append(eq)

    if not used:
        return False

    # derivative links of eliminated variables move to their representatives
    extra_eqs: list[Eq] = []
    for v in list(parent):
        r, s = find(v)
        if v.derivative is None:
            continue
        if r.derivative is None:
            if s > 0:
                r.derivative = v.derivative
                continue
            d = _new_derivative(dae, r)
            lookup[d.sym.name()] = d
        if r.derivative is not v.derivative:
            extra_eqs.append(
                Eq(v.derivative.sym - s * r.derivative.sym, "alias", text=f"der({v.name}) link")
            )
    for r in list(const_val):
        if r.derivative is not None:
            extra_eqs.append(Eq(r.derivative.sym, "alias", text=f"der({r.name}) = 0"))
            r.derivative = None

    used_ids = {id(e) for e in used}
    remaining = [e for e in dae.eqs if id(e) not in used_ids] + extra_eqs
    removed = [v for v in dae.vars if v in parent or v in const_val]
    const_syms, const_values = [], []  # removed variable -> a constant
    alias_syms, scales, representatives = [], [], []  # removed variable -> scale * representative
    for v in removed:
        if v in const_val:
            val = const_val[v]
            const_syms.append(v.sym)
            const_values.append(val)
            dae.aliases[v.name] = Alias(v.name, 0.0, None, val, v.unit, v.description)
            continue
        r, s = find(v)
        if r in const_val:
            const_syms.append(v.sym)
            const_values.append(s * const_val[r])
            dae.aliases[v.name] = Alias(v.name, 0.0, None, s * const_val[r], v.unit,
                                        v.description)
        else:
            alias_syms.append(v.sym)
            scales.append(s)
            representatives.append(r.sym)
            dae.aliases[v.name] = Alias(v.name, s, r, 0.0, v.unit, v.description)
            if r.start is None and v.start is not None:
                r.start, r.fixed = s * v.start, v.fixed
            if v.is_input:
                r.is_input = True
    targets = remaining + dae.initial_eqs
    if targets and removed:
        # one vector operation for all replacements (an SX operation per variable from Python
        # costs more than the substitution itself)
        repl = ca.vertcat(ca.DM(const_values),
                          ca.DM(scales) * ca.vertcat(*representatives) if representatives
                          else ca.SX(0, 1))
        res = ca.substitute(ca.vertcat(*[e.residual for e in targets]),
                            ca.vertcat(*const_syms, *alias_syms), repl)
        for e, r in zip(targets, ca.vertsplit(res), strict=True):
            e.residual = r
    removed_ids = {id(v) for v in removed}
    dae.vars = [v for v in dae.vars if id(v) not in removed_ids]
    # derivative pointers that referred to removed derivative vars
    for v in dae.vars:
        if v.derivative is not None and id(v.derivative) in removed_ids:
            r, s = find(v.derivative)
            if r in const_val or s < 0:
                d = v.derivative
                v.derivative = None
                remaining.append(Eq(_deriv_placeholder(dae, v, d, r, s, const_val), "alias"))
            else:
                v.derivative = r
    # re-point alias entries whose representative was itself removed later
    dae.eqs = remaining
    for name, a in list(dae.aliases.items()):
        if a.representative is not None and id(a.representative) in removed_ids:
            rr, s2 = find(a.representative)
            if rr in const_val:
                dae.aliases[name] = replace(a, scale=0.0, representative=None,
                                            offset=a.scale * s2 * const_val[rr] + a.offset)
            else:
                dae.aliases[name] = replace(a, scale=a.scale * s2, representative=rr)
    return True


def _in_derivative_chain(a: Var, b: Var) -> bool:
    """Whether ``b`` is a (higher) derivative of ``a``."""
    d = a.derivative
    while d is not None:
        if d is b:
            return True
        d = d.derivative
    return False


def _new_derivative(dae: DAE, v: Var) -> Var:
    """A new variable ``der(v)``, linked to ``v``. It replaces an alias entry of that name (an
    eliminated derivative of ``v``): one observed name, one value."""
    nd = Var(f"der({v.name})", ca.SX.sym(f"der_{v.sym.name()}"), derivative_unit(v.unit))
    nd.is_derivative = True
    dae.vars.append(nd)
    dae.aliases.pop(nd.name, None)
    v.derivative = nd
    return nd


def _deriv_placeholder(dae, v, d, r, s, const_val):
    """Re-create der(v) as its own variable equal to what its eliminated derivative became."""
    nd = _new_derivative(dae, v)
    target = ca.SX(s * const_val[r]) if r in const_val else s * r.sym
    return nd.sym - target


def run(state: AssemblyState) -> None:
    """Eliminate the aliases of ``state.dae`` in place; report how many variables went.

    Parameters
    ----------
    state : AssemblyState
        The assembly state the pass reads and updates.
    """
    state.require(NAME, "dae")
    n = len(state.dae.vars)
    eliminate_aliases(state.dae)
    state.report["aliases eliminated"] = n - len(state.dae.vars)
